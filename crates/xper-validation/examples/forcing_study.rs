//! The published immersed-grain cases under a forcing and a time scheme given on the command
//! line, for the convergence study of the marker forcing:
//! `cargo run --release -p xper-validation --example forcing_study -- single markers euler lub 16 24 32`
//! (case `single` or `dkt`, forcing `fraction` or `markers[:passes[:retraction]]`, scheme
//! `euler` or `rk3`, lubrication `lub` (one cell) or `nolub`, then the grids in cells per
//! diameter).
use xper_fluid::{Forcing, MarkerForcingParams, TimeScheme};
use xper_validation::fluid::{drafting_kissing_tumbling, single_disk_settling, Options};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if let Err(e) = run(&args) {
        eprintln!("forcing_study: {e}");
        std::process::exit(2);
    }
}

fn run(args: &[String]) -> Result<(), String> {
    let [case, forcing, scheme, lubrication, grids @ ..] = args else {
        return Err("usage: CASE FORCING SCHEME LUBRICATION GRIDS..".into());
    };
    let forcing = match forcing.split(':').collect::<Vec<_>>().as_slice() {
        ["fraction"] => Forcing::Fraction,
        ["markers", rest @ ..] => {
            let mut m = MarkerForcingParams::default();
            if let Some(n) = rest.first() {
                m.iterations = n.parse().map_err(|_| format!("passes: {n}"))?;
            }
            if let Some(r) = rest.get(1) {
                m.retraction = r.parse().map_err(|_| format!("retraction: {r}"))?;
            }
            Forcing::Markers(m)
        }
        _ => {
            return Err(format!(
                "forcing: {forcing} (fraction or markers[:passes[:retraction]])"
            ))
        }
    };
    let scheme = match scheme.as_str() {
        "euler" => TimeScheme::Euler,
        "rk3" => TimeScheme::Rk3,
        _ => return Err(format!("scheme: {scheme} (euler or rk3)")),
    };
    let grids: Vec<usize> = grids
        .iter()
        .map(|g| g.parse().map_err(|_| format!("grid: {g}")))
        .collect::<Result<_, _>>()?;
    let lubrication = match lubrication.as_str() {
        "lub" => Some(xper_fluid::Lubrication::default()),
        "nolub" => None,
        _ => return Err(format!("lubrication: {lubrication} (lub or nolub)")),
    };
    let options = Options {
        scheme,
        forcing,
        lubrication,
    };
    let cases = match case.as_str() {
        "single" => vec![single_disk_settling(&grids, options)?],
        "dkt" => drafting_kissing_tumbling(&grids, options)?,
        _ => return Err(format!("case: {case} (single or dkt)")),
    };
    for c in cases {
        println!("{}: {} (error {:.4})", c.name, c.measured, c.error);
    }
    Ok(())
}
