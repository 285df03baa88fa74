//! A band pressed by a punch whose gap is only piecewise smooth (a profile given by points, its
//! piecewise cubic, `C¹` with curvature jumps at its points), solved to the ring BEM's spectral
//! accuracy through the flat band's field and its edge derivatives.
//!
//! Collocating the gap itself converges only algebraically: the pressure has a weak singularity
//! (`(r - r_k) ln|r - r_k|`) at every curvature jump, which no polynomial basis resolves. Every
//! output the punch problems need is a linear functional of the deflection `v` imposed on the
//! band `[b, c]`, though, and each is an integral of `v` against fields of the **flat** band
//! (`w = 1`, pressure `p¹`: analytic, converged geometrically), integrated panel by panel
//! between the gap's break points (`dA = 2π s ds`, `a = E* = 1`):
//!
//! ```text
//! F[v]   = ∫ p¹ v dA                                              (Betti's reciprocal theorem)
//! K_b[v] = K_b[1] v(b) - ∫ ∂_b p¹ (v - v(b)) dA / (2π b K_b[1])    (inner edge b)
//! K_c[v] = K_c[1] v(c) + ∫ ∂_c p¹ (v - v(c)) dA / (2π c K_c[1])    (outer edge c)
//! ```
//!
//! The intensity formulas are Irwin's relation for a contact edge, polarised: for any two
//! deflections `∂_b ⟨p[u], v⟩ = -2π b K_b[u] K_b[v]` (`+2π c` at the outer edge), taken with
//! `u = 1`; subtracting `v(b)` keeps the derivative of the edge's `(s - b)^{-1/2}` singularity
//! integrable (`∂_b p¹ ~ (s - b)^{-3/2}` against `v - v(b) ~ (s - b)`). The derivatives of `p¹`
//! with respect to the edges at fixed `s`, `∂_b p¹ = ∂_b φ W + φ W / (2 (s - b))` and
//! `∂_c p¹ = ∂_c φ W - φ W / (2 (c - s))`, take `∂φ` from one-sided fifth-order differences
//! over neighbouring bands that contain the band ([`STENCIL`]). Only the remainder `g - g_s`
//! goes through them: the gap's smooth part `g_s` ([`SmoothPart`]) is collocated directly, so
//! the differences' rounding is relative to the small remainder. The surface inside the hole
//! follows by reciprocity ([`GapBand::hole_surface`]).

use std::f64::consts::PI;

use crate::bem::ring::{ContactRegion, RingField, RingSystem};
use crate::discretisation::quadrature::gauss_legendre;
use crate::error::Result;
use crate::numerics::chebyshev::{chebyshev_series, ChebyshevNodes};
use crate::numerics::elliptic::complete_k_from_complementary;
use crate::numerics::tanh_sinh::{PanelNode, TanhSinhRule};
use crate::punch::PiecewiseProfile;

use super::{no_convergence, RingBemSolver};

/// Step of the edge derivatives' differences, relative to the band's smaller natural length
/// (`b` or `c - b` for the inner edge, `c - b` for the outer): between the rounding of smaller
/// steps and the truncation of larger ones (docs/decisions.md, "Where the constants come from").
const EDGE_STEP: f64 = 1e-2;

/// One-sided difference of fifth order, `f'(x) ≈ Σ_k w_k f(x - k δ) / δ` (Fornberg's weights):
/// the neighbouring bands only ever grow the band, so every one contains it and its field is
/// never evaluated outside its own interval (continuing a high-degree interpolant beyond its
/// interval amplifies rounding).
const STENCIL: [(f64, f64); 6] = [
    (0.0, 137.0 / 60.0),
    (1.0, -5.0),
    (2.0, 5.0),
    (3.0, -10.0 / 3.0),
    (4.0, 5.0 / 4.0),
    (5.0, -1.0 / 5.0),
];

/// One-sided difference of second order, `f'(x) ≈ (3 f(x) - 4 f(x - δ) + f(x - 2 δ)) / (2 δ)`:
/// two factorisations instead of [`STENCIL`]'s five, for the rough pre-search (docs/decisions.md,
/// "Where the constants come from").
const ROUGH_STENCIL: [(f64, f64); 3] = [(0.0, 1.5), (1.0, -2.0), (2.0, 0.5)];

/// A gap `g(r)` (units of the punch's depth scale, `r` in units of `a`) that is smooth between
/// known break points.
pub(crate) trait PiecewiseGap {
    /// `g(r)`.
    fn value(&self, r: f64) -> f64;
    /// `g(r + offset) - g(r)`, precise relative to itself as `offset -> 0`.
    fn increment(&self, r: f64, offset: f64) -> f64;
    /// The break points (ascending), where derivatives of the gap jump.
    fn break_points(&self) -> &[f64];
}

impl PiecewiseGap for &dyn PiecewiseProfile {
    fn value(&self, r: f64) -> f64 {
        (**self).value(r)
    }
    fn increment(&self, r: f64, offset: f64) -> f64 {
        (**self).increment(r, offset)
    }
    fn break_points(&self) -> &[f64] {
        (**self).break_points()
    }
}

/// The flat band's quantities and the gap's functionals on one band at one node count
/// (dimensionless: `F` in units of `E* a L`, `K` of `E* L / sqrt(a)` for a deflection of scale
/// `L`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct GapFunctionals {
    /// `F¹`, the force of `w = 1`.
    pub flat_force: f64,
    /// `K_b[1]`.
    pub flat_inner_intensity: f64,
    /// `K_c[1]`.
    pub flat_outer_intensity: f64,
    /// `F[g]`, the force of `w = g`.
    pub gap_force: f64,
    /// `K_b[g]`.
    pub gap_inner_intensity: f64,
    /// `K_c[g]` (`None` where the band was built for its inner edge only,
    /// [`BandEdges::Inner`]).
    pub gap_outer_intensity: Option<f64>,
}

