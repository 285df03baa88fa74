//! A free band with the ring BEM: a contact band `[b, c]` whose both edges are free (the
//! profile's [`Contact::FreeBand`](crate::punch::Contact::FreeBand)).
//!
//! With `h = 1` (`a = E* = 1`) the gap `ĝ(r)` is defined on both sides of the ring radius. On
//! a band `[b, c]` the pressure is `d φ¹ + φ²` (`φ¹`: the field of `w = 1`, `φ²`: of `w = -ĝ`),
//! each with inverse-square-root coefficients `α_b` and `α_c` at the two edges. A free edge
//! carries none:
//!
//! ```text
//! d α¹_b + α²_b = 0    (inner edge)  ->  d = -α²_b / α¹_b
//! d α¹_c + α²_c = 0    (outer edge)  ->  R(c) = α²_c - α²_b α¹_c / α¹_b = 0
//! ```
//!
//! The first fixes the depth for a band; the second is one equation for the outer edge `c`
//! given the inner edge `b`, solved by the safeguarded secant. So the inner edge `b/a` (`eps`)
//! parametrises a band's states as it does the concave punches', `γ1(eps) = d/h` and
//! `γ2(eps) = F/(2 E* h a)` decrease with it. Depth or force control finds both edges at once by
//! Newton's method on `R(b, c) = 0`, `γ(b, c) = target` ([`BandSolver::band_at_target`])
//! at every rung of the node ladder ([`BandSolver::band_inverse`]), with the nested search
//! (the edge search inside the concave punches' search on `b`) where Newton does not converge.
//! Both unknown radii are found to the search's tolerance (1 % of the requested one) or its
//! rounding at each node count; the self-convergence estimate covers `b`, `c`, `γ1` and `γ2`
//! and the search's residual.
//!
//! **The contact never closes.** Near the axis the gap is `h (1 - 2r/a + ...)`: a linear-gap
//! dimple, whose full-contact pressure is logarithmically tensile at the apex (as the linear
//! gap's). The inner edge approaches the axis only as the load grows without bound, and the ring
//! BEM refuses `b < 1e-4 a` as for the linear gap.

use std::f64::consts::PI;

use crate::bem::ring::{ContactRegion, RingField, RingSystem};
use crate::error::Result;
use crate::numerics::roots::{find_root, RootError};
use crate::punch::PunchKind;

use super::{
    floored_estimate, free_edge_floor, free_edge_state, no_convergence, out_of_range,
    relative_change, starting_rung, ConcaveSample, RingBemSolver, RingState, FIRST_SEARCH_RUNG,
    MIN_BAND_RATIO, MIN_CONTACT_RATIO, NODE_LADDER,
};

/// Absolute tolerance of the outer edge `c/a` at each node count: far below every tolerance the
/// method accepts, so that the discretisation, not the search, sets the estimate.
const OUTER_EDGE_TOLERANCE: f64 = 1e-13;

/// The ring BEM's solver of free bands: its collocation systems and refinement ladder, asked for
/// bands `[b, c]` whose edges are both free.
pub(super) struct BandSolver<'a>(pub &'a RingBemSolver);

impl std::ops::Deref for BandSolver<'_> {
    type Target = RingBemSolver;
    fn deref(&self) -> &RingBemSolver {
        self.0
    }
}

