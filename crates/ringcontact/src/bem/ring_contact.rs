//! The punch problems solved with the ring BEM ([`crate::bem::ring`]): fixed contact for the flat
//! punches, the free inner radius of the concave punches, depth and force control, and the
//! self-convergence error estimate. Dimensionless throughout (`a = 1`, `E* = 1`, and `d = 1` for
//! flat punches or `h = 1` for concave ones).
//!
//! **Concave punches at a given contact ratio.** On the annulus `[eps, 1]` the deflection is
//! `w = d - h ĝ(r)`. By linearity the pressure is `d φ¹ + h φ²`, with `φ¹` the field for `w = 1`
//! and `φ²` the field for `w = -ĝ`. A free (non-adhesive) inner edge carries no singularity, so
//! `d φ¹(b) + h φ²(b) = 0`, which gives `γ1 = d/h = -φ²(b)/φ¹(b)` and
//! `γ2 = (γ1 F¹ + F²) / 2` from one factorisation and two right-hand sides.
//! A piecewise profile's piecewise-cubic gap, whose kinks the collocation converges on only
//! algebraically, takes `γ1`, `γ2` and the rim intensity from its flat band's fields instead
//! (`ring_contact/piecewise_gap.rs`); its collocated field only draws the pressure samples.
//!
//! **Depth or force control** inverts `γ1(eps)` or `γ2(eps)` (both decrease monotonically) by a
//! safeguarded secant iteration on `eps`.
//!
//! **Error estimate.** Each state is computed with two node counts from a ladder; the difference
//! bounds the error of the coarser one and is reported as the estimate for the finer one (a
//! conservative choice, since convergence is geometric). The ladder is climbed until the estimate
//! meets the tolerance; if it never does, that is an error, not a result.

use std::f64::consts::PI;
use std::sync::atomic::{AtomicUsize, Ordering};

use crate::bem::ring::{ContactRegion, RingField, RingSystem};
use crate::error::{Error, Result};
use crate::numerics::roots::RootError;
use crate::numerics::tanh_sinh::TanhSinhRule;
use crate::punch::starting_fit;
use crate::punch::PunchKind;

use piecewise_gap::{BandEdges, InnerStencil};

mod free_band;
mod inverse;
mod piecewise_gap;

/// Name of this method on the command line and in JSON.
pub const METHOD: &str = "ring-bem";

/// Node counts tried in turn by the adaptive refinement. The rungs above 80 serve the widest
/// rings of steep-walled profiles (`1 - ρ^50` at `b = 0.004 a` changes by 3e-5
/// from 64 to 80 nodes and by 2e-11 from 96 to 128); every other state meets its tolerance
/// below them.
const NODE_LADDER: [usize; 11] = [12, 16, 20, 24, 32, 40, 48, 64, 80, 96, 128];

/// Smallest contact ratio `b/a` of an annulus the method accepts (validated down to here).
pub(crate) const MIN_CONTACT_RATIO: f64 = 1e-4;
/// Largest contact ratio `b/a` the method accepts (a ring of width `1e-4 a`).
pub(crate) const MAX_CONTACT_RATIO: f64 = 0.9999;

/// Smallest contact ratio a piecewise profile's search visits: its band functionals
/// ([`piecewise_gap`]) settle to 1e-11 for `b >= 0.004 a` and to about 1e-9 at `1e-3 a`, while at
/// `1e-4 a` they return nonsense (`γ1 = -1322` for a sampled cosine dimple): a search that
/// reached down there wandered for 60 solves instead of saying that the state needs a narrower
/// ring.
const PIECEWISE_MIN_CONTACT_RATIO: f64 = 1e-3;

/// The smallest contact ratio the inverse problem of `kind` searches.
fn min_contact_ratio(kind: &PunchKind) -> f64 {
    if kind.piecewise().is_some() {
        PIECEWISE_MIN_CONTACT_RATIO
    } else {
        MIN_CONTACT_RATIO
    }
}

/// Below this relative tolerance the method's rounding floor (about 1e-13 relative) would be
/// mistaken for convergence.
pub(crate) const MIN_TOLERANCE: f64 = 1e-12;

/// Rounding floor of the method's dimensionless results (relative): node counts that agree better
/// than this are not taken as proof of a smaller error (converged results at N = 16..64 scatter
/// by 1e-14 to 1e-13).
const ROUNDING_FLOOR: f64 = 1e-13;

/// On a band `[b, c]` a free edge's position and the depth that places it there have a rounding
/// floor `c/b` times this: the free inner edge's depth of a linear gap at N = 32..128 nodes scatters
/// by 5e-10 relative at `b/c = 1e-4`, 5e-11 at 1e-3, 6e-12 at 1e-2, 4e-13 at 0.1 (whichever
/// quadrature assembles the rows: `φ(b) = 0` extrapolates the field to the edge). Node counts
/// that agree better than this are not taken as proof of a smaller error.
const FREE_EDGE_ROUNDING_PER_RATIO: f64 = 5e-14;

/// The rounding floor of a state with a free edge solved on `region` (and of the intensity at
/// any band's inner edge, free or not): [`ROUNDING_FLOOR`], or [`FREE_EDGE_ROUNDING_PER_RATIO`]
/// `c/b` where that is larger.
pub(crate) fn free_edge_floor(region: ContactRegion) -> f64 {
    ROUNDING_FLOOR.max(FREE_EDGE_ROUNDING_PER_RATIO * region.outer() / region.inner())
}

/// A rung's error estimate from the `change` between its samples: never below the samples'
/// rounding `floor`, and an error where the floor is above the tolerance and the rungs agree
/// within it (the ladder cannot certify the tolerance; climbing further only scatters).
pub(crate) fn floored_estimate(change: f64, floor: f64, tolerance: f64) -> Result<f64> {
    if floor > tolerance && change <= floor {
        return Err(out_of_range(format!(
            "tolerance {tolerance:.1e} is below the rounding floor {floor:.1e} of a free edge at \
             this contact ratio (5e-14 c/b on the band [b, c]: node counts scatter by that \
             much); use a tolerance >= {floor:.1e}"
        )));
    }
    Ok(change.max(floor))
}

/// Tension (relative to the largest pressure sample) above which a sample counts as tensile.
const TENSION_TOLERANCE: f64 = 1e-9;

/// Radii `r = b k / HOLE_PROBES`, `k = 0..HOLE_PROBES`, at which the hole's floor is checked.
pub const HOLE_PROBES: usize = 8;

/// Overlap of the surface and the hole's floor, relative to the depth, above which the punch
/// touches the floor (far above the method's rounding and its 1e-9 default tolerance).
pub const HOLE_OVERLAP_TOLERANCE: f64 = 1e-7;

/// Tanh-sinh step used for every row integral (about 1e-15 relative per row).
const QUADRATURE_STEP: f64 = 1.0 / 16.0;

