//! Generalized (semi-smooth) Newton method on Alart-Curnier's function of the whole problem.
//!
//! ```text
//! Phi(r) = 0,  Phi_a(r) = AC(r_a, u_a),  u = W r + q      (see crate::alart_curnier)
//! J_k d_k = -Phi(r_k),  J_k = A + B W  (A, B block diagonal: an element of Clarke's
//!                                        generalized Jacobian, Alart & Curnier 1991)
//! r_k+1 = r_k + t_k d_k,  t_k by Armijo backtracking on f = |Phi|^2 / 2
//!         (the Newton direction has slope -|Phi|^2)
//! ```
//!
//! (Alart, Curnier, CMAME 92, 1991; Christensen, Klarbring, Pang, Strömberg, IJNME 42, 1998;
//! Acary, Bremond, Huber 2018, "nonsmooth Newton" solvers.) Per-contact `rho`: by default
//! `rho_N = 1 / W_NN` and `rho_T = 2 / (W_T1T1 + W_T2T2)` (`1 / W_TT` in 2D), which makes the
//! diagonal of `B W` unit-scaled ([`RhoStrategy`] lists the alternatives). `J` is assembled in
//! CSR with one pattern for the whole solve (block rows of `W` plus the diagonal blocks), the
//! symbolic LU of faer is computed once, and each iteration does a numeric sparse LU with
//! partial pivoting. The CSR arrays of `J` are the CSC arrays of `J^T`, so faer factorizes
//! `J^T` and solves with its transpose. A singular `J` (rank-deficient `W` in stick) is
//! retried with a small diagonal shift; the iterate with the smallest shared error is
//! returned. For rank-deficient `W` use [`crate::proximal_newton`].

use crate::alart_curnier::{ac_function, AcEval};
use crate::nlgs::SolveError;
use crate::problem::error_measure;
use crate::problem::FrictionProblem;
use crate::solve::{prepare, ErrorScaling, SolveReport, SolverKind, SolverParams};
use faer::prelude::Solve;
use faer::sparse::linalg::solvers::{Lu, SymbolicLu};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::MatMut;

/// How the Alart-Curnier parameters `rho_N`, `rho_T` of each contact are chosen from the
/// diagonal block `W_aa` (plus the proximal shift when there is one).
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum RhoStrategy {
    /// `rho_N = 1 / W_NN`, `rho_T = (d - 1) / trace(W_TT)`.
    #[default]
    Diagonal,
    /// `rho_N = rho_T = 1 / lambda_max(sym(W_aa))` (power iteration).
    SpectralNorm,
    /// The same value for every contact.
    Constant(f64),
}

/// Tuning of the generalized Newton method.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct NewtonParams {
    /// Choice of `rho`.
    pub rho: RhoStrategy,
    /// Armijo constant `c` in `f(r + t d) <= (1 - 2 c t) f(r)`.
    pub armijo: f64,
    /// Step halvings before the line search gives up.
    pub line_search_steps: u32,
    /// When the line search gives up, take the full Newton step anyway (non-monotone: lets
    /// the iteration leave a local minimum of `|Phi|`; the best iterate is kept) rather than
    /// the last, shortest one.
    pub nonmonotone: bool,
    /// Relative diagonal shift tried when the Jacobian is singular (multiplied by 1e3 at each
    /// of three retries).
    pub singular_shift: f64,
}

impl Default for NewtonParams {
    fn default() -> Self {
        NewtonParams {
            rho: RhoStrategy::Diagonal,
            armijo: 1e-4,
            line_search_steps: 20,
            nonmonotone: true,
            singular_shift: 1e-12,
        }
    }
}

/// The outcome of one Newton run inside [`NewtonCore::run`].
#[derive(Clone, Debug)]
pub(crate) struct RunOutcome {
    /// Newton iterations done.
    pub iterations: u32,
    /// The error (original problem, chosen scaling) of the last iterate, written in `r`.
    pub error: f64,
    /// The smallest error met, of the iterate [`NewtonCore::best`].
    pub best_error: f64,
    /// Whether the regularized problem's own error went below `inner_tol`.
    pub inner_converged: bool,
}

