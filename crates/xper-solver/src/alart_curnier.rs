//! Alart-Curnier's function of one contact and the local (one-contact) 3D solver.
//!
//! For a contact with impulse `r = (r_N, r_T)` and velocity `u = (u_N, u_T)`, Alart and
//! Curnier (CMAME 92, 1991; in the form of Christensen, Klarbring, Pang, Strömberg,
//! IJNME 42, 1998, and of Siconos' `fc3d_AlartCurnier` "standard" variant) write the
//! Signorini-Coulomb law as the non-smooth equation
//!
//! ```text
//! Phi_N = r_N - max(0, r_N - rho_N u_N)                          = 0
//! Phi_T = r_T - P_D(mu max(0, r_N - rho_N u_N)) (r_T - rho_T u_T) = 0
//! ```
//!
//! with `P_D(R)` the projection on the disk (2D: interval) of radius `R` and `rho_N, rho_T > 0`.
//! `ac_function` returns `Phi` and an element of its generalized Jacobian as two blocks,
//! `dPhi = A dr + B du`; with `u = W r + q` the Newton matrix is `A + B W`.
//!
//! The local 3D solve (`u = W_aa r + q_a`, one contact) enumerates take-off (`q_N >= 0`) and
//! stick (`r = -W_aa^-1 q_a` inside the cone) in closed form, then runs a damped Newton on
//! `Phi` (Armijo backtracking on `|Phi|^2 / 2`). When Newton fails (about 0.4% of random
//! sliding cases, on ill-conditioned blocks where the sliding solution is near a pole of
//! `r_N`), the sliding solution is searched on the slip angle (`slide_by_angle`), and as a last
//! resort the projection on the cone with local iterations of Siconos
//! (`fc3d_projectionOnConeWithLocalIteration`) is run:
//! `r <- P_K(r - rho (u + mu |u_T| e_N))` with `rho` halved while
//! `rho |Δ(u + mu|u_T| e_N)| > 0.9 |Δr|` (a Lipschitz test in the style of Khobotov's
//! extragradient rule) and enlarged when the test holds with margin.

/// Tuning of the one-contact 3D solver.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct LocalParams {
    /// Newton iterations before falling back to the angle search and the projection.
    pub newton_iterations: u32,
    /// Iterations of the projection fallback.
    pub projection_iterations: u32,
    /// Relative tolerance on `|Phi|` (Newton) and on the step (projection), relative to
    /// `max(|r|, |q| / W_NN)`.
    pub tolerance: f64,
}

impl Default for LocalParams {
    fn default() -> Self {
        LocalParams {
            newton_iterations: 30,
            projection_iterations: 1000,
            tolerance: 1e-14,
        }
    }
}

/// `Phi` and the blocks `A = dPhi/dr`, `B = dPhi/du` (row-major `d x d` in `[f64; 9]`).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct AcEval {
    pub phi: [f64; 3],
    pub a: [f64; 9],
    pub b: [f64; 9],
}

/// Alart-Curnier's function of one contact in dimension `d` (2 or 3), see the module docs.
#[inline]
#[allow(clippy::needless_range_loop)] // block indices k * d + l read better than iterators
pub(crate) fn ac_function(
    d: usize,
    r: &[f64],
    u: &[f64],
    mu: f64,
    rho_n: f64,
    rho_t: f64,
) -> AcEval {
    let mut e = AcEval::default();
    let xn = r[0] - rho_n * u[0];
    if xn > 0.0 {
        e.phi[0] = rho_n * u[0];
        e.b[0] = rho_n;
    } else {
        e.phi[0] = r[0];
        e.a[0] = 1.0;
    }
    let radius = mu * xn.max(0.0);
    let mut xt = [0.0; 2];
    for (x, (rk, uk)) in xt.iter_mut().zip(r[1..d].iter().zip(&u[1..d])) {
        *x = rk - rho_t * uk;
    }
    let nx = xt.iter().map(|x| x * x).sum::<f64>().sqrt();
    if nx <= radius {
        for k in 1..d {
            e.phi[k] = rho_t * u[k];
            e.b[k * d + k] = rho_t;
        }
    } else {
        let s = [xt[0] / nx, xt[1] / nx];
        let c = radius / nx;
        for k in 1..d {
            e.phi[k] = r[k] - radius * s[k - 1];
            if xn > 0.0 {
                e.a[k * d] = -mu * s[k - 1];
                e.b[k * d] = mu * rho_n * s[k - 1];
            }
            for l in 1..d {
                // P = I - s s^T on the tangent plane (zero in 2D, where s = ±1).
                let p = f64::from(u8::from(k == l)) - s[k - 1] * s[l - 1];
                e.a[k * d + l] = f64::from(u8::from(k == l)) - c * p;
                e.b[k * d + l] = c * rho_t * p;
            }
        }
    }
    e
}

