//! Non-linear Gauss-Seidel (NLGS) over contacts, in a 2D or 3D contact frame.
//!
//! Each sweep visits the contacts in order; for contact `a` it forms the velocity without its
//! own impulse, `u_free = U_a - W_aa R_a`, solves the one-contact problem
//! ([`ContactFrame::solve`]: exactly in 2D, [`crate::solve_one_contact`]; by Alart-Curnier's
//! Newton in 3D) and applies the relaxed increment, so that later contacts of the sweep see it
//! (M. Jean, CMAME 177, 1999; LMGC90's `nlgs`). Convergence is checked every `check_every`
//! sweeps by LMGC90's norms or by the natural-map error.

use crate::anderson::{Acceleration, AndersonMixer};
use crate::cohesive::CohesiveTerm;
use crate::error::{natural_map_error_of, NormAccumulator};
pub use crate::outcome::{SolveError, SolveInfo};

use crate::frame::{is_zero, ContactFrame, Frame2};
use crate::operator::{ContactOperator, VectorOf};

/// Which measure decides convergence.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum ConvergenceNorm {
    /// LMGC90 "Quad": `|MeanDVoR|`, `QuadDV` and `QuadDVR` below 1.
    #[default]
    Quad,
    /// LMGC90 "Maxm": `|MeanDVoR|`, `MaxmDV` and `MaxmDVR` below 1.
    Maxm,
    /// Natural-map error divided by `max(|q|, |U|, |R|)` below the tolerance.
    NaturalMap,
}

/// Which updates a convergence check measures (LMGC90's norms; the natural-map error is
/// computed on the state after the sweep either way).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum CheckPass {
    /// LMGC90's check (`solve_nlgs(2)` of its `nlgs` module, between `prep_check_nlgs` and
    /// `comp_check_nlgs`): after the sweep, a pass that solves every contact's local problem
    /// on the state the sweep left and measures the change without applying it, so that every
    /// contact is measured against the same state. Not counted as a sweep (as in LMGC90); it
    /// costs about one sweep without the velocity updates.
    #[default]
    Lmgc90,
    /// Stricter: the norms of the check sweep's own updates, each contact measured after the
    /// updates of the contacts before it in the same sweep. On the slow modes of a packing its
    /// norms are larger than LMGC90's: box10k needs a median 210 sweeps per step instead of
    /// 150, and 392 steps end at the 1000-sweep cap instead of 96 (bench-results/NOTES.md).
    Strict,
}

/// Tuning of [`nlgs`](crate::nlgs()).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct NlgsParams {
    /// Tolerance of the chosen norm (LMGC90's default 1.666e-4).
    pub tolerance: f64,
    /// Maximum number of sweeps.
    pub max_iterations: u32,
    /// Sweeps between convergence checks.
    pub check_every: u32,
    /// Relaxation `omega` in (0, 2): `R <- omega R_local + (1 - omega) R`, projected on the
    /// Coulomb cone when `omega > 1` (over-relaxation); not applied to adhesive contacts.
    pub relaxation: f64,
    /// Convergence measure.
    pub norm: ConvergenceNorm,
    /// Acceleration of the sweeps (Anderson mixing, see [`crate::anderson`]); the convergence
    /// check stays on plain sweeps.
    pub acceleration: Acceleration,
    /// Which updates LMGC90's norms measure.
    #[serde(default)]
    pub check: CheckPass,
}

impl Default for NlgsParams {
    fn default() -> Self {
        NlgsParams {
            tolerance: 1.666e-4,
            max_iterations: 1000,
            check_every: 10,
            relaxation: 1.0,
            norm: ConvergenceNorm::Quad,
            acceleration: Acceleration::None,
            check: CheckPass::Lmgc90,
        }
    }
}

/// What NLGS prepares once per solve (checked data, proximal weights of singular blocks,
/// factorised cohesive contacts) and one Gauss-Seidel sweep over the contacts. [`nlgs`](crate::nlgs()) loops
/// the sweep with its convergence checks; a domain-decomposition solver interleaves sweeps
/// with exchanges between processes; both loop it with [`crate::sweep_until_converged`].
pub struct NlgsSweeper<'a, F: ContactFrame = Frame2> {
    mu: &'a [f64],
    normal_shift: &'a [f64],
    omega: f64,
    /// Proximal weight per contact; empty when no block is singular.
    proximal: Vec<f64>,
    /// Whether each contact is adhesive; empty when none is.
    is_adhesive: Vec<bool>,
    /// Factorised adhesive contacts; empty when none is adhesive.
    prepared: Vec<F::Cohesive>,
    /// What the local solve precomputes for each contact (of `W_aa + eps I` where
    /// proximal): in 2D the reciprocal of its determinant.
    factors: Vec<F::Factors>,
    q_norm: f64,
}

