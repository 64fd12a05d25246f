//! Readers of a fracture scene (a scene with a `[mesh]` section): `[scene]`, `[solver]`,
//! `[output]`, `[fracture]`, `[mesh]`, `[[regions]]`, `[[interfaces]]` and `[[loads]]`.
//! Everything that can be checked without the mesh is checked here; the rest is checked by
//! [`FractureScene::build`](crate::FractureScene::build).

pub(crate) mod build;
mod loads;
mod mesh;
mod periodic;
pub(crate) mod types;

use std::path::Path;

use xper_fem::{Hypothesis, Material};
use xper_fracture::{MassMatrix, PlasticStiffness};
use xper_laws::cohesive::{CohesiveError, CohesiveZone};
use xper_solver::NlgsParams;

use crate::read::{choose, ensure, Ctx, Got, Tbl};
use crate::sections;
use crate::tree::{Kind, Pos};
use crate::types::{ConvergenceNorm, OutputSettings, VelocitySolverKind};
use types::{
    EdgeSetRef, FractureScene, InterfaceDesc, InterfaceLawDesc, Place, RegionDesc, Stiffness,
};

/// Top-level keys of a fracture scene.
pub(crate) const TOP_KEYS: &[&str] = &[
    "scene",
    "solver",
    "output",
    "fracture",
    "mesh",
    "regions",
    "interfaces",
    "loads",
    "periodic",
];

const COHESIVE_KEYS: &[&str] = &[
    "kind",
    "normal_stiffness",
    "tangential_stiffness",
    "fracture_energy",
    "strength",
    "initial_damage",
    "friction",
];

pub(crate) fn place(pos: Pos, field: String) -> Place {
    Place {
        line: pos.line as usize,
        column: pos.column as usize,
        field,
    }
}

/// The sub-table under `key` if there is one (type errors are the section readers' job).
fn quiet_table<'a>(t: &Tbl<'a>, key: &str) -> Option<Tbl<'a>> {
    let n = t.get(key)?;
    match &n.kind {
        Kind::Table(entries) => Some(Tbl {
            entries,
            pos: n.pos,
            path: t.field(key),
        }),
        _ => None,
    }
}

/// A required table, reporting it missing.
pub(crate) fn required_table<'a>(ctx: &mut Ctx, t: &Tbl<'a>, key: &str) -> Option<Tbl<'a>> {
    t.table(ctx, key).req(ctx, t, key).map(|(t, _)| t)
}

/// A required number checked by `ok`.
pub(crate) fn number(
    ctx: &mut Ctx,
    t: &Tbl,
    key: &str,
    ok: impl Fn(f64) -> bool,
    what: &str,
) -> Option<f64> {
    let got = t.num(ctx, key).req(ctx, t, key);
    ensure(ctx, got, &t.field(key), ok, what)
}

/// An optional number checked by `ok`, `default` when absent.
pub(crate) fn number_or(
    ctx: &mut Ctx,
    t: &Tbl,
    key: &str,
    default: f64,
    ok: impl Fn(f64) -> bool,
    what: &str,
) -> Option<f64> {
    match t.num(ctx, key) {
        Got::Absent => Some(default),
        g => ensure(ctx, g.ok(), &t.field(key), ok, what),
    }
}

/// Reads a whole fracture scene; `None` when something was invalid (errors reported).
pub(crate) fn fracture_scene(ctx: &mut Ctx, root: &Tbl, file: &Path) -> Option<FractureScene> {
    root.check_keys(ctx, TOP_KEYS);
    let header = sections::header(ctx, root);
    if let Some(s) = quiet_table(root, "scene") {
        if header.dimension == Some(3) {
            let why = "fracture scenes are 2D only so far (3D fracture is planned)";
            s.forbid(ctx, "dimension", why);
        }
        s.forbid(
            ctx,
            "alert_distance",
            "does not apply to a fracture scene: its interfaces come from the mesh",
        );
        s.forbid(
            ctx,
            "detection",
            "does not apply to a fracture scene: its interfaces come from the mesh",
        );
    }
    let nlgs = nlgs(ctx, root);
    let output = output(ctx, root, header.steps);
    let fracture = fracture_section(ctx, root);
    let mesh = mesh::mesh(ctx, root, file);
    let (regions, names) = regions(ctx, root);
    let interfaces = interfaces(ctx, root, &names);
    let loads = loads::loads(ctx, root);
    let periodic = periodic::periodic(ctx, root);
    let (thickness, hypothesis, mass, plastic_stiffness, broken) = fracture?;
    Some(FractureScene {
        file: file.to_path_buf(),
        name: header.name?,
        dt: header.dt?,
        steps: header.steps?,
        theta: header.theta?,
        gravity: header.gravity?,
        nlgs,
        output: output?,
        thickness,
        hypothesis,
        mass,
        plastic_stiffness,
        mesh: mesh?,
        regions: regions?,
        interfaces: interfaces?,
        broken,
        loads: loads?,
        periodic: periodic?,
    })
}

