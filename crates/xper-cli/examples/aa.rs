use std::time::Instant;
use xper_nscd::{MoreauJean, RigidContactOperator, World};
use xper_solver::{nlgs, Acceleration};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let bytes = std::fs::read(&args[1]).unwrap();
    let (_h, w): (u64, Vec<u8>) = bincode::deserialize(&bytes).unwrap();
    let world = World::from_bytes(&w).unwrap();
    let cfgs: Vec<(u32, u32)> = args[2..]
        .iter()
        .map(|s| {
            let v: Vec<u32> = s.split(',').map(|x| x.parse().unwrap()).collect();
            (v[0], v[1])
        })
        .collect();
    let mut mj = MoreauJean::new();
    let prob = mj.next_rigid_problem(&world);
    let n = prob.rows.len();
    println!("step {} contacts {}", world.step, n);
    for rep in 0..3 {
        for &(m, period) in &cfgs {
            let mut params = world.params.nlgs;
            params.max_iterations = 5000;
            params.acceleration = if m == 0 {
                Acceleration::None
            } else {
                Acceleration::Anderson { depth: m, period }
            };
            let mut op = RigidContactOperator {
                bodies: prob.bodies.clone(),
                rows: prob.rows.clone(),
            };
            let mut imp = prob.impulses.clone();
            let t = Instant::now();
            let info = nlgs(&mut op, &prob.mu, &prob.shift, &mut imp, &params).unwrap();
            let el = t.elapsed().as_secs_f64();
            println!("[{rep}] m={m} p={period}: sweeps {} conv {} worst {:.3} {:.1} ms  {:.1} ns/sweep-contact", info.iterations, info.converged, info.norms.worst(false), el * 1e3, el * 1e9 / (n as f64 * info.iterations as f64));
        }
    }
}
