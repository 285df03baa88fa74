//! The torus with the ring BEM: a contact band `[b, c]` whose both edges are free.
//!
//! With `h = 1` (`a = E* = 1`) the gap is `ĝ(r) = (1 - r)²` on both sides of the ring radius. On
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
//! parametrises the torus's states as it does the concave punches', `γ1(eps) = d/h` and
//! `γ2(eps) = F/(2 E* h a)` decrease with it, and depth or force control inverts them with the
//! same search. Both unknown radii are found to rounding at each node count; the
//! self-convergence estimate covers `γ1`, `γ2` and `c`.
//!
//! **The contact never closes.** Near the axis the gap is `h (1 - 2r/a + ...)`: a conical
//! dimple, whose full-contact pressure is logarithmically tensile at the apex (as the cone's).
//! The inner edge approaches the axis only as the load grows without bound, and the ring BEM
//! refuses `b < 1e-4 a` as for the cone.

use std::f64::consts::PI;

use crate::bem::ring::{ContactRegion, RingField, RingSystem};
use crate::error::Result;
use crate::numerics::roots::{find_root, RootError};
use crate::punch::PunchKind;

use super::{
    free_edge_state, no_convergence, out_of_range, ConcaveSample, RingBemSolver, RingState,
    MIN_BAND_RATIO, MIN_CONTACT_RATIO,
};

/// Absolute tolerance of the outer edge `c/a` at each node count: far below every tolerance the
/// method accepts, so that the discretisation, not the search, sets the estimate.
const OUTER_EDGE_TOLERANCE: f64 = 1e-13;

impl RingBemSolver {
    /// The torus's band `[b, c]` at a fixed node count: its collocation system and the fields
    /// of `w = 1` and `w = -ĝ`.
    fn torus_band(&self, inner: f64, outer: f64, n: usize) -> Result<TorusBand> {
        let system = self.system(ContactRegion::Band { inner, outer }, n);
        let minus_gap: Vec<f64> = system
            .radii()
            .iter()
            .map(|&r| -PunchKind::Torus.gap_shape(r))
            .collect();
        let singular = || no_convergence("singular collocation matrix".into());
        let one = system.solve(&vec![1.0; n]).ok_or_else(singular)?;
        let gap = system.solve(&minus_gap).ok_or_else(singular)?;
        Ok(TorusBand { system, one, gap })
    }

    /// The torus at a fixed node count with its inner edge at `eps`: the outer edge `c` where
    /// both edges are free (by the safeguarded secant on [`TorusBand::mismatch`]), the depth
    /// `γ1 = d/h` and `γ2 = F/(2 E* h a)` (see the module docs). `outer_hint` starts the edge
    /// search (a nearby state's edge); without one it starts from [`outer_edge_guess`].
    pub(super) fn torus_sample(
        &self,
        eps: f64,
        n: usize,
        outer_hint: Option<f64>,
    ) -> Result<ConcaveSample> {
        let residual = |outer: f64| -> std::result::Result<f64, String> {
            let band = self.torus_band(eps, outer, n).map_err(|e| e.to_string())?;
            Ok(band.mismatch(0.0))
        };
        let lo = eps * (1.0 + 2.0 * MIN_BAND_RATIO);
        // Measured: c = 1.0001, 1.62, 3.60, 5.78 a at b = 0.9999, 0.6, 0.1, 0.01 a.
        let hi = 3.0 + 3.0 * (1.0 / eps).ln();
        let guess = outer_hint
            .filter(|c| c.is_finite())
            .unwrap_or_else(|| outer_edge_guess(eps))
            .clamp(lo, hi);
        let what = format!("torus with inner edge b/a = {}", crate::error::show(eps));
        let root = find_root(residual, lo, hi, guess, OUTER_EDGE_TOLERANCE, 80)
            .map_err(|e| search_error(e, &what, "outer edge", lo, hi))?;
        self.torus_band(eps, root.x, n)?.sample(0.0)
    }

    /// The torus's band of half-width `w` with the stress intensity `K = intensity` at both
    /// edges: the centre `m` (band `[m - w, m + w]`) by the safeguarded secant on
    /// [`TorusBand::mismatch`]. The JKR equilibria are parametrised by the width, not by the
    /// inner edge: a narrow adhesive band shifts toward the axis as it shrinks (measured: at
    /// `d0/h = 0.1` a band from `0.9867 a` to about `0.998 a` is an equilibrium, wholly inside
    /// `r < a`), so the inner edge is not monotone along the curve, while the width is.
    fn torus_width_sample(
        &self,
        half_width: f64,
        n: usize,
        centre_hint: Option<f64>,
        intensity: f64,
    ) -> Result<ConcaveSample> {
        let residual = |centre: f64| -> std::result::Result<f64, String> {
            let band = self
                .torus_band(centre - half_width, centre + half_width, n)
                .map_err(|e| e.to_string())?;
            Ok(band.mismatch(intensity))
        };
        let lo = half_width + MIN_CONTACT_RATIO;
        let hi = 3.0 + 3.0 * half_width;
        let guess = centre_hint
            .filter(|m| m.is_finite())
            .unwrap_or(1.0 + half_width * half_width)
            .clamp(lo, hi);
        let what = format!(
            "torus band of half-width {} a",
            crate::error::show(half_width)
        );
        let root = find_root(residual, lo, hi, guess, OUTER_EDGE_TOLERANCE, 80)
            .map_err(|e| search_error(e, &what, "centre", lo, hi))?;
        self.torus_band(root.x - half_width, root.x + half_width, n)?
            .sample(intensity)
    }