/// Which edges' intensities a band's functionals carry: each edge's derivative takes five more
/// factorisations ([`STENCIL`]'s neighbours). A search on the inner edge of a punch with a rim
/// needs only the inner one (its depth and force); the rim's intensity is the final state's.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum BandEdges {
    Inner,
    Both,
    /// The inner edge only, its derivative by [`ROUGH_STENCIL`] (two neighbours, not five): a
    /// pre-search's samples, which only start the accurate search.
    InnerRough,
}

impl BandEdges {
    /// The inner edge's difference stencil.
    fn inner_stencil(self) -> &'static [(f64, f64)] {
        match self {
            BandEdges::InnerRough => &ROUGH_STENCIL,
            BandEdges::Inner | BandEdges::Both => &STENCIL,
        }
    }
}

impl GapFunctionals {
    /// Depth `d` at which the inner edge is free for `w = d - g`: `K_b[g] / K_b[1]`.
    pub fn free_inner_depth(&self) -> f64 {
        self.gap_inner_intensity / self.flat_inner_intensity
    }

    /// Force of `w = d - g`.
    pub fn force(&self, depth: f64) -> f64 {
        depth * self.flat_force - self.gap_force
    }

    /// Inner edge's intensity of `w = d - g`.
    pub fn inner_intensity(&self, depth: f64) -> f64 {
        depth * self.flat_inner_intensity - self.gap_inner_intensity
    }

    /// Outer edge's intensity of `w = d - g` (`None` for a band built for its inner edge only).
    pub fn outer_intensity(&self, depth: f64) -> Option<f64> {
        Some(depth * self.flat_outer_intensity - self.gap_outer_intensity?)
    }
}

/// The flat band `[inner, outer]`'s field at `n` nodes.
struct FlatBand {
    system: RingSystem,
    field: RingField,
}

/// The flat field's smooth factor `φ` on `[b, c]` and its edge derivatives at fixed `s`
/// (the outer edge's only where it was asked for), each a Chebyshev series in the band's
/// parameter `t = 2 ln(s/b) / L - 1`, `L = ln(c/b)`. A derivative `Σ w_k φ_k / δ` takes the
/// fields `φ_k` of a stencil's neighbouring bands (the centre's own field is its first node): each
/// is a polynomial of degree `N - 1` in its own band's parameter, which is affine in `t` (every
/// parameter is affine in `ln s`), so its interpolant at the band's `N` Chebyshev points is the
/// same polynomial, and the derivative is one series with the coefficients `Σ w_k c_k / δ`
/// ([`derivative_series`]): the integrals evaluate three series per node instead of eleven.
struct SmoothFactor {
    centre: Series,
    by_inner: Option<Series>,
    by_outer: Option<Series>,
}

impl SmoothFactor {
    /// `(φ, ∂_b φ|_s, ∂_c φ|_s)` at `s` (a derivative not built is zero).
    fn at(&self, s: f64) -> (f64, f64, f64) {
        let t = self.centre.parameter(s);
        let value = |series: &Option<Series>| {
            series
                .as_ref()
                .map_or(0.0, |series| chebyshev_series(&series.coefficients, t))
        };
        (
            chebyshev_series(&self.centre.coefficients, t),
            value(&self.by_inner),
            value(&self.by_outer),
        )
    }
}

/// `∂φ ≈ (w_0 φ + Σ_{k≥1} w_k φ_k) / step` as one series on the band of `centre` (the flat
/// band's field, `φ` at its collocation radii, the `nodes`' points): the combination's values
/// there, each neighbour's series evaluated at them, interpolated ([`SmoothFactor`]).
fn derivative_series(
    centre: &FlatBand,
    nodes: &ChebyshevNodes,
    neighbours: &[Series],
    weights: &[f64; 6],
    step: f64,
) -> Series {
    let values: Vec<f64> = centre
        .system
        .radii()
        .iter()
        .zip(&centre.field.phi)
        .map(|(&r, &phi)| {
            (weights[0] * phi
                + neighbours
                    .iter()
                    .zip(&weights[1..])
                    .map(|(series, w)| w * series.at(r))
                    .sum::<f64>())
                / step
        })
        .collect();
    let region = centre.system.region();
    Series::of_band(
        (region.inner(), region.outer()),
        nodes.coefficients(&values),
    )
}

/// One band's `φ` as a Chebyshev series in its own parameter.
struct Series {
    band: (f64, f64),
    coefficients: Vec<f64>,
}

impl Series {
    fn new(nodes: &ChebyshevNodes, band: &FlatBand) -> Self {
        let region = band.system.region();
        Self::of_band(
            (region.inner(), region.outer()),
            nodes.coefficients(&band.field.phi),
        )
    }

    /// The series with `coefficients` on `band`.
    fn of_band(band: (f64, f64), coefficients: Vec<f64>) -> Self {
        Self { band, coefficients }
    }

    /// The band's parameter `t = 2 ln(s/b) / ln(c/b) - 1` of a radius.
    fn parameter(&self, s: f64) -> f64 {
        let (inner, outer) = self.band;
        2.0 * (s / inner).ln() / (outer / inner).ln() - 1.0
    }

    /// The series at radius `s`.
    fn at(&self, s: f64) -> f64 {
        chebyshev_series(&self.coefficients, self.parameter(s))
    }
}

/// Most nodes of the smooth part's interpolant (a polynomial of degree 23 in the band's
/// parameter); at `N` collocation nodes it takes `N/2` of them, which the collocation resolves.
const SMOOTH_PART_NODES: usize = 24;

/// The gap's smooth part on a band: its polynomial interpolant in the band's parameter
/// `t = 2 ln(s/b) / L - 1` at up to [`SMOOTH_PART_NODES`] Chebyshev points. Collocated directly (it is
/// analytic); only the small remainder `g - g_s` goes through the edge derivatives, whose
/// rounding is then relative to the remainder, not to the gap.
struct SmoothPart {
    series: Series,
}