/// The Jacobian pattern, the symbolic LU and the buffers of a Newton solve.
pub(crate) struct NewtonCore<'p> {
    problem: &'p FrictionProblem,
    blocks: &'p [[f64; 9]],
    params: NewtonParams,
    jac_ptr: Vec<usize>,
    jac_col: Vec<usize>,
    jac_val: Vec<f64>,
    /// Offset within its block row pattern of each stored value of `W`.
    w_pos: Vec<usize>,
    /// Offset within the block row pattern of each diagonal-block column `d a + l`.
    diag_pos: Vec<usize>,
    symbolic: SymbolicLu<usize>,
    rho: Vec<[f64; 2]>,
    ac: Vec<AcEval>,
    phi: Vec<f64>,
    u: Vec<f64>,
    u_true: Vec<f64>,
    dir: Vec<f64>,
    w_dir: Vec<f64>,
    r_try: Vec<f64>,
    u_try: Vec<f64>,
    phi_try: Vec<f64>,
    best_r: Vec<f64>,
}

impl<'p> NewtonCore<'p> {
    /// Builds the pattern of `J` and its symbolic LU.
    #[allow(clippy::needless_range_loop)] // rows d a + k index several arrays
    pub(crate) fn new(
        problem: &'p FrictionProblem,
        blocks: &'p [[f64; 9]],
        params: &NewtonParams,
    ) -> Result<Self, SolveError> {
        let (d, m) = (problem.dim, problem.q.len());
        let w = &problem.w;
        let mut jac_ptr = vec![0usize; m + 1];
        let mut jac_col = Vec::with_capacity(w.nnz() + d * m);
        let mut w_pos = vec![0usize; w.nnz()];
        let mut diag_pos = vec![0usize; m];
        let mut pattern: Vec<usize> = Vec::new();
        for a in 0..problem.mu.len() {
            pattern.clear();
            pattern.extend(d * a..d * (a + 1));
            for i in d * a..d * (a + 1) {
                pattern.extend_from_slice(&w.col_idx[w.row_ptr[i]..w.row_ptr[i + 1]]);
            }
            pattern.sort_unstable();
            pattern.dedup();
            let pos = |j: usize| pattern.binary_search(&j).unwrap_or(0);
            for i in d * a..d * (a + 1) {
                let (lo, hi) = (w.row_ptr[i], w.row_ptr[i + 1]);
                for (wp, &j) in w_pos[lo..hi].iter_mut().zip(&w.col_idx[lo..hi]) {
                    *wp = pos(j);
                }
                diag_pos[i] = pos(i);
            }
            for i in d * a..d * (a + 1) {
                jac_col.extend_from_slice(&pattern);
                jac_ptr[i + 1] = jac_col.len();
            }
        }
        let sym = SymbolicSparseColMatRef::new_checked(m, m, &jac_ptr, None, &jac_col);
        let symbolic = SymbolicLu::try_new(sym)
            .map_err(|e| SolveError::Breakdown(format!("symbolic LU of the Jacobian: {e:?}")))?;
        let nnz = jac_col.len();
        Ok(NewtonCore {
            problem,
            blocks,
            params: *params,
            jac_ptr,
            jac_col,
            jac_val: vec![0.0; nnz],
            w_pos,
            diag_pos,
            symbolic,
            rho: Vec::new(),
            ac: vec![AcEval::default(); problem.mu.len()],
            phi: vec![0.0; m],
            u: vec![0.0; m],
            u_true: vec![0.0; m],
            dir: vec![0.0; m],
            w_dir: vec![0.0; m],
            r_try: vec![0.0; m],
            u_try: vec![0.0; m],
            phi_try: vec![0.0; m],
            best_r: vec![0.0; m],
        })
    }

    /// `rho` of every contact for the operator `W + sigma I`.
    fn set_rho(&mut self, sigma: f64) {
        let d = self.problem.dim;
        self.rho = self
            .blocks
            .iter()
            .map(|b| {
                let mut b = *b;
                for k in 0..d {
                    b[k * d + k] += sigma;
                }
                match self.params.rho {
                    RhoStrategy::Diagonal => {
                        let tr: f64 = (1..d).map(|k| b[k * d + k]).sum();
                        let rn = 1.0 / b[0];
                        [rn, if tr > 0.0 { (d - 1) as f64 / tr } else { rn }]
                    }
                    RhoStrategy::SpectralNorm => {
                        let l = spectral_norm(&b, d);
                        let rn = if l > 0.0 { 1.0 / l } else { 1.0 / b[0] };
                        [rn, rn]
                    }
                    RhoStrategy::Constant(c) => [c, c],
                }
            })
            .collect();
    }

