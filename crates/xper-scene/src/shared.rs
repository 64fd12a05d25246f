//! State shared between the section readers: materials, groups and the bodies built so far
//! with where each one comes from.

use crate::read::Ctx;
use crate::tree::Pos;
use crate::types::BodyDesc;
use crate::types3d::BodyDesc3;

/// The materials declared in `[[materials]]`: name and density (None when invalid).
#[derive(Default)]
pub(crate) struct Materials {
    pub list: Vec<(String, Option<f64>)>,
}

impl Materials {
    /// The density of a named material; reports unknown names (listing the known ones).
    /// A known material with an invalid density yields `None` without a second error.
    pub fn density(&self, ctx: &mut Ctx, got: Option<(&str, Pos)>, field: &str) -> Option<f64> {
        let (name, pos) = got?;
        match self.list.iter().find(|(n, _)| n == name) {
            Some((_, d)) => *d,
            None => {
                let known: Vec<&str> = self.list.iter().map(|(n, _)| n.as_str()).collect();
                let known = if known.is_empty() {
                    "none declared".to_string()
                } else {
                    known.join(", ")
                };
                ctx.err(
                    pos,
                    field,
                    format!("unknown material `{name}` (known: {known})"),
                );
                None
            }
        }
    }
}

/// Group names in first-use order.
#[derive(Default)]
pub(crate) struct Groups {
    pub names: Vec<String>,
}

impl Groups {
    /// The index of a group, adding it if new.
    pub fn index(&mut self, name: &str) -> usize {
        if let Some(i) = self.names.iter().position(|n| n == name) {
            return i;
        }
        self.names.push(name.to_string());
        self.names.len() - 1
    }

    /// The index of an existing group.
    pub fn find(&self, name: &str) -> Option<usize> {
        self.names.iter().position(|n| n == name)
    }
}

/// What part of a file entry a body comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Part {
    Whole,
    Disk(usize),
    Wall(usize),
    /// A sphere of a 3D generator.
    Sphere(usize),
    /// A face of a 3D generator's box (floor, lid, x min, x max, y min, y max).
    Face(usize),
}

/// Where a body was declared.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Origin {
    pub section: &'static str,
    pub index: usize,
    pub part: Part,
    pub pos: Pos,
}

impl Origin {
    /// The field path of the declaring entry, e.g. `bodies[2]` or `generators[0]`.
    pub fn field(&self) -> String {
        format!("{}[{}]", self.section, self.index)
    }

    /// A human description, e.g. `generators[0] (disk 17)`.
    pub fn describe(&self) -> String {
        const SIDES: [&str; 4] = ["bottom", "right", "top", "left"];
        const FACES: [&str; 6] = ["floor", "lid", "x min", "x max", "y min", "y max"];
        match self.part {
            Part::Whole => self.field(),
            Part::Disk(k) => format!("{} (disk {k})", self.field()),
            Part::Wall(w) => format!("{} ({} wall)", self.field(), SIDES.get(w).unwrap_or(&"?")),
            Part::Sphere(k) => format!("{} (sphere {k})", self.field()),
            Part::Face(w) => format!("{} ({} wall)", self.field(), FACES.get(w).unwrap_or(&"?")),
        }
    }
}

/// The bodies built so far and their origins (same length); 2D bodies unless told.
pub(crate) struct Built<B = BodyDesc> {
    pub bodies: Vec<B>,
    pub origins: Vec<Origin>,
}

impl<B> Default for Built<B> {
    fn default() -> Self {
        Built {
            bodies: Vec::new(),
            origins: Vec::new(),
        }
    }
}

/// The bodies of a 3D scene built so far.
pub(crate) type Built3 = Built<BodyDesc3>;

impl<B> Built<B> {
    /// Room for `n` more bodies, so that a generator of a million disks does not hold two
    /// copies of the list while it grows.
    pub fn reserve(&mut self, n: usize) {
        self.bodies.reserve(n);
        self.origins.reserve(n);
    }

    pub fn push(&mut self, body: B, origin: Origin) {
        self.bodies.push(body);
        self.origins.push(origin);
    }
}