impl SmoothPart {
    fn new(gap: &dyn PiecewiseGap, inner: f64, outer: f64, count: usize) -> Self {
        let nodes = ChebyshevNodes::new(count);
        let span = (outer / inner).ln();
        let values: Vec<f64> = nodes
            .points
            .iter()
            .map(|&t| gap.value(inner * (0.5 * (1.0 + t) * span).exp()))
            .collect();
        Self {
            series: Series::of_band((inner, outer), nodes.coefficients(&values)),
        }
    }
}

impl PiecewiseGap for SmoothPart {
    fn value(&self, r: f64) -> f64 {
        self.series.at(r)
    }

    /// `Σ c_k (T_k(x) - T_k(y))` with the factor `x - y` taken out exactly:
    /// `T_k(x) - T_k(y) = (x - y) E_k`, `E_{k+1} = 2 x E_k - E_{k-1} + 2 T_k(y)`, `E_0 = 0`,
    /// `E_1 = 1` (from the three-term recurrence of both).
    fn increment(&self, r: f64, offset: f64) -> f64 {
        let (inner, outer) = self.series.band;
        let coefficients = &self.series.coefficients;
        let y = self.series.parameter(r);
        let step = 2.0 * (offset / r).ln_1p() / (outer / inner).ln();
        let x = y + step;
        let (mut e_prev, mut e) = (0.0, 1.0);
        let (mut t_prev, mut t) = (1.0, y);
        let mut sum = 0.0;
        for (k, &c) in coefficients.iter().enumerate().skip(1) {
            sum += c * e;
            if k + 1 < coefficients.len() {
                let e_next = 2.0 * x * e - e_prev + 2.0 * t;
                let t_next = 2.0 * y * t - t_prev;
                (e_prev, e, t_prev, t) = (e, e_next, t, t_next);
            }
        }
        step * sum
    }

    fn break_points(&self) -> &[f64] {
        &[]
    }
}

/// `g - g_s`: what the smooth part leaves of the gap.
struct Remainder<'a> {
    gap: &'a dyn PiecewiseGap,
    smooth: &'a SmoothPart,
}

impl PiecewiseGap for Remainder<'_> {
    fn value(&self, r: f64) -> f64 {
        self.gap.value(r) - self.smooth.value(r)
    }
    fn increment(&self, r: f64, offset: f64) -> f64 {
        self.gap.increment(r, offset) - self.smooth.increment(r, offset)
    }
    fn break_points(&self) -> &[f64] {
        self.gap.break_points()
    }
}

/// The ring BEM's bands of a piecewise gap: its collocation systems and band rule, asked for the
/// gap's functionals on a band and their derivatives in the band's edges.
pub(crate) struct GapBands<'a>(pub &'a RingBemSolver);

impl std::ops::Deref for GapBands<'_> {
    type Target = RingBemSolver;
    fn deref(&self) -> &RingBemSolver {
        self.0
    }
}