impl<'a, F: ContactFrame> NlgsSweeper<'a, F> {
    /// Checks the data, projects the warm start `impulses` on the cones (where not adhesive) and
    /// applies it to `op`, which must be in the state of zero impulses.
    pub fn new<O: ContactOperator<Frame = F>>(
        op: &mut O,
        mu: &'a [f64],
        normal_shift: &'a [f64],
        cohesion: &[CohesiveTerm],
        impulses: &mut [F::Vector],
        params: &NlgsParams,
    ) -> Result<Self, SolveError> {
        let n = op.contact_count();
        check_contact_sizes(n, mu, normal_shift, cohesion, impulses)?;
        if params.tolerance.is_nan()
            || params.tolerance <= 0.0
            || params.max_iterations == 0
            || params.check_every == 0
        {
            return Err(SolveError::InvalidParams(format!("{params:?}")));
        }
        if !params.acceleration.is_valid() {
            return Err(SolveError::InvalidParams(format!(
                "acceleration {:?}: depth in 1..={} and period >= 1",
                params.acceleration,
                crate::anderson::MAX_ANDERSON_DEPTH
            )));
        }
        if params.relaxation.is_nan() || params.relaxation <= 0.0 || params.relaxation >= 2.0 {
            return Err(SolveError::InvalidParams(format!(
                "relaxation {} not in (0, 2)",
                params.relaxation
            )));
        }
        let mut q_norm2 = 0.0;
        for a in 0..n {
            let w = op.diagonal_block(a);
            let u = op.local_velocity(a);
            if !(mu[a] >= 0.0 && mu[a].is_finite()) {
                return Err(SolveError::InvalidData {
                    contact: a,
                    what: format!("friction coefficient {}", mu[a]),
                });
            }
            if !w
                .as_ref()
                .iter()
                .chain(u.as_ref())
                .chain(impulses[a].as_ref())
                .all(|x| x.is_finite())
                || !normal_shift[a].is_finite()
            {
                return Err(SolveError::InvalidData {
                    contact: a,
                    what: "non-finite W, q, shift or warm start".into(),
                });
            }
            let w_nn = w.as_ref()[0];
            if w_nn <= 0.0 {
                return Err(SolveError::InvalidData {
                    contact: a,
                    what: format!("W_nn = {w_nn} is not positive"),
                });
            }
            let mut q2 = (u[0] + normal_shift[a]).powi(2);
            for &uk in &u.as_ref()[1..] {
                q2 += uk * uk;
            }
            q_norm2 += q2;
        }
        let is_adhesive: Vec<bool> = if cohesion.is_empty() {
            Vec::new()
        } else {
            cohesion.iter().map(|c| !c.is_zero()).collect()
        };
        let adhesive = |a: usize| !is_adhesive.is_empty() && is_adhesive[a];
        for (a, r) in impulses.iter_mut().enumerate() {
            if !adhesive(a) {
                *r = F::project_on_cone(*r, mu[a]);
            }
            if !is_zero(r) {
                op.apply_impulse(a, *r);
            }
        }
        let mut proximal: Vec<f64> = (0..n)
            .map(|a| F::proximal_weight(&op.diagonal_block(a)))
            .collect();
        if proximal.iter().all(|&eps| eps == 0.0) {
            proximal = Vec::new();
        }
        // The block each local solve uses: W_aa, plus eps I where proximal.
        let local_block = |a: usize| {
            let w = op.diagonal_block(a);
            let eps = proximal.get(a).copied().unwrap_or(0.0);
            F::add_to_diagonal(&w, eps)
        };
        let prepared: Vec<F::Cohesive> = if is_adhesive.is_empty() {
            Vec::new()
        } else {
            (0..n)
                .map(|a| {
                    if !adhesive(a) {
                        return Ok(F::Cohesive::default());
                    }
                    F::prepare_cohesive(&local_block(a), &cohesion[a])
                        .map_err(|what| SolveError::InvalidData { contact: a, what })
                })
                .collect::<Result<_, _>>()?
        };
        let factors: Vec<F::Factors> = (0..n).map(|a| F::factors(&local_block(a))).collect();
        Ok(NlgsSweeper {
            mu,
            normal_shift,
            omega: params.relaxation,
            proximal,
            is_adhesive,
            prepared,
            factors,
            q_norm: q_norm2.sqrt(),
        })
    }

