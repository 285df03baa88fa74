//! The concave punch's inverse problem: the contact ratio `eps` whose `γ1` (depth control) or
//! `γ2` (force control) meets a target, climbing the node ladder until two rungs agree.
//!
//! One rung runs four named phases: [`InverseSearch::search_rung`] (the root on that rung's node
//! count), [`InverseSearch::root_slopes`] (`dγ1/deps`, `dγ2/deps`, `dc/deps` at the root),
//! [`InverseSearch::rung_estimate`] (the change from the rung below carried to the root) and
//! [`InverseSearch::climb_from`] (what the next rung starts from). A piecewise profile first runs a
//! rough pre-search ([`InverseSearch::piecewise_presearch`]).

use super::piecewise_gap::{self, BandEdges, InnerStencil, InnerStencils};
use super::{
    floored_estimate, free_edge_floor, initial_ratio, inverse_error, min_contact_ratio,
    no_convergence, outer_edge_hint, piecewise_starting_rung, starting_rung, ConcaveSample,
    Controlled, RingBemSolver, RingState, FIRST_SEARCH_RUNG, MAX_CONTACT_RATIO, NODE_LADDER,
    PRESEARCH_EVALUATIONS, PRESEARCH_TOLERANCE, SLOPE_MIN_SEPARATION, SLOPE_TRUSTED_ESTIMATE,
};
use crate::error::Result;
use crate::numerics::roots::{find_root_descending, find_root_with_slope};
use crate::punch::{PiecewiseProfile, PunchKind};

/// Slopes `[dγ1/deps, dγ2/deps, dc/deps]` at a root.
type Slopes = [f64; 3];

/// The root of one rung's search: the contact ratio, its sample, and the farthest other sample
/// of the search `(eps, γ1, γ2, c)` for the secant slopes.
struct RungRoot {
    eps: f64,
    fine: ConcaveSample,
    neighbour: Option<(f64, f64, f64, f64)>,
}

/// What the search carries from one rung of the node ladder to the next.
pub(super) struct InverseSearch<'a> {
    solver: &'a RingBemSolver,
    kind: &'a PunchKind,
    target: f64,
    tolerance: f64,
    controlled: Controlled,
    /// The rung of [`NODE_LADDER`] searched next.
    rung: usize,
    /// Where the next search starts, with its slope and outer edge where known.
    guess: f64,
    slope_hint: Option<f64>,
    outer_guess: Option<f64>,
    /// The previous rung's slopes where that rung was close (reused without a new sample).
    previous_slopes: Option<Slopes>,
    /// Whether the first search measures its slope at its start before its first step.
    probe_slope: bool,
    /// Whether the first rung is the coarse sample of the second instead of being estimated.
    climb_first: bool,
    /// The previous rung's root and its sample: the coarse sample of the next rung where that
    /// one's root is the same ratio (its search stopped at its start).
    previous_root: Option<(usize, f64, ConcaveSample)>,
    /// A piecewise profile's samples at each node count share their neighbouring bands where they lie
    /// close together: the search's last samples, and the next rung's coarse sample.
    stencils: InnerStencils,
}

impl<'a> InverseSearch<'a> {
    /// The search's start: a guess from the paper's fits or the profile's closed forms, on a
    /// cheap rung whatever the guess (a fit's start can be far off, and a search on many nodes
    /// from there pays for every step); its root then says which rung the ratio needs.
    pub(super) fn start(
        solver: &'a RingBemSolver,
        kind: &'a PunchKind,
        target: f64,
        tolerance: f64,
        controlled: Controlled,
    ) -> Self {
        let guess = initial_ratio(kind, target, controlled);
        let mut search = InverseSearch {
            solver,
            kind,
            target,
            tolerance,
            controlled,
            rung: starting_rung(guess).min(FIRST_SEARCH_RUNG),
            guess,
            slope_hint: None,
            outer_guess: None,
            previous_slopes: None,
            probe_slope: false,
            climb_first: kind.piecewise().is_some(),
            previous_root: None,
            stencils: InnerStencils::default(),
        };
        if let Some(pieces) = kind.piecewise() {
            search.piecewise_presearch(pieces);
        }
        search
    }

