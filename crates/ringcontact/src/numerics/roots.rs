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
    /// The root: one of the last two points evaluated (the last, unless the search stopped at
    /// the function's rounding floor, [`find_root_with_slope`]), so a caller that keeps its
    /// last two evaluations may reuse the root's.
    pub x: f64,
    pub evaluations: usize,
    /// Secant slope `f'` from the last two iterates (at the rounding floor, from the two
    /// before them, the last step's being rounding; NaN if the last step was a bisection without
    /// a usable pair).
    pub slope: f64,
}

/// Find `x` in `[lo, hi]` with `f(x) = 0`, starting from `guess`, to an absolute tolerance `x_tol`.
///
/// `f` must be continuous and change sign on `[lo, hi]`. Evaluations are counted; at most
/// `max_evaluations` are spent.
pub(crate) fn find_root<F>(
    f: F,
    lo: f64,
    hi: f64,
    guess: f64,
    x_tol: f64,
    max_evaluations: usize,
) -> Result<Root, RootError>
where
    F: FnMut(f64) -> Result<f64, String>,
{
    find_root_with_slope(f, (lo, hi), guess, None, (x_tol, None), max_evaluations)
}

/// [`find_root`] given an estimate of the slope `f'` near the root (a nearby problem's): the
/// second point is Newton's step `guess - f(guess)/slope` instead of a small step, and where that
/// step is already below `x_tol` the search stops there (two evaluations from an excellent
/// start instead of four). A poor slope costs nothing but that step: the secant and the bracket
/// take over.
///
/// Given a residual tolerance (`residual_tol` not `None`), the search stops at its start where
/// `|f(guess)|` is at most `residual_tol` and Newton's step `|f(guess)/slope|` at most `x_tol`
/// (one evaluation; the root's slope is then the given one), and it stops where its next
/// step is known without taking it ([`stop_after`]): the function is linear over the last step
/// (its secant slope agrees with the one before to [`LINEAR_SLOPES`]), the secant's next step
/// `|f(x)/f'|` is below `x_tol` and `|f(x)|` below `residual_tol`; or the evaluations have
/// reached their rounding floor (over a step of at most [`FLOOR_STEPS`] `x_tol` the secant slope
/// disagrees with the one before by more than [`NOISY_SLOPES`]: the differences are rounding,
/// and further steps only wander in it), when the better of the last two points is the root.
/// Without it (`None`) every stop is a step or a bracket below `x_tol`, the root the last point
/// evaluated.
pub(crate) fn find_root_with_slope<F>(
    f: F,
    interval: (f64, f64),
    guess: f64,
    slope: Option<f64>,
    tolerances: (f64, Option<f64>),
    max_evaluations: usize,
) -> Result<Root, RootError>
where
    F: FnMut(f64) -> Result<f64, String>,
{
    search(
        f,
        interval,
        guess,
        slope,
        tolerances,
        max_evaluations,
        false,
    )
}

/// [`find_root_with_slope`] for a function that decreases across `[lo, hi]` overall but not
/// everywhere (`f(lo) > 0 > f(hi)`, with flat stretches and humps between): until a sign change
/// is bracketed, every step goes the way the sign of `f` points (left where `f < 0`), a secant
/// or Newton step that points the other way (a local rise) replaced by twice the last step the
/// right way. Near a hump just short of zero a plain secant bounces between its flanks (the
/// sampled parabolic gap's pre-search at `d/h = 2.97`: 20 evaluations); this one walks past it to a
/// bracket.
pub(crate) fn find_root_descending<F>(
    f: F,
    interval: (f64, f64),
    guess: f64,
    slope: Option<f64>,
    tolerances: (f64, Option<f64>),
    max_evaluations: usize,
) -> Result<Root, RootError>
where
    F: FnMut(f64) -> Result<f64, String>,
{
    search(f, interval, guess, slope, tolerances, max_evaluations, true)
}

