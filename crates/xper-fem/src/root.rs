//! A safeguarded Newton method for the scalar stress conditions of the strain drivers.
//!
//! Source: W.H. Press et al., "Numerical Recipes", 3rd ed., Cambridge 2007, section 9.4
//! (`rtsafe`: Newton-Raphson kept inside a bracket, bisecting when a step leaves it).

/// Most evaluations of `f` the solver spends.
const MAX_EVALUATIONS: usize = 400;

/// Solves `f(x) = 0` for a non-decreasing function `f` returning `(value, slope)`, from the
/// guess `x0`, to `|f(x)| <= tolerance` or until the bracket is as narrow as `f64` allows.
/// Returns the root, or the smallest residual reached if none is found (no sign change,
/// non-finite values).
pub(crate) fn solve_increasing(
    mut f: impl FnMut(f64) -> (f64, f64),
    x0: f64,
    tolerance: f64,
) -> Result<f64, f64> {
    let (mut x, (mut r, mut slope)) = (x0, f(x0));
    let mut evaluations = 1;
    let mut best = (r.abs(), x);
    // Bracket: walk downhill with Newton-sized steps, doubling, until the sign changes.
    let (mut lo, mut hi) = (f64::NAN, f64::NAN);
    let first = if slope > 0.0 && slope.is_finite() {
        -r / slope
    } else {
        -r.signum() * x.abs().max(1e-12)
    };
    let mut step = first;
    if r.abs() <= tolerance {
        return Ok(x);
    }
    while evaluations < MAX_EVALUATIONS {
        if !r.is_finite() || step == 0.0 || !step.is_finite() {
            return Err(best.0);
        }
        let trial = x + step;
        let (tr, ts) = f(trial);
        evaluations += 1;
        if tr.abs() < best.0 {
            best = (tr.abs(), trial);
        }
        if tr.abs() <= tolerance {
            return Ok(trial);
        }
        if tr.signum() != r.signum() {
            (lo, hi) = if r < 0.0 { (x, trial) } else { (trial, x) };
            (x, r, slope) = (trial, tr, ts);
            break;
        }
        (x, r, slope) = (trial, tr, ts);
        step *= 2.0;
    }
    if lo.is_nan() {
        return Err(best.0);
    }
    // Newton inside the bracket, bisection when Newton leaves it.
    while evaluations < MAX_EVALUATIONS {
        let newton = x - r / slope;
        x = if slope > 0.0 && newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        let (nr, ns) = f(x);
        evaluations += 1;
        (r, slope) = (nr, ns);
        if !r.is_finite() {
            return Err(best.0);
        }
        if r.abs() < best.0 {
            best = (r.abs(), x);
        }
        if r.abs() <= tolerance {
            return Ok(x);
        }
        if r < 0.0 {
            lo = x;
        } else {
            hi = x;
        }
        if hi - lo <= 4.0 * f64::EPSILON * lo.abs().max(hi.abs()) {
            return Ok(best.1);
        }
    }
    Err(best.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_roots_of_smooth_and_kinked_increasing_functions() {
        let cubic = |x: f64| (x * x * x + x - 10.0, 3.0 * x * x + 1.0);
        let root = solve_increasing(cubic, -50.0, 1e-12).unwrap();
        assert!((root * root * root + root - 10.0).abs() <= 1e-12);
        // A kink at 1 where the slope drops from 100 to 1: Newton alone would cycle.
        let kinked = |x: f64| {
            if x < 1.0 {
                (100.0 * (x - 1.0) + 0.5, 100.0)
            } else {
                (x - 1.0 + 0.5, 1.0)
            }
        };
        let root = solve_increasing(kinked, 3.0, 1e-14).unwrap();
        assert!((root - 0.995).abs() <= 1e-14);
        assert!(solve_increasing(|_| (1.0, 0.0), 0.0, 1e-12).is_err());
    }
}