    /// Climb the node ladder until a rung's estimate meets the tolerance.
    pub(super) fn run(mut self) -> Result<RingState> {
        loop {
            let n = NODE_LADDER[self.rung];
            let root = self.search_rung(n)?;
            let slopes = self.root_slopes(&root, n)?;
            if std::mem::take(&mut self.climb_first) && self.rung + 1 < NODE_LADDER.len() {
                // A piecewise profile's first rung is not estimated against the rung below (a search sample
                // there builds its own inner stencil: six factorisations) but taken as the
                // coarse sample of the rung above, whose search starts at this root with its
                // slope and, where the two node counts agree to the tolerance, stops there:
                // the same six factorisations buy the finer state and its estimate (the first
                // rung's own estimate misses 1e-9 below b/a = 0.2).
                self.rung += 1;
                self.climb_from(root, slopes, Some(slopes), n);
                continue;
            }
            let estimate = self.rung_estimate(&root, slopes)?;
            if estimate <= self.tolerance {
                let fine = self.solver.completed(self.kind, root.fine)?;
                return self
                    .solver
                    .concave_state(self.kind, root.eps, fine, n, estimate);
            }
            if self.rung + 1 >= NODE_LADDER.len() {
                return Err(no_convergence(format!(
                    "error estimate {estimate:.2e} at N = {n} exceeds the tolerance {:.1e}",
                    self.tolerance
                )));
            }
            let needed = match self.kind.piecewise() {
                Some(_) => piecewise_starting_rung(root.eps),
                None => starting_rung(root.eps),
            };
            self.rung = (self.rung + 1).max(needed);
            let trusted = (estimate <= SLOPE_TRUSTED_ESTIMATE).then_some(slopes);
            self.climb_from(root, slopes, trusted, n);
        }
    }

    /// The prescribed quantity of a sample, `γ1` or `γ2`.
    fn pick(&self, sample: &ConcaveSample) -> f64 {
        prescribed(self.controlled, sample)
    }

    /// A piecewise profile's rough pre-search: a sample takes six collocation systems (one within its
    /// stencil's reach, [`InnerStencil`]), a rough one, its inner derivative of second order,
    /// three. The rough root at 16 nodes (`γ` within 4e-6 of the accurate one, where the direct
    /// collocation is far off near closure) starts the search, with its slope, on the rung that
    /// root needs. The rough search walks downhill past `γ`'s humps ([`find_root_descending`]).
    fn piecewise_presearch(&mut self, pieces: &dyn PiecewiseProfile) {
        let n = NODE_LADDER[FIRST_SEARCH_RUNG];
        let (solver, controlled, target) = (self.solver, self.controlled, self.target);
        let mut stencil = InnerStencil::default();
        let mut rough = |eps: f64| -> std::result::Result<f64, String> {
            let band = piecewise_gap::GapBands(solver)
                .gap_band(&pieces, eps, 1.0, n, BandEdges::InnerRough, &mut stencil)
                .map_err(|e| e.to_string())?;
            let gamma1 = band.functionals.free_inner_depth();
            Ok(match controlled {
                Controlled::Depth => gamma1,
                Controlled::Force => 0.5 * band.functionals.force(gamma1),
            } - target)
        };
        let root = find_root_descending(
            &mut rough,
            (min_contact_ratio(self.kind), MAX_CONTACT_RATIO),
            self.guess,
            None,
            (PRESEARCH_TOLERANCE, None),
            PRESEARCH_EVALUATIONS,
        );
        match root {
            Ok(root) => {
                self.guess = root.x;
                self.slope_hint = Some(root.slope).filter(|s| s.is_finite() && *s != 0.0);
                // Without a slope the search measures one.
                self.probe_slope = self.slope_hint.is_none();
            }
            Err(_) => self.probe_slope = true,
        }
        // The start says which rung the state needs: the search starts there.
        self.rung = piecewise_starting_rung(self.guess);
    }

