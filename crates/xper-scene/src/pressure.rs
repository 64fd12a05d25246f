//! Pressure drives of walls with a mass (servo walls): `drive.<dof> = { pressure = p,
//! between = ["bottom", "top"] }`.
//!
//! The wall is pushed along its normal by the force `p A n_d` on the driven translation, with
//! `A` its loaded length: the distance between the two walls `between` names (one body per
//! group), measured along the wall at the beginning of each step, or the wall's own length.
//! This is the servo-controlled boundary of a biaxial test at constant confining pressure
//! (e.g. LMGC90's examples, where the same force is recomputed from the sample's height).

use crate::read::{Ctx, Tbl};
use crate::shared::{Built, Groups};
use crate::tree::{Kind, Pos};
use crate::types::{Drive, ExtentDesc, PressureDesc};

/// A `between` whose groups are resolved to bodies once every body is built.
pub(crate) struct PendingSpan {
    /// The index of the driven wall in the scene's bodies.
    pub body: usize,
    /// The driven degree of freedom.
    pub dof: usize,
    /// The two group names.
    pub groups: [String; 2],
    /// Where `between` is.
    pub pos: Pos,
    /// Its field path.
    pub field: String,
}

/// The wall a pressure drives: its index among the bodies, unit normal (the push direction),
/// unit direction along it and length (m).
pub(crate) struct WallFrame {
    pub body: usize,
    pub normal: [f64; 2],
    pub along: [f64; 2],
    pub length: f64,
}

/// Reads a `{ pressure = ..., between = [a, b] }` entry for degree of freedom `dof` of `wall`.
pub(crate) fn read(
    ctx: &mut Ctx,
    dof: usize,
    e: &Tbl,
    wall: &WallFrame,
    pending: &mut Vec<PendingSpan>,
) -> Option<Drive> {
    e.check_keys(ctx, &["pressure", "between"]);
    let p = e.get("pressure")?;
    let pressure = crate::bodies::time_function(ctx, p, &e.field("pressure"));
    let Some(&direction) = wall.normal.get(dof) else {
        let why = "a pressure drives a translation (`x` or `y`), not the rotation";
        ctx.err(p.pos, &e.field("pressure"), why);
        return None;
    };
    if direction.abs() < 1e-12 {
        let why = format!(
            "the wall's normal {:?} has no component along this degree of freedom: the pressure \
             cannot push it this way",
            wall.normal
        );
        ctx.err(p.pos, &e.field("pressure"), why);
        return None;
    }
    let extent = match e.get("between") {
        None => ExtentDesc::Fixed(wall.length),
        Some(n) => {
            let field = e.field("between");
            let names = match &n.kind {
                Kind::Array(a) if a.len() == 2 => {
                    let name = |k: usize| match &a[k].kind {
                        Kind::Str(s) => Some(s.clone()),
                        _ => None,
                    };
                    name(0).zip(name(1))
                }
                _ => None,
            };
            let Some((a, b)) = names else {
                ctx.expected(n, &field, "two group names, e.g. [\"bottom\", \"top\"]");
                return None;
            };
            pending.push(PendingSpan {
                body: wall.body,
                dof,
                groups: [a, b],
                pos: n.pos,
                field,
            });
            ExtentDesc::Between {
                bodies: [usize::MAX; 2],
                axis: [wall.along[0], wall.along[1], 0.0],
            }
        }
    };
    Some(Drive::Pressure(PressureDesc {
        pressure: pressure?,
        direction,
        extent: vec![extent],
    }))
}

/// Resolves the groups of every `between` to their one body each.
pub(crate) fn resolve(
    ctx: &mut Ctx,
    groups: &Groups,
    built: &mut Built,
    pending: Vec<PendingSpan>,
) {
    for span in pending {
        let mut bodies = [usize::MAX; 2];
        for (slot, name) in bodies.iter_mut().zip(&span.groups) {
            let members: Vec<usize> = match groups.find(name) {
                Some(g) => (built.bodies.iter().enumerate())
                    .filter(|(_, b)| b.group == g)
                    .map(|(k, _)| k)
                    .take(2)
                    .collect(),
                None => Vec::new(),
            };
            match members[..] {
                [k] => *slot = k,
                [] => ctx.err(
                    span.pos,
                    &span.field,
                    format!("no body is in group `{name}`"),
                ),
                _ => {
                    let why = format!(
                        "group `{name}` holds more than one body: `between` names groups of one \
                         wall each (the loaded length is the distance between them)"
                    );
                    ctx.err(span.pos, &span.field, why)
                }
            }
        }
        if let Drive::Pressure(p) = &mut built.bodies[span.body].drives[span.dof] {
            for f in &mut p.extent {
                if let ExtentDesc::Between { bodies: b, .. } = f {
                    *b = bodies;
                }
            }
        }
    }
}
