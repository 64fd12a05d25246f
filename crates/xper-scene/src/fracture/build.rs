//! From a [`FractureScene`] to what `xper_fracture::FractureModel::new` takes: the mesh is
//! read or generated, and everything that needs it is checked with the place in the scene
//! file it comes from (region names, neighbouring regions without a law, edge sets, node
//! selections, loads driving the same node twice, rule-of-thumb stiffnesses).

use std::collections::BTreeMap;

use xper_fem::Material;
use xper_fracture::{FractureSpec, InterfaceLaw, InterfaceRule, NodeLoad, PeriodicSpec};
use xper_laws::cohesive::CohesiveZone;
use xper_mesh::{
    double_edge_notched, periodic_cell, read_msh, rectangle_with_inclusions, Mesh, NodeSelector,
    PeriodicCell, Topology,
};

use super::cohesive_zone;
use super::types::{FractureScene, InterfaceLawDesc, MeshSource, Place, Stiffness};
use crate::error::{SceneError, SceneErrors};

/// A fracture scene ready to be built: the mesh and the engine's specification.
#[derive(Debug, Clone)]
pub struct FractureSetup {
    /// The mesh (read or generated).
    pub mesh: Mesh,
    /// The model specification (materials in `mesh.regions` order).
    pub spec: FractureSpec,
    /// Interior edges of the mesh, i.e. interfaces of the model.
    pub interfaces: usize,
    /// Values computed from the scene worth showing (rule-of-thumb stiffnesses).
    pub notes: Vec<String>,
}

/// Joins names for messages, `none` when empty.
fn list<'a>(names: impl Iterator<Item = &'a str>) -> String {
    let v: Vec<&str> = names.collect();
    if v.is_empty() {
        "none".to_string()
    } else {
        v.join(", ")
    }
}

struct Errors<'s> {
    scene: &'s FractureScene,
    list: Vec<SceneError>,
}

impl Errors<'_> {
    fn at(&mut self, place: &Place, message: impl Into<String>) {
        self.list.push(SceneError {
            file: self.scene.file.clone(),
            line: place.line,
            column: place.column,
            field: place.field.clone(),
            message: message.into(),
        });
    }
}

impl FractureScene {
    /// Reads or generates the mesh and checks the scene against it: every mesh region has a
    /// `[[regions]]` entry and every entry names a mesh region, every pair of neighbouring
    /// regions has an interface law, `broken` names edge sets of the mesh, each load selects
    /// at least one node (set names are checked, the known ones listed) and no node
    /// component is driven by two loads. Returns every error found, sorted by position.
    pub fn build(&self) -> Result<FractureSetup, SceneErrors> {
        let mut errors = Errors {
            scene: self,
            list: Vec::new(),
        };
        let mesh = self.make_mesh(&mut errors);
        let topology = mesh.as_ref().map(|m| m.neighbours());
        let (mesh, topology) = match (mesh, topology) {
            (Some(mesh), Some(Ok(t))) => (mesh, t),
            (_, Some(Err(e))) => {
                errors.at(&self.mesh.place, e.to_string());
                return Err(SceneErrors(errors.list));
            }
            _ => return Err(SceneErrors(errors.list)),
        };
        let materials = self.materials(&mesh, &mut errors);
        let (interface_laws, notes) = self.laws(&mesh, &topology, &materials, &mut errors);
        for b in &self.broken {
            if !mesh.edge_sets.contains_key(&b.name) {
                let known = list(mesh.edge_sets.keys().map(String::as_str));
                let msg = format!("unknown edge set `{}` (edge sets: {known})", b.name);
                errors.at(&b.place, msg);
            }
        }
        let loads = self.loads(&mesh, &mut errors);
        let periodic = self.periodic(&mesh, &mut errors);
        if !errors.list.is_empty() {
            let mut list = errors.list;
            list.sort_by_key(|e| (e.line, e.column));
            return Err(SceneErrors(list));
        }
        let spec = FractureSpec {
            thickness: self.thickness,
            hypothesis: self.hypothesis,
            materials: materials.into_iter().flatten().collect(),
            interface_laws,
            broken_edge_sets: self.broken.iter().map(|b| b.name.clone()).collect(),
            loads,
            gravity: self.gravity,
            mass: self.mass,
            dt: self.dt,
            theta: self.theta,
            nlgs: self.nlgs,
            periodic,
            plastic_stiffness: self.plastic_stiffness,
        };
        Ok(FractureSetup {
            interfaces: topology.interior.len(),
            mesh,
            spec,
            notes,
        })
    }

    /// The element size used by the stiffness rule of thumb: the generator's `element_size`,
    /// or the mean edge length of a mesh file (m).
    pub fn rule_of_thumb_length(&self, mesh: &Mesh) -> f64 {
        match &self.mesh.source {
            MeshSource::File(_) => mesh.edge_length_stats().mean,
            MeshSource::DoubleEdgeNotched(s) => s.element_size,
            MeshSource::RectangleWithInclusions(s) => s.element_size,
            MeshSource::PeriodicCell(s) => s.element_size,
        }
    }