/// The adjugate of `m` (row-major) and its determinant, `m adj(m) = det(m) I`.
#[inline]
fn adjugate3(m: &[f64; 9]) -> ([f64; 9], f64) {
    let adj = [
        m[4] * m[8] - m[5] * m[7],
        m[2] * m[7] - m[1] * m[8],
        m[1] * m[5] - m[2] * m[4],
        m[5] * m[6] - m[3] * m[8],
        m[0] * m[8] - m[2] * m[6],
        m[2] * m[3] - m[0] * m[5],
        m[3] * m[7] - m[4] * m[6],
        m[1] * m[6] - m[0] * m[7],
        m[0] * m[4] - m[1] * m[3],
    ];
    let det = m[0] * adj[0] + m[1] * adj[3] + m[2] * adj[6];
    (adj, det)
}

/// Whether `m` (with `adj`, `det` from [`adjugate3`]) is regular to working precision:
/// `|det m| > 1e-14 max|m_ij| max|adj_ij|`. Since `max|m^-1_ij| = max|adj_ij| / |det m|`, the
/// test reads `1 / (max|m_ij| max|m^-1_ij|) > 1e-14`, a reciprocal condition number in the
/// max norm (within a factor 9 of the 1-norm's).
#[inline]
fn regular3(m: &[f64; 9], adj: &[f64; 9], det: f64) -> bool {
    let largest = |x: &[f64; 9]| {
        x.iter()
            .fold(0.0f64, |s, v| if v.abs() > s { v.abs() } else { s })
    };
    let bound = 1e-14 * largest(m) * largest(adj);
    det.abs() > bound && bound.is_finite()
}

/// The inverse of `m` by its adjugate, `m^-1 = adj(m) / det(m)`; `None` when `m` is singular
/// to working precision ([`regular3`]).
pub(crate) fn inverse3(m: &[f64; 9]) -> Option<[f64; 9]> {
    let (adj, det) = adjugate3(m);
    if !regular3(m, &adj, det) {
        return None;
    }
    let inv = adj.map(|a| a / det);
    inv.iter().all(|v| v.is_finite()).then_some(inv)
}

/// Solves the 3x3 system `m x = b` by Cramer's rule, `x = adj(m) b / det(m)`; `None` when `m`
/// is singular to working precision ([`regular3`]).
pub(crate) fn solve3(m: &[f64; 9], b: [f64; 3]) -> Option<[f64; 3]> {
    let (adj, det) = adjugate3(m);
    if !regular3(m, &adj, det) {
        return None;
    }
    let inv_det = 1.0 / det;
    let x = mul3(&adj, &b, &[0.0; 3]).map(|v| v * inv_det);
    x.iter().all(|v| v.is_finite()).then_some(x)
}

#[inline]
fn mul3(w: &[f64; 9], r: &[f64; 3], q: &[f64; 3]) -> [f64; 3] {
    [
        q[0] + w[0] * r[0] + w[1] * r[1] + w[2] * r[2],
        q[1] + w[3] * r[0] + w[4] * r[1] + w[5] * r[2],
        q[2] + w[6] * r[0] + w[7] * r[1] + w[8] * r[2],
    ]
}