impl BandSolver<'_> {
    /// The band `[b, c]` at a fixed node count: its collocation system and the fields
    /// of `w = 1` and `w = -ĝ`.
    fn band(&self, kind: &PunchKind, inner: f64, outer: f64, n: usize) -> Result<Band> {
        let system = self.0.system(ContactRegion::Band { inner, outer }, n);
        let minus_gap: Vec<f64> = system.radii().iter().map(|&r| -kind.gap(r)).collect();
        let singular = || no_convergence("singular collocation matrix".into());
        let one = system.solve(&vec![1.0; n]).ok_or_else(singular)?;
        let gap = system.solve(&minus_gap).ok_or_else(singular)?;
        Ok(Band { system, one, gap })
    }

    /// The band at a fixed node count with its inner edge at `eps`: the outer edge `c` where
    /// both edges are free (by the safeguarded secant on [`Band::mismatch`]), the depth
    /// `γ1 = d/h` and `γ2 = F/(2 E* h a)` (see the module docs). `outer_hint` starts the edge
    /// search (a nearby state's edge); without one it starts from [`outer_edge_guess`].
    pub(super) fn band_sample(
        &self,
        kind: &PunchKind,
        eps: f64,
        n: usize,
        outer_hint: Option<f64>,
    ) -> Result<ConcaveSample> {
        let (lo, hi) = (eps * (1.0 + 2.0 * MIN_BAND_RATIO), outer_edge_bound(eps));
        let guess = outer_hint
            .filter(|c| c.is_finite())
            .unwrap_or_else(|| outer_edge_guess(eps))
            .clamp(lo, hi);
        let what = format!(
            "{} with inner edge b/a = {}",
            kind.name(),
            crate::error::show(eps)
        );
        search_band(
            |outer| self.band(kind, eps, outer, n),
            0.0,
            (lo, hi, guess),
            (&what, "outer edge"),
        )
    }

    /// The band of half-width `w` with the stress intensity `K = intensity` at both
    /// edges: the centre `m` (band `[m - w, m + w]`) by the safeguarded secant on
    /// [`Band::mismatch`]. The JKR equilibria are parametrised by the width, not by the
    /// inner edge: a narrow adhesive band shifts toward the axis as it shrinks (at `d0/h = 0.1`
    /// wholly inside `r < a`), so the inner edge is not monotone along the curve, while the width
    /// is.
    fn band_width_sample(
        &self,
        kind: &PunchKind,
        half_width: f64,
        n: usize,
        centre_hint: Option<f64>,
        intensity: f64,
    ) -> Result<ConcaveSample> {
        let lo = half_width + MIN_CONTACT_RATIO;
        let hi = 3.0 + 3.0 * half_width;
        let guess = centre_hint
            .filter(|m| m.is_finite())
            .unwrap_or(1.0 + half_width * half_width)
            .clamp(lo, hi);
        let what = format!(
            "{} band of half-width {} a",
            kind.name(),
            crate::error::show(half_width)
        );
        search_band(
            |centre| self.band(kind, centre - half_width, centre + half_width, n),
            intensity,
            (lo, hi, guess),
            (&what, "centre"),
        )
    }

    /// [`RingBemSolver::band_with_edge_intensity`].
    pub(super) fn band_with_edge_intensity(
        &self,
        kind: &PunchKind,
        half_width: f64,
        intensity: f64,
        tolerance: f64,
        centre_hint: Option<f64>,
    ) -> Result<RingState> {
        RingBemSolver::check_tolerance(tolerance)?;
        if !(intensity.is_finite() && half_width.is_finite() && half_width > 0.0) {
            return Err(out_of_range(format!(
                "{} band of half-width {} with edge intensity {}: need a finite positive \
                 width and a finite intensity",
                kind.name(),
                crate::error::show(half_width),
                crate::error::show(intensity)
            )));
        }
        let last_centre = std::cell::Cell::new(centre_hint);
        let (fine, n, estimate) = self.0.refine(
            tolerance,
            |n| {
                let sample =
                    self.band_width_sample(kind, half_width, n, last_centre.get(), intensity)?;
                let region = sample.system.region();
                last_centre.set(Some(0.5 * (region.inner() + region.outer())));
                Ok(sample)
            },
            |s| {
                let region = s.system.region();
                vec![s.gamma1, s.gamma2, region.inner(), region.outer()]
            },
            |s| free_edge_floor(s.system.region()),
        )?;
        let eps = fine.system.region().inner();
        let mut state = free_edge_state(eps, fine, n, estimate)?;
        state.inner_stress_intensity = intensity;
        Ok(state)
    }
}

/// Iterations of [`BandSolver::band_at_target`] before it gives up (and the nested search
/// takes over).
const DIRECT_MAX_ITERATIONS: usize = 40;

/// Consecutive steps of [`BandSolver::band_at_target`] that leave the residual above 0.9 of
/// its previous size before it gives up. Near the root the residual sits at rounding and the
/// steps stop on their own size first.
const DIRECT_MAX_STALLED: usize = 4;

