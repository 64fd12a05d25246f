//! Readers for `[scene]`, `[solver]`, `[output]`, `[[materials]]` and `[[laws]]`.

use crate::read::{choose, ensure, int_in, Ctx, Got, Tbl};
use crate::shared::{Groups, Materials};
use crate::tree::Kind;
use crate::types::{
    Acceleration, CheckPass, ConvergenceNorm, Detection, LawDesc, SolverSettings,
    VelocitySolverKind,
};

/// The `[scene]` table; `None` fields were invalid (errors reported).
pub(crate) struct Header {
    pub name: Option<String>,
    pub dt: Option<f64>,
    pub steps: Option<u64>,
    pub theta: Option<f64>,
    pub gravity: Option<[f64; 2]>,
    /// `dimension`: 2 (the default) or 3; `None` when invalid.
    pub dimension: Option<u8>,
    /// Gravity of a 3D scene (`[0, 0, -9.81]` unless given).
    pub gravity3: Option<[f64; 3]>,
    /// `Some(None)`: not given (default computed later).
    pub alert_distance: Option<Option<f64>>,
    pub detection: Option<Detection>,
}

const SCENE_KEYS: &[&str] = &[
    "name",
    "dimension",
    "dt",
    "duration",
    "steps",
    "theta",
    "gravity",
    "alert_distance",
    "detection",
];

/// Largest accepted number of steps (2^53, so that step counts are exact in f64).
const MAX_STEPS: f64 = 9_007_199_254_740_992.0;

pub(crate) fn header(ctx: &mut Ctx, root: &Tbl) -> Header {
    let t = match root.table(ctx, "scene") {
        Got::Val(t, _) => t,
        Got::Absent => {
            root.missing(ctx, "scene");
            return bad_header();
        }
        Got::Bad => return bad_header(),
    };
    t.check_keys(ctx, SCENE_KEYS);
    let name = t
        .string(ctx, "name")
        .req(ctx, &t, "name")
        .map(|(s, _)| s.to_string());
    let dt_got = t.num(ctx, "dt").req(ctx, &t, "dt");
    let dt = ensure(ctx, dt_got, &t.field("dt"), |v| v > 0.0, "> 0 s");
    let duration = t.num(ctx, "duration");
    let steps_got = t.int(ctx, "steps");
    let steps = match (duration, steps_got) {
        (Got::Absent, Got::Absent) => {
            ctx.err(
                t.pos,
                &t.field("duration"),
                "missing required key: give exactly one of `duration` (s) and `steps`",
            );
            None
        }
        (Got::Val(_, _), Got::Val(_, p)) => {
            ctx.err(
                p,
                &t.field("steps"),
                "give exactly one of `duration` and `steps`, not both",
            );
            None
        }
        (Got::Bad, _) | (_, Got::Bad) => None,
        (Got::Absent, s) => {
            int_in(ctx, s.ok(), &t.field("steps"), 1, MAX_STEPS as i64).map(|s| s as u64)
        }
        (d, Got::Absent) => {
            let d = ensure(ctx, d.ok(), &t.field("duration"), |v| v > 0.0, "> 0 s");
            match (d, dt) {
                (Some(d), Some(dt)) => {
                    let ratio = d / dt;
                    // Rounded up, but a ratio within 1e-9 (relative) of an integer is that integer.
                    let n = (ratio - 1e-9 * ratio).ceil().max(1.0);
                    if n.is_finite() && n <= MAX_STEPS {
                        Some(n as u64)
                    } else {
                        let pos = t.get("duration").map_or(t.pos, |n| n.pos);
                        ctx.err(
                            pos,
                            &t.field("duration"),
                            format!("duration/dt = {ratio:.3e} steps is too many (limit 2^53)"),
                        );
                        None
                    }
                }
                _ => None,
            }
        }
    };
    let theta_got = t.num(ctx, "theta");
    let theta = match theta_got {
        Got::Absent => Some(0.5),
        g => ensure(
            ctx,
            g.ok(),
            &t.field("theta"),
            |v| (0.5..=1.0).contains(&v),
            "in [0.5, 1]",
        ),
    };
    let dimension = match t.int(ctx, "dimension") {
        Got::Absent => Some(2),
        g => int_in(ctx, g.ok(), &t.field("dimension"), 2, 3).map(|d| d as u8),
    };
    let (gravity, gravity3) = match dimension {
        Some(3) => (
            Some([0.0, -9.81]),
            t.vec3(ctx, "gravity").or([0.0, 0.0, -9.81]),
        ),
        _ => (
            t.vec2(ctx, "gravity").or([0.0, -9.81]),
            Some([0.0, 0.0, -9.81]),
        ),
    };
    let alert_distance = match t.num(ctx, "alert_distance") {
        Got::Absent => Some(None),
        g => ensure(
            ctx,
            g.ok(),
            &t.field("alert_distance"),
            |v| v >= 0.0,
            ">= 0 m",
        )
        .map(Some),
    };
    let detections = [
        ("begin", Detection::Begin),
        ("predicted", Detection::Predicted),
    ];
    let detection = match t.string(ctx, "detection") {
        Got::Absent => Some(Detection::default()),
        g => choose(
            ctx,
            g.ok(),
            &t.field("detection"),
            "detection configuration",
            &detections,
        ),
    };
    Header {
        name,
        dt,
        steps,
        theta,
        gravity,
        dimension,
        gravity3,
        alert_distance,
        detection,
    }
}