    /// `phi = Phi(r, u)`, filling `ac` when `store`; returns `|Phi|^2`.
    /// (`r_try` equals the current iterate whenever `trial` is false.)
    fn eval(&mut self, store: bool, trial: bool) -> f64 {
        let d = self.problem.dim;
        let (r, u, phi) = if trial {
            (&self.r_try, &self.u_try, &mut self.phi_try)
        } else {
            (&self.r_try, &self.u, &mut self.phi)
        };
        let mut sum = 0.0;
        for a in 0..self.problem.mu.len() {
            let s = d * a..d * (a + 1);
            let [rn, rt] = self.rho[a];
            let e = ac_function(d, &r[s.clone()], &u[s.clone()], self.problem.mu[a], rn, rt);
            phi[s.clone()].copy_from_slice(&e.phi[..d]);
            sum += e.phi[..d].iter().map(|x| x * x).sum::<f64>();
            if store {
                self.ac[a] = e;
            }
        }
        sum
    }

    /// Fills the values of `J = A + B (W + sigma I) + shift I`.
    fn assemble(&mut self, sigma: f64, shift: f64) {
        let (d, w) = (self.problem.dim, &self.problem.w);
        self.jac_val.fill(0.0);
        for (a, e) in self.ac.iter().enumerate() {
            for k in 0..d {
                let i = d * a + k;
                let row = &mut self.jac_val[self.jac_ptr[i]..self.jac_ptr[i + 1]];
                for l in 0..d {
                    let c = e.b[k * d + l];
                    if c != 0.0 {
                        let wi = d * a + l;
                        for p in w.row_ptr[wi]..w.row_ptr[wi + 1] {
                            row[self.w_pos[p]] += c * w.values[p];
                        }
                    }
                    let diag = e.a[k * d + l] + sigma * e.b[k * d + l];
                    row[self.diag_pos[d * a + l]] += diag + if k == l { shift } else { 0.0 };
                }
            }
        }
    }

    /// Solves `J dir = -phi` by sparse LU; `false` when singular or non-finite.
    fn solve_direction(&mut self) -> bool {
        let m = self.phi.len();
        let sym = SymbolicSparseColMatRef::new_checked(m, m, &self.jac_ptr, None, &self.jac_col);
        let jt = SparseColMatRef::new(sym, &self.jac_val);
        let Ok(lu) = Lu::try_new_with_symbolic(self.symbolic.clone(), jt) else {
            return false;
        };
        for (x, p) in self.dir.iter_mut().zip(&self.phi) {
            *x = -p;
        }
        lu.solve_transpose_in_place(MatMut::from_column_major_slice_mut(&mut self.dir, m, 1));
        self.dir.iter().all(|x| x.is_finite())
    }