impl BandSolver<'_> {
    /// The band at a fixed node count with the depth (`depth_controlled`) or the force at
    /// `target` (`γ1` or `γ2`): both unknown edges at once, by Newton's method on
    ///
    /// ```text
    /// R(b, c) = 0              (both edges free, [`Band::mismatch`])
    /// γ(b, c)/target - 1 = 0   (γ = γ1 or γ2 at the depth of a free inner edge)
    /// ```
    ///
    /// with a Jacobian of `[R, γ1, γ2]` by differences at the start (or `jacobian`, a nearby
    /// problem's: the previous node count's) and Broyden's update after each step (each step
    /// one band: assembly and two solves), from the start `(b0, c0)`. Stops after a step
    /// below `eps_tolerance` in `b` (absolute) and in `c` (relative, at least ten times
    /// [`OUTER_EDGE_TOLERANCE`]), or where the next step would be and the target is met to
    /// `eps_tolerance` (relative), returning the target's residual there; a step that would
    /// leave `MIN_CONTACT_RATIO <= b < c <= hi` is shortened. `None` where it
    /// does not converge: the caller then runs the nested search (an edge search inside a
    /// search on `b`), which is safeguarded but costs several times more bands.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn band_at_target(
        &self,
        kind: &PunchKind,
        n: usize,
        target: f64,
        depth_controlled: bool,
        start: (f64, f64),
        jacobian: Option<BandJacobian>,
        eps_tolerance: f64,
    ) -> Option<BandTarget> {
        let newton = BandNewton {
            solver: self,
            kind,
            n,
            target,
            pick: if depth_controlled { 1 } else { 2 },
            eps_tolerance,
        };
        let (mut b, mut c) = start;
        if !(b.is_finite() && c.is_finite() && newton.admissible(b, c)) {
            return None;
        }
        let (mut v, mut band) = newton.values(b, c)?;
        let mut jacobian = match jacobian.filter(|j| j.iter().flatten().all(|x| x.is_finite())) {
            Some(given) => given,
            None => newton.differenced_jacobian(b, c, &v)?,
        };
        // Steps that did not shrink the residual (a start outside Newton's basin): after a few
        // the nested search takes over.
        let mut stalled = 0;
        for _ in 0..DIRECT_MAX_ITERATIONS {
            let f = newton.residual(&v);
            let mut step = newton.step(&jacobian, &f)?;
            let outer_tolerance = (10.0 * OUTER_EDGE_TOLERANCE).max(eps_tolerance * c);
            if step[0].abs() <= eps_tolerance && step[1].abs() <= outer_tolerance {
                return newton.converged((b, c), band, &f, step, jacobian);
            }
            newton.shorten(&mut step, b, c)?;
            let (next, next_band) = newton.values(b + step[0], c + step[1])?;
            broyden_update(&mut jacobian, step, &v, &next, c);
            stalled = if size(&newton.residual(&next)) < 0.9 * size(&f) {
                0
            } else {
                stalled + 1
            };
            if stalled >= DIRECT_MAX_STALLED {
                return None;
            }
            (b, c, v, band) = (b + step[0], c + step[1], next, next_band);
        }
        None
    }
}

/// The size of a residual `[R, γ/target - 1]`.
fn size(r: &[f64; 2]) -> f64 {
    r[0].hypot(r[1])
}

/// Broyden's update, `J += ((Δv - J s) sᵀ) / (sᵀ s)`, where the step is long enough for the
/// values' rounding (about 1e-14) not to swamp it: the Jacobian also gives the next node count
/// its start.
fn broyden_update(
    jacobian: &mut BandJacobian,
    step: [f64; 2],
    v: &[f64; 3],
    next: &[f64; 3],
    c: f64,
) {
    let norm = step[0] * step[0] + step[1] * step[1];
    if norm.sqrt() > BROYDEN_MIN_STEP * c {
        for (i, row) in jacobian.iter_mut().enumerate() {
            let predicted = row[0] * step[0] + row[1] * step[1];
            let miss = (next[i] - v[i]) - predicted;
            row[0] += miss * step[0] / norm;
            row[1] += miss * step[1] / norm;
        }
    }
}

/// Newton's method on both edges of a band at one node count
/// ([`BandSolver::band_at_target`]): the problem and its phases.
struct BandNewton<'a> {
    solver: &'a BandSolver<'a>,
    kind: &'a PunchKind,
    n: usize,
    target: f64,
    /// 1: depth control (`γ1`), 2: force control (`γ2`).
    pick: usize,
    eps_tolerance: f64,
}