/// Tanh-sinh step of the rows of systems with more than [`COARSE_QUADRATURE_NODES`] nodes,
/// whose basis polynomials of degree 95 and more the coarser step integrates only to about 1e-9.
const FINE_QUADRATURE_STEP: f64 = 1.0 / 32.0;

/// The largest node count whose rows are integrated with [`QUADRATURE_STEP`].
const COARSE_QUADRATURE_NODES: usize = 80;

/// A dimensionless pressure sample `(r/a, p a/(E* L))` with `L = d` (flat) or `L = h` (concave).
type ScaledPressure = (f64, f64);

/// Result of a ring-BEM state in dimensionless form.
#[derive(Clone, Debug)]
pub struct RingState {
    /// Contact ratio `b/a` (0 for full contact).
    pub eps: f64,
    /// Outer contact edge `c/a`: 1 (the rim) for every punch but a free band.
    pub outer_edge: f64,
    /// Flat punches: `γ`. Concave punches: `γ2` is in `gamma2` and this is `None`.
    pub gamma: Option<f64>,
    /// `γ1 = d/h` (concave).
    pub gamma1: Option<f64>,
    /// `γ2 = F/(2 E* h a)` (concave).
    pub gamma2: Option<f64>,
    /// Stress intensity at the rim, units of `E* L / sqrt(a)`.
    pub rim_stress_intensity: f64,
    /// Stress intensity at the inner edge, units of `E* L / sqrt(a)`.
    pub inner_stress_intensity: f64,
    /// Pressure at the collocation radii, ascending in `r`.
    pub pressure: Vec<ScaledPressure>,
    /// Estimated error (see [`crate::solution::Solution::error_estimate`]).
    pub error_estimate: f64,
    /// Unknowns of the finer discretisation.
    pub unknowns: usize,
}

/// A prescribed contact band `[b, c]` pressed to depth `d` by a punch of gap `g(r)`: the force
/// and the stress intensity factors at both edges (dimensionless, `a = E* = 1`; `K` in units of
/// `E* sqrt(a)`). An edge where `K = 0` is free (non-adhesive); `K > 0` a compressive edge, the
/// Griffith condition `K² = 2 E* Δw` an adhesive one.
#[derive(Clone, Debug)]
pub struct BandState {
    /// Inner edge `b/a`.
    pub inner: f64,
    /// Outer edge `c/a`.
    pub outer: f64,
    /// Depth `d/a` of the punch's reference plane (where `g = 0`).
    pub depth: f64,
    /// `F / (E* a²)`.
    pub force: f64,
    /// `K` at the inner edge, `lim sqrt(2π (r - b)) p(r)`.
    pub inner_stress_intensity: f64,
    /// `K` at the outer edge, `lim sqrt(2π (c - r)) p(r)`.
    pub outer_stress_intensity: f64,
    /// Largest change of the force (relative) and of either intensity (relative to the larger
    /// intensity or to the band's natural scale `F / (2π r_mid sqrt(c - b))`) between the last
    /// two node counts of the ladder.
    pub error_estimate: f64,
    /// Unknowns of the finer discretisation.
    pub unknowns: usize,
}

/// Narrowest band accepted, `c/b - 1` (the annulus's `1 - 0.9999`).
const MIN_BAND_RATIO: f64 = 1e-4;

/// A concave state at fixed `eps` and fixed node count.
struct ConcaveSample {
    gamma1: f64,
    gamma2: f64,
    /// Rim intensity, units of `E* h / sqrt(a)` (`None` in a piecewise profile's search sample,
    /// [`RingBemSolver::search_sample`]).
    rim_stress_intensity: Option<f64>,
    system: RingSystem,
    /// The collocated pressure field (pressure samples, the hole's floor).
    field: RingField,
    /// The depth `d/h` the field was built with: `gamma1`, except for a piecewise profile, whose
    /// `γ1`, `γ2` and rim intensity come from [`piecewise_gap`] while its field (collocated,
    /// converging algebraically at the table's points) only draws the pressure and checks the
    /// surface.
    field_depth: f64,
    /// A piecewise profile's band fields, which draw the surface in the hole to the method's
    /// accuracy (the collocated field's is algebraic).
    piecewise_band: Option<piecewise_gap::GapBand>,
}

/// The ring-BEM solver; holds the quadrature rule so it is built once, and counts the
/// collocation systems it assembles and factorises.
pub struct RingBemSolver {
    rule: TanhSinhRule,
    /// The rule of [`FINE_QUADRATURE_STEP`], for the ladder's top rungs.
    fine_rule: TanhSinhRule,
    /// The rule of [`piecewise_gap::BAND_INTEGRAL_STEP`], for a table band's integrals.
    band_rule: TanhSinhRule,
    factorisations: AtomicUsize,
}

impl Default for RingBemSolver {
    fn default() -> Self {
        Self::new()
    }
}

fn no_convergence(reason: String) -> Error {
    Error::NoConvergence {
        method: METHOD.into(),
        reason,
    }
}

fn out_of_range(reason: String) -> Error {
    Error::OutOfRange {
        method: METHOD.into(),
        reason,
    }
}

fn relative_change(fine: f64, coarse: f64) -> f64 {
    (fine - coarse).abs() / fine.abs().max(f64::MIN_POSITIVE)
}

impl RingBemSolver {
    /// A solver with the default quadrature.
    pub fn new() -> Self {
        Self {
            rule: TanhSinhRule::new(QUADRATURE_STEP),
            fine_rule: TanhSinhRule::new(FINE_QUADRATURE_STEP),
            band_rule: TanhSinhRule::new(piecewise_gap::BAND_INTEGRAL_STEP),
            factorisations: AtomicUsize::new(0),
        }
    }

    /// Collocation systems assembled and factorised by this solver so far (every node count,
    /// every step of every edge search).
    pub fn factorisations(&self) -> usize {
        self.factorisations.load(Ordering::Relaxed)
    }

    /// The rule that integrates the deflection off the contact of a field of `nodes` unknowns
    /// ([`RingSystem::deflection_beyond`], [`RingSystem::deflection_in_hole`]): the one that
    /// assembles its rows, fine enough for its basis polynomials' degree.
    pub(crate) fn deflection_rule(&self, nodes: usize) -> &TanhSinhRule {
        if nodes > COARSE_QUADRATURE_NODES {
            &self.fine_rule
        } else {
            &self.rule
        }
    }

    /// The collocation system of `region` at `nodes` unknowns, assembled with the rule its
    /// node count needs (and counted).
    pub(crate) fn system(&self, region: ContactRegion, nodes: usize) -> RingSystem {
        self.factorisations.fetch_add(1, Ordering::Relaxed);
        let rule = if nodes > COARSE_QUADRATURE_NODES {
            &self.fine_rule
        } else {
            &self.rule
        };
        RingSystem::assemble(region, nodes, rule)
    }