impl GapBands<'_> {
    fn flat_band(&self, inner: f64, outer: f64, n: usize) -> Result<FlatBand> {
        let system = self.0.system(ContactRegion::Band { inner, outer }, n);
        let field = system
            .solve(&vec![1.0; n])
            .ok_or_else(|| no_convergence("singular collocation matrix".into()))?;
        Ok(FlatBand { system, field })
    }

    /// [`GapFunctionals`] of `gap` on the band `[inner, outer]` at `n` nodes.
    pub(crate) fn gap_functionals(
        &self,
        gap: &dyn PiecewiseGap,
        inner: f64,
        outer: f64,
        n: usize,
    ) -> Result<GapFunctionals> {
        Ok(self
            .gap_band(
                gap,
                inner,
                outer,
                n,
                BandEdges::Both,
                &mut InnerStencil::default(),
            )?
            .functionals)
    }

    /// `∂_c φ` of the flat band `centre` from [`STENCIL`]'s neighbouring bands `[b, c + k δ]`
    /// (`k = 1..5`, `δ` = [`EDGE_STEP`] of the width).
    fn outer_derivative(&self, centre: &FlatBand, nodes: &ChebyshevNodes) -> Result<Series> {
        let region = centre.system.region();
        let (inner, outer) = (region.inner(), region.outer());
        let n = nodes.len();
        let step = EDGE_STEP * (outer - inner);
        let neighbours = STENCIL[1..]
            .iter()
            .map(|&(k, _)| {
                Ok(Series::new(
                    nodes,
                    &self.flat_band(inner, outer + k * step, n)?,
                ))
            })
            .collect::<Result<Vec<_>>>()?;
        Ok(derivative_series(
            centre,
            nodes,
            &neighbours,
            &STENCIL.map(|(_, w)| w),
            -step,
        ))
    }

    /// The outer edge's intensity of a band built for its inner edge only
    /// ([`BandEdges::Inner`]): its stencil's five factorisations and the edge's integral, the
    /// same to the bit as [`BandEdges::Both`] would have given.
    pub(crate) fn complete_outer_edge(
        &self,
        gap: &dyn PiecewiseGap,
        band: &mut GapBand,
    ) -> Result<()> {
        if band.functionals.gap_outer_intensity.is_some() {
            return Ok(());
        }
        let n = band.system.unknowns();
        let region = band.system.region();
        let (inner, outer) = (region.inner(), region.outer());
        let centre = FlatBand {
            system: band.system.clone(),
            field: band.flat.clone(),
        };
        let nodes = ChebyshevNodes::new(n);
        let by_outer = self.outer_derivative(&centre, &nodes)?;
        let factor = SmoothFactor {
            centre: Series::new(&nodes, &centre),
            by_inner: None,
            by_outer: Some(by_outer),
        };
        let remainder = Remainder {
            gap,
            smooth: &band.smooth,
        };
        let integrals = band_integrals(&self.0.band_rule, &remainder, (inner, outer), &factor);
        band.functionals.gap_outer_intensity = Some(outer_edge_intensity(
            &band.system,
            &band.smooth_gap,
            &remainder,
            band.functionals.flat_outer_intensity,
            integrals.outer_derivative,
        ));
        Ok(())
    }

    /// [`GapBand`] of `gap` on the band `[inner, outer]` at `n` nodes: the band and
    /// [`STENCIL`]'s neighbours for the derivative of each edge in `edges`, one factorisation
    /// each, the inner edge's taken from `stencil` where it holds a search's bands that contain
    /// this one ([`InnerStencil`]: one factorisation instead of six), else built for this band and
    /// kept there (a fresh `InnerStencil::default()` for a band alone).
    pub(crate) fn gap_band(
        &self,
        gap: &dyn PiecewiseGap,
        inner: f64,
        outer: f64,
        n: usize,
        edges: BandEdges,
        stencil: &mut InnerStencil,
    ) -> Result<GapBand> {
        let width = outer - inner;
        let centre = self.flat_band(inner, outer, n)?;
        let nodes = ChebyshevNodes::new(n);
        let kept = match stencil.kept.take() {
            Some(kept) if kept.holds(inner, outer, n, edges.inner_stencil()) => kept,
            _ => {
                let step = EDGE_STEP * inner.min(width);
                let neighbours = edges.inner_stencil()[1..]
                    .iter()
                    .map(|&(k, _)| {
                        Ok(Series::new(
                            &nodes,
                            &self.flat_band(inner - k * step, outer, n)?,
                        ))
                    })
                    .collect::<Result<Vec<_>>>()?;
                KeptStencil {
                    anchor: inner,
                    outer,
                    n,
                    step,
                    rule: edges.inner_stencil(),
                    neighbours,
                }
            }
        };
        let kept = stencil.kept.insert(kept);
        let series = Series::new(&nodes, &centre);
        let by_inner = derivative_series(
            &centre,
            &nodes,
            &kept.neighbours,
            &kept.weights(inner),
            kept.step,
        );
        let by_outer = match edges {
            BandEdges::Both => Some(self.outer_derivative(&centre, &nodes)?),
            BandEdges::Inner | BandEdges::InnerRough => None,
        };
        let factor = SmoothFactor {
            centre: series,
            by_inner: Some(by_inner),
            by_outer,
        };
        let smooth = SmoothPart::new(gap, inner, outer, (n / 2).min(SMOOTH_PART_NODES));
        let target: Vec<f64> = centre
            .system
            .radii()
            .iter()
            .map(|&r| smooth.value(r))
            .collect();
        let direct = centre
            .system
            .solve(&target)
            .ok_or_else(|| no_convergence("singular collocation matrix".into()))?;
        let remainder = Remainder {
            gap,
            smooth: &smooth,
        };
        let integrals = band_integrals(&self.0.band_rule, &remainder, (inner, outer), &factor);
        let flat_inner = centre.system.inner_stress_intensity(&centre.field);
        let flat_outer = centre.system.rim_stress_intensity(&centre.field);
        let functionals = GapFunctionals {
            flat_force: centre.field.force,
            flat_inner_intensity: flat_inner,
            flat_outer_intensity: flat_outer,
            gap_force: direct.force + integrals.force,
            gap_inner_intensity: centre.system.inner_stress_intensity(&direct)
                + flat_inner * remainder.value(inner)
                - integrals.inner_derivative / (2.0 * PI * inner * flat_inner),
            gap_outer_intensity: factor.by_outer.as_ref().map(|_| {
                outer_edge_intensity(
                    &centre.system,
                    &direct,
                    &remainder,
                    flat_outer,
                    integrals.outer_derivative,
                )
            }),
        };
        Ok(GapBand {
            functionals,
            system: centre.system,
            flat: centre.field,
            smooth_gap: direct,
            smooth,
        })
    }
}

/// `K_c[g] = K_c[g_s] + K_c[1] g_r(c) + ∫ ∂_c p¹ (g_r - g_r(c)) dA / (2π c K_c[1])` on the band
/// of `system` (outer edge `c`): the smooth part's intensity from its collocated field `direct`,
/// the remainder `g_r`'s through the outer derivative's integral `outer_derivative`.
fn outer_edge_intensity(
    system: &RingSystem,
    direct: &RingField,
    remainder: &Remainder,
    flat_outer: f64,
    outer_derivative: f64,
) -> f64 {
    let outer = system.region().outer();
    system.rim_stress_intensity(direct)
        + flat_outer * remainder.value(outer)
        + outer_derivative / (2.0 * PI * outer * flat_outer)
}

/// How far, in units of the kept stencil's step `δ`, a band's inner edge may lie from the
/// stencil's anchor and still take its neighbours ([`InnerStencil`]).
const STENCIL_REACH: f64 = 0.25;

/// The distance `|b - b₀|` within which bands `[b, c]` share the inner stencil of the band
/// `[b₀, c]` = `[inner, outer]` ([`InnerStencil`]): samples that close cost one factorisation.
pub(crate) fn inner_stencil_reach(inner: f64, outer: f64) -> f64 {
    STENCIL_REACH * EDGE_STEP * inner.min(outer - inner)
}

/// The inner edge's neighbouring bands `[b₀ - k δ, c]` (`k = 1..5`, `δ` = [`EDGE_STEP`] of
/// `min(b₀, c - b₀)`) of the first band `[b₀, c]` a search sampled at one node count. The search's
/// later samples land close to it; a band `[b, c]` with `|b - b₀| <= δ/4` ([`STENCIL_REACH`])
/// takes the same neighbours (they contain it) and the derivative weights of its own nodes
/// `{b, b₀ - δ, ..., b₀ - 5δ}`, so each of its samples costs one factorisation, not six.
/// Truncation stays within 1.7 times the uniform stencil's (the product of the nodes' distances
/// from `b`, `Π (b - x_k)`, at most `1.25·2.25·3.25·4.25·5.25 δ⁵` against `5! δ⁵`).
#[derive(Default)]
pub(crate) struct InnerStencil {
    kept: Option<KeptStencil>,
}