impl BandNewton<'_> {
    /// The band's values `[R, γ1, γ2]` at `(b, c)`, `None` where they are not finite.
    fn values(&self, b: f64, c: f64) -> Option<([f64; 3], Band)> {
        let band = self.solver.band(self.kind, b, c, self.n).ok()?;
        let v = band.values();
        v.iter().all(|x| x.is_finite()).then_some((v, band))
    }

    /// The residual `[R, γ/target - 1]`.
    fn residual(&self, v: &[f64; 3]) -> [f64; 2] {
        [v[0], v[self.pick] / self.target - 1.0]
    }

    /// Whether `MIN_CONTACT_RATIO <= b < c <= hi` holds, with room for the band.
    fn admissible(&self, b: f64, c: f64) -> bool {
        (MIN_CONTACT_RATIO..=super::MAX_CONTACT_RATIO).contains(&b)
            && c > b * (1.0 + 2.0 * MIN_BAND_RATIO)
            && c <= outer_edge_bound(b)
    }

    /// The Jacobian by forward differences (steps far above rounding, far below the edges'
    /// scales).
    fn differenced_jacobian(&self, b: f64, c: f64, v: &[f64; 3]) -> Option<BandJacobian> {
        let (hb, hc) = (1e-7 * b.max(1e-3), 1e-7 * c);
        let (vb, _) = self.values(b + hb, c)?;
        let (vc, _) = self.values(b, c + hc)?;
        Some(std::array::from_fn(|i| {
            [(vb[i] - v[i]) / hb, (vc[i] - v[i]) / hc]
        }))
    }

    /// Newton's step for the residual `f`, `None` where the Jacobian is singular.
    fn step(&self, jacobian: &BandJacobian, f: &[f64; 2]) -> Option<[f64; 2]> {
        let target = self.target;
        let newton = [
            jacobian[0],
            [
                jacobian[self.pick][0] / target,
                jacobian[self.pick][1] / target,
            ],
        ];
        let det = newton[0][0] * newton[1][1] - newton[0][1] * newton[1][0];
        if !(det.is_finite() && det != 0.0) {
            return None;
        }
        Some([
            -(newton[1][1] * f[0] - newton[0][1] * f[1]) / det,
            -(-newton[1][0] * f[0] + newton[0][0] * f[1]) / det,
        ])
    }

    /// Shorten a step that leaves the admissible edges (or moves `b` by more than half);
    /// `None` after 30 halvings.
    fn shorten(&self, step: &mut [f64; 2], b: f64, c: f64) -> Option<()> {
        let mut shortened = 0;
        while !self.admissible(b + step[0], c + step[1]) || step[0].abs() > 0.5 * b {
            *step = [0.5 * step[0], 0.5 * step[1]];
            shortened += 1;
            if shortened > 30 {
                return None;
            }
        }
        Some(())
    }

    /// Converged: this state where it meets the target to the tolerance, else the state after
    /// the last (small) step, whose residual is far below the step's but not below the values'
    /// rounding; of the two the one with the smaller residuals where the step's only moved them
    /// in the rounding. The residual is returned for the caller's estimate.
    fn converged(
        &self,
        (b, c): (f64, f64),
        band: Band,
        f: &[f64; 2],
        step: [f64; 2],
        jacobian: BandJacobian,
    ) -> Option<BandTarget> {
        let (b, band, residual) = if f[1].abs() <= self.eps_tolerance {
            (b, band, f[1])
        } else {
            let (b_next, c_next) = (b + step[0], c + step[1]);
            if !self.admissible(b_next, c_next) {
                return None;
            }
            let (v_next, band_next) = self.values(b_next, c_next)?;
            let f_next = self.residual(&v_next);
            if size(&f_next) < size(f) {
                (b_next, band_next, f_next[1])
            } else {
                (b, band, f[1])
            }
        };
        Some(BandTarget {
            eps: b,
            sample: band.sample(0.0),
            jacobian,
            residual: residual.abs(),
        })
    }
}

