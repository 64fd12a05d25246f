use std::time::Instant;
use xper_nscd::{MoreauJean, RigidContactOperator, World};
use xper_solver::nlgs;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let bytes = std::fs::read(&args[1]).unwrap();
    let (_h, w): (u64, Vec<u8>) = bincode::deserialize(&bytes).unwrap();
    let world = World::from_bytes(&w).unwrap();
    let mut mj = MoreauJean::new();
    let prob = mj.next_rigid_problem(&world);
    let n = prob.rows.len();
    let sweeps: u32 = args[2].parse().unwrap();
    // consecutive contacts sharing a body
    let share = |order: &[usize]| {
        order
            .windows(2)
            .filter(|p| {
                let (a, b) = (prob.rows[p[0]].bodies, prob.rows[p[1]].bodies);
                a[0] == b[0] || a[0] == b[1] || a[1] == b[0] || a[1] == b[1]
            })
            .count()
    };
    let ident: Vec<usize> = (0..n).collect();
    let k = 4;
    let chunk = n.div_ceil(k);
    let inter: Vec<usize> = (0..chunk)
        .flat_map(|i| (0..k).map(move |j| j * chunk + i))
        .filter(|&x| x < n)
        .collect();
    println!(
        "contacts {n}, sharing consecutive: ident {} inter {}",
        share(&ident),
        share(&inter)
    );
    for rep in 0..3 {
        for (name, order) in [("ident", &ident), ("inter", &inter)] {
            let mut op = RigidContactOperator {
                bodies: prob.bodies.clone(),
                rows: order.iter().map(|&a| prob.rows[a]).collect(),
            };
            let mu: Vec<f64> = order.iter().map(|&a| prob.mu[a]).collect();
            let shift: Vec<f64> = order.iter().map(|&a| prob.shift[a]).collect();
            let mut imp: Vec<[f64; 2]> = order.iter().map(|&a| prob.impulses[a]).collect();
            let mut params = world.params.nlgs;
            params.max_iterations = sweeps;
            params.tolerance = 1e-30;
            let t = Instant::now();
            let info = nlgs(&mut op, &mu, &shift, &mut imp, &params).unwrap();
            let el = t.elapsed().as_secs_f64();
            println!(
                "[{rep}] {name}: {} sweeps {:.2} ns/update worst {:.3}",
                info.iterations,
                el * 1e9 / (n as f64 * info.iterations as f64),
                info.norms.worst(false)
            );
        }
    }
}
