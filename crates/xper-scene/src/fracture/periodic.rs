//! `[periodic]`: a fracture scene's mesh as a periodic cell under a macroscopic strain or
//! stress history, one drive per component of the strain `[xx, yy, xy]`.

use xper_fracture::MacroDrive;

use super::mesh::two_points;
use super::place;
use super::types::PeriodicDesc;
use crate::bodies::time_function;
use crate::read::{Ctx, Tbl};

/// The components, in Voigt order.
const COMPONENTS: [&str; 3] = ["xx", "yy", "xy"];

/// `[periodic]`, if present.
pub(super) fn periodic(ctx: &mut Ctx, root: &Tbl) -> Option<Option<Box<PeriodicDesc>>> {
    if !root.has("periodic") {
        return Some(None);
    }
    let t = root.table(ctx, "periodic").ok()?.0;
    let mut keys = vec!["cell".to_string()];
    for c in COMPONENTS {
        keys.push(format!("strain_{c}"));
        keys.push(format!("stress_{c}"));
    }
    let known: Vec<&str> = keys.iter().map(String::as_str).collect();
    t.check_keys(ctx, &known);
    let cell = match t.get("cell") {
        None => Some(None),
        Some(n) => two_points(ctx, n, &t.field("cell")).and_then(|[a, b]| {
            if a[0] < b[0] && a[1] < b[1] {
                Some(Some([a, b]))
            } else {
                ctx.err(
                    n.pos,
                    &t.field("cell"),
                    format!(
                        "needs [[xmin, ymin], [xmax, ymax]] with min < max (m), got {a:?}, {b:?}"
                    ),
                );
                None
            }
        }),
    };
    let mut drives = Vec::new();
    for c in COMPONENTS {
        let (strain, stress) = (format!("strain_{c}"), format!("stress_{c}"));
        let drive = match (t.get(&strain), t.get(&stress)) {
            (Some(n), None) => time_function(ctx, n, &t.field(&strain)).map(MacroDrive::Strain),
            (None, Some(n)) => time_function(ctx, n, &t.field(&stress)).map(MacroDrive::Stress),
            (Some(_), Some(n)) => {
                ctx.err(
                    n.pos,
                    &t.field(&stress),
                    format!("give either {strain} or {stress}, not both"),
                );
                None
            }
            (None, None) => {
                ctx.err(
                    t.pos,
                    &t.field(&strain),
                    format!(
                        "missing: each component is driven by its strain (dimensionless) or \
                         its stress (Pa); give {strain} or {stress}"
                    ),
                );
                None
            }
        };
        drives.push(drive);
    }
    let [xx, yy, xy]: [Option<MacroDrive>; 3] = drives.try_into().ok()?;
    Some(Some(Box::new(PeriodicDesc {
        cell: cell?,
        drives: [xx?, yy?, xy?],
        place: place(t.pos, t.path.clone()),
    })))
}