    /// The torus's band of half-width `half_width` (units of `a`) with the stress intensity
    /// `intensity` at both edges (units of `E* h / sqrt(a)`; the JKR edges in equilibrium:
    /// `-sqrt(2 E* Δw) sqrt(a)/(E* h) = -(d0/h)/sqrt(π)`), its centre found, refined until
    /// `γ1`, `γ2` and both edges change by less than `tolerance` between node counts. No check
    /// of the pressure's sign (adhesive edges are tensile by design). `centre_hint` starts the
    /// centre's search (a neighbouring state's centre, to follow one branch); without one it
    /// starts at `1 + w²` (units of `a`).
    pub fn torus_with_edge_intensity(
        &self,
        half_width: f64,
        intensity: f64,
        tolerance: f64,
        centre_hint: Option<f64>,
    ) -> Result<RingState> {
        Self::check_tolerance(tolerance)?;
        if !(intensity.is_finite() && half_width.is_finite() && half_width > 0.0) {
            return Err(out_of_range(format!(
                "torus band of half-width {} with edge intensity {}: need a finite positive \
                 width and a finite intensity",
                crate::error::show(half_width),
                crate::error::show(intensity)
            )));
        }
        let last_centre = std::cell::Cell::new(centre_hint);
        let (fine, n, estimate, solves) = self.refine(
            tolerance,
            |n| {
                let sample =
                    self.torus_width_sample(half_width, n, last_centre.get(), intensity)?;
                let region = sample.system.region();
                last_centre.set(Some(0.5 * (region.inner() + region.outer())));
                Ok(sample)
            },
            |s| {
                let region = s.system.region();
                vec![s.gamma1, s.gamma2, region.inner(), region.outer()]
            },
        )?;
        let eps = fine.system.region().inner();
        let mut state = free_edge_state(eps, fine, n, estimate, solves);
        state.inner_stress_intensity = intensity;
        Ok(state)
    }
}

/// A band of the torus at one node count: its system and the fields of `w = 1` and `w = -ĝ`.
struct TorusBand {
    system: RingSystem,
    one: RingField,
    gap: RingField,
}

impl TorusBand {
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

    /// The state at the depth of [`Self::depth`].
    fn sample(self, intensity: f64) -> Result<ConcaveSample> {
        let gamma1 = self.depth(intensity);
        let target = self.coefficient(intensity);
        let combine = |a: f64, b: f64| gamma1 * a + b;
        let field = RingField {
            phi: self
                .one
                .phi
                .iter()
                .zip(&self.gap.phi)
                .map(|(a, b)| combine(*a, *b))
                .collect(),
            force: combine(self.one.force, self.gap.force),
            rim_coefficient: combine(self.one.rim_coefficient, self.gap.rim_coefficient),
            inner_coefficient: target,
        };
        Ok(ConcaveSample {
            gamma1,
            gamma2: 0.5 * field.force,
            system: self.system,
            field,
        })
    }
}

/// A failed edge search, said with what was searched and where.
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

/// Starting outer edge for the inner edge `eps` (the search finds the exact edge): the band
/// symmetric about the ring radius, as the narrow torus's plane-strain contact is, or for a wide
/// band the logarithmic growth measured (`c = 3.60, 4.77, 5.78 a` at `b = 0.1, 0.03, 0.01 a`).
fn outer_edge_guess(eps: f64) -> f64 {
    (2.0 - eps).max(1.3 + (1.0 / eps).ln())
}

/// Starting inner edge of the torus for a depth (`γ1 = d/h`) or a force (`γ2 = F/(2 E* h a)`)
/// target, from the larger of two approximants of the ring BEM's curves. Narrow: the ring as a
/// plane-strain cylinder of half-width `w = 1 - eps` (`ρ = a/2` when `h = 1`), `γ2 ≈ π² w²/2`
/// (Hertz, `P = π E* w²/(4ρ)` per unit length over the length `2πa`) and `γ1 ≈ w² (ln(16/w) - 1)`
/// (the ring's logarithmic approach). Wide: powers of `L = ln(a/b)` through the measured curves
/// (`γ1 = 15.6, 49.7, 163` and `γ2 = 41.9, 205, 1109` at `b = 0.1, 0.01, 1e-4 a`),
/// `γ1 ≈ 3.8 L^1.7`, `γ2 ≈ 5.8 L^2.35`. A start only: the search converges on the ring BEM's
/// own `γ1` or `γ2`, and a poor start costs evaluations (and a higher first node count), not
/// accuracy.
pub(super) fn initial_inner_edge(target: f64, depth_controlled: bool) -> f64 {
    let approximant = |eps: f64| {
        let (w, log) = (1.0 - eps, (1.0 / eps).ln());
        if depth_controlled {
            (w * w * ((16.0 / w).ln() - 1.0)).max(3.8 * log.powf(1.7))
        } else {
            (0.5 * std::f64::consts::PI.powi(2) * w * w).max(5.8 * log.powf(2.35))
        }
    };
    // Bisection on the approximant, decreasing in eps.
    let (mut lo, mut hi) = (super::MIN_CONTACT_RATIO, super::MAX_CONTACT_RATIO);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if approximant(mid) > target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}