    /// The periodic cell of `[periodic]` (the mesh's bounding box unless given), its sides
    /// checked to match.
    fn periodic(&self, mesh: &Mesh, errors: &mut Errors) -> Option<PeriodicSpec> {
        let p = self.periodic.as_ref()?;
        let cell = match p.cell {
            Some([a, b]) => PeriodicCell {
                lower: a,
                size: [b[0] - a[0], b[1] - a[1]],
            },
            None => PeriodicCell::bounding(mesh),
        };
        if let Err(e) = mesh.periodic_edges(&cell) {
            errors.at(&p.place, format!("the mesh is not a periodic cell: {e}"));
            return None;
        }
        Some(PeriodicSpec {
            cell,
            drives: p.drives.clone(),
        })
    }

    fn make_mesh(&self, errors: &mut Errors) -> Option<Mesh> {
        let m = &self.mesh;
        let result = match &m.source {
            MeshSource::File(path) => read_msh(path),
            MeshSource::DoubleEdgeNotched(s) => double_edge_notched(s),
            MeshSource::RectangleWithInclusions(s) => rectangle_with_inclusions(s),
            MeshSource::PeriodicCell(s) => periodic_cell(s),
        };
        match result {
            Ok(mesh) => Some(mesh),
            Err(e) => {
                // A generator names the offending parameter first in its place
                // (`notch_depth`, `inclusions[1] = [...]`); a file error is the file's.
                let key = match &m.source {
                    MeshSource::File(_) => "file".to_string(),
                    _ => (e.place.as_deref().unwrap_or(""))
                        .split(['[', ' ', '.'])
                        .next()
                        .unwrap_or("")
                        .to_string(),
                };
                let place = (m.keys.iter().find(|(k, _)| *k == key)).map_or(&m.place, |(_, p)| p);
                let msg = match (&m.source, e.kind) {
                    (MeshSource::File(_), xper_mesh::MeshErrorKind::Io) => {
                        format!("mesh file: {e}")
                    }
                    (MeshSource::File(_), _) => format!("bad mesh file: {e}"),
                    _ => format!("cannot generate the mesh: {e}"),
                };
                errors.at(place, msg);
                None
            }
        }
    }

    /// The material of each mesh region (`None` where missing: reported).
    fn materials(&self, mesh: &Mesh, errors: &mut Errors) -> Vec<Option<Material>> {
        let mut out = vec![None; mesh.regions.len()];
        let names = || list(mesh.regions.iter().map(|r| r.name.as_str()));
        for r in &self.regions {
            match mesh.regions.iter().position(|m| m.name == r.name) {
                Some(i) => out[i] = Some(r.material),
                None => {
                    let msg = format!(
                        "region `{}` is not in the mesh (mesh regions: {})",
                        r.name,
                        names()
                    );
                    errors.at(&r.place, msg);
                }
            }
        }
        for (region, m) in mesh.regions.iter().zip(&out) {
            if m.is_none() {
                let place = Place {
                    field: "regions".into(),
                    ..self.mesh.place.clone()
                };
                let msg = format!(
                    "the mesh has a region `{}` with no [[regions]] entry: give its material",
                    region.name
                );
                errors.at(&place, msg);
            }
        }
        out
    }

