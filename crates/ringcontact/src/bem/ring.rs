//! Axisymmetric ring-element BEM with the exact elliptic-integral ring kernel.
//!
//! Surface deflection of an elastic half-space under an axisymmetric pressure `p(s)` on the
//! contact interval `b <= s <= a` (Johnson, *Contact Mechanics*, eq. 3.39 integrated over rings):
//!
//! ```text
//! w(r) = 4 / (π E*) ∫_b^a p(s) s K(m) / (r + s) ds,   m = 4 r s / (r + s)²,   1 - m = ((r - s)/(r + s))²
//! ```
//!
//! **Discretisation (Gauss-Chebyshev collocation).** The pressure carries the exact edge
//! behaviour in a weight, `p(s) = E* φ(s) W(s)`, with
//! `W = 1 / sqrt((a - s)(s - b))` for an annulus (inverse square roots at both edges) and
//! `W = 1 / sqrt(a² - s²)` for a full disk (`b = 0`). The smooth factor `φ` is the polynomial
//! interpolant through its values at `N` Chebyshev points of the first kind, in `ln s` on
//! `[b, a]` for the annulus (and any band) and in `s²` on `[0, a²]` for the disk (the disk's
//! pressure is even in `s`).
//! The equation `w(r_i) = w_target(r_i)` is imposed at the same points. On an annulus or band the
//! rows are integrated in the interpolation variable by product integration on one set of
//! Chebyshev points ([`band_matrix`]: the logarithm of `K` in closed form against the Chebyshev
//! polynomials, the rest by Gauss-Chebyshev); on the disk each row is split at `r_i` and
//! integrated by tanh-sinh quadrature. Both integrate the logarithmic singularity at `s = r_i`
//! and the edge singularities of `W` to near machine precision, so the error of the method is
//! the interpolation error of `φ`: geometric in `N` wherever `φ` is analytic.
//!
//! Lengths are scaled by the rim radius `a` and pressures by `E*`; everything in this module is
//! dimensionless (`a = 1`, `E* = 1`).

use std::f64::consts::PI;

use nalgebra::{DMatrix, DVector};
use rayon::prelude::*;

use crate::numerics::chebyshev::ChebyshevNodes;
use crate::numerics::elliptic::complete_k_from_complementary;
use crate::numerics::tanh_sinh::{PanelNode, TanhSinhRule};

mod band_matrix;

/// Shape of the contact region, in units of the rim radius `a = 1`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ContactRegion {
    /// Full disk `0 <= r <= 1`.
    Disk,
    /// Annulus `eps <= r <= 1`, `0 < eps < 1`.
    Annulus { eps: f64 },
    /// Band `inner <= r <= outer`, `0 < inner < outer` (either edge may lie beyond `a = 1`: the
    /// contact of a convex ring, or any prescribed annulus).
    Band { inner: f64, outer: f64 },
}

impl ContactRegion {
    /// The inner edge: 0 for the disk.
    pub(crate) fn inner(&self) -> f64 {
        match *self {
            ContactRegion::Disk => 0.0,
            ContactRegion::Annulus { eps } => eps,
            ContactRegion::Band { inner, .. } => inner,
        }
    }

    /// The outer edge: the rim `1` for the disk and the annulus.
    pub(crate) fn outer(&self) -> f64 {
        match *self {
            ContactRegion::Band { outer, .. } => outer,
            _ => 1.0,
        }
    }
}

/// The assembled and factorised collocation system for one contact region.
#[derive(Clone)]
pub struct RingSystem {
    region: ContactRegion,
    nodes: ChebyshevNodes,
    /// Collocation radii `r_i` (same order as the nodes).
    radii: Vec<f64>,
    lu: nalgebra::LU<f64, nalgebra::Dyn, nalgebra::Dyn>,
    /// `F = Σ_j force_weights[j] φ_j` (with `E* = 1`, `a = 1`).
    force_weights: Vec<f64>,
    /// `φ(a) = Σ_j rim_basis[j] φ_j`.
    rim_basis: Vec<f64>,
    /// `φ(b) = Σ_j inner_basis[j] φ_j` (annulus only).
    inner_basis: Vec<f64>,
}

/// A solved pressure field on a fixed contact region.
#[derive(Clone, Debug)]
pub struct RingField {
    /// Values of the smooth factor `φ` at the collocation radii.
    pub phi: Vec<f64>,
    /// Total force `F = 2π ∫ p s ds` (units of `E* a²`).
    pub force: f64,
    /// `φ(a)`: the coefficient of the rim singularity.
    pub rim_coefficient: f64,
    /// `φ(b)`: the coefficient of the inner-edge singularity (0 for a disk).
    pub inner_coefficient: f64,
}

