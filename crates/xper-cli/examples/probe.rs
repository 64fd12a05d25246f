use xper_nscd::{MoreauJean, World};
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let bytes = std::fs::read(&args[1]).unwrap();
    let (_h, w): (u64, Vec<u8>) = bincode::deserialize(&bytes).unwrap();
    let mut world = World::from_bytes(&w).unwrap();
    let steps: u32 = args[2].parse().unwrap();
    let mut s = MoreauJean::new();
    for _ in 0..steps {
        for k in [10u32, 20, 30] {
            let mut w = world.clone();
            w.params.nlgs.max_iterations = k;
            let mut s2 = MoreauJean::new();
            let r = s2.step(&mut w).unwrap();
            let n = r.norms;
            print!(
                "  k={k}: meanDVoR {:.3} quadDV {:.3} quadDVR {:.3} act {}",
                n.mean_dvor, n.quad_dv, n.quad_dvr, n.active
            );
        }
        let r = s.step(&mut world).unwrap();
        println!(
            "\nstep {} sweeps {} contacts {}",
            r.step, r.iterations, r.contacts
        );
    }
}