struct KeptStencil {
    anchor: f64,
    outer: f64,
    n: usize,
    step: f64,
    /// The difference stencil ([`STENCIL`] or [`ROUGH_STENCIL`]).
    rule: &'static [(f64, f64)],
    neighbours: Vec<Series>,
}

impl KeptStencil {
    /// Whether the kept neighbours serve the band `[inner, outer]` at `n` nodes with the
    /// difference stencil `rule`.
    fn holds(&self, inner: f64, outer: f64, n: usize, rule: &[(f64, f64)]) -> bool {
        self.n == n
            && self.outer == outer
            && self.rule == rule
            && (inner - self.anchor).abs() <= STENCIL_REACH * self.step
    }

    /// The derivative's weights at `b = inner` in units of the kept step (zero beyond the
    /// stencil's nodes): its own at the anchor, else the Lagrange basis's derivatives at `b`
    /// over the nodes `x_0 = b`, `x_k = b₀ - k δ`: with `u_k = (b - x_k) / δ`,
    /// `w_0 = Σ_{k≥1} 1/u_k` and `w_j = -Π_{k≠0,j} u_k / (u_j Π_{k≠0,j} (u_k - u_j))`.
    fn weights(&self, inner: f64) -> [f64; 6] {
        let mut w = [0.0; 6];
        let count = self.rule.len();
        if inner == self.anchor {
            for (w, &(_, weight)) in w.iter_mut().zip(self.rule) {
                *w = weight;
            }
            return w;
        }
        let u: Vec<f64> = (0..count)
            .map(|k| {
                if k == 0 {
                    0.0
                } else {
                    (inner - (self.anchor - self.rule[k].0 * self.step)) / self.step
                }
            })
            .collect();
        w[0] = u[1..].iter().map(|u| 1.0 / u).sum();
        for j in 1..count {
            let (mut numerator, mut denominator) = (1.0, -u[j]);
            for k in (1..count).filter(|&k| k != j) {
                numerator *= u[k];
                denominator *= u[k] - u[j];
            }
            w[j] = numerator / denominator;
        }
        w
    }
}

/// The [`InnerStencil`] of each node count an inverse problem samples.
#[derive(Default)]
pub(crate) struct InnerStencils(std::collections::HashMap<usize, InnerStencil>);

impl InnerStencils {
    /// The stencil kept for `n` nodes (empty at first).
    pub fn at(&mut self, n: usize) -> &mut InnerStencil {
        self.0.entry(n).or_default()
    }
}

/// The fields behind [`GapFunctionals`], kept to draw the surface inside the band's hole.
pub(crate) struct GapBand {
    pub functionals: GapFunctionals,
    system: RingSystem,
    /// The field of `w = 1`.
    flat: RingField,
    /// The field of `w = g_s` (collocated directly).
    smooth_gap: RingField,
    smooth: SmoothPart,
}

impl GapBand {
    /// The band's collocation system.
    pub fn system(&self) -> &RingSystem {
        &self.system
    }

    /// The surface inside the band's hole when the band is held at `w = d - g` (`d` = `depth`):
    /// `w(r) = d w¹ - w[g_s] - w[g - g_s]` ([`HoleSurface::at`]), the first two from one
    /// collocated field (`d φ¹ - φ[g_s]`, [`RingSystem::deflection_in_hole`]), the remainder's by
    /// reciprocity, `w[g_r](r) = ∫ g_r q dA`, with `q` the band's field whose deflection on the
    /// band is the ring kernel `H(r, s) = (2/π²) K(m) / (r + s)` of the point `r` (analytic on the
    /// band, so collocated to the method's accuracy). `q`'s smooth factor is the interpolant
    /// `Σ_j q_j L_j(t)` of its values at the nodes, so the integral is `Σ_j q_j μ_j` with the
    /// moments `μ_j = ∫ L_j(t(s)) W(s) g_r(s) dA`, integrated piece by piece once per surface
    /// (every radius of the hole shares them).
    pub fn hole_surface(
        &self,
        gap: &dyn PiecewiseGap,
        depth: f64,
        rule: &TanhSinhRule,
    ) -> HoleSurface<'_> {
        let region = self.system.region();
        let (inner, outer) = (region.inner(), region.outer());
        let remainder = Remainder {
            gap,
            smooth: &self.smooth,
        };
        let n = self.system.unknowns();
        let nodes = ChebyshevNodes::new(n);
        let log_span = (outer / inner).ln();
        let mut moments = vec![0.0; n];
        let mut basis = vec![0.0; n];
        for node in band_nodes(rule, gap, (inner, outer)) {
            let c = node.area * node.weight * remainder.value(node.s);
            nodes.basis_at(2.0 * (node.s / inner).ln() / log_span - 1.0, &mut basis);
            for (moment, &l) in moments.iter_mut().zip(&basis) {
                *moment += c * l;
            }
        }
        HoleSurface {
            system: &self.system,
            field: self.flat.combined(depth, &self.smooth_gap, -1.0),
            moments,
        }
    }
}

/// The surface inside a [`GapBand`]'s hole at one depth ([`GapBand::hole_surface`]).
pub(crate) struct HoleSurface<'a> {
    system: &'a RingSystem,
    /// `d φ¹ - φ[g_s]`: the collocated part of the band's field.
    field: RingField,
    /// `μ_j = ∫ L_j W g_r dA`: the remainder's moments against the nodes' basis.
    moments: Vec<f64>,
}

impl HoleSurface<'_> {
    /// Surface deflection `w(r)` at a radius `0 <= r < b` (`None` outside the hole):
    /// `w[d - g_s](r) - Σ_j q_j μ_j`, with `q` the field of `H(r, ·)` on the band.
    pub fn at(&self, r: f64, rule: &TanhSinhRule) -> Option<f64> {
        let collocated = self.system.deflection_in_hole(&self.field, r, rule)?;
        let kernel: Vec<f64> = self
            .system
            .radii()
            .iter()
            .map(|&s| {
                2.0 / (PI * PI) * complete_k_from_complementary((s - r).abs() / (s + r)) / (s + r)
            })
            .collect();
        let reciprocal = self.system.solve(&kernel)?;
        let integral: f64 = reciprocal
            .phi
            .iter()
            .zip(&self.moments)
            .map(|(q, mu)| q * mu)
            .sum();
        Some(collocated - integral)
    }
}