    /// Friction coefficient of each contact.
    pub fn mu(&self) -> &[f64] {
        self.mu
    }

    /// Shift of each contact's normal velocity in the Signorini condition.
    pub fn normal_shift(&self) -> &[f64] {
        self.normal_shift
    }

    /// `|q + shift|` at zero impulses, the scale of the natural-map error.
    pub fn q_norm(&self) -> f64 {
        self.q_norm
    }

    /// Anderson mixing of the impulses after a sweep: each mixed impulse is projected on its
    /// cone and its change applied to `op`. An adhesive contact's mixed impulse is kept as
    /// mixed (its admissible set is not a cone); the next sweep's cohesive local solve
    /// constrains it.
    /// `reduce` sums the mixer's partial sums over the processes of a distributed solve (see
    /// [`AndersonMixer::mix_reduced`]); a solve on one process passes a no-op.
    pub fn accelerate<O: ContactOperator<Frame = F>>(
        &self,
        op: &mut O,
        impulses: &mut [F::Vector],
        mixer: &mut AndersonMixer<F>,
        reduce: impl FnOnce(&mut [f64]),
    ) {
        mixer.mix_reduced(impulses, reduce, |a, old, mixed| {
            let adhesive = !self.is_adhesive.is_empty() && self.is_adhesive[a];
            let r = if adhesive {
                mixed
            } else {
                F::project_on_cone(mixed, self.mu[a])
            };
            let d = F::sub(r, old);
            if !is_zero(&d) {
                op.apply_impulse(a, d);
            }
            r
        });
    }

    /// One sweep over the contacts in order.
    pub fn sweep<O: ContactOperator<Frame = F>>(&self, op: &mut O, impulses: &mut [F::Vector]) {
        self.sweep_accumulating(op, impulses, None);
    }

    /// One sweep, adding each contact's update to `acc` when given.
    pub fn sweep_accumulating<O: ContactOperator<Frame = F>>(
        &self,
        op: &mut O,
        impulses: &mut [F::Vector],
        acc: Option<&mut NormAccumulator>,
    ) {
        match acc {
            None => self.sweep_into::<O, (), false>(op, impulses, 0..0, &mut ()),
            Some(acc) => self.sweep_into::<O, _, false>(op, impulses, 0..0, acc),
        }
    }

    /// The part `contacts` of a sweep (in order), adding each contact's update to `acc` when
    /// given: a domain decomposition sweeps the contacts of its interface bodies first, then
    /// the others while their velocities travel.
    pub fn sweep_part_accumulating<O: ContactOperator<Frame = F>>(
        &self,
        op: &mut O,
        impulses: &mut [F::Vector],
        contacts: std::ops::Range<usize>,
        acc: Option<&mut NormAccumulator>,
    ) {
        match acc {
            None => self.sweep_into::<O, (), true>(op, impulses, contacts, &mut ()),
            Some(acc) => self.sweep_into::<O, _, true>(op, impulses, contacts, acc),
        }
    }

    /// [`Self::sweep_with`] compiled for the terms present in this problem, so that the usual
    /// sweep (no relaxation, no proximal or adhesive term) has no per-contact branch on them.
    /// With `PART`, the contacts `contacts` only; else all of them (`contacts` unused), with
    /// the indices known to start at 0: computed from a range's start, they cost the plain
    /// sweep 15 % on box10k's settled steps.
    #[inline(always)]
    fn sweep_into<O: ContactOperator<Frame = F>, A: AccumulateUpdate<F>, const PART: bool>(
        &self,
        op: &mut O,
        impulses: &mut [F::Vector],
        contacts: std::ops::Range<usize>,
        acc: &mut A,
    ) {
        let relaxed = !(self.proximal.is_empty() && self.omega == 1.0);
        let c = if PART { contacts } else { 0..impulses.len() };
        match (relaxed, !self.is_adhesive.is_empty()) {
            (false, false) => self.sweep_with::<O, A, false, false, PART>(op, impulses, c, acc),
            (false, true) => self.sweep_with::<O, A, false, true, PART>(op, impulses, c, acc),
            (true, false) => self.sweep_with::<O, A, true, false, PART>(op, impulses, c, acc),
            (true, true) => self.sweep_with::<O, A, true, true, PART>(op, impulses, c, acc),
        }
    }