    fn check_tolerance(tolerance: f64) -> Result<()> {
        if tolerance < MIN_TOLERANCE {
            return Err(out_of_range(format!(
                "tolerance {tolerance:e} is below the ring BEM's rounding floor; use >= {MIN_TOLERANCE:e}"
            )));
        }
        Ok(())
    }

    fn check_ratio(eps: f64) -> Result<()> {
        if !(MIN_CONTACT_RATIO..=MAX_CONTACT_RATIO).contains(&eps) {
            return Err(out_of_range(format!(
                "contact ratio b/a = {} is outside the validated range \
                 [{MIN_CONTACT_RATIO}, {MAX_CONTACT_RATIO}] of the annulus discretisation",
                crate::error::show(eps)
            )));
        }
        Ok(())
    }

    fn check_band(inner: f64, outer: f64, depth: f64) -> Result<()> {
        if !(inner.is_finite() && outer.is_finite() && depth.is_finite())
            || inner <= 0.0
            || outer <= inner * (1.0 + MIN_BAND_RATIO)
        {
            return Err(out_of_range(format!(
                "band [{}, {}] at depth {}: need finite 0 < b and c > b (1 + {MIN_BAND_RATIO})",
                crate::error::show(inner),
                crate::error::show(outer),
                crate::error::show(depth)
            )));
        }
        Ok(())
    }

    /// Climb the node ladder until `values(n)` changes by less than `tolerance` (relative, per
    /// component) between consecutive rungs. Returns the finer sample, its rung and the estimate.
    fn refine<T>(
        &self,
        tolerance: f64,
        sample: impl FnMut(usize) -> Result<T>,
        values: impl Fn(&T) -> Vec<f64>,
        floor: impl Fn(&T) -> f64,
    ) -> Result<(T, usize, f64)> {
        self.refine_by(tolerance, sample, floor, |fine, coarse| {
            values(fine)
                .iter()
                .zip(values(coarse))
                .map(|(f, c)| relative_change(*f, c))
                .fold(0.0, f64::max)
        })
    }

    /// [`Self::refine`] with the change between two rungs given by `change(fine, coarse)`
    /// (never below the finer sample's rounding `floor`: [`ROUNDING_FLOOR`], or
    /// [`free_edge_floor`] for a free edge).
    fn refine_by<T>(
        &self,
        tolerance: f64,
        mut sample: impl FnMut(usize) -> Result<T>,
        floor: impl Fn(&T) -> f64,
        change: impl Fn(&T, &T) -> f64,
    ) -> Result<(T, usize, f64)> {
        let mut coarse = sample(NODE_LADDER[0])?;
        let mut last_estimate = f64::INFINITY;
        for &n in &NODE_LADDER[1..] {
            let fine = sample(n)?;
            let estimate = floored_estimate(change(&fine, &coarse), floor(&fine), tolerance)?;
            if estimate <= tolerance {
                return Ok((fine, n, estimate));
            }
            last_estimate = estimate;
            coarse = fine;
        }
        Err(no_convergence(format!(
            "self-convergence estimate {last_estimate:.2e} at N = {} nodes exceeds the tolerance {tolerance:.1e}",
            NODE_LADDER[NODE_LADDER.len() - 1]
        )))
    }

    /// The band `[inner, outer]` held in contact at `depth` by a punch of gap `gap(r)` (any
    /// profile, `r` in units of `a`): `w(r) = depth - gap(r)` on the band, the force and both
    /// edges' stress intensity factors, refined until the estimate meets `tolerance`.
    pub fn prescribed_band(
        &self,
        gap: impl Fn(f64) -> f64,
        inner: f64,
        outer: f64,
        depth: f64,
        tolerance: f64,
    ) -> Result<BandState> {
        Self::check_tolerance(tolerance)?;
        Self::check_band(inner, outer, depth)?;
        let region = ContactRegion::Band { inner, outer };
        self.band_refined(inner, outer, tolerance, |n: usize| -> Result<BandState> {
            let system = self.system(region, n);
            let target: Vec<f64> = system.radii().iter().map(|&r| depth - gap(r)).collect();
            if target.iter().any(|w| !w.is_finite()) {
                return Err(out_of_range("the gap is not finite on the band".into()));
            }
            let field = system
                .solve(&target)
                .ok_or_else(|| no_convergence("singular collocation matrix".into()))?;
            Ok(BandState {
                inner,
                outer,
                depth,
                force: field.force,
                inner_stress_intensity: system.inner_stress_intensity(&field),
                outer_stress_intensity: system.rim_stress_intensity(&field),
                error_estimate: f64::NAN,
                unknowns: n,
            })
        })
    }

    /// The band `[inner, outer]` held in contact at `depth` (`d/h`) by the punch `kind` (gap
    /// `ĝ(r)`, `h = a = E* = 1`): [`Self::prescribed_band`] for every punch whose gap is
    /// analytic on the band; a piecewise profile's piecewise cubic through its flat band's fields
    /// (`ring_contact/piecewise_gap.rs`), which keeps the geometric convergence the collocation of its kinks
    /// loses.
    pub fn punch_band(
        &self,
        kind: &PunchKind,
        inner: f64,
        outer: f64,
        depth: f64,
        tolerance: f64,
    ) -> Result<BandState> {
        let Some(pieces) = kind.piecewise() else {
            return self.prescribed_band(|r| kind.gap(r), inner, outer, depth, tolerance);
        };
        Self::check_tolerance(tolerance)?;
        Self::check_band(inner, outer, depth)?;
        self.band_refined(inner, outer, tolerance, |n: usize| -> Result<BandState> {
            let band = piecewise_gap::GapBands(self).gap_functionals(&pieces, inner, outer, n)?;
            Ok(BandState {
                inner,
                outer,
                depth,
                force: band.force(depth),
                inner_stress_intensity: band.inner_intensity(depth),
                outer_stress_intensity: band.outer_intensity(depth).ok_or_else(|| {
                    no_convergence("the band's outer edge was not computed".into())
                })?,
                error_estimate: f64::NAN,
                unknowns: n,
            })
        })
    }

    /// A band's state refined on the node ladder until the force and both intensities settle
    /// (intensities near zero, a free edge, are compared on the larger intensity or the band's
    /// natural scale `F / (2π r_mid sqrt(c - b))`, not on themselves).
    fn band_refined(
        &self,
        inner: f64,
        outer: f64,
        tolerance: f64,
        sample: impl FnMut(usize) -> Result<BandState>,
    ) -> Result<BandState> {
        let change = |fine: &BandState, coarse: &BandState| {
            let scale = fine
                .inner_stress_intensity
                .abs()
                .max(fine.outer_stress_intensity.abs())
                .max(fine.force.abs() / (PI * (inner + outer) * (outer - inner).sqrt()))
                .max(f64::MIN_POSITIVE);
            relative_change(fine.force, coarse.force)
                .max((fine.inner_stress_intensity - coarse.inner_stress_intensity).abs() / scale)
                .max((fine.outer_stress_intensity - coarse.outer_stress_intensity).abs() / scale)
        };
        let (mut state, _, estimate) = self
            .refine_by(tolerance, sample, |_| ROUNDING_FLOOR, change)
            .map_err(|e| match e {
                Error::NoConvergence { reason, .. } => {
                    no_convergence(format!("band [{inner}, {outer}]: {reason}"))
                }
                other => other,
            })?;
        state.error_estimate = estimate;
        Ok(state)
    }