/// The ends of the quadrature panels over `[inner, outer]`: the edges and the gap's break points
/// between them, so every panel's integrand is smooth.
fn panel_ends(gap: &dyn PiecewiseGap, inner: f64, outer: f64) -> Vec<f64> {
    let mut ends = vec![inner];
    ends.extend(
        gap.break_points()
            .iter()
            .copied()
            .filter(|&k| k > inner && k < outer),
    );
    ends.push(outer);
    ends
}

/// Gauss-Legendre points of a panel away from the band's edges (see [`panel_nodes`]).
const INTERIOR_POINTS: usize = 14;

/// Tanh-sinh step of a band's integrals ([`band_integrals`]; about 1e-14 for the edge panels'
/// inverse square roots, where the collocation rows take 1/16): the results move within the free
/// edge's rounding floor for fewer nodes (docs/decisions.md, "Where the constants come from").
pub(crate) const BAND_INTEGRAL_STEP: f64 = 1.0 / 8.0;

/// The nodes of the panel `[lo, hi]` of the band `[inner, outer]`: the tanh-sinh `rule` where
/// the panel reaches an edge or lies closer to one than half its length (the edge weight's
/// inverse square root is singular there), else [`INTERIOR_POINTS`] Gauss-Legendre points. Their
/// integrand is analytic inside the ellipse with foci at the panel's ends through the nearest
/// edge (semi-axis ratio `ρ >= 2 + sqrt 3`), so the rule's error is of order
/// `ρ^{-2n} <= 1e-16`, with under a quarter of the tanh-sinh nodes.
fn panel_nodes(rule: &TanhSinhRule, panel: (f64, f64), band: (f64, f64)) -> Vec<PanelNode> {
    static INTERIOR: std::sync::OnceLock<(Vec<f64>, Vec<f64>)> = std::sync::OnceLock::new();
    let ((lo, hi), (inner, outer)) = (panel, band);
    let length = hi - lo;
    if (lo - inner).min(outer - hi) < 0.5 * length {
        return rule.panel(lo, hi).collect();
    }
    let (points, weights) = INTERIOR.get_or_init(|| gauss_legendre(INTERIOR_POINTS));
    points
        .iter()
        .zip(weights)
        .map(|(&x, &w)| PanelNode {
            position: lo + x * length,
            from_lo: x * length,
            from_hi: (1.0 - x) * length,
            weight: w * length,
        })
        .collect()
}

/// `∫ p¹ g dA`, `∫ ∂_b p¹ (g - g(b)) dA` and `∫ ∂_c p¹ (g - g(c)) dA`.
struct BandIntegrals {
    force: f64,
    inner_derivative: f64,
    outer_derivative: f64,
}

/// The three integrals over `[b, c]` = `band`, by tanh-sinh on the panels between the gap's
/// break points, from the flat field's smooth factor and its edge derivatives. Distances to the
/// edges are summed from the panel's end and the node's own distance to it, so the edge weights
/// keep their precision at nodes next to an edge.
fn band_integrals(
    rule: &TanhSinhRule,
    gap: &dyn PiecewiseGap,
    band: (f64, f64),
    factor: &SmoothFactor,
) -> BandIntegrals {
    let (inner, outer) = band;
    let mut total = BandIntegrals {
        force: 0.0,
        inner_derivative: 0.0,
        outer_derivative: 0.0,
    };
    for node in band_nodes(rule, gap, band) {
        let (s, area, weight) = (node.s, node.area, node.weight);
        let (phi, phi_by_inner, phi_by_outer) = factor.at(s);
        total.force += area * phi * weight * gap.value(s);
        let by_inner = (phi_by_inner + 0.5 * phi / node.from_inner) * weight;
        total.inner_derivative += area * by_inner * gap.increment(inner, node.from_inner);
        if factor.by_outer.is_some() {
            let by_outer = (phi_by_outer - 0.5 * phi / node.from_outer) * weight;
            total.outer_derivative += area * by_outer * gap.increment(outer, -node.from_outer);
        }
    }
    total
}

/// A node of the band's piecewise rule ([`band_nodes`]).
struct BandNode {
    /// The radius `s`.
    s: f64,
    /// `2π s` times the rule's weight: the area element.
    area: f64,
    /// The edge weight `W(s) = 1 / sqrt((s - b)(c - s))`.
    weight: f64,
    /// `s - b` and `c - s`, each summed from its panel's end and the node's own distance to it,
    /// so the edge weight keeps its precision next to an edge.
    from_inner: f64,
    from_outer: f64,
}