    /// The contacts `contacts` of a sweep in order: `RELAXED` when some contact has a
    /// proximal weight or the relaxation is not 1, `ADHESIVE` when some contact has an
    /// adhesive term, `PART` when `contacts` may not be all of them.
    #[inline(always)]
    fn sweep_with<
        O: ContactOperator<Frame = F>,
        A: AccumulateUpdate<F>,
        const RELAXED: bool,
        const ADHESIVE: bool,
        const PART: bool,
    >(
        &self,
        op: &mut O,
        impulses: &mut [F::Vector],
        contacts: std::ops::Range<usize>,
        acc: &mut A,
    ) {
        // Slices of the part's length and the operator's count checked once, so that the
        // usual sweep indexes its contact data without a bounds check per contact (the
        // proximal and adhesive data of the other variants keep theirs).
        assert_eq!(
            op.contact_count(),
            impulses.len(),
            "a sweeper is used with its own operator"
        );
        let first = if PART { contacts.start } else { 0 };
        let (mu, shift, factors) = (
            &self.mu[contacts.clone()],
            &self.normal_shift[contacts.clone()],
            &self.factors[contacts.clone()],
        );
        let impulses = &mut impulses[contacts];
        let n = impulses.len();
        let (mu, shift, factors) = (&mu[..n], &shift[..n], &factors[..n]);
        let omega = self.omega;
        for (k, impulse) in impulses.iter_mut().enumerate() {
            let a = first + k;
            let r = *impulse;
            let mut r_new = r;
            let (w, delta) = op.update_contact(a, |w, u| {
                let local = self.local_solution::<RELAXED, ADHESIVE>(
                    a,
                    w,
                    u,
                    r,
                    (mu[k], shift[k], &factors[k]),
                );
                let adhesive = ADHESIVE && self.is_adhesive[a];
                r_new = if !RELAXED || omega == 1.0 || adhesive {
                    local
                } else {
                    let mut relaxed = local;
                    for (x, &r) in relaxed.as_mut().iter_mut().zip(r.as_ref()) {
                        *x = omega * *x + (1.0 - omega) * r;
                    }
                    F::project_on_cone(relaxed, mu[k])
                };
                F::sub(r_new, r)
            });
            *impulse = r_new;
            acc.add(&w, r, r_new, delta);
        }
    }
}

impl<F: ContactFrame> NlgsSweeper<'_, F> {
    /// The solution of contact `a`'s local problem (before relaxation) for its block `w`, its
    /// local velocity `u` with every current impulse applied and its impulse `r`; `(mu, shift,
    /// factors)` are its own.
    #[inline(always)]
    fn local_solution<const RELAXED: bool, const ADHESIVE: bool>(
        &self,
        a: usize,
        w: &F::Block,
        u: F::Vector,
        r: F::Vector,
        (mu, shift, factors): (f64, f64, &F::Factors),
    ) -> F::Vector {
        let wr = F::block_mul(w, r);
        let mut shifted = u;
        shifted[0] += shift;
        let mut u_free = F::sub(shifted, wr);
        let eps = if RELAXED && !self.proximal.is_empty() {
            self.proximal[a]
        } else {
            0.0
        };
        if eps > 0.0 {
            // A singular block: proximal step, exact at convergence (see proximal_weight).
            for (x, &r) in u_free.as_mut().iter_mut().zip(r.as_ref()) {
                *x -= eps * r;
            }
        }
        if ADHESIVE && self.is_adhesive[a] {
            F::solve_cohesive(&self.prepared[a], u_free, mu)
        } else if eps > 0.0 {
            F::solve(&F::add_to_diagonal(w, eps), factors, u_free, mu, r)
        } else {
            F::solve(w, factors, u_free, mu, r)
        }
    }

    /// LMGC90's check pass ([`CheckPass::Lmgc90`]) over the contacts `contacts`: each
    /// contact's local problem is solved on the current state and its change (without
    /// relaxation) added to `acc`; nothing is applied, so `op` and `impulses` are unchanged.
    pub fn check_pass<O: ContactOperator<Frame = F>>(
        &self,
        op: &O,
        impulses: &[F::Vector],
        contacts: std::ops::Range<usize>,
        acc: &mut NormAccumulator,
    ) {
        match (!self.proximal.is_empty(), !self.is_adhesive.is_empty()) {
            (false, false) => self.check_pass_with::<O, false, false>(op, impulses, contacts, acc),
            (false, true) => self.check_pass_with::<O, false, true>(op, impulses, contacts, acc),
            (true, false) => self.check_pass_with::<O, true, false>(op, impulses, contacts, acc),
            (true, true) => self.check_pass_with::<O, true, true>(op, impulses, contacts, acc),
        }
    }

    /// [`Self::check_pass`] compiled for the terms present (as [`Self::sweep_with`]).
    fn check_pass_with<
        O: ContactOperator<Frame = F>,
        const PROXIMAL: bool,
        const ADHESIVE: bool,
    >(
        &self,
        op: &O,
        impulses: &[F::Vector],
        contacts: std::ops::Range<usize>,
        acc: &mut NormAccumulator,
    ) {
        for a in contacts {
            let (w, u, r) = (op.diagonal_block(a), op.local_velocity(a), impulses[a]);
            let data = (self.mu[a], self.normal_shift[a], &self.factors[a]);
            let local = self.local_solution::<PROXIMAL, ADHESIVE>(a, &w, u, r, data);
            AccumulateUpdate::<F>::add(acc, &w, r, local, F::sub(local, r));
        }
    }
}