/// The search behind [`find_root_with_slope`] and [`find_root_descending`]: two starting points
/// ([`Search::start`]), then secant steps, bisection once a sign change is bracketed
/// ([`Search::next_point`]), until a stop.
fn search<F>(
    f: F,
    (lo, hi): (f64, f64),
    guess: f64,
    slope: Option<f64>,
    (x_tol, residual_tol): (f64, Option<f64>),
    max_evaluations: usize,
    descending: bool,
) -> Result<Root, RootError>
where
    F: FnMut(f64) -> Result<f64, String>,
{
    let mut search = Search {
        f,
        lo,
        hi,
        x_tol,
        residual_tol,
        descending,
        evaluations: 0,
    };
    match search.start(guess, slope)? {
        Start::Root(root) => Ok(root),
        Start::Points(a, b) => search.iterate(a, b, max_evaluations),
    }
}

/// The way to the root while it is not bracketed (descending functions only): right where
/// `f > 0`.
fn downhill(fx: f64) -> f64 {
    if fx > 0.0 {
        1.0
    } else {
        -1.0
    }
}

/// A sign change of `f` over `[l, h]`, with the values at its ends.
#[derive(Clone, Copy)]
struct Bracket {
    l: f64,
    fl: f64,
    h: f64,
}

impl Bracket {
    /// The bracket between two points of opposite sign, `None` where their signs agree.
    fn of((xa, fa): (f64, f64), (xb, fb): (f64, f64)) -> Option<Bracket> {
        (fa.signum() != fb.signum()).then_some(if xa < xb {
            Bracket {
                l: xa,
                fl: fa,
                h: xb,
            }
        } else {
            Bracket {
                l: xb,
                fl: fb,
                h: xa,
            }
        })
    }

    /// The bracket shrunk by a point inside it, keeping the sign change.
    fn shrunk(self, x: f64, fx: f64) -> Bracket {
        if fx.signum() == self.fl.signum() {
            Bracket {
                l: x,
                fl: fx,
                ..self
            }
        } else {
            Bracket { h: x, ..self }
        }
    }
}

/// How a search starts: already at the root, or with two points to step from.
enum Start {
    Root(Root),
    Points((f64, f64), (f64, f64)),
}

/// One root search: the function, its interval and tolerances, and the evaluations spent.
struct Search<F> {
    f: F,
    lo: f64,
    hi: f64,
    x_tol: f64,
    residual_tol: Option<f64>,
    descending: bool,
    evaluations: usize,
}

impl<F: FnMut(f64) -> Result<f64, String>> Search<F> {
    fn eval(&mut self, x: f64) -> Result<f64, RootError> {
        self.evaluations += 1;
        (self.f)(x).map_err(RootError::Evaluation)
    }

    /// The first two points: the guess, and Newton's step from it with the given slope (else a
    /// small step toward the interior, or downhill); either may already be the root.
    fn start(&mut self, guess: f64, slope: Option<f64>) -> Result<Start, RootError> {
        let (lo, hi, x_tol) = (self.lo, self.hi, self.x_tol);
        let x0 = guess.clamp(lo, hi);
        let f0 = self.eval(x0)?;
        if f0 == 0.0 {
            return Ok(Start::Root(self.root(x0, f64::NAN)));
        }
        // A start already within both tolerances by the given slope (a root of a nearby
        // problem: the next node count's, where the two agree to the tolerance) is the root.
        let descending = self.descending;
        let hint = slope.filter(|s| s.is_finite() && *s != 0.0 && !(descending && *s > 0.0));
        if let (Some(s), Some(residual_tol)) = (hint, self.residual_tol) {
            if f0.abs() <= residual_tol && (f0 / s).abs() <= x_tol {
                return Ok(Start::Root(self.root(x0, s)));
            }
        }
        let newton = hint
            .map(|s| x0 - f0 / s)
            .filter(|x| (lo..=hi).contains(x) && *x != x0);
        let x1 = newton.unwrap_or_else(|| {
            let step = (1e-3 * (hi - lo)).max(10.0 * x_tol);
            let downhill_step = x0 + downhill(f0) * step;
            if descending && (lo..=hi).contains(&downhill_step) {
                downhill_step
            } else if descending {
                // At an end whose side the sign points beyond: the other way, where the ends
                // then decide whether a root exists.
                x0 - downhill(f0) * step
            } else if x0 + step <= hi {
                x0 + step
            } else {
                x0 - step
            }
        });
        let f1 = self.eval(x1)?;
        if f1 == 0.0 || (newton.is_some() && (x1 - x0).abs() <= x_tol) {
            return Ok(Start::Root(self.root(x1, (f1 - f0) / (x1 - x0))));
        }
        if let (Some(hint), Some(residual_tol)) =
            (slope.filter(|_| newton.is_some()), self.residual_tol)
        {
            let tolerances = (x_tol, residual_tol);
            if let Some(root) = stop_after((x0, f0), (x1, f1), hint, tolerances, self.evaluations) {
                return Ok(Start::Root(root));
            }
        }
        Ok(Start::Points((x0, f0), (x1, f1)))
    }