impl RingField {
    /// The field of the deflection `x w + y w'` on the same system, `x` times this field (of
    /// `w`) plus `y` times `other` (of `w'`): every part is linear in the deflection.
    pub fn combined(&self, x: f64, other: &RingField, y: f64) -> RingField {
        let combine = |a: f64, b: f64| x * a + y * b;
        RingField {
            phi: self
                .phi
                .iter()
                .zip(&other.phi)
                .map(|(a, b)| combine(*a, *b))
                .collect(),
            force: combine(self.force, other.force),
            rim_coefficient: combine(self.rim_coefficient, other.rim_coefficient),
            inner_coefficient: combine(self.inner_coefficient, other.inner_coefficient),
        }
    }
}

/// Exact ring kernel `G(r, s) = s K(m) / (r + s)`, given `|r - s|` computed without
/// cancellation.
#[inline]
fn ring_kernel(r: f64, s: f64, distance: f64) -> f64 {
    let sum = r + s;
    s * complete_k_from_complementary(distance / sum) / sum
}

impl RingSystem {
    /// Assemble and factorise the collocation system for `region` at `n` Chebyshev collocation
    /// points (the unknowns): a band's or annulus's rows by [`band_matrix`] (product
    /// integration), the disk's (and a band too long for it) by the tanh-sinh `rule` (a step of
    /// `1/8` integrates a row to about 1e-14).
    pub fn assemble(region: ContactRegion, n: usize, rule: &TanhSinhRule) -> Self {
        let nodes = ChebyshevNodes::new(n);
        let (inner, outer) = (region.inner(), region.outer());
        let radii: Vec<f64> = nodes.points.iter().map(|&t| radius_of(region, t)).collect();
        let band = match region {
            ContactRegion::Disk => None,
            ContactRegion::Annulus { .. } | ContactRegion::Band { .. } => {
                band_matrix::band_matrix(inner, outer, &nodes)
            }
        };
        let (matrix, force_weights) = match band {
            Some(band) => (band.matrix, band.force_weights),
            None => (
                tanh_sinh_matrix(region, &nodes, &radii, rule),
                tanh_sinh_force_weights(region, &nodes, rule),
            ),
        };
        let mut rim_basis = vec![0.0; n];
        nodes.basis_at(1.0, &mut rim_basis);
        let mut inner_basis = vec![0.0; n];
        nodes.basis_at(-1.0, &mut inner_basis);
        Self {
            region,
            nodes,
            radii,
            lu: matrix.lu(),
            force_weights,
            rim_basis,
            inner_basis,
        }
    }

    /// Collocation radii `r_i / a`.
    pub fn radii(&self) -> &[f64] {
        &self.radii
    }

    /// Number of unknowns.
    pub fn unknowns(&self) -> usize {
        self.radii.len()
    }

    /// The contact region this system was assembled for.
    pub fn region(&self) -> ContactRegion {
        self.region
    }

    /// Solve for the pressure that produces the deflection `w(r_i) = target[i]` (units of `a`).
    ///
    /// Returns `None` if the collocation matrix is singular (it is not for any valid region).
    pub fn solve(&self, target: &[f64]) -> Option<RingField> {
        let rhs = DVector::from_column_slice(target);
        let phi = self.lu.solve(&rhs)?;
        let phi: Vec<f64> = phi.iter().copied().collect();
        let dot = |w: &[f64]| w.iter().zip(&phi).map(|(a, b)| a * b).sum::<f64>();
        Some(RingField {
            force: dot(&self.force_weights),
            rim_coefficient: dot(&self.rim_basis),
            inner_coefficient: match self.region {
                ContactRegion::Disk => 0.0,
                ContactRegion::Annulus { .. } | ContactRegion::Band { .. } => {
                    dot(&self.inner_basis)
                }
            },
            phi,
        })
    }

    /// Pressure `p(r) / E*` of a solved field at radius `r` (strictly inside the region).
    pub fn pressure(&self, field: &RingField, r: f64) -> f64 {
        let inner = self.region.inner();
        let phi = self
            .nodes
            .interpolate(&field.phi, parameter_of(self.region, r));
        phi * edge_weight(self.region, r - inner, self.region.outer() - r, r)
    }