    /// The flat disk (`eps = 0`) or fixed annulus (`0 < eps <= 0.9999`) at unit depth: `γ(eps)`.
    pub fn flat(&self, eps: f64, tolerance: f64) -> Result<RingState> {
        Ok(self.flat_with_hole_lag(eps, tolerance, false)?.0)
    }

    /// The fixed annulus `[eps, 1]` pressed to unit depth ([`Self::flat`]) and how far its
    /// surface in the hole lags behind the punch, `1 - w(r)` at the radii of [`hole_probes`]
    /// (positive: the surface there sinks less than the punch).
    pub fn flat_hole_lag(&self, eps: f64, tolerance: f64) -> Result<(RingState, Vec<f64>)> {
        self.flat_with_hole_lag(eps, tolerance, true)
    }

    fn flat_with_hole_lag(
        &self,
        eps: f64,
        tolerance: f64,
        with_lag: bool,
    ) -> Result<(RingState, Vec<f64>)> {
        Self::check_tolerance(tolerance)?;
        let region = if eps == 0.0 {
            ContactRegion::Disk
        } else {
            Self::check_ratio(eps)?;
            ContactRegion::Annulus { eps }
        };
        let (sample, n, estimate) = self.refine(
            tolerance,
            |n| {
                let system = self.system(region, n);
                let field = system
                    .solve(&vec![1.0; n])
                    .ok_or_else(|| no_convergence("singular collocation matrix".into()))?;
                Ok((system, field))
            },
            |(_, field)| vec![0.5 * field.force],
            |_| ROUNDING_FLOOR,
        )?;
        let (system, field) = sample;
        let lag = if with_lag && eps > 0.0 {
            hole_probes(eps)
                .map(|r| {
                    let w = system.deflection_in_hole(&field, r, &self.rule);
                    1.0 - w.unwrap_or(f64::NAN)
                })
                .collect()
        } else {
            Vec::new()
        };
        let state = RingState {
            eps,
            outer_edge: 1.0,
            gamma: Some(0.5 * field.force),
            gamma1: None,
            gamma2: None,
            rim_stress_intensity: system.rim_stress_intensity(&field),
            inner_stress_intensity: system.inner_stress_intensity(&field),
            pressure: pressure_profile(&system, &field),
            error_estimate: estimate,
            unknowns: n,
        };
        Ok((state, lag))
    }

    /// Concave punch at a fixed node count and contact ratio.
    /// `outer_hint`: a guess of a free band's outer edge (from a nearby state), ignored by the
    /// punches whose outer edge is the rim.
    fn concave_sample(
        &self,
        kind: &PunchKind,
        eps: f64,
        n: usize,
        outer_hint: Option<f64>,
    ) -> Result<ConcaveSample> {
        self.concave_sample_with(
            kind,
            eps,
            n,
            outer_hint,
            BandEdges::Both,
            &mut InnerStencil::default(),
        )
    }

    /// [`Self::concave_sample`] for a search on the inner edge, which needs `γ1` and `γ2` only:
    /// a piecewise profile's band is built without its rim's derivative (six factorisations instead of
    /// eleven), so its `rim_stress_intensity` is `None` until [`Self::completed`] adds it. The
    /// same as [`Self::concave_sample`] for every other punch. A search passes the same
    /// `stencil` to all its samples at one node count: a piecewise profile's samples close to the first
    /// reuse its neighbouring bands ([`InnerStencil`]).
    fn search_sample(
        &self,
        kind: &PunchKind,
        eps: f64,
        n: usize,
        outer_hint: Option<f64>,
        stencil: &mut InnerStencil,
    ) -> Result<ConcaveSample> {
        self.concave_sample_with(kind, eps, n, outer_hint, BandEdges::Inner, stencil)
    }

    fn concave_sample_with(
        &self,
        kind: &PunchKind,
        eps: f64,
        n: usize,
        outer_hint: Option<f64>,
        edges: BandEdges,
        stencil: &mut InnerStencil,
    ) -> Result<ConcaveSample> {
        if kind.is_free_band() {
            return free_band::BandSolver(self).band_sample(kind, eps, n, outer_hint);
        }
        // A piecewise profile's collocated field (which draws the pressure) is solved on its band's system.
        let (system, piecewise_band) = match kind.piecewise() {
            Some(pieces) => {
                let band =
                    piecewise_gap::GapBands(self).gap_band(&pieces, eps, 1.0, n, edges, stencil)?;
                (band.system().clone(), Some(band))
            }
            None => (self.system(ContactRegion::Annulus { eps }, n), None),
        };
        let collocated = Self::collocated_sample(kind, system)?;
        match piecewise_band {
            Some(band) => {
                let gamma1 = band.functionals.free_inner_depth();
                Ok(ConcaveSample {
                    gamma1,
                    gamma2: 0.5 * band.functionals.force(gamma1),
                    rim_stress_intensity: band.functionals.outer_intensity(gamma1),
                    piecewise_band: Some(band),
                    ..collocated
                })
            }
            None => Ok(collocated),
        }
    }

    /// The concave punch's gap collocated on `system` (an annulus with its rim at `a`): the
    /// depth of a free inner edge, `γ1 = -α²_b / α¹_b` from the fields of `w = 1` and `w = -ĝ`,
    /// its force and rim intensity. Spectrally accurate for an analytic gap; for a piecewise profile's
    /// piecewise cubic only algebraically (its value there draws the pressure and starts the
    /// search, [`piecewise_gap`] gives the state).
    fn collocated_sample(kind: &PunchKind, system: RingSystem) -> Result<ConcaveSample> {
        let n = system.unknowns();
        let unit_depth = vec![1.0; n];
        let minus_gap: Vec<f64> = system.radii().iter().map(|&r| -kind.gap(r)).collect();
        let singular = || no_convergence("singular collocation matrix".into());
        let depth_field = system.solve(&unit_depth).ok_or_else(singular)?;
        let gap_field = system.solve(&minus_gap).ok_or_else(singular)?;
        let gamma1 = -gap_field.inner_coefficient / depth_field.inner_coefficient;
        let field = RingField {
            inner_coefficient: 0.0,
            ..depth_field.combined(gamma1, &gap_field, 1.0)
        };
        Ok(ConcaveSample {
            gamma1,
            gamma2: 0.5 * field.force,
            rim_stress_intensity: Some(system.rim_stress_intensity(&field)),
            field_depth: gamma1,
            piecewise_band: None,
            system,
            field,
        })
    }