    /// Newton on `u = (W + sigma I) r + q_eff` from `r`, at most `max_iter` iterations.
    ///
    /// Stops when the original problem's error (`u = W r + q`) is below `tol`, or when the
    /// regularized problem's own error is below `inner_tol` (only when `sigma > 0`). `r` holds
    /// the last iterate on return, [`NewtonCore::best`] the one of smallest original error.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn run(
        &mut self,
        q_eff: &[f64],
        sigma: f64,
        r: &mut [f64],
        max_iter: u32,
        tol: f64,
        inner_tol: f64,
        scaling: ErrorScaling,
    ) -> RunOutcome {
        let p = self.problem;
        self.set_rho(sigma);
        self.r_try.copy_from_slice(r);
        self.u.copy_from_slice(q_eff);
        p.w.mul_add(r, &mut self.u);
        for (ui, ri) in self.u.iter_mut().zip(r.iter()) {
            *ui += sigma * ri;
        }
        let mut f = self.eval(true, false);
        let mut out = RunOutcome {
            iterations: 0,
            error: f64::INFINITY,
            best_error: f64::INFINITY,
            inner_converged: false,
        };
        let mut current = r.to_vec();
        for it in 0..=max_iter {
            // Errors of the current iterate: original problem and regularized one.
            for i in 0..current.len() {
                self.u_true[i] = self.u[i] - sigma * current[i] + p.q[i] - q_eff[i];
            }
            let e_true = scaling.pick(&error_measure(p.dim, &p.q, &self.u_true, &current, &p.mu));
            out.error = e_true;
            if e_true < out.best_error {
                out.best_error = e_true;
                self.best_r.copy_from_slice(&current);
            }
            out.iterations = it;
            if !e_true.is_finite() || e_true < tol {
                break;
            }
            if sigma > 0.0 {
                let e_in = scaling.pick(&error_measure(p.dim, q_eff, &self.u, &current, &p.mu));
                if e_in < inner_tol {
                    out.inner_converged = true;
                    break;
                }
            }
            if it == max_iter {
                break;
            }
            let mut ok = false;
            let mut shift = 0.0;
            let diag_scale = self.jac_scale();
            for attempt in 0..4 {
                self.assemble(sigma, shift);
                if self.solve_direction() {
                    ok = true;
                    break;
                }
                shift = self.params.singular_shift * diag_scale * 1e3f64.powi(attempt);
            }
            if !ok {
                break;
            }
            // W_sigma dir, then the line search along dir.
            self.w_dir.fill(0.0);
            p.w.mul_add(&self.dir, &mut self.w_dir);
            let mut t = 1.0;
            let mut accepted = false;
            for _ in 0..=self.params.line_search_steps {
                self.try_step(&current, t, sigma);
                let ft = self.eval(false, true);
                if ft <= (1.0 - 2.0 * self.params.armijo * t) * f {
                    accepted = true;
                    break;
                }
                t *= 0.5;
            }
            if !accepted && self.params.nonmonotone {
                self.try_step(&current, 1.0, sigma);
            }
            current.copy_from_slice(&self.r_try);
            self.u.copy_from_slice(&self.u_try);
            f = self.eval(true, false);
        }
        r.copy_from_slice(&current);
        out
    }

    /// The iterate of smallest original error of the last [`NewtonCore::run`].
    pub(crate) fn best(&self) -> &[f64] {
        &self.best_r
    }

    /// `r_try = current + t dir`, `u_try = u + t (W + sigma I) dir`.
    fn try_step(&mut self, current: &[f64], t: f64, sigma: f64) {
        for (i, &c) in current.iter().enumerate() {
            self.r_try[i] = c + t * self.dir[i];
            self.u_try[i] = self.u[i] + t * (self.w_dir[i] + sigma * self.dir[i]);
        }
    }

    /// Largest diagonal magnitude of the last assembled Jacobian (1 before the first).
    fn jac_scale(&self) -> f64 {
        let d = self.problem.dim;
        let mut s = 0.0f64;
        for i in 0..self.phi.len() {
            let a = i / d;
            let v = self.jac_val[self.jac_ptr[i] + self.diag_pos[d * a + i % d]];
            s = s.max(v.abs());
        }
        if s > 0.0 && s.is_finite() {
            s
        } else {
            1.0
        }
    }
}

/// Largest eigenvalue magnitude of the symmetric part of a `d x d` block (power iteration).
fn spectral_norm(b: &[f64; 9], d: usize) -> f64 {
    let mut x = [1.0, 0.7, 0.4];
    let mut l = 0.0;
    for _ in 0..50 {
        let mut y = [0.0; 3];
        for i in 0..d {
            for j in 0..d {
                y[i] += 0.5 * (b[i * d + j] + b[j * d + i]) * x[j];
            }
        }
        let n = y[..d].iter().map(|v| v * v).sum::<f64>().sqrt();
        if !(n > 0.0 && n.is_finite()) {
            return 0.0;
        }
        l = n;
        for i in 0..d {
            x[i] = y[i] / n;
        }
    }
    l
}

/// Solves `problem` by the generalized Newton method from `warm_start` (zero when `None`).
pub fn newton(
    problem: &FrictionProblem,
    params: &SolverParams,
    warm_start: Option<&[f64]>,
) -> Result<SolveReport, SolveError> {
    let (blocks, mut r) = prepare(problem, params, warm_start)?;
    if problem.mu.is_empty() {
        return Ok(SolveReport::new(
            SolverKind::Newton,
            problem,
            params,
            0,
            0,
            r,
        ));
    }
    let mut core = NewtonCore::new(problem, &blocks, &params.newton)?;
    let out = core.run(
        &problem.q,
        0.0,
        &mut r,
        params.max_iterations,
        params.tolerance,
        params.tolerance,
        params.scaling,
    );
    Ok(SolveReport::new(
        SolverKind::Newton,
        problem,
        params,
        out.iterations,
        0,
        core.best().to_vec(),
    ))
}