    /// Surface deflection `w(r)` (units of `a`) of a solved field at a radius `r` inside the
    /// annulus's hole (`0 <= r < b`), where the punch does not touch:
    /// `w(r) = (4/π) ∫_b^a φ(s) W(s) s K(m) / (r + s) ds`, integrated by tanh-sinh on panels no
    /// longer than their distance to `r` (the kernel's logarithm at `s = r` stays outside).
    /// `None` for a disk or a radius outside the hole.
    pub fn deflection_in_hole(
        &self,
        field: &RingField,
        r: f64,
        rule: &TanhSinhRule,
    ) -> Option<f64> {
        let inner = match self.region {
            ContactRegion::Annulus { eps } if (0.0..eps).contains(&r) => eps,
            ContactRegion::Band { inner, .. } if (0.0..inner).contains(&r) => inner,
            _ => return None,
        };
        let outer = self.region.outer();
        let mut panels = Vec::new();
        let mut lo = inner;
        loop {
            let mut hi = lo + (lo - r);
            if hi >= 0.75 * outer {
                hi = outer;
            }
            panels.push(Panel { lo, hi });
            if hi == outer {
                break;
            }
            lo = hi;
        }
        Some(self.deflection_over(field, r, &panels, rule))
    }

    /// Surface deflection `w(r)` (units of `a`) of a solved field at a radius `r` beyond the
    /// contact's outer edge (`r > c`), as [`Self::deflection_in_hole`] inside: panels from the
    /// edge inward, each no longer than its distance to `r`. `None` for `r <= c`.
    pub fn deflection_beyond(&self, field: &RingField, r: f64, rule: &TanhSinhRule) -> Option<f64> {
        let (inner, outer) = (self.region.inner(), self.region.outer());
        if !(r > outer && r.is_finite()) {
            return None;
        }
        let mut panels = Vec::new();
        let mut hi = outer;
        loop {
            let mut lo = hi - (r - hi);
            if lo <= inner + 0.25 * (outer - inner) {
                lo = inner;
            }
            panels.push(Panel { lo, hi });
            if lo == inner {
                break;
            }
            hi = lo;
        }
        Some(self.deflection_over(field, r, &panels, rule))
    }

    /// `(4/π) ∫ φ(s) W(s) s K(m) / (r + s) ds` over `panels` (which cover the contact and keep
    /// `s = r` outside).
    fn deflection_over(
        &self,
        field: &RingField,
        r: f64,
        panels: &[Panel],
        rule: &TanhSinhRule,
    ) -> f64 {
        let (inner, outer) = (self.region.inner(), self.region.outer());
        let mut total = 0.0;
        for panel in panels {
            for node in rule.panel(panel.lo, panel.hi) {
                let (s, from_inner, from_rim, _) = panel.locate(&node, inner, outer, f64::NAN);
                let phi = self
                    .nodes
                    .interpolate(&field.phi, parameter_of(self.region, s));
                let weight = edge_weight(self.region, from_inner, from_rim, s);
                total += node.weight * phi * weight * ring_kernel(r, s, (s - r).abs());
            }
        }
        4.0 / PI * total
    }

    /// Mode-I stress intensity factor at the rim, `K = lim sqrt(2π (a - r)) p(r)`, in units of
    /// `E* sqrt(a)`.
    pub fn rim_stress_intensity(&self, field: &RingField) -> f64 {
        match self.region {
            ContactRegion::Disk => field.rim_coefficient * PI.sqrt(),
            ContactRegion::Annulus { eps } => {
                field.rim_coefficient * (2.0 * PI / (1.0 - eps)).sqrt()
            }
            ContactRegion::Band { inner, outer } => {
                field.rim_coefficient * (2.0 * PI / (outer - inner)).sqrt()
            }
        }
    }

    /// Stress intensity factor at the inner edge `r = b` (zero for a disk).
    pub fn inner_stress_intensity(&self, field: &RingField) -> f64 {
        match self.region {
            ContactRegion::Disk => 0.0,
            ContactRegion::Annulus { eps } => {
                field.inner_coefficient * (2.0 * PI / (1.0 - eps)).sqrt()
            }
            ContactRegion::Band { inner, outer } => {
                field.inner_coefficient * (2.0 * PI / (outer - inner)).sqrt()
            }
        }
    }
}

/// The collocation matrix `A_ij = (4/π) ∫ W(s) G(r_i, s) L_j(t(s)) ds` at the collocation `radii`
/// `r_i` of the `nodes`, with each row split at `r_i` into tanh-sinh panels (the disk's rows, and any band too long for
/// [`band_matrix`]). The rows are independent: computed in parallel, each summed in the same
/// order as on one thread, so the matrix is the same to the bit.
fn tanh_sinh_matrix(
    region: ContactRegion,
    nodes: &ChebyshevNodes,
    radii: &[f64],
    rule: &TanhSinhRule,
) -> DMatrix<f64> {
    let n = nodes.len();
    let (inner, outer) = (region.inner(), region.outer());
    let rows: Vec<Vec<f64>> = radii
        .par_iter()
        .map(|&r| {
            let mut basis = vec![0.0; n];
            let mut row = vec![0.0; n];
            for panel in row_panels(inner, outer, r) {
                for node in rule.panel(panel.lo, panel.hi) {
                    let (s, from_inner, from_rim, distance) = panel.locate(&node, inner, outer, r);
                    let weight = edge_weight(region, from_inner, from_rim, s);
                    let c = node.weight * weight * ring_kernel(r, s, distance);
                    let c = c * nodes.scaled_basis_at(parameter_of(region, s), &mut basis);
                    for (acc, &l) in row.iter_mut().zip(&basis) {
                        *acc += c * l;
                    }
                }
            }
            row
        })
        .collect();
    DMatrix::<f64>::from_fn(n, n, |i, j| 4.0 / PI * rows[i][j])
}

