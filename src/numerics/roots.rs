//! Safeguarded secant (Illinois-bracketed) root finder for a monotone scalar function.
//!
//! Used to invert `d = h γ1(ε)` and `F = 2 E* h a γ2(ε)` for the contact ratio. The secant steps
//! converge superlinearly from a good guess; once a sign change is bracketed, any step that leaves
//! the bracket is replaced by bisection, so the iteration cannot wander off or cycle.

/// Why a root search stopped without a root.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum RootError {
    /// The function has the same sign at both ends of the admissible interval.
    NotBracketed {
        lo: f64,
        hi: f64,
        f_lo: f64,
        f_hi: f64,
    },
    /// The iteration cap was reached before the tolerance.
    NoConvergence { iterations: usize, last_step: f64 },
    /// The function could not be evaluated (its own error message).
    Evaluation(String),
}

/// Result of a successful root search.
#[derive(Debug, Clone, Copy)]
pub struct Root {
    pub x: f64,
    pub evaluations: usize,
    /// Secant slope `f'` from the last two iterates (NaN if the last step was a bisection
    /// without a usable pair).
    pub slope: f64,
}

/// Find `x` in `[lo, hi]` with `f(x) = 0`, starting from `guess`, to an absolute tolerance `x_tol`.
///
/// `f` must be continuous and change sign on `[lo, hi]`. Evaluations are counted; at most
/// `max_evaluations` are spent.
pub(crate) fn find_root<F>(
    mut f: F,
    lo: f64,
    hi: f64,
    guess: f64,
    x_tol: f64,
    max_evaluations: usize,
) -> Result<Root, RootError>
where
    F: FnMut(f64) -> Result<f64, String>,
{
    let mut evaluations = 0;
    let mut eval = |x: f64, count: &mut usize| -> Result<f64, RootError> {
        *count += 1;
        f(x).map_err(RootError::Evaluation)
    };
    let x0 = guess.clamp(lo, hi);
    let f0 = eval(x0, &mut evaluations)?;
    if f0 == 0.0 {
        return Ok(Root {
            x: x0,
            evaluations,
            slope: f64::NAN,
        });
    }
    // Second point: a small step toward the interior.
    let step = (1e-3 * (hi - lo)).max(10.0 * x_tol);
    let x1 = if x0 + step <= hi {
        x0 + step
    } else {
        x0 - step
    };
    let f1 = eval(x1, &mut evaluations)?;
    // Bracket, if the two points already straddle the root.
    let mut bracket: Option<(f64, f64, f64, f64)> = None;
    let update_bracket =
        |b: &mut Option<(f64, f64, f64, f64)>, xa: f64, fa: f64, xb: f64, fb: f64| {
            if fa.signum() != fb.signum() {
                let (l, fl, h, fh) = if xa < xb {
                    (xa, fa, xb, fb)
                } else {
                    (xb, fb, xa, fa)
                };
                match b {
                    Some((bl, _, bh, _)) if h - l >= *bh - *bl => {}
                    _ => *b = Some((l, fl, h, fh)),
                }
            }
        };
    update_bracket(&mut bracket, x0, f0, x1, f1);
    let (mut xa, mut fa, mut xb, mut fb) = (x0, f0, x1, f1);
    let mut last_step = f64::INFINITY;
    while evaluations < max_evaluations {
        let mut next = if fb != fa {
            xb - fb * (xb - xa) / (fb - fa)
        } else {
            f64::NAN
        };
        match bracket {
            Some((l, _, h, _)) => {
                if !next.is_finite() || next <= l || next >= h {
                    next = 0.5 * (l + h);
                }
            }
            None => {
                // A flat or overflowing secant (e.g. a target of 1e308, where f(x0) and f(x1)
                // round to the same value) cannot step: the interval's ends decide whether a
                // root exists at all.
                // (A secant step below rounding inside the interval, `next == xb` at a root,
                // is convergence, not an end: the evaluation below returns it.)
                let clamped = next.is_finite() && next.clamp(lo, hi) != next;
                let stuck = !next.is_finite() || (clamped && next.clamp(lo, hi) == xb);
                next = if next.is_finite() {
                    next.clamp(lo, hi)
                } else {
                    xb
                };
                if stuck {
                    // Stuck at an end of the admissible interval: check whether it brackets.
                    let f_lo = eval(lo, &mut evaluations)?;
                    let f_hi = eval(hi, &mut evaluations)?;
                    if f_lo.signum() == f_hi.signum() {
                        return Err(RootError::NotBracketed { lo, hi, f_lo, f_hi });
                    }
                    bracket = Some((lo, f_lo, hi, f_hi));
                    next = 0.5 * (lo + hi);
                }
            }
        }
        let fnext = eval(next, &mut evaluations)?;
        last_step = (next - xb).abs();
        if fnext == 0.0 || last_step <= x_tol {
            let slope = (fnext - fb) / (next - xb);
            return Ok(Root {
                x: next,
                evaluations,
                slope,
            });
        }
        // Shrink the bracket with the new point.
        if let Some((l, fl, h, fh)) = bracket {
            bracket = Some(if fnext.signum() == fl.signum() {
                (next, fnext, h, fh)
            } else {
                (l, fl, next, fnext)
            });
        } else {
            update_bracket(&mut bracket, xb, fb, next, fnext);
        }
        xa = xb;
        fa = fb;
        xb = next;
        fb = fnext;
        if let Some((l, _, h, _)) = bracket {
            if h - l <= x_tol {
                let slope = (fb - fa) / (xb - xa);
                return Ok(Root {
                    x: 0.5 * (l + h),
                    evaluations,
                    slope,
                });
            }
        }
    }
    Err(RootError::NoConvergence {
        iterations: evaluations,
        last_step,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_a_root_and_reports_missing_bracket() {
        let r = find_root(|x| Ok(x.cos() - x), 0.0, 1.0, 0.2, 1e-14, 50).unwrap();
        assert!((r.x - 0.739_085_133_215_160_6).abs() < 1e-13);
        assert!(r.evaluations < 12);
        let e = find_root(|x| Ok(x * x + 1.0), 0.0, 1.0, 0.5, 1e-12, 50).unwrap_err();
        assert!(matches!(e, RootError::NotBracketed { .. }));
    }
}