    /// The root on `n` nodes, from the guess and slope the previous phases left; the last three
    /// samples of the search are kept for the root's state and the secant slopes.
    fn search_rung(&mut self, n: usize) -> Result<RungRoot> {
        let (solver, kind, target) = (self.solver, self.kind, self.target);
        let outer_guess = self.outer_guess;
        let controlled = self.controlled;
        let pick = |sample: &ConcaveSample| prescribed(controlled, sample);
        let mut stencils = std::mem::take(&mut self.stencils);
        let mut history: Vec<(f64, ConcaveSample)> = Vec::with_capacity(3);
        let mut evaluate = |eps: f64| -> std::result::Result<f64, String> {
            if let Some((_, sample)) = history.iter().find(|(at, _)| *at == eps) {
                return Ok(pick(sample) - target);
            }
            let hint = outer_edge_hint(&history, eps).or(outer_guess);
            let sample = solver
                .search_sample(kind, eps, n, hint, stencils.at(n))
                .map_err(|e| e.to_string())?;
            let value = pick(&sample) - target;
            if history.len() == 3 {
                history.remove(0);
            }
            history.push((eps, sample));
            Ok(value)
        };
        let mut slope_hint = self.slope_hint;
        if self.probe_slope {
            // A piecewise profile's pre-search slope can be far off where `γ` is flat (deep states), and a
            // step from it lands outside the first sample's inner stencil, whose neighbours the
            // next sample then rebuilds (five factorisations). The slope from a second sample
            // inside that stencil (one factorisation) makes the first step Newton's on the
            // accurate `γ`.
            let guess = self.guess;
            let probe = 0.5 * piecewise_gap::inner_stencil_reach(guess, 1.0);
            let probe = if guess - probe >= min_contact_ratio(kind) {
                -probe
            } else {
                probe
            };
            if let (Ok(at_guess), Ok(at_probe)) = (evaluate(guess), evaluate(guess + probe)) {
                slope_hint = Some((at_probe - at_guess) / probe)
                    .filter(|s| s.is_finite() && *s != 0.0)
                    .or(slope_hint);
            }
        }
        let root = find_root_with_slope(
            &mut evaluate,
            (min_contact_ratio(kind), MAX_CONTACT_RATIO),
            self.guess,
            slope_hint,
            // In `eps`, and in the controlled quantity relative to its target (where `γ` is
            // steep, as in deep states, an `eps` good to 1e-11 can leave a residual far above
            // the tolerance).
            (
                0.01 * self.tolerance,
                Some(0.01 * self.tolerance * target.abs()),
            ),
            60,
        )
        .map_err(|e| inverse_error(e, kind, target, self.controlled));
        self.stencils = stencils;
        self.probe_slope = false;
        self.slope_hint = slope_hint;
        let eps = root?.x;
        let neighbour = history
            .iter()
            .filter(|(at, _)| *at != eps)
            .max_by(|(a, _), (b, _)| (a - eps).abs().total_cmp(&(b - eps).abs()))
            .map(|(at, s)| (*at, s.gamma1, s.gamma2, s.system.region().outer()));
        // The root's sample becomes the state's (a piecewise profile's search sample gains its rim
        // intensity once the state is accepted: the estimate does not read it).
        let fine = match history.iter().position(|(at, _)| *at == eps) {
            Some(i) => history.remove(i).1,
            None => solver.concave_sample(kind, eps, n, outer_edge_hint(&history, eps))?,
        };
        Ok(RungRoot {
            eps,
            fine,
            neighbour,
        })
    }