/// Force weights `F = 2π ∫ φ W s ds = Σ_j w_j φ_j` by one tanh-sinh panel over the region.
fn tanh_sinh_force_weights(
    region: ContactRegion,
    nodes: &ChebyshevNodes,
    rule: &TanhSinhRule,
) -> Vec<f64> {
    let (inner, outer) = (region.inner(), region.outer());
    let mut basis = vec![0.0; nodes.len()];
    let mut force_weights = vec![0.0; nodes.len()];
    for node in rule.panel(inner, outer) {
        let s = node.position;
        let weight = edge_weight(region, node.from_lo, node.from_hi, s);
        let c = 2.0 * PI * node.weight * weight * s;
        nodes.basis_at(parameter_of(region, s), &mut basis);
        for (acc, &l) in force_weights.iter_mut().zip(&basis) {
            *acc += c * l;
        }
    }
    force_weights
}

/// Interpolation parameter `t ∈ [-1, 1]` of a radius: linear in `ln s` (annulus, band) or in
/// `s²` (disk).
fn parameter_of(region: ContactRegion, s: f64) -> f64 {
    match region {
        ContactRegion::Disk => 2.0 * s * s - 1.0,
        ContactRegion::Annulus { eps } => 2.0 * (s / eps).ln() / (1.0 / eps).ln() - 1.0,
        ContactRegion::Band { inner, outer } => 2.0 * (s / inner).ln() / (outer / inner).ln() - 1.0,
    }
}

/// Radius of an interpolation parameter (inverse of [`parameter_of`]).
fn radius_of(region: ContactRegion, t: f64) -> f64 {
    match region {
        ContactRegion::Disk => (0.5 * (1.0 + t)).sqrt(),
        ContactRegion::Annulus { eps } => eps.powf(0.5 * (1.0 - t)),
        ContactRegion::Band { inner, outer } => inner * (outer / inner).powf(0.5 * (1.0 + t)),
    }
}

/// Edge weight `W(s)` given the distances to the inner edge and to the rim.
#[inline]
fn edge_weight(region: ContactRegion, from_inner: f64, from_rim: f64, s: f64) -> f64 {
    match region {
        ContactRegion::Disk => 1.0 / (from_rim * (1.0 + s)).sqrt(),
        ContactRegion::Annulus { .. } | ContactRegion::Band { .. } => {
            1.0 / (from_rim * from_inner).sqrt()
        }
    }
}

/// A quadrature panel of one collocation row, with how its ends relate to the inner edge, the
/// rim and the collocation radius.
struct Panel {
    lo: f64,
    hi: f64,
}

impl Panel {
    /// Position of a node plus its exact distances to the inner edge, the rim and `r`.
    #[inline]
    fn locate(&self, node: &PanelNode, inner: f64, outer: f64, r: f64) -> (f64, f64, f64, f64) {
        let s = node.position;
        // Distances from the nearest panel end that coincides with a singular point.
        let from_inner = if self.lo == inner {
            node.from_lo
        } else {
            s - inner
        };
        let from_rim = if self.hi == outer {
            node.from_hi
        } else {
            outer - s
        };
        let distance = if self.hi == r {
            node.from_hi
        } else if self.lo == r {
            node.from_lo
        } else {
            (s - r).abs()
        };
        (s, from_inner, from_rim, distance)
    }
}

/// Panels for row `r`: `[b, r]` and `[r, a]`, the latter cut geometrically when the kernel's
/// near-singularity at `s = -r` is close relative to the panel length (collocation points near the
/// axis).
fn row_panels(inner: f64, outer: f64, r: f64) -> Vec<Panel> {
    let mut panels = vec![Panel { lo: inner, hi: r }];
    let mut lo = r;
    loop {
        // A panel [lo, hi] is kept no longer than its distance lo + r to the point s = -r.
        let hi = lo + (lo + r);
        if hi >= 0.75 * outer {
            panels.push(Panel { lo, hi: outer });
            break;
        }
        panels.push(Panel { lo, hi });
        lo = hi;
    }
    panels
}