    fn root(&self, x: f64, slope: f64) -> Root {
        Root {
            x,
            evaluations: self.evaluations,
            slope,
        }
    }

    /// Secant steps from `a` and `b`, bisection inside a bracket, until a step or the bracket
    /// is below `x_tol`, [`stop_after`] stops it, or the evaluations run out.
    fn iterate(
        &mut self,
        (mut xa, mut fa): (f64, f64),
        (mut xb, mut fb): (f64, f64),
        max_evaluations: usize,
    ) -> Result<Root, RootError> {
        let mut bracket = Bracket::of((xa, fa), (xb, fb));
        let mut last_step = f64::INFINITY;
        while self.evaluations < max_evaluations {
            let (next, widened) = self.next_point((xa, fa), (xb, fb), bracket)?;
            if widened.is_some() {
                bracket = widened;
            }
            let fnext = self.eval(next)?;
            last_step = (next - xb).abs();
            if fnext == 0.0 || last_step <= self.x_tol {
                return Ok(self.root(next, (fnext - fb) / (next - xb)));
            }
            if let Some(residual_tol) = self.residual_tol {
                let slope_before = (fb - fa) / (xb - xa);
                let tolerances = (self.x_tol, residual_tol);
                let stop = stop_after(
                    (xb, fb),
                    (next, fnext),
                    slope_before,
                    tolerances,
                    self.evaluations,
                );
                if let Some(root) = stop {
                    return Ok(root);
                }
            }
            bracket = match bracket {
                Some(b) => Some(b.shrunk(next, fnext)),
                None => Bracket::of((xb, fb), (next, fnext)),
            };
            (xa, fa, xb, fb) = (xb, fb, next, fnext);
            if bracket.is_some_and(|b| b.h - b.l <= self.x_tol) {
                // The last iterate is an end of the bracket, so within `x_tol` of the root, and
                // it has been evaluated (the caller may keep its evaluation).
                return Ok(self.root(xb, (fb - fa) / (xb - xa)));
            }
        }
        Err(RootError::NoConvergence {
            iterations: self.evaluations,
            last_step,
        })
    }

    /// The next point: the secant's, or the bracket's midpoint where the secant leaves it;
    /// unbracketed, a descending function's step taken downhill, and a step stuck at an end
    /// of the interval evaluates both ends (the bracket they make is returned).
    fn next_point(
        &mut self,
        (xa, fa): (f64, f64),
        (xb, fb): (f64, f64),
        bracket: Option<Bracket>,
    ) -> Result<(f64, Option<Bracket>), RootError> {
        let (lo, hi) = (self.lo, self.hi);
        let mut next = if fb != fa {
            xb - fb * (xb - xa) / (fb - fa)
        } else {
            f64::NAN
        };
        if let Some(b) = bracket {
            if !next.is_finite() || next <= b.l || next >= b.h {
                next = 0.5 * (b.l + b.h);
            }
            return Ok((next, None));
        }
        // A descending function's step the wrong way (a local rise) or none at all: twice the
        // last step the right way.
        let way = downhill(fb);
        if self.descending && (!next.is_finite() || (next - xb) * way <= 0.0) {
            next = xb + way * 2.0 * (xb - xa).abs();
        }
        // A flat or overflowing secant (e.g. a target of 1e308, where f(x0) and f(x1) round to
        // the same value) cannot step: the interval's ends decide whether a root exists at all.
        // (A secant step below rounding inside the interval, `next == xb` at a root, is
        // convergence, not an end: the evaluation that follows returns it.)
        let clamped = next.is_finite() && next.clamp(lo, hi) != next;
        let stuck = !next.is_finite() || (clamped && next.clamp(lo, hi) == xb);
        next = if next.is_finite() {
            next.clamp(lo, hi)
        } else {
            xb
        };
        if !stuck {
            return Ok((next, None));
        }
        // Stuck at an end of the admissible interval: check whether it brackets.
        let f_lo = self.eval(lo)?;
        let f_hi = self.eval(hi)?;
        if f_lo.signum() == f_hi.signum() {
            return Err(RootError::NotBracketed { lo, hi, f_lo, f_hi });
        }
        let ends = Bracket {
            l: lo,
            fl: f_lo,
            h: hi,
        };
        Ok((0.5 * (lo + hi), Some(ends)))
    }
}