    /// Slopes at the root: from the root and an earlier iterate where they lie far enough apart
    /// for rounding not to show (a secant converges to iterates 1e-13 apart, whose slope can be
    /// 8 times too small), else the previous rung's where that rung was close (its estimate
    /// below [`SLOPE_TRUSTED_ESTIMATE`]), else from a small step.
    fn root_slopes(&mut self, root: &RungRoot, n: usize) -> Result<Slopes> {
        let (eps, fine) = (root.eps, &root.fine);
        let outer_fine = fine.system.region().outer();
        let separated = root
            .neighbour
            .filter(|(at, ..)| (eps - at).abs() >= SLOPE_MIN_SEPARATION);
        if let Some((at, g1, g2, c)) = separated {
            return Ok([
                (fine.gamma1 - g1) / (eps - at),
                (fine.gamma2 - g2) / (eps - at),
                (outer_fine - c) / (eps - at),
            ]);
        }
        if let Some(slopes) = self.previous_slopes {
            return Ok(slopes);
        }
        let step = 1e-6_f64.min(0.5 * (MAX_CONTACT_RATIO - eps)).max(1e-9);
        let s = self.solver.search_sample(
            self.kind,
            eps + step,
            n,
            Some(outer_fine),
            self.stencils.at(n),
        )?;
        Ok([
            (s.gamma1 - fine.gamma1) / step,
            (s.gamma2 - fine.gamma2) / step,
            (s.system.region().outer() - outer_fine) / step,
        ])
    }

    /// The slope of the prescribed quantity among `slopes`.
    fn controlled_slope(&self, slopes: Slopes) -> f64 {
        match self.controlled {
            Controlled::Depth => slopes[0],
            Controlled::Force => slopes[1],
        }
    }

    /// The root's relative error: the discretisation error at fixed `eps` (the change from the
    /// rung below), carried to `eps` through the controlled quantity's slope and from there to
    /// the other quantity and the outer edge; plus the root search's own error, its residual
    /// over the slope, doubled because the slope is a secant's (the search stops at 1 % of the
    /// tolerance in `eps`, far above the discretisation error at a loose tolerance).
    fn rung_estimate(&mut self, root: &RungRoot, slopes: Slopes) -> Result<f64> {
        let (eps, fine) = (root.eps, &root.fine);
        let outer_fine = fine.system.region().outer();
        let coarse_n = NODE_LADDER[self.rung - 1];
        let coarse = match self.previous_root.take() {
            Some((m, at, sample)) if m == coarse_n && at == eps => sample,
            _ => self.solver.search_sample(
                self.kind,
                eps,
                coarse_n,
                Some(outer_fine),
                self.stencils.at(coarse_n),
            )?,
        };
        let slope = self.controlled_slope(slopes);
        let [slope1, slope2, outer_slope] = slopes;
        let (other_slope, other_fine, other_coarse) = match self.controlled {
            Controlled::Depth => (slope2, fine.gamma2, coarse.gamma2),
            Controlled::Force => (slope1, fine.gamma1, coarse.gamma1),
        };
        let eps_error = ((self.pick(fine) - self.pick(&coarse)).abs()
            + 2.0 * (self.pick(fine) - self.target).abs())
            / slope.abs();
        let other_error = (other_fine - other_coarse).abs() + other_slope.abs() * eps_error;
        // The outer edge (a free band's; the rim, exactly 1, for the others).
        let outer_error =
            (outer_fine - coarse.system.region().outer()).abs() + outer_slope.abs() * eps_error;
        let change = eps_error
            .max(other_error / other_fine.abs())
            .max(outer_error);
        let floor = free_edge_floor(fine.system.region());
        floored_estimate(change, floor, self.tolerance)
    }

    /// The next rung starts at this root with its slope (Newton's step at once) and outer
    /// edge; `kept` slopes are reused there when its own iterates lie too close together.
    fn climb_from(&mut self, root: RungRoot, slopes: Slopes, kept: Option<Slopes>, n: usize) {
        self.slope_hint = Some(self.controlled_slope(slopes));
        self.previous_slopes = kept;
        self.guess = root.eps;
        self.outer_guess = Some(root.fine.system.region().outer());
        self.previous_root = Some((n, root.eps, root.fine));
    }
}

/// The prescribed quantity of a sample: `γ1` under depth control, `γ2` under force control.
fn prescribed(controlled: Controlled, sample: &ConcaveSample) -> f64 {
    match controlled {
        Controlled::Depth => sample.gamma1,
        Controlled::Force => sample.gamma2,
    }
}