/// `[solver]`: the NLGS keys of the rigid format; other kinds and the position projection
/// do not apply.
fn nlgs(ctx: &mut Ctx, root: &Tbl) -> NlgsParams {
    let s = sections::solver(ctx, root);
    if let Some(t) = quiet_table(root, "solver") {
        if s.kind != VelocitySolverKind::Nlgs {
            if let Some(n) = t.get("kind") {
                ctx.err(
                    n.pos,
                    &t.field("kind"),
                    "a fracture scene is solved by NLGS only (kind = \"nlgs\")",
                );
            }
        }
        t.forbid(
            ctx,
            "position_projection",
            "does not apply to a fracture scene (interfaces are solved on velocities only)",
        );
    }
    NlgsParams {
        tolerance: s.tolerance,
        max_iterations: s.max_iterations,
        check_every: s.check_every,
        relaxation: s.relaxation,
        norm: match s.norm {
            ConvergenceNorm::Quad => xper_solver::ConvergenceNorm::Quad,
            ConvergenceNorm::Maxm => xper_solver::ConvergenceNorm::Maxm,
            ConvergenceNorm::NaturalMap => xper_solver::ConvergenceNorm::NaturalMap,
        },
        acceleration: s.acceleration,
        check: s.check,
    }
}

/// `[output]`: `frame_every` and `checkpoint_every` with the rigid format's defaults.
fn output(ctx: &mut Ctx, root: &Tbl, steps: Option<u64>) -> Option<OutputSettings> {
    let o = sections::output(ctx, root, steps);
    if let Some(t) = quiet_table(root, "output") {
        t.forbid(
            ctx,
            "dump_problems",
            "does not apply to a fracture scene (only rigid scenes dump contact problems)",
        );
        t.forbid(
            ctx,
            "micro",
            "does not apply to a fracture scene (the granular measures are of rigid scenes)",
        );
    }
    let steps = steps.unwrap_or(1);
    Some(OutputSettings {
        frame_every: o.frame_every?.unwrap_or(steps.div_ceil(100).max(1)),
        checkpoint_every: o.checkpoint_every?.unwrap_or(steps.div_ceil(10).max(1)),
        dump_problems: Vec::new(),
        micro: None,
    })
}

type FractureSection = (
    f64,
    Hypothesis,
    MassMatrix,
    PlasticStiffness,
    Vec<EdgeSetRef>,
);

/// `[fracture]`: thickness, hypothesis, mass matrix, pre-broken edge sets.
fn fracture_section(ctx: &mut Ctx, root: &Tbl) -> Option<FractureSection> {
    let t = required_table(ctx, root, "fracture")?;
    t.check_keys(
        ctx,
        &[
            "thickness",
            "hypothesis",
            "mass",
            "plastic_stiffness",
            "broken",
        ],
    );
    let thickness = number(ctx, &t, "thickness", |v| v > 0.0, "> 0 m");
    let hypotheses = [
        ("plane_strain", Hypothesis::PlaneStrain),
        ("plane_stress", Hypothesis::PlaneStress),
    ];
    let hypothesis = match t.string(ctx, "hypothesis") {
        Got::Absent => Some(Hypothesis::PlaneStrain),
        g => choose(
            ctx,
            g.ok(),
            &t.field("hypothesis"),
            "hypothesis",
            &hypotheses,
        ),
    };
    let masses = [
        ("consistent", MassMatrix::Consistent),
        ("lumped", MassMatrix::Lumped),
    ];
    let mass = match t.string(ctx, "mass") {
        Got::Absent => Some(MassMatrix::Consistent),
        g => choose(ctx, g.ok(), &t.field("mass"), "mass matrix", &masses),
    };
    let stiffnesses = [
        ("tangent", PlasticStiffness::Tangent),
        ("elastic", PlasticStiffness::Elastic),
    ];
    let plastic_stiffness = match t.string(ctx, "plastic_stiffness") {
        Got::Absent => Some(PlasticStiffness::Tangent),
        g => choose(
            ctx,
            g.ok(),
            &t.field("plastic_stiffness"),
            "plastic stiffness",
            &stiffnesses,
        ),
    };
    let broken = names_list(ctx, &t, "broken");
    Some((thickness?, hypothesis?, mass?, plastic_stiffness?, broken?))
}