fn bad_header() -> Header {
    Header {
        name: None,
        dt: None,
        steps: None,
        theta: None,
        gravity: None,
        dimension: Some(2),
        gravity3: None,
        detection: None,
        alert_distance: None,
    }
}

const SOLVER_KEYS: &[&str] = &[
    "kind",
    "tolerance",
    "max_iterations",
    "check_every",
    "relaxation",
    "norm",
    "check",
    "acceleration",
    "anderson_depth",
    "anderson_period",
    "position_projection",
];

/// The `[solver]` table (optional; every key has a documented default).
pub(crate) fn solver(ctx: &mut Ctx, root: &Tbl) -> SolverSettings {
    let mut s = SolverSettings::default();
    let Got::Val(t, _) = root.table(ctx, "solver") else {
        return s;
    };
    t.check_keys(ctx, SOLVER_KEYS);
    let kind = t.string(ctx, "kind");
    if !kind.is_absent() {
        let kinds = [
            ("nlgs", VelocitySolverKind::Nlgs),
            ("newton", VelocitySolverKind::Newton),
            ("proximal_newton", VelocitySolverKind::ProximalNewton),
        ];
        if let Some(k) = choose(ctx, kind.ok(), &t.field("kind"), "solver kind", &kinds) {
            s.kind = k;
            s.max_iterations = SolverSettings::default_max_iterations(k);
        }
    }
    let tol = t.num(ctx, "tolerance").ok();
    if let Some(v) = ensure(ctx, tol, &t.field("tolerance"), |v| v > 0.0, "> 0") {
        s.tolerance = v;
    }
    let max = i64::from(u32::MAX);
    let it = t.int(ctx, "max_iterations").ok();
    if let Some(v) = int_in(ctx, it, &t.field("max_iterations"), 1, max) {
        s.max_iterations = v as u32;
    }
    let every = t.int(ctx, "check_every").ok();
    if let Some(v) = int_in(ctx, every, &t.field("check_every"), 1, max) {
        s.check_every = v as u32;
    }
    let relax = t.num(ctx, "relaxation").ok();
    if let Some(v) = ensure(
        ctx,
        relax,
        &t.field("relaxation"),
        |v| v > 0.0 && v < 2.0,
        "in (0, 2)",
    ) {
        s.relaxation = v;
    }
    let norms = [
        ("quad", ConvergenceNorm::Quad),
        ("maxm", ConvergenceNorm::Maxm),
        ("natural_map", ConvergenceNorm::NaturalMap),
    ];
    if s.kind == VelocitySolverKind::Nlgs {
        let norm = t.string(ctx, "norm").ok();
        if let Some(n) = choose(ctx, norm, &t.field("norm"), "norm", &norms) {
            s.norm = n;
        }
        let checks = [("lmgc90", CheckPass::Lmgc90), ("strict", CheckPass::Strict)];
        let check = t.string(ctx, "check").ok();
        if let Some(c) = choose(ctx, check, &t.field("check"), "convergence check", &checks) {
            s.check = c;
        }
    } else {
        t.forbid(
            ctx,
            "check",
            "applies to kind = \"nlgs\" only (which updates LMGC90's norms measure)",
        );
        t.forbid(
            ctx,
            "norm",
            "applies to kind = \"nlgs\" only: the Newton kinds (and their position projection) \
             use the natural-map error",
        );
        s.norm = ConvergenceNorm::NaturalMap;
    }
    s.acceleration = acceleration(ctx, &t, s.kind);
    if let Some(b) = t.boolean(ctx, "position_projection").val() {
        s.position_projection = b;
    }
    s
}