/// Checks that `n` contacts have one friction coefficient, shift and impulse each, and one
/// cohesive term each or none.
pub fn check_contact_sizes<V>(
    n: usize,
    mu: &[f64],
    normal_shift: &[f64],
    cohesion: &[CohesiveTerm],
    impulses: &[V],
) -> Result<(), SolveError> {
    if mu.len() != n
        || normal_shift.len() != n
        || impulses.len() != n
        || !(cohesion.is_empty() || cohesion.len() == n)
    {
        return Err(SolveError::SizeMismatch {
            what: format!(
                "{n} contacts, {} mu, {} shifts, {} cohesive terms, {} impulses",
                mu.len(),
                normal_shift.len(),
                cohesion.len(),
                impulses.len()
            ),
        });
    }
    Ok(())
}

/// Where a sweep puts each contact's update: nowhere (`()`), or LMGC90's sums on a check
/// sweep. A type parameter so that the plain sweep compiles without the accumulation.
trait AccumulateUpdate<F: ContactFrame> {
    fn add(&mut self, w: &F::Block, r: F::Vector, r_new: F::Vector, delta: F::Vector);
}

impl<F: ContactFrame> AccumulateUpdate<F> for () {
    #[inline(always)]
    fn add(&mut self, _: &F::Block, _: F::Vector, _: F::Vector, _: F::Vector) {}
}

impl<F: ContactFrame> AccumulateUpdate<F> for NormAccumulator {
    /// The velocity change of the contact is `-W delta`.
    #[inline(always)]
    fn add(&mut self, w: &F::Block, r: F::Vector, r_new: F::Vector, delta: F::Vector) {
        let mut du = F::block_mul(w, delta);
        for x in du.as_mut() {
            *x = -*x;
        }
        NormAccumulator::add_in::<F>(self, w, r, r_new, du);
    }
}

/// Natural-map error of the current state, divided by `max(|q|, |U|, |R|)`
/// (Siconos' scaling), or by 1 when all are zero.
pub(crate) fn scaled_natural_map_error<O: ContactOperator>(
    op: &O,
    mu: &[f64],
    normal_shift: &[f64],
    impulses: &[VectorOf<O>],
    q_norm: f64,
) -> f64 {
    let u: Vec<VectorOf<O>> = (0..op.contact_count())
        .map(|a| {
            let mut u = op.local_velocity(a);
            u[0] += normal_shift[a];
            u
        })
        .collect();
    let norm = |v: &[VectorOf<O>]| {
        v.iter()
            .map(|x| <O::Frame as ContactFrame>::dot(x, x))
            .sum::<f64>()
            .sqrt()
    };
    let scale = q_norm.max(norm(&u)).max(norm(impulses));
    natural_map_error_of::<O::Frame>(&u, impulses, mu) / if scale > 0.0 { scale } else { 1.0 }
}
