use xper_nscd::{MoreauJean, World};
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let bytes = std::fs::read(&args[1]).unwrap();
    let (_h, w): (u64, Vec<u8>) = bincode::deserialize(&bytes).unwrap();
    let world = World::from_bytes(&w).unwrap();
    let steps: u32 = args[2].parse().unwrap();
    println!(
        "step {} contacts {}",
        world.step,
        world.contacts.contacts.len()
    );
    for om in args[3..].iter().map(|s| s.parse::<f64>().unwrap()) {
        let mut w = world.clone();
        w.params.nlgs.relaxation = om;
        let mut s = MoreauJean::new();
        let (mut it, mut t, mut nc, mut ov) = (0, 0.0, 0, 0.0f64);
        for _ in 0..steps {
            let r = s.step(&mut w).unwrap();
            it += r.iterations;
            t += r.times.solve;
            nc += (!r.converged) as u32;
            ov = ov.max(r.max_overlap);
        }
        println!("omega {om:.2}: sweeps/step {:.1} solve {:.1} ms/step nonconv {nc} maxov {ov:.2e} KE {:.3e}", it as f64/steps as f64, t*1e3/steps as f64, w.kinetic_energy());
    }
}