    /// A search sample made whole: a piecewise profile's rim intensity added
    /// ([`RingBemSolver::complete_outer_edge`], the same to the bit as a full sample's).
    fn completed(&self, kind: &PunchKind, mut sample: ConcaveSample) -> Result<ConcaveSample> {
        if let (Some(pieces), Some(band)) = (kind.piecewise(), sample.piecewise_band.as_mut()) {
            piecewise_gap::GapBands(self).complete_outer_edge(&pieces, band)?;
            sample.rim_stress_intensity = band.functionals.outer_intensity(sample.gamma1);
        }
        Ok(sample)
    }

    /// The punch must not touch the floor of the hole: the surface there stays clear of the
    /// punch, `w(r) >= d - g(r)` for `r < b` (deflection positive into the solid), checked at
    /// [`HOLE_PROBES`] radii. A profile flatter than a parabola at the axis (`1 - ρ^n`
    /// with `n > 2`) touches the floor before the ring closes: its contact is then a disk and an
    /// annulus, which one annulus does not model.
    fn check_hole_clear(&self, kind: &PunchKind, eps: f64, sample: &ConcaveSample) -> Result<()> {
        if !kind.has_rim() {
            self.check_clear_beyond(kind, sample)?;
        }
        let (depth, inside) = self.hole_surface(kind, sample);
        if let Some((r, overlap)) = first_overlap(kind, depth, hole_probes(eps), inside) {
            return Err(out_of_range(format!(
                "the {kind} touches the floor of its hole at r/a = {} before the ring \
                 [{}, 1] closes (the surface would rise {overlap:.2e} h into the punch): the \
                 contact there is a disk and an annulus, which the ring BEM's single annulus \
                 does not model",
                crate::error::show(r),
                crate::error::show(eps)
            )));
        }
        Ok(())
    }