/// Relative disagreement of the last secant slope with the one before below which the function
/// counts as linear over the last step, so that the secant's next step is the root's distance.
const LINEAR_SLOPES: f64 = 0.25;

/// Relative disagreement of the last secant slope with the one before above which, over a step
/// of at most [`FLOOR_STEPS`] `x_tol`, the evaluations count as rounding.
const NOISY_SLOPES: f64 = 0.5;

/// The longest step, in units of `x_tol`, over which disagreeing slopes are taken for rounding
/// (beyond it they are the function's curvature, as in the first steps from a poor start).
const FLOOR_STEPS: f64 = 1e3;

/// The search's stop after the step from `(xb, fb)` to `(x, fx)`, given the slope before that
/// step (the previous secant's, or the caller's hint after Newton's first step):
/// - linear: the step's secant slope `s` agrees with `slope_before` to [`LINEAR_SLOPES`], the
///   next step `|fx / s|` is at most `x_tol` and the residual `|fx|` at most `residual_tol`:
///   the root is `x`;
/// - rounding floor: the step is at most [`FLOOR_STEPS`] `x_tol` and `s` disagrees with
///   `slope_before` by more than [`NOISY_SLOPES`] (or has the other sign): the root is the
///   point of the two with the smaller `|f|`, its slope `slope_before`.
fn stop_after(
    (xb, fb): (f64, f64),
    (x, fx): (f64, f64),
    slope_before: f64,
    (x_tol, residual_tol): (f64, f64),
    evaluations: usize,
) -> Option<Root> {
    let slope = (fx - fb) / (x - xb);
    let disagreement = (slope / slope_before - 1.0).abs();
    if disagreement <= LINEAR_SLOPES && (fx / slope).abs() <= x_tol && fx.abs() <= residual_tol {
        return Some(Root {
            x,
            evaluations,
            slope,
        });
    }
    let at_floor = (x - xb).abs() <= FLOOR_STEPS * x_tol
        && slope_before.is_finite()
        && slope_before != 0.0
        && (disagreement > NOISY_SLOPES || disagreement.is_nan());
    at_floor.then(|| Root {
        x: if fx.abs() <= fb.abs() { x } else { xb },
        evaluations,
        slope: slope_before,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A decreasing function with humps between the start and its one root
    /// (`f = 0.3 - x + 0.04 sin(40 x)`, root 0.2638, local maxima -0.0053 at 0.337, -0.162 at
    /// 0.494 and -0.320 at 0.651), started on a rising flank (0.64, where a secant steps
    /// uphill, away from the root): the downhill search brackets the root and finds it, in
    /// fewer evaluations than the plain secant.
    #[test]
    fn a_descending_search_walks_past_humps() {
        let f = |x: f64| 0.3 - x + 0.04 * (40.0 * x).sin();
        let exact = find_root(|x| Ok(f(x)), 0.2, 0.3, 0.26, 1e-15, 100)
            .unwrap()
            .x;
        let root =
            find_root_descending(|x| Ok(f(x)), (0.0, 1.0), 0.64, None, (1e-12, None), 60).unwrap();
        assert!((root.x - exact).abs() < 1e-11, "{} against {exact}", root.x);
        // The plain secant, wandering uphill first, finds it too but with more evaluations
        // (25 against 19).
        let plain =
            find_root_with_slope(|x| Ok(f(x)), (0.0, 1.0), 0.64, None, (1e-12, None), 60).unwrap();
        assert!(
            root.evaluations < plain.evaluations,
            "descending {} against plain {}",
            root.evaluations,
            plain.evaluations
        );
        // A start whose sign points past an end turns back, and an interval without a root
        // says so.
        let at_end =
            find_root_descending(|x| Ok(0.5 - x), (0.0, 1.0), 1.0, None, (1e-12, None), 60)
                .unwrap();
        assert!((at_end.x - 0.5).abs() < 1e-11);
        let none = find_root_descending(|x| Ok(-1.0 - x), (0.0, 1.0), 0.3, None, (1e-12, None), 60);
        assert!(
            matches!(none, Err(RootError::NotBracketed { .. })),
            "{none:?}"
        );
    }

    #[test]
    fn finds_a_root_and_reports_missing_bracket() {
        let r = find_root(|x| Ok(x.cos() - x), 0.0, 1.0, 0.2, 1e-14, 50).unwrap();
        assert!((r.x - DOTTIE).abs() < 1e-13);
        assert!(r.evaluations < 12);
        let e = find_root(|x| Ok(x * x + 1.0), 0.0, 1.0, 0.5, 1e-12, 50).unwrap_err();
        assert!(matches!(e, RootError::NotBracketed { .. }));
    }

    /// Root of `cos x - x` (0.7390851332151607, the Dottie number, by fixed-point iteration).
    const DOTTIE: f64 = 0.739_085_133_215_160_6;

    #[test]
    fn a_good_slope_saves_evaluations_and_a_bad_one_does_no_harm() {
        let f = |x: f64| Ok(x.cos() - x);
        // The exact slope at the root, -(sin x + 1), from a start 1e-9 off: two evaluations.
        let slope = -(DOTTIE.sin() + 1.0);
        let r = find_root_with_slope(f, (0.0, 1.0), DOTTIE + 1e-9, Some(slope), (1e-11, None), 50)
            .unwrap();
        assert!((r.x - DOTTIE).abs() < 1e-14, "{}", r.x);
        assert_eq!(r.evaluations, 2);
        let plain = find_root(f, 0.0, 1.0, DOTTIE + 1e-9, 1e-11, 50).unwrap();
        assert!(plain.evaluations > 2, "{}", plain.evaluations);
        // A slope of the wrong sign or far off, from a poor start: the same root.
        for bad in [1.0, -1e-6, -1e6, f64::NAN] {
            let r = find_root_with_slope(f, (0.0, 1.0), 0.2, Some(bad), (1e-14, None), 60).unwrap();
            assert!((r.x - DOTTIE).abs() < 1e-13, "slope {bad}: {}", r.x);
        }
    }

    #[test]
    fn the_root_returned_is_the_last_point_evaluated() {
        for (guess, slope) in [(0.2, None), (0.9, Some(-1.5)), (DOTTIE, None)] {
            let mut last = f64::NAN;
            let r = find_root_with_slope(
                |x| {
                    last = x;
                    Ok(x.cos() - x)
                },
                (0.0, 1.0),
                guess,
                slope,
                (1e-13, None),
                60,
            )
            .unwrap();
            assert_eq!(r.x, last);
            assert!((r.x - DOTTIE).abs() < 1e-12);
        }
    }

    /// A start within both tolerances by the given slope is the root, after one evaluation;
    /// a start outside either is not.
    #[test]
    fn a_start_within_the_tolerances_is_the_root() {
        let f = |x: f64| Ok(x.cos() - x);
        let slope = -(DOTTIE.sin() + 1.0);
        let tolerances = (1e-11, Some(1e-11));
        let close = DOTTIE + 2e-12;
        let r = find_root_with_slope(f, (0.0, 1.0), close, Some(slope), tolerances, 50).unwrap();
        assert_eq!((r.x, r.evaluations, r.slope), (close, 1, slope));
        // 2e-12 off (f' = -1.67): the residual 3.3e-12 is within 1e-11, Newton's step too;
        // 1e-11 off: the residual 1.7e-11 is not, and the search steps on.
        let far = DOTTIE + 1e-11;
        let r = find_root_with_slope(f, (0.0, 1.0), far, Some(slope), tolerances, 50).unwrap();
        assert!(r.evaluations >= 2 && (r.x - DOTTIE).abs() <= 1e-11, "{r:?}");
        // Without a residual tolerance or a slope every stop is a step below x_tol.
        let r = find_root_with_slope(f, (0.0, 1.0), close, Some(slope), (1e-11, None), 50).unwrap();
        assert!(r.evaluations >= 2, "{r:?}");
        let r = find_root_with_slope(f, (0.0, 1.0), close, None, tolerances, 50).unwrap();
        assert!(r.evaluations >= 2, "{r:?}");
    }

    /// With a residual tolerance the search stops where the secant's next step is known to be
    /// below `x_tol` (no confirming step): one evaluation fewer where the last step lands within
    /// both tolerances, never more, the same root to `x_tol`.
    #[test]
    fn a_residual_tolerance_spares_the_confirming_step() {
        let f = |x: f64| Ok(x.cos() - x);
        let slope = -(0.7_f64.sin() + 1.0);
        for guess in [0.7, 0.2, 0.95] {
            let strict =
                find_root_with_slope(f, (0.0, 1.0), guess, Some(slope), (1e-11, None), 50).unwrap();
            let spared =
                find_root_with_slope(f, (0.0, 1.0), guess, Some(slope), (1e-11, Some(1e-11)), 50)
                    .unwrap();
            // From 0.7 the last step lands within the tolerance (5 evaluations against 6); from
            // 0.2 it lands at a residual of 2e-11, above it, and both take 7.
            let spares = if guess == 0.2 { 0 } else { 1 };
            assert!(
                spared.evaluations + spares <= strict.evaluations,
                "guess {guess}: {} against {}",
                spared.evaluations,
                strict.evaluations
            );
            assert!((spared.x - DOTTIE).abs() <= 1e-11, "{}", spared.x);
            assert!((spared.x.cos() - spared.x).abs() <= 1e-11);
        }
    }

    /// A function whose evaluations carry rounding of 1e-12 (a deterministic pseudo-random
    /// perturbation) on a slope of 1e-3, so its root is known only to about 1e-9, asked for
    /// 1e-13: with a residual tolerance the search stops once its steps wander in the rounding,
    /// at the better of its last two points, within the rounding's reach of the root; without,
    /// it wanders until its bracket closes.
    #[test]
    fn a_search_at_its_rounding_floor_stops_at_the_better_point() {
        let noise = |x: f64| 1e-12 * ((x.to_bits() % 1000) as f64 / 500.0 - 1.0);
        let root = 0.3;
        let mut evaluated = Vec::new();
        let mut f = |x: f64| {
            evaluated.push(x);
            Ok(1e-3 * (x - root) + noise(x))
        };
        let found = find_root_with_slope(
            &mut f,
            (0.0, 1.0),
            0.5,
            Some(1e-3),
            (1e-13, Some(1e-16)),
            60,
        )
        .unwrap();
        assert!((found.x - root).abs() < 3e-9, "{}", found.x);
        let last_two = &evaluated[evaluated.len().saturating_sub(2)..];
        assert!(last_two.contains(&found.x));
        let value = |x: f64| (1e-3 * (x - root) + noise(x)).abs();
        let other = last_two.iter().copied().find(|&x| x != found.x).unwrap();
        assert!(value(found.x) <= value(other));
        let wandering = find_root_with_slope(
            |x| Ok(1e-3 * (x - root) + noise(x)),
            (0.0, 1.0),
            0.5,
            Some(1e-3),
            (1e-13, None),
            60,
        );
        let wandering_evaluations = wandering.map_or(60, |r| r.evaluations);
        assert!(
            found.evaluations + 2 <= wandering_evaluations,
            "{} against {wandering_evaluations}",
            found.evaluations
        );
    }

    /// Secant slopes that disagree over long steps are the function's curvature, not rounding:
    /// a steep function searched from far off (`1/x - 1/x*`, slopes from 4 to 1e4 on the way)
    /// with a residual tolerance still finds its root to `x_tol`.
    #[test]
    fn curvature_far_from_the_root_is_not_taken_for_rounding() {
        let target = 0.01;
        for guess in [0.5, 0.9, 0.002] {
            let found = find_root_with_slope(
                |x| Ok(1.0 / x - 1.0 / target),
                (1e-4, 1.0),
                guess,
                None,
                (1e-14, Some(1e-12)),
                80,
            )
            .unwrap();
            assert!(
                (found.x - target).abs() <= 1e-14,
                "guess {guess}: {}",
                found.x
            );
        }
    }
}