impl BandSolver<'_> {
    /// The band at a depth (`depth_controlled`, `target = γ1 = d/h`) or a force
    /// (`target = γ2 = F/(2 E* h a)`), both edges by Newton's method at every rung of the node
    /// ladder ([`Self::band_at_target`]), each rung started from the previous rung's edges and
    /// Jacobian; a state whose inner edge needs a rung ([`starting_rung`]) more than one above
    /// the first climbs to the rung just below that one first, which starts the needed rung
    /// close to its root and is its rung below (six evaluations on the cheaper rung, two on the
    /// needed one, instead of the reverse). The estimate is the change of the state from
    /// the rung below (solved the same way, from this rung's edges, where the ladder skipped it;
    /// none on a rung below the one the inner edge needs, which only starts that one): of `b` and
    /// `c` (absolute, units of `a`) and of `γ1` and `γ2` (relative), plus twice the target's
    /// residual (the search's own error: each rung stops after a step below 1 % of the tolerance,
    /// and the residual of the state, at rounding then, is counted). `None` where Newton's method
    /// does not converge at some rung: the caller then runs the nested search.
    pub(super) fn band_inverse(
        &self,
        kind: &PunchKind,
        target: f64,
        tolerance: f64,
        depth_controlled: bool,
    ) -> Option<Result<RingState>> {
        let search_tolerance = 0.01 * tolerance;
        let controlled = if depth_controlled {
            super::Controlled::Depth
        } else {
            super::Controlled::Force
        };
        let start_eps = super::initial_ratio(kind, target, controlled);
        let mut start = (start_eps, outer_edge_guess(start_eps));
        let mut jacobian = None;
        let mut rung = FIRST_SEARCH_RUNG;
        let mut below: Option<(usize, BandTarget)> = None;
        loop {
            let n = NODE_LADDER[rung];
            let at = |n: usize, start: (f64, f64), jacobian: Option<BandJacobian>| {
                self.band_at_target(
                    kind,
                    n,
                    target,
                    depth_controlled,
                    start,
                    jacobian,
                    search_tolerance,
                )
            };
            let fine = at(n, start, jacobian)?;
            let edges = (fine.eps, fine.sample.system.region().outer());
            // The rung below: the previous one where the ladder did not skip it, else solved
            // from this rung's edges. None where this rung is below the one the inner edge
            // needs (the state is then a start for that rung, not an answer) or where the
            // search fails there (a rung too coarse for the state).
            let needed = starting_rung(edges.0);
            let coarse = match below.take() {
                Some((previous, found)) if previous + 1 == rung => Some(found),
                _ if rung < needed => None,
                _ => at(NODE_LADDER[rung - 1], edges, Some(fine.jacobian)),
            };
            let change = coarse.as_ref().map_or(f64::INFINITY, |coarse| {
                fine.change_from(coarse) + 2.0 * fine.residual
            });
            let floor = free_edge_floor(fine.sample.system.region());
            let estimate = match floored_estimate(change, floor, tolerance) {
                Ok(estimate) => estimate,
                Err(e) => return Some(Err(e)),
            };
            if estimate <= tolerance {
                return Some(
                    self.0
                        .concave_state(kind, fine.eps, fine.sample, n, estimate),
                );
            }
            if rung + 1 >= NODE_LADDER.len() {
                return Some(Err(no_convergence(if estimate.is_finite() {
                    format!(
                        "error estimate {estimate:.2e} at N = {n} exceeds the tolerance \
                         {tolerance:.1e}"
                    )
                } else {
                    format!("no error estimate at N = {n}: the search at the rung below failed")
                })));
            }
            start = edges;
            jacobian = Some(fine.jacobian);
            below = Some((rung, fine));
            // The rung below the needed one first: it starts the needed one and is its estimate's
            // rung below.
            rung = (rung + 1).max(needed.saturating_sub(1));
        }
    }
}

/// What [`BandSolver::band_at_target`] found at one node count.
pub(super) struct BandTarget {
    /// The inner edge `b/a`.
    pub eps: f64,
    /// The state there (both edges free, the target met).
    pub sample: ConcaveSample,
    /// The Jacobian of `[R, γ1, γ2]` in `(b, c)` at the end (Broyden's estimate).
    pub jacobian: BandJacobian,
    /// The target's residual there, `|γ/target - 1|` (the search's error; at rounding once
    /// converged, about 1e-10 for the widest bands).
    pub residual: f64,
}

impl BandTarget {
    /// The change from the state `coarse` (another node count's): of the edges `b` and `c`
    /// (absolute, units of `a`) and of `γ1` and `γ2` (relative), the largest.
    fn change_from(&self, coarse: &BandTarget) -> f64 {
        let outer = |t: &BandTarget| t.sample.system.region().outer();
        (self.eps - coarse.eps)
            .abs()
            .max((outer(self) - outer(coarse)).abs())
            .max(relative_change(self.sample.gamma1, coarse.sample.gamma1))
            .max(relative_change(self.sample.gamma2, coarse.sample.gamma2))
    }
}