    /// The depth `d/h` of a concave sample's field and its surface `w(r)` in the hole (units
    /// of `h`): the table's from its band fields, every other punch's from its collocated field.
    #[allow(clippy::type_complexity)]
    fn hole_surface<'s>(
        &'s self,
        kind: &PunchKind,
        sample: &'s ConcaveSample,
    ) -> (f64, Box<dyn Fn(f64) -> Option<f64> + 's>) {
        match (kind.piecewise(), &sample.piecewise_band) {
            (Some(pieces), Some(band)) => {
                let surface = band.hole_surface(&pieces, sample.gamma1, &self.rule);
                (sample.gamma1, Box::new(move |r| surface.at(r, &self.rule)))
            }
            _ => (
                sample.field_depth,
                Box::new(|r| {
                    sample
                        .system
                        .deflection_in_hole(&sample.field, r, &self.rule)
                }),
            ),
        }
    }

    /// Beyond a free outer edge `c` the surface stays clear of the punch as well,
    /// `w(r) >= d - g(r)`, checked at [`HOLE_PROBES`] radii `c + (c - b) k / HOLE_PROBES`.
    fn check_clear_beyond(&self, kind: &PunchKind, sample: &ConcaveSample) -> Result<()> {
        let region = sample.system.region();
        let (inner, outer) = (region.inner(), region.outer());
        let radii =
            (1..=HOLE_PROBES).map(|k| outer + (outer - inner) * k as f64 / HOLE_PROBES as f64);
        let beyond = |r| {
            sample
                .system
                .deflection_beyond(&sample.field, r, &self.rule)
        };
        if let Some((r, overlap)) = first_overlap(kind, sample.field_depth, radii, beyond) {
            return Err(out_of_range(format!(
                "the {kind} touches the surface at r/a = {} beyond its contact's outer edge \
                 c/a = {} (the surface would rise {overlap:.2e} h into the punch): the contact \
                 there is not one band",
                crate::error::show(r),
                crate::error::show(outer)
            )));
        }
        Ok(())
    }

    fn concave_state(
        &self,
        kind: &PunchKind,
        eps: f64,
        fine: ConcaveSample,
        n: usize,
        estimate: f64,
    ) -> Result<RingState> {
        self.check_hole_clear(kind, eps, &fine)?;
        // The collocated field's own error (the table's: its depth against the accurate γ1)
        // widens the tolerance of the sign check by ten times that error.
        let field_error = (fine.field_depth - fine.gamma1).abs() / fine.gamma1.abs();
        let state = free_edge_state(eps, fine, n, estimate)?;
        check_compressive(
            &state.pressure,
            eps,
            (10.0 * field_error).max(TENSION_TOLERANCE),
        )?;
        Ok(state)
    }

    /// Concave punch with the contact ratio prescribed: `γ1(eps)` and `γ2(eps)` of the
    /// non-adhesive state, refused where that state is not one (tension at the inner edge, or
    /// the punch touching the hole's floor).
    pub fn concave_at_ratio(
        &self,
        kind: &PunchKind,
        eps: f64,
        tolerance: f64,
    ) -> Result<RingState> {
        let (fine, n, estimate) = self.concave_refined(kind, eps, tolerance)?;
        self.concave_state(kind, eps, fine, n, estimate)
    }

    /// The field with a free inner edge at a prescribed `eps` (zero inverse-square-root
    /// coefficient there), whether or not it is a non-adhesive contact: the JKR branches add the
    /// fixed annulus's field to it, and their own edges decide. No check of its sign or of the
    /// hole's floor.
    pub fn free_inner_edge_field(
        &self,
        kind: &PunchKind,
        eps: f64,
        tolerance: f64,
    ) -> Result<RingState> {
        let (fine, n, estimate) = self.concave_refined(kind, eps, tolerance)?;
        free_edge_state(eps, fine, n, estimate)
    }

    /// [`Self::free_inner_edge_field`] and the clearance of its surface over the punch's floor
    /// in the hole, `w(r) - (d - g(r))` (units of `h`) at the radii of [`hole_probes`]:
    /// negative where the punch would rise into the surface (a state that is not one).
    pub fn free_inner_edge_clearance(
        &self,
        kind: &PunchKind,
        eps: f64,
        tolerance: f64,
    ) -> Result<(RingState, Vec<f64>)> {
        let (fine, n, estimate) = self.concave_refined(kind, eps, tolerance)?;
        let clearance = {
            let (depth, inside) = self.hole_surface(kind, &fine);
            hole_probes(eps)
                .map(|r| inside(r).map_or(f64::NAN, |w| -floor_overlap(kind, depth, r, w)))
                .collect()
        };
        Ok((free_edge_state(eps, fine, n, estimate)?, clearance))
    }

    fn concave_refined(
        &self,
        kind: &PunchKind,
        eps: f64,
        tolerance: f64,
    ) -> Result<(ConcaveSample, usize, f64)> {
        Self::check_tolerance(tolerance)?;
        Self::check_ratio(eps)?;
        // Each node count's edge search starts from the previous one's edge.
        let last_outer = std::cell::Cell::new(None);
        self.refine(
            tolerance,
            |n| {
                let sample = self.concave_sample(kind, eps, n, last_outer.get())?;
                last_outer.set(Some(sample.system.region().outer()));
                Ok(sample)
            },
            |s| vec![s.gamma1, s.gamma2, s.system.region().outer()],
            |s| free_edge_floor(s.system.region()),
        )
    }

    /// Concave punch under depth control, `target = d/h`: finds `eps` with `γ1(eps) = d/h`.
    pub fn concave_at_depth(
        &self,
        kind: &PunchKind,
        target: f64,
        tolerance: f64,
    ) -> Result<RingState> {
        if is_closed(kind, target, Controlled::Depth) {
            return self.full_contact(kind, target, tolerance);
        }
        self.concave_inverse(kind, target, tolerance, Controlled::Depth)
    }

    /// Concave punch under force control, `target = F/(2 E* h a)`: finds `eps` with
    /// `γ2(eps) = target`.
    pub fn concave_at_force(
        &self,
        kind: &PunchKind,
        target: f64,
        tolerance: f64,
    ) -> Result<RingState> {
        if is_closed(kind, target, Controlled::Force) {
            // Full contact: the solver finds the depth from its own force (not from the MDR's
            // closed forms, which the tests check it against).
            return self.full_contact_at_force(kind, target, tolerance);
        }
        self.concave_inverse(kind, target, tolerance, Controlled::Force)
    }

    /// The contact ratio whose `γ1` or `γ2` meets `target` ([`inverse::InverseSearch`]).
    fn concave_inverse(
        &self,
        kind: &PunchKind,
        target: f64,
        tolerance: f64,
        controlled: Controlled,
    ) -> Result<RingState> {
        Self::check_tolerance(tolerance)?;
        if kind.is_free_band() {
            let depth_controlled = matches!(controlled, Controlled::Depth);
            if let Some(state) =
                free_band::BandSolver(self).band_inverse(kind, target, tolerance, depth_controlled)
            {
                return state;
            }
        }
        inverse::InverseSearch::start(self, kind, target, tolerance, controlled).run()
    }

    /// The disk with `w = d - g(r)` refined to `tolerance`: `((system, field), N, estimate,
    /// factorisations)`.
    fn full_contact_disk(
        &self,
        kind: &PunchKind,
        depth_over_hole: f64,
        tolerance: f64,
    ) -> Result<((RingSystem, RingField), usize, f64)> {
        self.refine(
            tolerance,
            |n| {
                let system = self.system(ContactRegion::Disk, n);
                let target: Vec<f64> = system
                    .radii()
                    .iter()
                    .map(|&r| depth_over_hole - kind.gap(r))
                    .collect();
                let field = system
                    .solve(&target)
                    .ok_or_else(|| no_convergence("singular collocation matrix".into()))?;
                Ok((system, field))
            },
            |(_, field)| vec![0.5 * field.force],
            |_| ROUNDING_FLOOR,
        )
        .map_err(|e| match (e, kind.concave_exponent()) {
            (Error::NoConvergence { method, reason }, Some(n)) if !is_even_integer(n) => {
                Error::NoConvergence {
                    method,
                    reason: format!(
                        "{reason}: the gap's (r/a)^{n} has a branch point at the axis, where the \
                         full-contact disk's basis in r² converges only algebraically (ask a \
                         tolerance above that estimate, or --method fem)"
                    ),
                }
            }
            (e, _) => e,
        })
    }

    /// The free band `kind` of half-width `half_width` (units of `a`) with the stress intensity
    /// `intensity` at both edges (units of `E* h / sqrt(a)`; the JKR edges in equilibrium:
    /// `-sqrt(2 E* Δw) sqrt(a)/(E* h) = -(d0/h)/sqrt(π)`), its centre found, refined until
    /// `γ1`, `γ2` and both edges change by less than `tolerance` between node counts. No check
    /// of the pressure's sign (adhesive edges are tensile by design). `centre_hint` starts the
    /// centre's search (a neighbouring state's centre, to follow one branch); without one it
    /// starts at `1 + w²` (units of `a`).
    pub fn band_with_edge_intensity(
        &self,
        kind: &PunchKind,
        half_width: f64,
        intensity: f64,
        tolerance: f64,
        centre_hint: Option<f64>,
    ) -> Result<RingState> {
        free_band::BandSolver(self).band_with_edge_intensity(
            kind,
            half_width,
            intensity,
            tolerance,
            centre_hint,
        )
    }

    /// A concave punch whose contact closes (`1 - ρ^n` with `n > 1` at
    /// `d >= h (1 + κ_n/(n - 1))`, `3h` for `n = 2`) in full contact: the disk with `w = d - g(r)`.
    pub fn full_contact(
        &self,
        kind: &PunchKind,
        depth_over_hole: f64,
        tolerance: f64,
    ) -> Result<RingState> {
        Self::check_tolerance(tolerance)?;
        if let Some(pieces) = kind.piecewise() {
            return Ok(piecewise_full_contact(pieces, depth_over_hole));
        }
        let ((system, field), n, estimate) =
            self.full_contact_disk(kind, depth_over_hole, tolerance)?;
        let pressure = pressure_profile(&system, &field);
        check_compressive(&pressure, 0.0, TENSION_TOLERANCE)?;
        Ok(RingState {
            eps: 0.0,
            outer_edge: 1.0,
            gamma: None,
            gamma1: Some(depth_over_hole),
            gamma2: Some(0.5 * field.force),
            rim_stress_intensity: system.rim_stress_intensity(&field),
            inner_stress_intensity: 0.0,
            pressure,
            error_estimate: estimate,
            unknowns: n,
        })
    }

    /// A closing concave punch in full contact under force control. In full contact the force
    /// is linear in the depth, `F(d) = F(0) + d F'`, so two disk solves give the depth exactly.
    fn full_contact_at_force(
        &self,
        kind: &PunchKind,
        target: f64,
        tolerance: f64,
    ) -> Result<RingState> {
        if let Some(pieces) = kind.piecewise() {
            let offset = crate::reference::mdr::piecewise_full_contact(pieces).force_offset;
            return self.full_contact(kind, target + offset, tolerance);
        }
        let gamma2 = |d: f64| -> Result<f64> {
            Ok(0.5 * self.full_contact_disk(kind, d, tolerance)?.0 .1.force)
        };
        // γ2 is linear in the depth: the line through two states in full contact, at closure
        // and h deeper. (Through d = 0 and h, tensile states, `1 - ρ³` stopped at an
        // estimate of 1.1e-7 at N = 80, where its compressive states meet 1e-9 at N = 40.)
        let closed = closure(kind).map_or(0.0, |(depth, _)| depth);
        let (at_closure, deeper) = (gamma2(closed)?, gamma2(closed + 1.0)?);
        let depth = closed + (target - at_closure) / (deeper - at_closure);
        self.full_contact(kind, depth, tolerance)
    }
}

