//! Brent's minimisation on an interval: parabolic interpolation through the three best points,
//! a golden-section step wherever the parabola's step is not trusted (R. P. Brent, Algorithms
//! for Minimization without Derivatives, 1973, ch. 5).
//!
//! On a smooth minimum it converges superlinearly (order about 1.3), where the golden section
//! shrinks the bracket by a constant 0.618 per evaluation; each evaluation of the adhesion
//! analyses' searches is a ring-BEM solve (the tests ask for fewer than 70 % of the golden
//! section's evaluations).

/// `(3 - √5)/2`: the golden section's fraction of the larger part.
const GOLDEN: f64 = 0.381_966_011_250_105_1;

/// The abscissa and value of a minimum of `f` in `[lo, hi]` (`f` unimodal there), located to
/// `tolerance` in `x`: the search stops once the bracket around its best point is at most
/// `4 tolerance` wide (`tolerance` at least the rounding of the abscissa), so the true minimum
/// lies within that of the point returned. Every
/// evaluation lies inside `[lo, hi]`; an error of `f` ends the search and is returned.
pub fn brent_minimum<E>(
    mut f: impl FnMut(f64) -> Result<f64, E>,
    lo: f64,
    hi: f64,
    tolerance: f64,
) -> Result<(f64, f64), E> {
    let (mut a, mut b) = if lo <= hi { (lo, hi) } else { (hi, lo) };
    // x: the best point so far; w: the second best; v: the previous w.
    let mut x = a + GOLDEN * (b - a);
    let mut fx = f(x)?;
    let (mut w, mut fw, mut v, mut fv) = (x, fx, x, fx);
    // d: the last step; e: the step before it.
    let (mut d, mut e) = (0.0f64, 0.0f64);
    loop {
        let middle = 0.5 * (a + b);
        // Below the rounding of `x` a step cannot move it: the search would never end.
        let tol1 = tolerance.max(4.0 * f64::EPSILON * x.abs());
        let tol2 = 2.0 * tol1;
        if (x - middle).abs() <= tol2 - 0.5 * (b - a) {
            return Ok((x, fx));
        }
        let mut golden_step = true;
        if e.abs() > tol1 {
            // The parabola through (v, fv), (w, fw), (x, fx): its vertex at x + p/q.
            let r = (x - w) * (fx - fv);
            let q0 = (x - v) * (fx - fw);
            let mut p = (x - v) * q0 - (x - w) * r;
            let mut q = 2.0 * (q0 - r);
            if q > 0.0 {
                p = -p;
            }
            q = q.abs();
            let previous = e;
            e = d;
            // Trusted: inside the bracket and less than half the step before last.
            if p.abs() < (0.5 * q * previous).abs() && p > q * (a - x) && p < q * (b - x) {
                d = p / q;
                let u = x + d;
                if u - a < tol2 || b - u < tol2 {
                    d = tol1.copysign(middle - x);
                }
                golden_step = false;
            }
        }
        if golden_step {
            e = if x >= middle { a - x } else { b - x };
            d = GOLDEN * e;
        }
        let u = if d.abs() >= tol1 {
            x + d
        } else {
            x + tol1.copysign(d)
        };
        let fu = f(u)?;
        if fu <= fx {
            if u >= x {
                a = x;
            } else {
                b = x;
            }
            (v, fv, w, fw, x, fx) = (w, fw, x, fx, u, fu);
        } else {
            if u < x {
                a = u;
            } else {
                b = u;
            }
            if fu <= fw || w == x {
                (v, fv, w, fw) = (w, fw, u, fu);
            } else if fu <= fv || v == x || v == w {
                (v, fv) = (u, fu);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::brent_minimum;
    use std::cell::Cell;

    /// The minimum of smooth functions with known minimisers (closed forms) to the tolerance,
    /// or to the width `sqrt(2 ε |f| / f'')` within which rounding hides it, the evaluations
    /// inside the interval and fewer than the golden section's `ln(width/tol)/ln(1.618)`.
    #[test]
    fn locates_known_minima_in_few_evaluations() {
        // (f, lo, hi, the minimiser, f and f'' there)
        type Case = (fn(f64) -> f64, f64, f64, f64, f64, f64);
        let e = 1.0f64.exp();
        let cases: [Case; 4] = [
            (|x| (x - 0.3) * (x - 0.3), 0.0, 1.0, 0.3, 0.0, 2.0),
            (|x| x * x.ln(), 0.1, 0.9, 1.0 / e, -1.0 / e, e),
            (
                |x| -x.sin(),
                1.0,
                2.5,
                std::f64::consts::FRAC_PI_2,
                -1.0,
                1.0,
            ),
            // A quartic (flat: the fourth power) with a small quadratic part.
            (
                |x| (x - 0.61).powi(4) + 0.1 * (x - 0.61).powi(2),
                0.5,
                0.7,
                0.61,
                0.0,
                0.2,
            ),
        ];
        for (f, lo, hi, at, value, curvature) in cases {
            let hidden = (2.0 * f64::EPSILON * value.abs() / curvature).sqrt();
            let calls = Cell::new(0usize);
            let inside = Cell::new(true);
            let (x, _) = brent_minimum(
                |x| {
                    calls.set(calls.get() + 1);
                    inside.set(inside.get() && (lo..=hi).contains(&x));
                    Ok::<_, ()>(f(x))
                },
                lo,
                hi,
                1e-9,
            )
            .unwrap();
            assert!(
                (x - at).abs() <= 4e-9 + 2.0 * hidden,
                "minimum at {at}: found {x}"
            );
            assert!(inside.get(), "an evaluation left [{lo}, {hi}]");
            let golden = ((hi - lo) / 4e-9).ln() / 1.618f64.ln();
            assert!(
                (calls.get() as f64) < 0.7 * golden,
                "{} evaluations (golden section: {golden:.0})",
                calls.get()
            );
        }
    }

    /// A tolerance below the rounding of the abscissa (here 1e-15 at x = 100, where doubles
    /// are 1.4e-14 apart) still ends the search, at the rounding; the evaluations are capped
    /// so that a search that would not end fails instead.
    #[test]
    fn a_tolerance_below_the_abscissa_s_rounding_ends_the_search() {
        let mut evaluations = 0;
        let r = brent_minimum(
            |x: f64| {
                evaluations += 1;
                if evaluations > 10_000 {
                    return Err("the search did not end");
                }
                Ok((x - 100.3) * (x - 100.3))
            },
            100.0,
            101.0,
            1e-15,
        );
        let (x, _) = r.unwrap();
        assert!((x - 100.3).abs() < 1e-7, "{x}");
    }

    #[test]
    fn the_function_s_error_ends_the_search() {
        let r = brent_minimum(|x| if x > 0.5 { Err("no") } else { Ok(x) }, 0.0, 1.0, 1e-9);
        assert_eq!(r, Err("no"));
    }
}