/// The derivatives of a band's `[R, γ1, γ2]` ([`Band::values`]) in its edges
/// `(b, c)`, one row per value.
pub(super) type BandJacobian = [[f64; 2]; 3];

/// The least step (relative to the outer edge) that updates [`BandJacobian`] by Broyden's rule.
const BROYDEN_MIN_STEP: f64 = 1e-9;

/// A band at one node count: its system and the fields of `w = 1` and `w = -ĝ`.
struct Band {
    system: RingSystem,
    one: RingField,
    gap: RingField,
}

impl Band {
    /// Edge coefficient of the intensity `K`: `α = K sqrt((c - b)/(2π))`.
    fn coefficient(&self, intensity: f64) -> f64 {
        let region = self.system.region();
        intensity * ((region.outer() - region.inner()) / (2.0 * PI)).sqrt()
    }

    /// The depth `d/h` that gives the inner edge the intensity: `d α¹_b + α²_b = α`.
    fn depth(&self, intensity: f64) -> f64 {
        (self.coefficient(intensity) - self.gap.inner_coefficient) / self.one.inner_coefficient
    }

    /// At that depth, the outer edge's coefficient minus the wanted one,
    /// `d α¹_c + α²_c - α`, over `|α¹_c|` (order one whatever the node count): zero when both
    /// edges carry the intensity.
    fn mismatch(&self, intensity: f64) -> f64 {
        let depth = self.depth(intensity);
        (self.gap.rim_coefficient + depth * self.one.rim_coefficient - self.coefficient(intensity))
            / self.one.rim_coefficient.abs()
    }

    /// `[R, γ1, γ2]` with both edges free of intensity: the outer edge's mismatch
    /// ([`Self::mismatch`]), the depth `d/h` that frees the inner edge and the force
    /// `F/(2 E* h a)` there.
    fn values(&self) -> [f64; 3] {
        let gamma1 = self.depth(0.0);
        [
            self.mismatch(0.0),
            gamma1,
            0.5 * (gamma1 * self.one.force + self.gap.force),
        ]
    }

    /// The state at the depth of [`Self::depth`].
    fn sample(self, intensity: f64) -> ConcaveSample {
        let gamma1 = self.depth(intensity);
        let target = self.coefficient(intensity);
        let field = RingField {
            inner_coefficient: target,
            ..self.one.combined(gamma1, &self.gap, 1.0)
        };
        ConcaveSample {
            gamma1,
            gamma2: 0.5 * field.force,
            rim_stress_intensity: Some(self.system.rim_stress_intensity(&field)),
            field_depth: gamma1,
            piecewise_band: None,
            system: self.system,
            field,
        }
    }
}

/// A failed edge search, said with what was searched and where.
/// The last band a one-unknown search evaluated, kept so that the root's band is not solved
/// again (`Root::x` is the last point a search evaluates).
#[derive(Default)]
struct LastBand(std::cell::RefCell<Option<(f64, Band)>>);

impl LastBand {
    /// The search's residual: the mismatch `R` of the band `band_at(x)` from the edge
    /// intensity `intensity` ([`Band::mismatch`]), the band kept.
    fn residual<'a>(
        &'a self,
        band_at: impl Fn(f64) -> Result<Band> + 'a,
        intensity: f64,
    ) -> impl FnMut(f64) -> std::result::Result<f64, String> + 'a {
        move |x| {
            let band = band_at(x).map_err(|e| e.to_string())?;
            let mismatch = band.mismatch(intensity);
            *self.0.borrow_mut() = Some((x, band));
            Ok(mismatch)
        }
    }

    /// The band at `x`: the kept one if it is there, else solved by `band_at`.
    fn at(self, x: f64, band_at: impl Fn(f64) -> Result<Band>) -> Result<Band> {
        match self.0.into_inner() {
            Some((kept, band)) if kept == x => Ok(band),
            _ => band_at(x),
        }
    }
}

/// The band of `band_at(x)` whose edges both carry the intensity `intensity`, `x` found by the
/// safeguarded secant on [`Band::mismatch`] in `(lo, hi)` from `guess`; `what` and `unknown`
/// name the band and `x` in errors.
fn search_band(
    band_at: impl Fn(f64) -> Result<Band>,
    intensity: f64,
    (lo, hi, guess): (f64, f64, f64),
    (what, unknown): (&str, &str),
) -> Result<ConcaveSample> {
    let last = LastBand::default();
    let root = find_root(
        last.residual(&band_at, intensity),
        lo,
        hi,
        guess,
        OUTER_EDGE_TOLERANCE,
        80,
    )
    .map_err(|e| search_error(e, what, unknown, lo, hi))?;
    Ok(last.at(root.x, band_at)?.sample(intensity))
}