#[inline]
fn dot3(x: &[f64; 3], y: &[f64; 3]) -> f64 {
    x[0] * y[0] + x[1] * y[1] + x[2] * y[2]
}

#[inline]
fn norm3(x: &[f64; 3]) -> f64 {
    dot3(x, x).sqrt()
}

/// Projection on the 3D Coulomb cone.
#[inline]
fn project3(x: [f64; 3], mu: f64) -> [f64; 3] {
    let mut y = x;
    crate::problem::project_on_cone_nd(&mut y, mu);
    y
}

/// Natural-map residual `|r - P_K(r - u - mu |u_T| e_N)|` of one 3D contact.
#[inline]
pub(crate) fn local_residual3(r: &[f64; 3], u: &[f64; 3], mu: f64) -> f64 {
    let ut = (u[1] * u[1] + u[2] * u[2]).sqrt();
    let p = project3([r[0] - u[0] - mu * ut, r[1] - u[1], r[2] - u[2]], mu);
    norm3(&[r[0] - p[0], r[1] - p[1], r[2] - p[2]])
}

/// How a local problem was solved.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum LocalPath {
    /// Closed form: take-off, frictionless, or stick.
    Closed,
    /// Alart-Curnier Newton converged.
    Newton,
    /// Newton failed; the sliding solution was found by a search on the slip angle.
    Angle,
    /// Newton and the angle search failed; the projection fallback gave the answer.
    Projection,
}

/// Solves the one-contact 3D problem `u = w r + q` in place (`r` holds the warm start).
pub(crate) fn solve_contact_3d(
    w: &[f64; 9],
    q: [f64; 3],
    mu: f64,
    r: &mut [f64; 3],
    p: &LocalParams,
) -> LocalPath {
    solve_contact_3d_sticking(w, q, mu, r, p, |q| solve3(w, [-q[0], -q[1], -q[2]]))
}

/// [`solve_contact_3d`] with the inverse of `w` computed beforehand ([`inverse3`]), for a
/// block solved many times (an NLGS sweep): the sticking candidate is `-w^-1 q`.
pub(crate) fn solve_contact_3d_inverse(
    w: &[f64; 9],
    inverse: &Option<[f64; 9]>,
    q: [f64; 3],
    mu: f64,
    r: &mut [f64; 3],
    p: &LocalParams,
) -> LocalPath {
    solve_contact_3d_sticking(w, q, mu, r, p, |q| {
        inverse.map(|m| {
            [
                -(m[0] * q[0] + m[1] * q[1] + m[2] * q[2]),
                -(m[3] * q[0] + m[4] * q[1] + m[5] * q[2]),
                -(m[6] * q[0] + m[7] * q[1] + m[8] * q[2]),
            ]
        })
    })
}

/// [`solve_contact_3d`] with the sticking candidate `w^-1 (-q)` given by `sticking`.
#[inline(always)]
fn solve_contact_3d_sticking(
    w: &[f64; 9],
    q: [f64; 3],
    mu: f64,
    r: &mut [f64; 3],
    p: &LocalParams,
    sticking: impl FnOnce(&[f64; 3]) -> Option<[f64; 3]>,
) -> LocalPath {
    if q[0] >= 0.0 {
        *r = [0.0; 3];
        return LocalPath::Closed;
    }
    if mu == 0.0 {
        *r = [-q[0] / w[0], 0.0, 0.0];
        return LocalPath::Closed;
    }
    if let Some(s) = sticking(&q) {
        // |s_T| <= mu s_N, squared (s_N >= 0).
        if s[0] >= 0.0 && s[1] * s[1] + s[2] * s[2] <= mu * mu * (s[0] * s[0]) {
            *r = s;
            return LocalPath::Closed;
        }
    }
    let rho_n = 1.0 / w[0];
    let wt = w[4] + w[8];
    let rho_t = if wt > 0.0 { 2.0 / wt } else { rho_n };
    let scale_r2 = rho_n * rho_n * dot3(&q, &q);
    let start = if r[0] > 0.0 && r.iter().all(|x| x.is_finite()) {
        *r
    } else {
        [-q[0] / w[0], 0.0, 0.0]
    };
    if let Some(x) = local_newton(w, &q, mu, rho_n, rho_t, start, scale_r2, p) {
        *r = x;
        return LocalPath::Newton;
    }
    if let Some(x) = slide_by_angle(w, &q, mu) {
        let u = mul3(w, &x, &q);
        if local_residual3(&x, &u, mu) <= 1e3 * p.tolerance * scale_r2.sqrt().max(norm3(&x)) {
            *r = x;
            return LocalPath::Angle;
        }
    }
    *r = local_projection(w, &q, mu, start, scale_r2.sqrt(), p);
    LocalPath::Projection
}