    /// The interface rules, and notes on rule-of-thumb stiffnesses.
    fn laws(
        &self,
        mesh: &Mesh,
        topology: &Topology,
        materials: &[Option<Material>],
        errors: &mut Errors,
    ) -> (Vec<InterfaceRule>, Vec<String>) {
        let index = |name: &str| mesh.regions.iter().position(|r| r.name == name);
        let length = self.rule_of_thumb_length(mesh);
        let (mut rules, mut notes) = (Vec::new(), Vec::new());
        for (k, desc) in self.interfaces.iter().enumerate() {
            let (Some(ra), Some(rb)) = (index(&desc.regions[0]), index(&desc.regions[1])) else {
                continue; // a region not in the mesh: reported by `materials`
            };
            let law = match desc.law {
                InterfaceLawDesc::Contact { friction } => InterfaceLaw::Contact { friction },
                InterfaceLawDesc::Cohesive {
                    normal_stiffness,
                    tangential_stiffness,
                    ..
                } => {
                    let rule = [normal_stiffness, tangential_stiffness]
                        .contains(&Stiffness::RuleOfThumb)
                        .then(|| {
                            let stiffer = (materials[ra].iter().chain(&materials[rb]))
                                .max_by(|a, b| a.young().total_cmp(&b.young()))
                                .copied();
                            stiffer.map(|m| (m, rule_of_thumb(&m, length)))
                        })
                        .flatten();
                    let zone = match rule {
                        Some((m, Ok((c_n, c_t)))) => {
                            notes.push(format!(
                                "interfaces[{k}] ({} / {}): rule of thumb with E = {:e} Pa, \
                                 nu = {}, L = {length:e} m: C_N = {c_n:.4e} Pa/m, \
                                 C_T = {c_t:.4e} Pa/m",
                                desc.regions[0],
                                desc.regions[1],
                                m.young(),
                                m.poisson()
                            ));
                            cohesive_zone(&desc.law, Some((c_n, c_t)))
                        }
                        Some((_, Err(e))) => {
                            errors.at(&desc.place, format!("stiffness rule of thumb: {e}"));
                            continue;
                        }
                        None => cohesive_zone(&desc.law, None),
                    };
                    let Some(zone) = zone else {
                        continue; // the regions' materials are missing: reported
                    };
                    if let Err(e) = zone.validate() {
                        errors.at(&desc.place, e.to_string());
                        continue;
                    }
                    InterfaceLaw::Cohesive(zone)
                }
            };
            rules.push(InterfaceRule {
                regions: [ra as u32, rb as u32],
                law,
            });
        }
        let mut pairs: BTreeMap<[u32; 2], usize> = BTreeMap::new();
        for e in &topology.interior {
            let [a, b] = e.regions(mesh);
            *pairs.entry([a.min(b), a.max(b)]).or_default() += 1;
        }
        // Pairs with an entry (kept even when its law was refused above, already reported).
        let declared: Vec<[usize; 2]> = (self.interfaces.iter())
            .filter_map(|d| Some([index(&d.regions[0])?, index(&d.regions[1])?]))
            .collect();
        for ([a, b], count) in pairs {
            let (a, b) = (a as usize, b as usize);
            let given = |r: usize| materials[r].is_some();
            if !given(a) || !given(b) || declared.iter().any(|&p| p == [a, b] || p == [b, a]) {
                continue;
            }
            let place = self.interfaces.first().map_or_else(
                || Place {
                    field: "interfaces".into(),
                    ..self.mesh.place.clone()
                },
                |d| Place {
                    field: "interfaces".into(),
                    ..d.place.clone()
                },
            );
            let (na, nb) = (&mesh.regions[a].name, &mesh.regions[b].name);
            let msg = if a == b {
                format!(
                    "the {count} interfaces inside region `{na}` have no law: add an \
                     [[interfaces]] entry with between = [\"{na}\", \"{na}\"]"
                )
            } else {
                format!(
                    "regions `{na}` and `{nb}` are neighbours ({count} interfaces) but have no \
                     law: add an [[interfaces]] entry with between = [\"{na}\", \"{nb}\"]"
                )
            };
            errors.at(&place, msg);
        }
        (rules, notes)
    }

    fn loads(&self, mesh: &Mesh, errors: &mut Errors) -> Vec<NodeLoad> {
        let mut out = Vec::new();
        let mut driver: BTreeMap<(u32, usize), usize> = BTreeMap::new();
        for (l, load) in self.loads.iter().enumerate() {
            let nodes = match mesh.select_nodes(&load.nodes) {
                Ok(nodes) => nodes,
                Err(e) => {
                    let msg = match &load.nodes {
                        NodeSelector::Set(name) => format!(
                            "unknown node set `{name}` (node sets: {})",
                            list(mesh.node_sets.keys().map(String::as_str))
                        ),
                        _ => e.to_string(),
                    };
                    errors.at(&load.place, msg);
                    continue;
                }
            };
            if nodes.is_empty() {
                let (lo, hi) = bounding_box(mesh);
                let msg = format!(
                    "load `{}` selects no node of the mesh (nodes span [{:e}, {:e}] x [{:e}, {:e}] m)",
                    load.name, lo[0], hi[0], lo[1], hi[1]
                );
                errors.at(&load.place, msg);
                continue;
            }
            let driven: Vec<(u32, usize)> = (nodes.iter())
                .flat_map(|&n| (0..2).map(move |d| (n, d)))
                .filter(|&(_, d)| !matches!(load.drives[d], xper_bodies::Drive::Free))
                .collect();
            if let Some((&(n, d), &other)) = driven
                .iter()
                .find_map(|key| driver.get(key).map(|o| (key, o)))
            {
                let p = mesh.nodes[n as usize];
                let msg = format!(
                    "node {n} at ({:e}, {:e}) m is already driven along {} by load `{}`",
                    p[0],
                    p[1],
                    ["x", "y"][d],
                    self.loads[other].name
                );
                errors.at(&load.place, msg);
                continue;
            }
            driver.extend(driven.into_iter().map(|key| (key, l)));
            out.push(NodeLoad {
                name: load.name.clone(),
                nodes,
                drives: load.drives.clone(),
            });
        }
        out
    }
}

fn rule_of_thumb(
    m: &Material,
    length: f64,
) -> Result<(f64, f64), xper_laws::cohesive::CohesiveError> {
    CohesiveZone::stiffness_rule_of_thumb(m.young(), m.poisson(), length)
}

fn bounding_box(mesh: &Mesh) -> ([f64; 2], [f64; 2]) {
    mesh.nodes.iter().fold(
        ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]),
        |(lo, hi), p| {
            (
                [lo[0].min(p[0]), lo[1].min(p[1])],
                [hi[0].max(p[0]), hi[1].max(p[1])],
            )
        },
    )
}