/// A piecewise profile in full contact at `d/h = depth`, from the method of dimensionality
/// reduction's quadrature over its pieces ([`crate::reference::mdr`], exact for a piecewise
/// polynomial but for rounding): `γ2 = d/h - c_F` and the rim intensity
/// `K = (d/h + κ_h) / sqrt(π)` (units `E* h / sqrt(a)`). The collocated disk would converge only
/// algebraically at the break points; no pressure samples are drawn.
fn piecewise_full_contact(pieces: &dyn crate::punch::PiecewiseProfile, depth: f64) -> RingState {
    let full = crate::reference::mdr::piecewise_full_contact(pieces);
    RingState {
        eps: 0.0,
        outer_edge: 1.0,
        gamma: None,
        gamma1: Some(depth),
        gamma2: Some(depth - full.force_offset),
        rim_stress_intensity: (depth + full.kappa_h) / PI.sqrt(),
        inner_stress_intensity: 0.0,
        pressure: Vec::new(),
        error_estimate: ROUNDING_FLOOR,
        unknowns: 0,
    }
}

/// Whether the exponent `n` is an even integer (`(r/a)^n` is then a polynomial in `r²`).
fn is_even_integer(n: f64) -> bool {
    n.rem_euclid(2.0) == 0.0
}

/// The state of a concave sample with a free inner edge at `eps` (no check of its sign or of the
/// hole's floor). An error for a search sample without its rim intensity.
fn free_edge_state(eps: f64, fine: ConcaveSample, n: usize, estimate: f64) -> Result<RingState> {
    let rim_stress_intensity = fine.rim_stress_intensity.ok_or_else(|| {
        no_convergence("a search sample (no rim intensity) was taken for a state".into())
    })?;
    Ok(RingState {
        eps,
        outer_edge: fine.system.region().outer(),
        gamma: None,
        gamma1: Some(fine.gamma1),
        gamma2: Some(fine.gamma2),
        rim_stress_intensity,
        inner_stress_intensity: 0.0,
        pressure: pressure_profile(&fine.system, &fine.field),
        error_estimate: estimate,
        unknowns: n,
    })
}

/// Radii `r = b k / HOLE_PROBES`, `k = 0..HOLE_PROBES`, where the floor of the hole `[0, b)`
/// of a ring `[b, 1]` is checked.
pub fn hole_probes(eps: f64) -> impl Iterator<Item = f64> {
    (0..HOLE_PROBES).map(move |k| eps * k as f64 / HOLE_PROBES as f64)
}

/// How far the punch at depth `d/h = depth` rises into the surface `w` (units of `h`) at the
/// radius `r` outside the contact: `(d - g(r)) - w` (negative: the surface clears the punch).
fn floor_overlap(kind: &PunchKind, depth: f64, r: f64, w: f64) -> f64 {
    (depth - kind.gap(r)) - w
}

/// The first of `radii` where the surface `w(r)` (from `deflection`, `None`: not evaluated
/// there) rises into the punch at depth `d/h = depth`, `(d - g(r)) - w(r)` above
/// [`HOLE_OVERLAP_TOLERANCE`] (relative to the depth, at least 1): the radius and the overlap.
fn first_overlap(
    kind: &PunchKind,
    depth: f64,
    radii: impl Iterator<Item = f64>,
    deflection: impl Fn(f64) -> Option<f64>,
) -> Option<(f64, f64)> {
    radii
        .filter_map(|r| deflection(r).map(|w| (r, floor_overlap(kind, depth, r, w))))
        .find(|&(_, overlap)| overlap > HOLE_OVERLAP_TOLERANCE * depth.abs().max(1.0))
}

/// A guess of the outer edge at `eps` from the last samples of a search: the line through the
/// last two, or the last one's edge (`None` before any).
fn outer_edge_hint(history: &[(f64, ConcaveSample)], eps: f64) -> Option<f64> {
    let edge = |s: &ConcaveSample| s.system.region().outer();
    match history {
        [.., (e0, s0), (e1, s1)] if e1 != e0 => {
            Some(edge(s1) + (edge(s1) - edge(s0)) / (e1 - e0) * (eps - e1))
        }
        [.., (_, s1)] => Some(edge(s1)),
        [] => None,
    }
}

/// Turn a failed contact-ratio search into an error that says why.
fn inverse_error(e: RootError, kind: &PunchKind, target: f64, controlled: Controlled) -> Error {
    match e {
        RootError::NotBracketed { f_lo, f_hi, .. } => out_of_range(format!(
            "{} {} = {} needs a contact ratio outside [{}, {MAX_CONTACT_RATIO}]{}{}",
            kind,
            controlled.symbol(),
            crate::error::show(target),
            min_contact_ratio(kind),
            if target.abs() < 1e12 {
                format!(
                    " (the value ranges over [{}, {}] there)",
                    crate::error::show(f_hi + target),
                    crate::error::show(f_lo + target)
                )
            } else {
                String::new()
            },
            match (closure(kind), f_lo < 0.0) {
                (Some((depth, _)), true) if flatter_than_the_sphere(kind) => {
                    floor_touch_note("up to", depth, "is")
                }
                (None, true) => format!(
                    "; the {}'s contact closes only as d -> infinity",
                    kind.name()
                ),
                (Some((depth, _)), true) => format!(
                    "; this is within a hair of full contact (d = {} h)",
                    crate::error::show(depth)
                ),
                _ => "; the contact ring would be narrower than 1e-4 a".into(),
            }
        )),
        RootError::NoConvergence {
            iterations,
            last_step,
        } => no_convergence(format!(
            "contact-ratio search stopped after {iterations} solves (last step {last_step:.1e}){}",
            match closure(kind) {
                // A profile flatter than a parabola can spend the whole search between annuli
                // that all touch the floor (`1 - ρ³` under F = 4 E* h a).
                Some((depth, _)) if flatter_than_the_sphere(kind) => {
                    floor_touch_note("short of", depth, "can be")
                }
                _ => String::new(),
            }
        )),
        RootError::Evaluation(m) => no_convergence(m),
    }
}

/// Whether the contact of a closing punch is the full disk at `target` (`d/h` or
/// `F/(2 E* h a)`, as `controlled` says): at or beyond [`closure`]. A table is first compared
/// with the MDR's lower bounds of its closure
/// ([`crate::reference::mdr::piecewise_closure_lower_bounds`]): a state short of them is open
/// without the closure's maximisation.
fn is_closed(kind: &PunchKind, target: f64, controlled: Controlled) -> bool {
    let pick = |(depth, force): (f64, f64)| match controlled {
        Controlled::Depth => depth,
        Controlled::Force => force,
    };
    if let Some(pieces) = kind.piecewise() {
        match crate::reference::mdr::piecewise_closure_lower_bounds(pieces) {
            Some(bounds) if target < pick(bounds) => return false,
            None => return false,
            Some(_) => {}
        }
    }
    closure(kind).is_some_and(|c| target >= pick(c))
}