/// The nodes of the band `[b, c]` = `band` panel by panel between the gap's break points
/// ([`panel_ends`], [`panel_nodes`]).
fn band_nodes<'a>(
    rule: &'a TanhSinhRule,
    gap: &dyn PiecewiseGap,
    band: (f64, f64),
) -> impl Iterator<Item = BandNode> + 'a {
    let (inner, outer) = band;
    let ends = panel_ends(gap, inner, outer);
    (0..ends.len() - 1).flat_map(move |k| {
        let (lo, hi) = (ends[k], ends[k + 1]);
        panel_nodes(rule, (lo, hi), band)
            .into_iter()
            .map(move |node| {
                let from_inner = (lo - inner) + node.from_lo;
                let from_outer = (outer - hi) + node.from_hi;
                BandNode {
                    s: node.position,
                    area: 2.0 * PI * node.position * node.weight,
                    weight: 1.0 / (from_inner * from_outer).sqrt(),
                    from_inner,
                    from_outer,
                }
            })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A smooth gap with a wave the smooth part's 24 points do not resolve,
    /// `1 - r² + 0.05 sin(25 r)`, cut into panels at made-up break points: the remainder is not
    /// small, and the direct collocation (geometric, the gap is analytic) is the reference.
    struct Wavy {
        breaks: Vec<f64>,
    }

    impl PiecewiseGap for Wavy {
        fn value(&self, r: f64) -> f64 {
            1.0 - r * r + 0.05 * (25.0 * r).sin()
        }
        fn increment(&self, r: f64, offset: f64) -> f64 {
            -offset * (2.0 * r + offset)
                + 0.1 * (25.0 * (r + 0.5 * offset)).cos() * (12.5 * offset).sin()
        }
        fn break_points(&self) -> &[f64] {
            &self.breaks
        }
    }

    #[test]
    fn functionals_of_a_smooth_gap_equal_its_direct_collocation() {
        let owner = RingBemSolver::new();
        let solver = GapBands(&owner);
        let gap = Wavy {
            breaks: vec![0.05, 0.3, 0.55, 0.8, 0.95, 1.2],
        };
        for (inner, outer) in [(0.3, 1.0), (0.02, 1.0), (0.7, 0.9), (0.5, 1.4)] {
            let depth = 0.7;
            let direct = solver
                .prescribed_band(|r| gap.value(r), inner, outer, depth, 1e-12)
                .unwrap();
            let f = solver.gap_functionals(&gap, inner, outer, 48).unwrap();
            let scale = direct
                .inner_stress_intensity
                .abs()
                .max(direct.outer_stress_intensity.abs());
            let errors = [
                (f.force(depth) - direct.force).abs() / direct.force.abs(),
                (f.inner_intensity(depth) - direct.inner_stress_intensity).abs() / scale,
                (f.outer_intensity(depth).unwrap() - direct.outer_stress_intensity).abs() / scale,
            ];
            // 3e-14 on [0.3, 1], 1.4e-10 on [0.02, 1] (the wave leaves a remainder of 5 % of
            // the gap, far more than a piecewise profile's, for the edge derivatives to carry).
            assert!(
                errors.iter().all(|e| *e < 1e-9),
                "band [{inner}, {outer}]: {errors:?}"
            );
        }
    }

    /// A band built for its inner edge and completed with its outer edge carries the same
    /// functionals, to the bit, as one built with both (the state's rim intensity is the
    /// completed one).
    #[test]
    fn a_band_completed_with_its_outer_edge_equals_one_built_with_both() {
        let owner = RingBemSolver::new();
        let solver = GapBands(&owner);
        let gap = Wavy {
            breaks: vec![0.05, 0.3, 0.55, 0.8, 0.95],
        };
        for (inner, outer) in [(0.3, 1.0), (0.02, 1.0), (0.7, 0.9)] {
            let both = solver
                .gap_band(
                    &gap,
                    inner,
                    outer,
                    24,
                    BandEdges::Both,
                    &mut InnerStencil::default(),
                )
                .unwrap()
                .functionals;
            let mut band = solver
                .gap_band(
                    &gap,
                    inner,
                    outer,
                    24,
                    BandEdges::Inner,
                    &mut InnerStencil::default(),
                )
                .unwrap();
            assert!(band.functionals.gap_outer_intensity.is_none());
            solver.complete_outer_edge(&gap, &mut band).unwrap();
            let completed = band.functionals;
            assert!(completed.gap_outer_intensity.is_some());
            assert_eq!(completed.gap_outer_intensity, both.gap_outer_intensity);
            assert_eq!(completed.gap_inner_intensity, both.gap_inner_intensity);
            assert_eq!(completed.gap_force, both.gap_force);
        }
    }

    /// The weights of a reused stencil differentiate a quintic exactly at any `b` within a
    /// quarter step of the anchor (the Lagrange basis over six nodes), and are [`STENCIL`]'s at
    /// the anchor itself.
    #[test]
    fn a_reused_stencil_differentiates_quintics_exactly() {
        let (anchor, step) = (0.4, 0.003);
        let stencil = KeptStencil {
            anchor,
            outer: 1.0,
            n: 16,
            step,
            rule: &STENCIL,
            neighbours: Vec::new(),
        };
        let quintic = |x: f64| 0.3 - 2.0 * x + x.powi(2) - 4.0 * x.powi(3) + 3.0 * x.powi(5);
        let slope = |x: f64| -2.0 + 2.0 * x - 12.0 * x.powi(2) + 15.0 * x.powi(4);
        for offset in [-0.25, -0.1, 0.0, 0.13, 0.25] {
            let b = anchor + offset * step;
            let weights = stencil.weights(b);
            let nodes: Vec<f64> = std::iter::once(b)
                .chain(STENCIL[1..].iter().map(|&(k, _)| anchor - k * step))
                .collect();
            let derivative = weights
                .iter()
                .zip(&nodes)
                .map(|(w, &x)| w * quintic(x))
                .sum::<f64>()
                / step;
            assert!(
                (derivative - slope(b)).abs() < 1e-9,
                "offset {offset}: {derivative} against {}",
                slope(b)
            );
        }
        assert_eq!(stencil.weights(anchor), STENCIL.map(|(_, w)| w));
    }

    /// The rough stencil's reused weights differentiate quadratics exactly (the Lagrange basis
    /// over three nodes), are [`ROUGH_STENCIL`]'s at the anchor, and a rough stencil is never
    /// taken for a full one.
    #[test]
    fn a_reused_rough_stencil_differentiates_quadratics_exactly() {
        let (anchor, step) = (0.2, 0.002);
        let stencil = KeptStencil {
            anchor,
            outer: 1.0,
            n: 16,
            step,
            rule: &ROUGH_STENCIL,
            neighbours: Vec::new(),
        };
        let quadratic = |x: f64| 0.7 - 3.0 * x + 5.0 * x * x;
        let slope = |x: f64| -3.0 + 10.0 * x;
        for offset in [-0.25, 0.0, 0.2] {
            let b = anchor + offset * step;
            let weights = stencil.weights(b);
            assert_eq!(&weights[3..], &[0.0; 3]);
            let derivative = weights[0] * quadratic(b)
                + weights[1] * quadratic(anchor - step)
                + weights[2] * quadratic(anchor - 2.0 * step);
            assert!(
                (derivative / step - slope(b)).abs() < 1e-9,
                "offset {offset}: {} against {}",
                derivative / step,
                slope(b)
            );
        }
        assert_eq!(
            &stencil.weights(anchor)[..3],
            &ROUGH_STENCIL.map(|(_, w)| w)
        );
        assert!(stencil.holds(anchor, 1.0, 16, &ROUGH_STENCIL));
        assert!(!stencil.holds(anchor, 1.0, 16, &STENCIL));
    }

    /// A rough band's depth of a free inner edge is within the stated 4e-6 of the full
    /// stencil's on the wavy gap (its remainder is far larger than a piecewise profile's) at 16 nodes.
    #[test]
    fn a_rough_band_is_close_to_the_full_one() {
        let owner = RingBemSolver::new();
        let solver = GapBands(&owner);
        let gap = Wavy {
            breaks: vec![0.05, 0.3, 0.55, 0.8, 0.95],
        };
        for inner in [0.02, 0.1, 0.4, 0.8] {
            let depth = |edges| {
                solver
                    .gap_band(&gap, inner, 1.0, 16, edges, &mut InnerStencil::default())
                    .unwrap()
                    .functionals
                    .free_inner_depth()
            };
            let (full, rough) = (depth(BandEdges::Inner), depth(BandEdges::InnerRough));
            assert!(
                (rough - full).abs() <= 4e-6 * full.abs().max(1.0),
                "b = {inner}: rough {rough} against {full}"
            );
        }
    }

    /// A band next to a search's first one reuses its neighbours (one factorisation, not six)
    /// and its inner intensity is as accurate as that of the band built alone ([`STENCIL`] at
    /// its own edge); the reference is the direct collocation of the (analytic) wavy gap.
    #[test]
    fn a_band_on_a_reused_stencil_is_as_accurate_as_one_built_alone() {
        let owner = RingBemSolver::new();
        let solver = GapBands(&owner);
        let gap = Wavy {
            breaks: vec![0.05, 0.3, 0.55, 0.8, 0.95],
        };
        let depth = 0.7;
        // At 48 nodes, both ways: at most 3.2e-13 on [0.3, 1] and [0.7, 1]; 4.4e-9 near
        // [0.02, 1], where the wave leaves a remainder of 5 % of the gap for the differences'
        // rounding (a piecewise profile's is far smaller).
        for (first, bound) in [(0.3, 1e-11), (0.02, 1e-8), (0.7, 1e-11)] {
            let mut stencil = InnerStencil::default();
            solver
                .gap_band(&gap, first, 1.0, 48, BandEdges::Inner, &mut stencil)
                .unwrap();
            let step = EDGE_STEP * first.min(1.0 - first);
            for offset in [-0.24, 0.1, 0.24] {
                let inner = first + offset * step;
                let direct = solver
                    .prescribed_band(|r| gap.value(r), inner, 1.0, depth, 1e-12)
                    .unwrap()
                    .inner_stress_intensity;
                let before = solver.factorisations();
                let reused = solver
                    .gap_band(&gap, inner, 1.0, 48, BandEdges::Inner, &mut stencil)
                    .unwrap()
                    .functionals;
                assert_eq!(solver.factorisations() - before, 1, "b = {inner}");
                let alone = solver
                    .gap_band(
                        &gap,
                        inner,
                        1.0,
                        48,
                        BandEdges::Inner,
                        &mut InnerStencil::default(),
                    )
                    .unwrap()
                    .functionals;
                for (way, f) in [("reused", reused), ("alone", alone)] {
                    let error = (f.inner_intensity(depth) - direct).abs() / direct.abs();
                    assert!(error < bound, "b = {inner}, {way}: {error:.1e}");
                }
                assert_eq!(reused.gap_force, alone.gap_force, "b = {inner}");
            }
            // Beyond a quarter step the neighbours are rebuilt.
            let before = solver.factorisations();
            let farther = first + 0.3 * step;
            solver
                .gap_band(&gap, farther, 1.0, 48, BandEdges::Inner, &mut stencil)
                .unwrap();
            assert_eq!(solver.factorisations() - before, 6);
        }
    }

    /// The surface in the hole, drawn through the smooth part and the remainder's reciprocal
    /// field, equals the direct collocation's (the wavy gap is analytic: 64 nodes converge).
    #[test]
    fn the_surface_in_the_hole_equals_its_direct_collocation() {
        let owner = RingBemSolver::new();
        let solver = GapBands(&owner);
        let rule = TanhSinhRule::new(1.0 / 16.0);
        let gap = Wavy {
            breaks: vec![0.05, 0.3, 0.55, 0.8, 0.95],
        };
        for inner in [0.3, 0.05] {
            let depth = 1.7;
            let system = RingSystem::assemble(ContactRegion::Band { inner, outer: 1.0 }, 64, &rule);
            let target: Vec<f64> = system
                .radii()
                .iter()
                .map(|&r| depth - gap.value(r))
                .collect();
            let direct = system.solve(&target).unwrap();
            let band = solver
                .gap_band(
                    &gap,
                    inner,
                    1.0,
                    40,
                    BandEdges::Inner,
                    &mut InnerStencil::default(),
                )
                .unwrap();
            let surface = band.hole_surface(&gap, depth, &rule);
            for k in 0..8 {
                let r = inner * k as f64 / 8.0;
                let expected = system.deflection_in_hole(&direct, r, &rule).unwrap();
                let got = surface.at(r, &rule).unwrap();
                assert!(
                    (got - expected).abs() < 1e-10 * depth,
                    "b = {inner}, r = {r}: {got} against {expected}"
                );
            }
        }
    }
}