/// An optional array of names (empty when absent).
fn names_list(ctx: &mut Ctx, t: &Tbl, key: &str) -> Option<Vec<EdgeSetRef>> {
    let field = t.field(key);
    let Some(n) = t.get(key) else {
        return Some(Vec::new());
    };
    let Kind::Array(items) = &n.kind else {
        ctx.expected(n, &field, "an array of edge set names [\"a\", ...]");
        return None;
    };
    let mut out = Vec::new();
    let mut ok = true;
    for (k, e) in items.iter().enumerate() {
        let f = format!("{field}[{k}]");
        match &e.kind {
            Kind::Str(s) => out.push(EdgeSetRef {
                name: s.clone(),
                place: place(e.pos, f),
            }),
            _ => {
                ctx.expected(e, &f, "an edge set name");
                ok = false;
            }
        }
    }
    ok.then_some(out)
}

/// `[[regions]]`: the valid entries (`None` if one is invalid) and every name given.
fn regions(ctx: &mut Ctx, root: &Tbl) -> (Option<Vec<RegionDesc>>, Vec<String>) {
    let (mut out, mut names, mut ok) = (Vec::new(), Vec::<String>::new(), true);
    if !root.has("regions") {
        root.missing(ctx, "regions");
        ok = false;
    }
    for (_, t) in root.tables(ctx, "regions") {
        t.check_keys(ctx, &["name", "material"]);
        let name = t.string(ctx, "name").req(ctx, &t, "name");
        let material = required_table(ctx, &t, "material").and_then(|m| material(ctx, &m));
        let Some((name, pos)) = name else {
            ok = false;
            continue;
        };
        if names.iter().any(|n| n == name) {
            let msg = format!("duplicate region `{name}`");
            ctx.err(pos, &t.field("name"), msg);
            ok = false;
            continue;
        }
        names.push(name.to_string());
        match material {
            Some(material) => out.push(RegionDesc {
                name: name.to_string(),
                material,
                place: place(pos, t.field("name")),
            }),
            None => ok = false,
        }
    }
    (ok.then_some(out), names)
}

/// A bulk material: `{ kind = "elastic" | "j2", young, poisson, density, ... }`.
fn material(ctx: &mut Ctx, m: &Tbl) -> Option<Material> {
    const J2: &[&str] = &[
        "kind",
        "young",
        "poisson",
        "density",
        "yield_stress",
        "hardening",
    ];
    let got = m.string(ctx, "kind").req(ctx, m, "kind");
    let kinds = [("elastic", false), ("j2", true)];
    let plastic = choose(ctx, got, &m.field("kind"), "material kind", &kinds);
    m.check_keys(ctx, if plastic == Some(false) { &J2[..4] } else { J2 });
    let young = number(ctx, m, "young", |v| v > 0.0, "> 0 Pa");
    let poisson = number(ctx, m, "poisson", |v| v > -1.0 && v < 0.5, "in (-1, 0.5)");
    let density = number(ctx, m, "density", |v| v > 0.0, "> 0 kg/m^3");
    if plastic? {
        let yield_stress = number(ctx, m, "yield_stress", |v| v > 0.0, "> 0 Pa");
        let hardening = number(ctx, m, "hardening", |v| v >= 0.0, ">= 0 Pa");
        Some(Material::J2Plastic {
            young: young?,
            poisson: poisson?,
            density: density?,
            yield_stress: yield_stress?,
            hardening: hardening?,
        })
    } else {
        Some(Material::LinearElastic {
            young: young?,
            poisson: poisson?,
            density: density?,
        })
    }
}

/// `[[interfaces]]`; `names` are the region names given in `[[regions]]`.
fn interfaces(ctx: &mut Ctx, root: &Tbl, names: &[String]) -> Option<Vec<InterfaceDesc>> {
    let (mut out, mut ok) = (Vec::<InterfaceDesc>::new(), true);
    for (_, t) in root.tables(ctx, "interfaces") {
        t.check_keys(ctx, &["between", "law"]);
        let between = between(ctx, &t, names);
        let law = required_table(ctx, &t, "law").and_then(|l| law(ctx, &l));
        let (Some((regions, pos)), Some(law)) = (between, law) else {
            ok = false;
            continue;
        };
        let [a, b] = &regions;
        let same = |i: &InterfaceDesc| {
            (&i.regions[0] == a && &i.regions[1] == b) || (&i.regions[0] == b && &i.regions[1] == a)
        };
        if out.iter().any(same) {
            let msg = format!("a law between `{a}` and `{b}` is already given");
            ctx.err(pos, &t.field("between"), msg);
            ok = false;
            continue;
        }
        out.push(InterfaceDesc {
            regions,
            law,
            place: place(pos, t.field("between")),
        });
    }
    ok.then_some(out)
}