/// `acceleration` with its `anderson_*` parameters (NLGS only).
fn acceleration(ctx: &mut Ctx, t: &Tbl, kind: VelocitySolverKind) -> Acceleration {
    const KEYS: [&str; 3] = ["acceleration", "anderson_depth", "anderson_period"];
    if kind != VelocitySolverKind::Nlgs {
        for key in KEYS {
            t.forbid(ctx, key, "applies to kind = \"nlgs\" only");
        }
        return Acceleration::None;
    }
    let kinds = [("none", Some(false)), ("anderson", Some(true))];
    let given = t.string(ctx, "acceleration");
    let on = if given.is_absent() {
        Some(false)
    } else {
        choose(
            ctx,
            given.ok(),
            &t.field("acceleration"),
            "acceleration",
            &kinds,
        )
        .flatten()
    };
    match on {
        // An invalid `acceleration` is reported once; its parameters are not judged.
        None => return Acceleration::None,
        Some(false) => {
            for key in &KEYS[1..] {
                t.forbid(ctx, key, "needs acceleration = \"anderson\"");
            }
            return Acceleration::None;
        }
        Some(true) => {}
    }
    let (mut depth, mut period) = (3, 3);
    let max_depth = i64::from(xper_solver::anderson::MAX_ANDERSON_DEPTH);
    let d = t.int(ctx, "anderson_depth").ok();
    if let Some(v) = int_in(ctx, d, &t.field("anderson_depth"), 1, max_depth) {
        depth = v as u32;
    }
    let p = t.int(ctx, "anderson_period").ok();
    if let Some(v) = int_in(ctx, p, &t.field("anderson_period"), 1, i64::from(u32::MAX)) {
        period = v as u32;
    }
    Acceleration::Anderson { depth, period }
}

/// What `[output]` gives: each cadence `Some(None)` when not given, `None` when invalid.
pub(crate) struct Output {
    pub frame_every: Option<Option<u64>>,
    pub checkpoint_every: Option<Option<u64>>,
    /// Sorted step numbers (empty when not given or invalid).
    pub dump_problems: Vec<u64>,
    pub micro: Option<crate::types::MicroVolume>,
}

impl Output {
    /// The settings of a scene of `steps` steps: a cadence not given is a hundredth of the run
    /// for frames and a tenth for checkpoints (at least 1).
    pub fn settings(self, steps: u64) -> crate::types::OutputSettings {
        crate::types::OutputSettings {
            frame_every: (self.frame_every.flatten()).unwrap_or(steps.div_ceil(100).max(1)),
            checkpoint_every: (self.checkpoint_every.flatten())
                .unwrap_or(steps.div_ceil(10).max(1)),
            dump_problems: self.dump_problems,
            micro: self.micro,
        }
    }
}

/// The `[output]` table; `steps` (if known) bounds the steps of `dump_problems`.
pub(crate) fn output(ctx: &mut Ctx, root: &Tbl, steps: Option<u64>) -> Output {
    let Got::Val(t, _) = root.table(ctx, "output") else {
        return Output {
            frame_every: Some(None),
            checkpoint_every: Some(None),
            dump_problems: Vec::new(),
            micro: None,
        };
    };
    t.check_keys(
        ctx,
        &["frame_every", "checkpoint_every", "dump_problems", "micro"],
    );
    let mut one = |key: &str| match t.int(ctx, key) {
        Got::Absent => Some(None),
        g => int_in(ctx, g.ok(), &t.field(key), 1, i64::MAX).map(|v| Some(v as u64)),
    };
    let frame_every = one("frame_every");
    let checkpoint_every = one("checkpoint_every");
    let volumes = [
        ("walls", crate::types::MicroVolume::Walls),
        ("grains", crate::types::MicroVolume::Grains),
        ("cell", crate::types::MicroVolume::Cell),
    ];
    let micro = match t.string(ctx, "micro") {
        Got::Absent => None,
        g => choose(
            ctx,
            g.ok(),
            &t.field("micro"),
            "volume of the measures",
            &volumes,
        ),
    };
    Output {
        frame_every,
        checkpoint_every,
        dump_problems: dump_problems(ctx, &t, steps),
        micro,
    }
}

/// `dump_problems = [step, ...]`: distinct integers in `1..=steps`, sorted.
fn dump_problems(ctx: &mut Ctx, t: &Tbl, steps: Option<u64>) -> Vec<u64> {
    let field = t.field("dump_problems");
    let Some(n) = t.get("dump_problems") else {
        return Vec::new();
    };
    let Kind::Array(items) = &n.kind else {
        ctx.expected(n, &field, "an array of step numbers [1, 100, ...]");
        return Vec::new();
    };
    let mut out: Vec<u64> = Vec::with_capacity(items.len());
    for (k, e) in items.iter().enumerate() {
        let f = format!("{field}[{k}]");
        let Kind::Int(v) = e.kind else {
            ctx.expected(e, &f, "a step number (integer >= 1)");
            continue;
        };
        let Some(v) = int_in(ctx, Some((v, e.pos)), &f, 1, i64::MAX) else {
            continue;
        };
        let v = v as u64;
        if let Some(last) = steps.filter(|&last| v > last) {
            ctx.err(
                e.pos,
                &f,
                format!("step {v} is after the last step of the run ({last})"),
            );
        } else if out.contains(&v) {
            ctx.err(e.pos, &f, format!("step {v} is listed twice"));
        } else {
            out.push(v);
        }
    }
    out.sort_unstable();
    out
}