/// Where a concave punch's contact closes, `(d/h, F/(2 E* h a))`, as its profile declares it
/// ([`crate::punch::Profile::closure`]); `None` for a profile with a slope at the axis, whose
/// hole never closes.
fn closure(kind: &PunchKind) -> Option<(f64, f64)> {
    kind.profile().closure()
}

/// Why a profile flatter than a parabola at the axis has no annulus state `where_` (`up to`,
/// `short of`) full contact at `d = depth h`: its contact `is` or `can be` a disk and an annulus.
fn floor_touch_note(where_: &str, depth: f64, is: &str) -> String {
    format!(
        "; a profile flatter than a parabola at the axis (1 - (r/a)^n with n > 2, a table whose \
         full contact opens on a ring) touches the floor of its hole before the ring closes: \
         {where_} full contact at d = {} h the contact {is} a disk and an annulus, which the \
         ring BEM does not model",
        crate::error::show(depth)
    )
}

/// Whether the profile is flatter than a parabola at the axis (`1 - ρ^n` with `n > 2`; a
/// table whose full-contact pressure first vanishes on a ring, `OPENING_OFF_AXIS` or more
/// from the axis, by the MDR): its contact closes from a disk and an annulus, not by a
/// shrinking hole.
fn flatter_than_the_sphere(kind: &PunchKind) -> bool {
    kind.profile().flatter_than_the_sphere()
}

/// Which quantity a concave inverse problem prescribes.
#[derive(Clone, Copy)]
enum Controlled {
    Depth,
    Force,
}

impl Controlled {
    fn symbol(self) -> &'static str {
        match self {
            Controlled::Depth => "d/h",
            Controlled::Force => "F/(2E*ha)",
        }
    }
}

/// First rung of the node ladder worth trying at contact ratio `eps` (N = 16 meets 1e-9 for
/// eps >= 0.1, N = 20 down to 0.03, N = 32 down to 1e-3). Too low a rung costs one more
/// root search from an excellent start, never a wrong answer.
fn starting_rung(eps: f64) -> usize {
    let n = if eps >= 0.1 {
        16
    } else if eps >= 0.03 {
        20
    } else if eps >= 1e-3 {
        32
    } else {
        40
    };
    NODE_LADDER.iter().position(|&m| m == n).unwrap_or(1)
}

/// First rung of the node ladder worth trying for a piecewise profile's band at contact ratio `eps`: its
/// flat band's field and the gap's smooth part, not the gap itself, set the node count
/// (docs/decisions.md, "Where the constants come from").
fn piecewise_starting_rung(eps: f64) -> usize {
    let n = if eps >= 0.1 {
        16
    } else if eps >= 0.02 {
        20
    } else if eps >= 0.005 {
        24
    } else {
        32
    };
    NODE_LADDER.iter().position(|&m| m == n).unwrap_or(1)
}

/// The least distance in `eps` between two states whose difference gives a slope for the error
/// estimate (the values' rounding, about 1e-14, then moves it by 1e-5 of itself or less where
/// the slope is 1 or more; the estimate needs a few per cent).
const SLOPE_MIN_SEPARATION: f64 = 1e-9;

/// The largest error estimate of a rung whose slopes the next rung may reuse for its own
/// estimate (the slopes are then good to about this, and the estimate needs a few per cent).
const SLOPE_TRUSTED_ESTIMATE: f64 = 1e-3;

/// Tolerance in `eps` of a piecewise profile's pre-search on its rough samples: below their own error
/// (about 1e-6), which the accurate search then removes.
const PRESEARCH_TOLERANCE: f64 = 1e-6;

/// Most evaluations of a piecewise profile's pre-search (5 to 8 where `γ` is monotone, about 13
/// where it is flat with humps); past these the search starts from the fit's guess.
const PRESEARCH_EVALUATIONS: usize = 24;

/// The rung of the inverse problem's first search (N = 16): a state that needs more nodes
/// climbs from its root.
const FIRST_SEARCH_RUNG: usize = 1;

/// Starting contact ratio for the inverse problem: the profile's approximant where it has one,
/// else the fit [`starting_fit`] picks for its rim slope. Fits only start the
/// search: the root is that of the ring BEM's own `γ1` or `γ2`, whatever the start.
fn initial_ratio(kind: &PunchKind, target: f64, controlled: Controlled) -> f64 {
    let depth_controlled = matches!(controlled, Controlled::Depth);
    if kind.approximate_gamma(0.5, depth_controlled).is_some() {
        let approximant = |eps: f64| kind.approximate_gamma(eps, depth_controlled).unwrap_or(0.0);
        return bisect_decreasing(
            approximant,
            target,
            (MIN_CONTACT_RATIO, MAX_CONTACT_RATIO),
            60,
        );
    }
    if kind.is_free_band() {
        // A band the profile gives no approximant for: its middle, the search does the rest.
        return 0.5;
    }
    let i = match controlled {
        Controlled::Depth => 1,
        Controlled::Force => 2,
    };
    let (target, fit) = starting_fit(kind.rim_slope(), target);
    // Bisection on the (monotone) fit: cheap and always lands inside the admissible range.
    bisect_decreasing(
        |eps| fit(i, eps),
        target,
        (min_contact_ratio(kind), MAX_CONTACT_RATIO),
        50,
    )
}

/// Where `f`, decreasing on `(lo, hi)`, crosses `target`: the midpoint after `halvings`
/// bisections (an end of the range where it does not cross).
fn bisect_decreasing(
    f: impl Fn(f64) -> f64,
    target: f64,
    (lo, hi): (f64, f64),
    halvings: usize,
) -> f64 {
    let (mut lo, mut hi) = (lo, hi);
    for _ in 0..halvings {
        let mid = 0.5 * (lo + hi);
        if f(mid) > target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Pressure at the collocation radii, ascending in `r`.
fn pressure_profile(system: &RingSystem, field: &RingField) -> Vec<ScaledPressure> {
    let mut samples: Vec<ScaledPressure> = system
        .radii()
        .iter()
        .map(|&r| (r, system.pressure(field, r)))
        .collect();
    samples.sort_by(|a, b| a.0.total_cmp(&b.0));
    samples
}

/// A non-adhesive contact must be compressive everywhere; a tensile sample means the assumed
/// contact region is wrong (or the discretisation is not resolved).
/// `tolerance`: the largest tension accepted, relative to the largest pressure sample.
fn check_compressive(pressure: &[ScaledPressure], eps: f64, tolerance: f64) -> Result<()> {
    let scale = pressure.iter().map(|s| s.1.abs()).fold(0.0, f64::max);
    if let Some(&(r, p)) = pressure.iter().find(|s| s.1 < -tolerance * scale) {
        return Err(no_convergence(format!(
            "tensile pressure p = {p:.3e} at r/a = {r:.4} for contact ratio {eps}: \
             the contact region is not the non-adhesive one"
        )));
    }
    Ok(())
}