/// The sliding solution by a search on the slip angle `theta` (the "enumerative" idea of
/// Bonnefon, Daviet, Bertails-Descoubes and Acary for the one-contact problem, done here
/// numerically): with `d = (1, mu cos theta, mu sin theta)` and `r = r_N d`, `u_N = 0` gives
/// `r_N = -q_N / (W_N. d)`, and the slip condition is that
/// `u_T = r_N W_T. d + q_T` be anti-parallel to `(cos theta, sin theta)`: the root of
/// `g = u_T x (cos, sin)` with `u_T . (cos, sin) <= 0` and `r_N >= 0`. Roots are bracketed
/// on 128 angles and refined by bisection; `None` when no bracket qualifies.
fn slide_by_angle(w: &[f64; 9], q: &[f64; 3], mu: f64) -> Option<[f64; 3]> {
    const SAMPLES: usize = 128;
    let denom = |theta: f64| w[0] + mu * (w[1] * theta.cos() + w[2] * theta.sin());
    // (g, u_T . (cos, sin), r) at theta; None where W_N. d <= 0 (no positive r_N).
    let eval = |theta: f64| -> Option<(f64, f64, [f64; 3])> {
        let (s, c) = theta.sin_cos();
        let den = denom(theta);
        if den <= 0.0 {
            return None;
        }
        let rn = -q[0] / den;
        let r = [rn, rn * mu * c, rn * mu * s];
        let u = mul3(w, &r, q);
        Some((u[1] * s - u[2] * c, u[1] * c + u[2] * s, r))
    };
    let step = std::f64::consts::TAU / SAMPLES as f64;
    let mut best: Option<(f64, [f64; 3])> = None;
    let mut consider = |a: f64, b: f64| {
        let (Some((ga, _, _)), Some((gb, _, _))) = (eval(a), eval(b)) else {
            return;
        };
        if ga != 0.0 && ga.signum() == gb.signum() {
            return;
        }
        let (mut lo, mut hi) = (a, b);
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            match eval(mid) {
                Some((gm, _, _)) if gm != 0.0 && gm.signum() == ga.signum() => lo = mid,
                Some(_) => hi = mid,
                None => return,
            }
        }
        if let Some((_, dot, r)) = eval(0.5 * (lo + hi)) {
            let u = mul3(w, &r, q);
            let res = local_residual3(&r, &u, mu);
            if dot <= 0.0 && best.is_none_or(|(b, _)| res < b) {
                best = Some((res, r));
            }
        }
    };
    for k in 0..SAMPLES {
        let (a, b) = (k as f64 * step, (k + 1) as f64 * step);
        match (denom(a) > 0.0, denom(b) > 0.0) {
            (true, true) => consider(a, b),
            (false, false) => {}
            (pos_a, _) => {
                // A pole of r_N (W_N. d = 0) inside: bracket from just beside it to the end
                // where r_N > 0, since the sliding root may lie between two samples.
                let (mut lo, mut hi) = (a, b);
                for _ in 0..60 {
                    let mid = 0.5 * (lo + hi);
                    if (denom(mid) > 0.0) == pos_a {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                if pos_a {
                    consider(a, lo);
                } else {
                    consider(hi, b);
                }
            }
        }
    }
    best.map(|(_, r)| r)
}

/// Where Alart-Curnier's function of one 3D contact was evaluated: which pieces are active,
/// enough to assemble its Newton matrix ([`Branch3::jacobian`]).
#[derive(Clone, Copy)]
struct Branch3 {
    /// `r_N - rho_N u_N > 0`: the normal part is `rho_N u_N`.
    normal: bool,
    /// The tangential part slides: the unit direction `s` of `r_T - rho_T u_T` and
    /// `c = mu max(0, r_N - rho_N u_N) / |r_T - rho_T u_T|`.
    slide: Option<([f64; 2], f64)>,
}

/// Alart-Curnier's function of one 3D contact with `u = w r + q` ([`ac_function`]'s `Phi`)
/// and its branch.
#[inline]
fn ac_phi3(
    w: &[f64; 9],
    q: &[f64; 3],
    r: &[f64; 3],
    mu: f64,
    rho_n: f64,
    rho_t: f64,
) -> ([f64; 3], Branch3) {
    let u = mul3(w, r, q);
    let xn = r[0] - rho_n * u[0];
    let normal = xn > 0.0;
    let phi0 = if normal { rho_n * u[0] } else { r[0] };
    let radius = mu * xn.max(0.0);
    let xt = [r[1] - rho_t * u[1], r[2] - rho_t * u[2]];
    let nx = (xt[0] * xt[0] + xt[1] * xt[1]).sqrt();
    if nx <= radius {
        let phi = [phi0, rho_t * u[1], rho_t * u[2]];
        return (
            phi,
            Branch3 {
                normal,
                slide: None,
            },
        );
    }
    let inv_nx = 1.0 / nx;
    let s = [xt[0] * inv_nx, xt[1] * inv_nx];
    let phi = [phi0, r[1] - radius * s[0], r[2] - radius * s[1]];
    let slide = Some((s, radius * inv_nx));
    (phi, Branch3 { normal, slide })
}

impl Branch3 {
    /// The Newton matrix `J = A + B w` of [`ac_function`]'s blocks at this branch, assembled
    /// row by row without the zero blocks.
    #[inline]
    fn jacobian(&self, w: &[f64; 9], mu: f64, rho_n: f64, rho_t: f64) -> [f64; 9] {
        let mut j = [0.0; 9];
        if self.normal {
            for (jl, wl) in j[..3].iter_mut().zip(&w[..3]) {
                *jl = rho_n * wl;
            }
        } else {
            j[0] = 1.0;
        }
        let Some((s, c)) = self.slide else {
            for (jk, wk) in j[3..].iter_mut().zip(&w[3..]) {
                *jk = rho_t * wk;
            }
            return j;
        };
        for k in 1..3 {
            let sk = s[k - 1];
            // P = I - s s^T on the tangent plane; row k of J is A_k + B_k w.
            let p = [
                f64::from(u8::from(k == 1)) - sk * s[0],
                f64::from(u8::from(k == 2)) - sk * s[1],
            ];
            let row = &mut j[3 * k..3 * k + 3];
            for l in 0..3 {
                row[l] = c * rho_t * (p[0] * w[3 + l] + p[1] * w[6 + l]);
            }
            row[1] += f64::from(u8::from(k == 1)) - c * p[0];
            row[2] += f64::from(u8::from(k == 2)) - c * p[1];
            if self.normal {
                row[0] -= mu * sk;
                for l in 0..3 {
                    row[l] += mu * rho_n * sk * w[l];
                }
            }
        }
        j
    }
}

/// Damped Newton on Alart-Curnier's function of one contact from `r`; `None` without
/// convergence. Converged when `|Phi| <= tol max(scale_r, |r|)`, tested on squares
/// (`scale_r2 = scale_r^2`).
#[allow(clippy::too_many_arguments)]
fn local_newton(
    w: &[f64; 9],
    q: &[f64; 3],
    mu: f64,
    rho_n: f64,
    rho_t: f64,
    mut r: [f64; 3],
    scale_r2: f64,
    p: &LocalParams,
) -> Option<[f64; 3]> {
    let eval = |r: &[f64; 3]| ac_phi3(w, q, r, mu, rho_n, rho_t);
    let tol2 = p.tolerance * p.tolerance;
    let converged = |f2: f64, r: &[f64; 3]| f2 <= tol2 * scale_r2.max(dot3(r, r));
    let (mut phi, mut branch) = eval(&r);
    let mut f2 = dot3(&phi, &phi);
    for _ in 0..p.newton_iterations {
        if converged(f2, &r) {
            return Some(r);
        }
        let j = branch.jacobian(w, mu, rho_n, rho_t);
        let dr = solve3(&j, [-phi[0], -phi[1], -phi[2]])?;
        let mut t = 1.0;
        loop {
            let rt = [r[0] + t * dr[0], r[1] + t * dr[1], r[2] + t * dr[2]];
            let (phi_t, branch_t) = eval(&rt);
            let ft2 = dot3(&phi_t, &phi_t);
            // Armijo on |Phi|^2 / 2: the Newton direction has slope -|Phi|^2.
            if ft2 <= (1.0 - 2e-4 * t) * f2 || t < 1e-3 {
                (r, phi, branch, f2) = (rt, phi_t, branch_t, ft2);
                break;
            }
            t *= 0.5;
        }
        if !f2.is_finite() {
            return None;
        }
    }
    converged(f2, &r).then_some(r)
}

/// Projection on the cone with local iterations and an adaptive `rho` (see the module docs);
/// returns the best iterate by the local natural-map residual.
fn local_projection(
    w: &[f64; 9],
    q: &[f64; 3],
    mu: f64,
    start: [f64; 3],
    scale_r: f64,
    p: &LocalParams,
) -> [f64; 3] {
    let shifted = |u: [f64; 3]| [u[0] + mu * (u[1] * u[1] + u[2] * u[2]).sqrt(), u[1], u[2]];
    let mut r = project3(start, mu);
    let mut u = mul3(w, &r, q);
    let mut rho = 1.0 / w[0];
    let mut best = (local_residual3(&r, &u, mu), r);
    for _ in 0..p.projection_iterations {
        let v = shifted(u);
        let (mut r_new, mut u_new, mut dr_norm);
        let mut tries = 0;
        loop {
            r_new = project3(
                [r[0] - rho * v[0], r[1] - rho * v[1], r[2] - rho * v[2]],
                mu,
            );
            let dr = [r_new[0] - r[0], r_new[1] - r[1], r_new[2] - r[2]];
            u_new = mul3(w, &dr, &u);
            let v_new = shifted(u_new);
            dr_norm = norm3(&dr);
            let dv = norm3(&[v_new[0] - v[0], v_new[1] - v[1], v_new[2] - v[2]]);
            tries += 1;
            if rho * dv <= 0.9 * dr_norm || dr_norm == 0.0 || tries > 30 {
                if rho * dv < 0.3 * dr_norm {
                    rho *= 1.5;
                }
                break;
            }
            rho *= 0.5;
        }
        r = r_new;
        u = u_new;
        let res = local_residual3(&r, &u, mu);
        if res < best.0 {
            best = (res, r);
        }
        if dr_norm <= p.tolerance * scale_r.max(norm3(&r)) {
            break;
        }
    }
    best.1
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solve3_solves_and_detects_singular() {
        let m = [4.0, 1.0, 0.0, 1.0, 3.0, 1.0, 0.0, 1.0, 2.0];
        let x = solve3(&m, [1.0, 2.0, 3.0]).unwrap();
        let y = mul3(&m, &x, &[0.0; 3]);
        assert!((y[0] - 1.0).abs() + (y[1] - 2.0).abs() + (y[2] - 3.0).abs() < 1e-14);
        assert!(solve3(&[1.0, 2.0, 3.0, 2.0, 4.0, 6.0, 0.0, 0.0, 1.0], [1.0; 3]).is_none());
    }

    /// The specialised 3D evaluation equals the generic one: `Phi` and `A + B W`, in the
    /// three tangential cases (stick, slide with the normal active, take-off).
    #[test]
    fn newton_matrix_matches_the_generic_blocks() {
        let w = [2.0, 0.1, 0.2, 0.1, 1.5, 0.05, 0.2, 0.05, 1.2];
        let q = [-1.0, 0.4, -0.3];
        for r in [
            [0.5, 0.01, 0.02],
            [0.5, 0.9, -0.7],
            [-0.2, 0.3, 0.1],
            [0.6, 0.0, 0.0],
        ] {
            let (phi, branch) = ac_phi3(&w, &q, &r, 0.4, 0.5, 0.7);
            let j = branch.jacobian(&w, 0.4, 0.5, 0.7);
            let e = ac_function(3, &r, &mul3(&w, &r, &q), 0.4, 0.5, 0.7);
            for i in 0..3 {
                assert!((phi[i] - e.phi[i]).abs() < 1e-15, "{r:?}: phi");
                for k in 0..3 {
                    let g =
                        e.a[3 * i + k] + (0..3).map(|l| e.b[3 * i + l] * w[3 * l + k]).sum::<f64>();
                    assert!(
                        (j[3 * i + k] - g).abs() < 1e-14,
                        "{r:?}: J[{i}][{k}] {} {g}",
                        j[3 * i + k]
                    );
                }
            }
        }
    }

    #[test]
    fn local_3d_cases() {
        let w = [2.0, 0.1, 0.2, 0.1, 1.5, 0.05, 0.2, 0.05, 1.2];
        let p = LocalParams::default();
        for (q, mu) in [
            ([1.0, 3.0, 1.0], 0.3),
            ([-1.0, 0.01, 0.02], 0.5),
            ([-1.0, 3.0, -2.0], 0.3),
            ([-1.0, -3.0, 0.5], 0.0),
            ([-1.0, -0.3, 0.5], 1.5),
        ] {
            let mut r = [0.0; 3];
            solve_contact_3d(&w, q, mu, &mut r, &p);
            let u = mul3(&w, &r, &q);
            assert!(
                local_residual3(&r, &u, mu) < 1e-12,
                "{q:?} {mu} {r:?} {u:?}"
            );
        }
    }

    #[test]
    fn random_blocks_are_solved_to_rounding() {
        let mut s = 17u64;
        let mut rnd = || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        let p = LocalParams::default();
        let mut paths = [0usize; 4];
        let mut projection_misses = 0;
        for case in 0..20_000 {
            // W = L L^T + 0.05 I, plus a small skew part in one case out of four (as in the
            // slightly non-symmetric Capsules problems).
            let l: Vec<f64> = (0..9).map(|_| rnd()).collect();
            let mut w = [0.0; 9];
            for i in 0..3 {
                for j in 0..3 {
                    w[i * 3 + j] = (0..3).map(|k| l[i * 3 + k] * l[j * 3 + k]).sum::<f64>()
                        + if i == j { 0.05 } else { 0.0 };
                }
            }
            if case % 4 == 0 {
                let e = 0.01 * rnd();
                w[1] += e;
                w[3] -= e;
            }
            let q = [rnd(), 2.0 * rnd(), 2.0 * rnd()];
            let mu = 1.2 * rnd().abs();
            let mut r = [0.0; 3];
            let path = solve_contact_3d(&w, q, mu, &mut r, &p);
            paths[path as usize] += 1;
            let u = mul3(&w, &r, &q);
            let scale = norm3(&q).max(norm3(&r)).max(norm3(&u));
            assert!(
                local_residual3(&r, &u, mu) < 1e-10 * scale,
                "case {case} {path:?}: {w:?} {q:?} {mu} -> {r:?}"
            );
            // The projection alone converges only linearly (slowly on ill-conditioned blocks).
            let x = local_projection(&w, &q, mu, [0.0; 3], 1.0 / w[0] * norm3(&q), &p);
            let ux = mul3(&w, &x, &q);
            if local_residual3(&x, &ux, mu) > 1e-6 * scale {
                projection_misses += 1;
            }
        }
        assert!(projection_misses <= 20, "{projection_misses}");
        // Most sliding cases are Newton's; the closed forms take the rest.
        assert!(paths[LocalPath::Newton as usize] > 5000, "{paths:?}");
    }
}