fn search_error(e: RootError, what: &str, unknown: &str, lo: f64, hi: f64) -> crate::error::Error {
    match e {
        RootError::NotBracketed { f_lo, f_hi, .. } => out_of_range(format!(
            "{what}: no {unknown} in [{lo:.6}, {hi:.6}] a where both edges are in equilibrium \
             (edge mismatches {f_lo:.2e}, {f_hi:.2e} at the ends)"
        )),
        RootError::NoConvergence {
            iterations,
            last_step,
        } => no_convergence(format!(
            "{what}: the {unknown} search stopped after {iterations} solves (last step \
             {last_step:.1e})"
        )),
        RootError::Evaluation(m) => no_convergence(m),
    }
}

/// Largest outer edge searched for the inner edge `eps`, `3 + 3 ln(a/b)` (units of `a`): about
/// twice the ring BEM's `c = 1.0001, 1.62, 3.60, 5.78 a` at `b = 0.9999, 0.6, 0.1, 0.01 a`.
fn outer_edge_bound(eps: f64) -> f64 {
    3.0 + 3.0 * (1.0 / eps).ln()
}

/// Starting outer edge for the inner edge `eps` (the search finds the exact edge): `a²/b` for
/// a band not far from the ring radius and, for a wide band, the logarithmic growth the ring
/// BEM's edges follow (`c = 2.44, 3.60, 4.77, 5.78 a` at `b = 0.3, 0.1, 0.03, 0.01 a`),
/// whichever is smaller.
pub(super) fn outer_edge_guess(eps: f64) -> f64 {
    (1.0 / eps).min(1.3 + (1.0 / eps).ln())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The direct solve of both edges and the nested search (the edge search inside a secant
    /// on `b`) find the same state at one node count, under depth and under force control; a
    /// start outside Newton's basin (a narrow band started at `c = 1.3 a`) gives up rather than
    /// return a wrong state.
    #[test]
    fn newton_on_both_edges_agrees_with_the_nested_search() {
        let owner = RingBemSolver::new();
        let solver = BandSolver(&owner);
        let n = 16;
        let band = PunchKind::built_in(crate::punch::Contact::FreeBand)[0].clone();
        for (depth_controlled, target) in [(true, 0.01), (true, 1.0), (false, 2.0), (false, 1e-4)] {
            let pick = |s: &ConcaveSample| if depth_controlled { s.gamma1 } else { s.gamma2 };
            let controlled = if depth_controlled {
                super::super::Controlled::Depth
            } else {
                super::super::Controlled::Force
            };
            let start = super::super::initial_ratio(&band, target, controlled);
            let direct = solver
                .band_at_target(
                    &band,
                    n,
                    target,
                    depth_controlled,
                    (start, outer_edge_guess(start)),
                    None,
                    1e-12,
                )
                .expect("Newton converges from the usual start");
            let nested = find_root(
                |eps| {
                    let s = solver
                        .band_sample(&band, eps, n, None)
                        .map_err(|e| e.to_string())?;
                    Ok(pick(&s) - target)
                },
                MIN_CONTACT_RATIO,
                super::super::MAX_CONTACT_RATIO,
                start,
                1e-13,
                80,
            )
            .unwrap();
            let outer = solver.band_sample(&band, nested.x, n, None).unwrap();
            let (b, c) = (direct.eps, direct.sample.system.region().outer());
            println!(
                "target {target}: direct b {b:.15} c {c:.15}, nested b {:.15} c {:.15}",
                nested.x,
                outer.system.region().outer()
            );
            assert!((b - nested.x).abs() < 1e-11, "b {b} against {}", nested.x);
            assert!((c - outer.system.region().outer()).abs() < 1e-11);
            assert!((pick(&direct.sample) / target - 1.0).abs() < 1e-11);
        }
        // A narrow band started far off: no state, or the right one.
        let wrong = solver.band_at_target(&band, n, 1e-4, false, (0.9968, 1.303), None, 1e-12);
        if let Some(found) = wrong {
            assert!((found.eps - 0.99683348).abs() < 1e-6, "{}", found.eps);
        }
    }
}