fn between(ctx: &mut Ctx, t: &Tbl, names: &[String]) -> Option<([String; 2], Pos)> {
    let field = t.field("between");
    let Some(n) = t.get("between") else {
        t.missing(ctx, "between");
        return None;
    };
    let what = "two region names [\"a\", \"b\"]";
    let Kind::Array(a) = &n.kind else {
        ctx.expected(n, &field, what);
        return None;
    };
    if a.len() != 2 {
        ctx.expected(n, &field, what);
        return None;
    }
    let mut out: [String; 2] = Default::default();
    let mut ok = true;
    for (k, e) in a.iter().enumerate() {
        let f = format!("{field}[{k}]");
        match &e.kind {
            Kind::Str(s) if names.contains(s) => out[k] = s.clone(),
            Kind::Str(s) => {
                let known = if names.is_empty() {
                    "none".to_string()
                } else {
                    names.join(", ")
                };
                let msg = format!("unknown region `{s}` (regions: {known})");
                ctx.err(e.pos, &f, msg);
                ok = false;
            }
            _ => {
                ctx.expected(e, &f, "a region name");
                ok = false;
            }
        }
    }
    ok.then_some((out, n.pos))
}

/// An interface law table.
fn law(ctx: &mut Ctx, l: &Tbl) -> Option<InterfaceLawDesc> {
    let got = l.string(ctx, "kind").req(ctx, l, "kind");
    let kinds = [("cohesive", true), ("contact", false)];
    let cohesive = choose(ctx, got, &l.field("kind"), "interface law kind", &kinds);
    if cohesive == Some(false) {
        l.check_keys(ctx, &["kind", "friction"]);
    } else {
        l.check_keys(ctx, COHESIVE_KEYS);
    }
    let friction = number_or(ctx, l, "friction", 0.0, |v| v >= 0.0, ">= 0");
    if !cohesive? {
        return Some(InterfaceLawDesc::Contact {
            friction: friction?,
        });
    }
    let normal_stiffness = stiffness(ctx, l, "normal_stiffness");
    let tangential_stiffness = stiffness(ctx, l, "tangential_stiffness");
    let fracture_energy = number(ctx, l, "fracture_energy", |v| v > 0.0, "> 0 J/m^2");
    let strength = number(ctx, l, "strength", |v| v > 0.0, "> 0 Pa");
    let beta0 = |v: f64| v > 0.0 && v <= 1.0;
    let initial_damage = number_or(ctx, l, "initial_damage", 1.0, beta0, "in (0, 1]");
    let desc = InterfaceLawDesc::Cohesive {
        normal_stiffness: normal_stiffness?,
        tangential_stiffness: tangential_stiffness?,
        fracture_energy: fracture_energy?,
        strength: strength?,
        initial_damage: initial_damage?,
        friction: friction?,
    };
    if let Some(zone) = cohesive_zone(&desc, None) {
        if let Err(e) = zone.validate() {
            let key = match e {
                CohesiveError::NoSoftening { .. } => "strength",
                _ => "kind",
            };
            let pos = l.get(key).map_or(l.pos, |n| n.pos);
            ctx.err(pos, &l.field(key), e.to_string());
            return None;
        }
    }
    Some(desc)
}

/// The cohesive zone of a law, with `rule` standing for rule-of-thumb stiffnesses
/// (`None` if a stiffness is a rule of thumb and `rule` is not given, or for contact laws).
pub(crate) fn cohesive_zone(
    law: &InterfaceLawDesc,
    rule: Option<(f64, f64)>,
) -> Option<CohesiveZone> {
    let InterfaceLawDesc::Cohesive {
        normal_stiffness,
        tangential_stiffness,
        fracture_energy,
        strength,
        initial_damage,
        friction,
    } = *law
    else {
        return None;
    };
    let value = |s: Stiffness, k: usize| match s {
        Stiffness::Value(v) => Some(v),
        Stiffness::RuleOfThumb => rule.map(|r| if k == 0 { r.0 } else { r.1 }),
    };
    Some(CohesiveZone {
        normal_stiffness: value(normal_stiffness, 0)?,
        tangential_stiffness: value(tangential_stiffness, 1)?,
        fracture_energy,
        strength,
        initial_damage,
        friction,
    })
}

/// A stiffness: a number (Pa/m) or `"rule_of_thumb"`.
fn stiffness(ctx: &mut Ctx, l: &Tbl, key: &str) -> Option<Stiffness> {
    let field = l.field(key);
    let Some(n) = l.get(key) else {
        l.missing(ctx, key);
        return None;
    };
    match &n.kind {
        Kind::Str(s) if s == "rule_of_thumb" => Some(Stiffness::RuleOfThumb),
        Kind::Int(_) | Kind::Float(_) => {
            let v = crate::read::as_num(ctx, n, &field);
            ensure(ctx, v.map(|v| (v, n.pos)), &field, |v| v > 0.0, "> 0 Pa/m")
                .map(Stiffness::Value)
        }
        _ => {
            ctx.expected(n, &field, "a number (Pa/m) or \"rule_of_thumb\"");
            None
        }
    }
}