/// The `[[materials]]` array.
pub(crate) fn materials(ctx: &mut Ctx, root: &Tbl) -> Materials {
    let mut m = Materials::default();
    for (_, t) in root.tables(ctx, "materials") {
        t.check_keys(ctx, &["name", "density"]);
        let name = t.string(ctx, "name").req(ctx, &t, "name");
        let density_got = t.num(ctx, "density").req(ctx, &t, "density");
        let density = ensure(
            ctx,
            density_got,
            &t.field("density"),
            |v| v > 0.0,
            "> 0 kg/m^3",
        );
        let Some((name, pos)) = name else { continue };
        if m.list.iter().any(|(n, _)| n == name) {
            ctx.err(
                pos,
                &t.field("name"),
                format!("duplicate material name `{name}`"),
            );
            continue;
        }
        m.list.push((name.to_string(), density));
    }
    m
}

const LAW_KEYS: &[&str] = &["between", "kind", "friction", "restitution"];

/// The `[[laws]]` array; the groups must already be known from the bodies.
pub(crate) fn laws(ctx: &mut Ctx, root: &Tbl, groups: &Groups) -> Vec<LawDesc> {
    let mut out: Vec<LawDesc> = Vec::new();
    for (_, t) in root.tables(ctx, "laws") {
        t.check_keys(ctx, LAW_KEYS);
        let kind = t.string(ctx, "kind").req(ctx, &t, "kind");
        let kind = choose(
            ctx,
            kind,
            &t.field("kind"),
            "law kind",
            &[("signorini_coulomb", ())],
        );
        let fr = t.num(ctx, "friction").req(ctx, &t, "friction");
        let friction = ensure(ctx, fr, &t.field("friction"), |v| v >= 0.0, ">= 0");
        let restitution = match t.num(ctx, "restitution") {
            Got::Absent => Some(0.0),
            g => ensure(
                ctx,
                g.ok(),
                &t.field("restitution"),
                |v| (0.0..=1.0).contains(&v),
                "in [0, 1]",
            ),
        };
        let pair = between(ctx, &t, groups);
        if let (Some(_), Some(friction), Some(restitution), Some((pair, pos))) =
            (kind, friction, restitution, pair)
        {
            let same = |l: &LawDesc| l.groups == pair || l.groups == [pair[1], pair[0]];
            if out.iter().any(same) {
                let (a, b) = (&groups.names[pair[0]], &groups.names[pair[1]]);
                ctx.err(
                    pos,
                    &t.field("between"),
                    format!("a law between `{a}` and `{b}` is already given"),
                );
                continue;
            }
            out.push(LawDesc {
                groups: pair,
                friction,
                restitution,
            });
        }
    }
    out
}

pub(crate) fn between(
    ctx: &mut Ctx,
    t: &Tbl,
    groups: &Groups,
) -> Option<([usize; 2], crate::tree::Pos)> {
    let field = t.field("between");
    let Some(n) = t.get("between") else {
        t.missing(ctx, "between");
        return None;
    };
    let Kind::Array(a) = &n.kind else {
        ctx.expected(n, &field, "two group names [\"a\", \"b\"]");
        return None;
    };
    if a.len() != 2 {
        ctx.expected(n, &field, "two group names [\"a\", \"b\"]");
        return None;
    }
    let mut idx = [0usize; 2];
    let mut ok = true;
    for (k, e) in a.iter().enumerate() {
        let f = format!("{field}[{k}]");
        match &e.kind {
            Kind::Str(s) => match groups.find(s) {
                Some(i) => idx[k] = i,
                None => {
                    let known = if groups.names.is_empty() {
                        "none".to_string()
                    } else {
                        groups.names.join(", ")
                    };
                    ctx.err(
                        e.pos,
                        &f,
                        format!("group `{s}` is used by no body (groups: {known})"),
                    );
                    ok = false;
                }
            },
            _ => {
                ctx.expected(e, &f, "a group name");
                ok = false;
            }
        }
    }
    ok.then_some((idx, n.pos))
}
