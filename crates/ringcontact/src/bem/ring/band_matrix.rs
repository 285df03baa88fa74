//! The collocation matrix of a band (or annulus) by product integration on one set of points.
//!
//! On a band `b <= s <= c` the smooth factor `φ` is interpolated in `t = 2 ln(s/b) / L - 1`,
//! `L = ln(c/b)`. In `t` the matrix entries of [`super::RingSystem`] are
//!
//! ```text
//! A_ij = (4/π) ∫_{-1}^{1} ω(t) σ(Δ) K(m) L_j(t) dt / sqrt(1 - t²),   Δ = t - t_i,
//! ω(t) = W(s) s (L/2) sqrt(1 - t²) = (L/2) e^{(1+t)L/4} sqrt((1-t)/E(1-t)) sqrt((1+t)/E(1+t)),
//! E(x) = e^{xL/2} - 1,   σ = s / (r_i + s) = 1 / (1 + e^{-ΔL/2}),   k' = |tanh(ΔL/4)|,
//! ```
//!
//! since the ring kernel depends on `s / r_i = e^{ΔL/2}` alone. `K(m)` splits into the logarithm
//! of its singularity and analytic parts (DLMF 19.12.1, whose series of `k'^{2m} ln(1/k')` sums
//! to `(2/π) K(m₁) ln(1/k')`): `K(m) = P(m₁) - ln(m₁) Q(m₁)`, `m₁ = 1 - m = k'²`,
//! `Q(m₁) = K(m₁) / π`, `P` analytic, and
//! `ln m₁ = 2 ln|Δ| + 2 ln|tanh(ΔL/4) / Δ|`, so
//!
//! ```text
//! A_ij = (4/π) Σ_m [(π/M) S_i(t_m) + v_m(t_i) R_i(t_m)] L_j(t_m),
//! S_i = ω σ (K(m) + 2 ln|Δ| Q(m₁)),   R_i = -2 ω σ Q(m₁),
//! ```
//!
//! with the Gauss-Chebyshev weights `π/M` for the analytic part and the logarithmic product
//! weights `v_m` of [`crate::numerics::log_product`] for `ln|t - t_i| R_i`. Both `S_i` and `R_i` are
//! analytic in a strip `|Im t| < 2π/L` around `[-1, 1]` (the nearest singularity is the kernel's
//! point `s = -r_i`), so `M` follows from `L`: the points needed for the product `R_i L_j` to 16
//! digits are `N` for `L_j` plus those of the Bernstein ellipse through `±1 + 2πi/L`. One kernel
//! evaluation per row and point replaces the tanh-sinh panels of each row, and the Lagrange basis
//! at the points is one table per `(N, M)`, shared by every band.

use std::collections::HashMap;
use std::f64::consts::PI;
use std::sync::{Arc, Mutex, OnceLock};

use nalgebra::{DMatrix, DVector};
use rayon::prelude::*;

use crate::numerics::chebyshev::ChebyshevNodes;
use crate::numerics::elliptic::complete_k_from_complementary;
use crate::numerics::log_product::log_weights_at_chebyshev_points;

/// A cap on `M` (reached only for `ln(c/b)` in the hundreds, far beyond any band the solvers
/// build): past it the caller keeps the tanh-sinh panels.
const MAX_POINTS: usize = 640;

/// The rule resolves the Chebyshev coefficients of `R_i L_j` down to `e^{-50}`: a margin over 16
/// digits, since their decay is estimated from the nearest singularity alone (sized for
/// `e^{-37}`, the free-edge depth of `1 - ρ^0.25` at `b/c = 1e-4` moved by 4e-10).
const LOG_RESOLUTION: f64 = 50.0;

/// Points, product weights and Lagrange table of one `(N, M)` pair.
struct Rule {
    points: Vec<f64>,
    /// `v_m(t_i)`, row `i` of length `M` each.
    log_weights: Vec<Vec<f64>>,
    /// `L_j(t_m)`: `M` rows, `N` columns.
    lagrange: DMatrix<f64>,
}

/// Rules by `(N, M)`.
type Rules = Mutex<HashMap<(usize, usize), Arc<Rule>>>;

/// Rules already built, by `(N, M)`: they depend on neither the band nor the punch.
fn rule(nodes: &ChebyshevNodes, count: usize) -> Arc<Rule> {
    static RULES: OnceLock<Rules> = OnceLock::new();
    let key = (nodes.len(), count);
    let rules = RULES.get_or_init(|| Mutex::new(HashMap::new()));
    if let Some(rule) = rules.lock().ok().and_then(|r| r.get(&key).cloned()) {
        return rule;
    }
    let n = nodes.len();
    let points = ChebyshevNodes::new(count).points;
    let log_weights = log_weights_at_chebyshev_points(n, count);
    let mut lagrange = DMatrix::zeros(count, n);
    let mut basis = vec![0.0; n];
    for (m, &t) in points.iter().enumerate() {
        nodes.basis_at(t, &mut basis);
        for (j, &l) in basis.iter().enumerate() {
            lagrange[(m, j)] = l;
        }
    }
    let built = Arc::new(Rule {
        points,
        log_weights,
        lagrange,
    });
    if let Ok(mut r) = rules.lock() {
        r.insert(key, built.clone());
    }
    built
}

/// Number of points `M` for `N` nodes on a band of log-length `L`: `N` plus the degree at which
/// the Chebyshev coefficients of a function analytic inside the Bernstein ellipse through
/// `1 + i y`, `y = 2π/L`, fall below `e^{-LOG_RESOLUTION}` (rounded up to a multiple of 8, so
/// that few distinct rules are built); of the parity opposite to `N`'s, so that no point
/// coincides with a collocation node (they coincide exactly when `N` and `M` have the same power
/// of two). `None` past [`MAX_POINTS`].
fn point_count(n: usize, log_length: f64) -> Option<usize> {
    let y = 2.0 * PI / log_length;
    // Semi-major axis of the ellipse with foci ±1 through 1 + iy, and its parameter ρ.
    let semi_major = 0.5 * (y + (4.0 + y * y).sqrt());
    let rho = semi_major + (semi_major * semi_major - 1.0).sqrt();
    let extra = (LOG_RESOLUTION / rho.ln() / 8.0).ceil() * 8.0;
    if !extra.is_finite() || extra > MAX_POINTS as f64 {
        return None;
    }
    let mut count = n + extra as usize;
    if (count + n).is_multiple_of(2) {
        count += 1;
    }
    (count <= MAX_POINTS).then_some(count)
}

/// `ω = W(s) s (L/2) sqrt(1 - t²)` from `1 + t` and `1 - t` (each exact, so the edges keep
/// their precision) and `L/2`.
fn omega(one_plus_t: f64, one_minus_t: f64, half: f64) -> f64 {
    let lower = one_plus_t / (one_plus_t * half).exp_m1();
    let upper = one_minus_t / (one_minus_t * half).exp_m1();
    half * (0.5 * one_plus_t * half).exp() * (lower * upper).sqrt()
}

/// The ring kernel between `r_i` and `s` at `Δ = t - t_i` on a band of `L = 2 half`, and
/// what it is at `-Δ` (the same `K(m)` and `Q(m₁)`, the share `1 - σ`).
struct Kernel {
    /// `K(m)`, `k' = |tanh(ΔL/4)|`.
    k: f64,
    /// `Q(m₁) = K(m₁) / π`, the coefficient of `-ln m₁` in `K(m)` (`sech(ΔL/4)` the
    /// complementary modulus of `m₁`).
    log_coefficient: f64,
    /// `σ = s / (r_i + s)`.
    share: f64,
    /// `1 - σ = r_i / (r_i + s)`, the share at `-Δ`.
    other_share: f64,
}

impl Kernel {
    fn at(delta: f64, half: f64) -> Self {
        // e^{2z} and e^{2z} - 1 for z = ΔL/4: tanh z, sech z and σ without cancellation.
        let twice = delta * half;
        let (grown, excess) = (twice.exp(), twice.exp_m1());
        let denominator = grown + 1.0;
        let secant = 2.0 * grown.sqrt() / denominator;
        Self {
            k: complete_k_from_complementary((excess / denominator).abs()),
            log_coefficient: complete_k_from_complementary(secant) / PI,
            share: grown / denominator,
            other_share: 1.0 / denominator,
        }
    }
}

/// The collocation matrix of the band `[inner, outer]` (`0 < inner < outer`) for the Chebyshev
/// `nodes` in `t`, with the force weights (the same points' Gauss-Chebyshev rule), or `None`
/// when the band is too long in `ln(c/b)` for the rule (see [`MAX_POINTS`]).
pub(super) fn band_matrix(inner: f64, outer: f64, nodes: &ChebyshevNodes) -> Option<BandAssembly> {
    let n = nodes.len();
    let log_length = (outer / inner).ln();
    if !(log_length > 0.0 && log_length.is_finite()) {
        return None;
    }
    let count = point_count(n, log_length)?;
    let rule = rule(nodes, count);
    let half = 0.5 * log_length;
    // ω(t_m): the edge weight, the Jacobian and the Chebyshev weight's inverse.
    let omega: Vec<f64> = rule
        .points
        .iter()
        .map(|&t| omega(1.0 + t, 1.0 - t, half))
        .collect();
    let gauss = PI / count as f64;
    // Row i's entry at point m, from the kernel at Δ = t_m - t_i and the share σ there.
    let entry = |m: usize, i: usize, delta: f64, kernel: &Kernel, share: f64| {
        let factor = omega[m] * share;
        let q = kernel.log_coefficient;
        gauss * factor * (kernel.k + 2.0 * delta.abs().ln() * q)
            - rule.log_weights[i][m] * 2.0 * factor * q
    };
    // The nodes and the points are symmetric about 0 (t_{N-1-i} = -t_i, t_{M-1-m} = -t_m), so
    // the mirror row N-1-i at the mirror point M-1-m has Δ' = -Δ: the same K(m) and Q(m₁), the
    // share 1 - σ. Each kernel serves both rows (half the elliptic integrals); the middle row of
    // an odd N is its own mirror and is computed alone.
    let pairs = n / 2;
    let rows: Vec<(Vec<f64>, Vec<f64>)> = (0..n.div_ceil(2))
        .into_par_iter()
        .map(|i| {
            let ti = nodes.points[i];
            let mirrored = i < pairs;
            let mut row = vec![0.0; count];
            let mut mirror = vec![0.0; if mirrored { count } else { 0 }];
            for (m, &t) in rule.points.iter().enumerate() {
                let delta = t - ti;
                let kernel = Kernel::at(delta, half);
                row[m] = entry(m, i, delta, &kernel, kernel.share);
                if mirrored {
                    let (i_mirror, m_mirror) = (n - 1 - i, count - 1 - m);
                    mirror[m_mirror] =
                        entry(m_mirror, i_mirror, -delta, &kernel, kernel.other_share);
                }
            }
            (row, mirror)
        })
        .collect();
    let row = |i: usize| -> &[f64] {
        if i < rows.len() {
            &rows[i].0
        } else {
            &rows[n - 1 - i].1
        }
    };
    let coefficients = DMatrix::from_fn(n, count, |i, m| 4.0 / PI * row(i)[m]);
    // F = 2π ∫ φ W s ds = 2π ∫ φ ω s dt / sqrt(1 - t²): Gauss-Chebyshev on the same points.
    let force: Vec<f64> = rule
        .points
        .iter()
        .zip(&omega)
        .map(|(&t, &omega)| 2.0 * PI * gauss * omega * inner * ((1.0 + t) * half).exp())
        .collect();
    let force_weights = rule.lagrange.tr_mul(&DVector::from_vec(force));
    Some(BandAssembly {
        matrix: coefficients * &rule.lagrange,
        force_weights: force_weights.as_slice().to_vec(),
    })
}

/// What [`band_matrix`] assembles: the collocation matrix and the force weights
/// `F = Σ_j force_weights[j] φ_j`.
pub(super) struct BandAssembly {
    /// `A_ij`, `N x N`.
    pub matrix: DMatrix<f64>,
    /// `F = 2π ∫ φ W s ds = Σ_j force_weights[j] φ_j` (`E* = a = 1`).
    pub force_weights: Vec<f64>,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bem::ring::{radius_of, tanh_sinh_force_weights, tanh_sinh_matrix, ContactRegion};
    use crate::numerics::tanh_sinh::TanhSinhRule;

    /// Largest difference of two matrices, relative to the largest entry of each column (the
    /// columns of the nodes near a small inner edge are small).
    fn column_difference(a: &DMatrix<f64>, b: &DMatrix<f64>) -> f64 {
        (0..a.ncols())
            .map(|j| (a.column(j) - b.column(j)).amax() / b.column(j).amax())
            .fold(0.0, f64::max)
    }

    /// The product-integration matrix against the tanh-sinh panels of each row in `s` (an
    /// independent quadrature and kernel, at a finer step than the solver uses), and the force
    /// weights against one tanh-sinh panel, for bands from
    /// nearly closed annuli (`b/c = 1e-4`, the ring BEM's smallest contact ratio) to rings of
    /// `c/b = 1.2`. (On thinner bands the panels in `s` lose the interpolation parameter
    /// `t = 2 ln(s/b)/L - 1` to rounding: see the next test.)
    #[test]
    fn agrees_with_the_tanh_sinh_rows_in_s() {
        let rule = TanhSinhRule::new(1.0 / 64.0);
        let bands = [
            (1e-4, 1.0),
            (0.02, 1.0),
            (0.5, 1.0),
            (0.9, 1.1),
            (0.01, 3.0),
        ];
        for (inner, outer) in bands {
            for n in [6, 16, 33, 40, 64] {
                let nodes = ChebyshevNodes::new(n);
                let fast = band_matrix(inner, outer, &nodes).expect("a rule for this band");
                let region = ContactRegion::Band { inner, outer };
                let radii: Vec<f64> = nodes.points.iter().map(|&t| radius_of(region, t)).collect();
                let reference = tanh_sinh_matrix(region, &nodes, &radii, &rule);
                let difference = column_difference(&fast.matrix, &reference);
                assert!(
                    difference < 1e-12,
                    "band [{inner}, {outer}], N = {n}: relative difference {difference:e}"
                );
                let force = tanh_sinh_force_weights(region, &nodes, &rule);
                let largest = force.iter().fold(0.0_f64, |m, w| m.max(w.abs()));
                for (a, b) in fast.force_weights.iter().zip(&force) {
                    assert!(
                        (a - b).abs() < 1e-12 * largest,
                        "band [{inner}, {outer}], N = {n}: force weight {a} against {b}"
                    );
                }
            }
        }
    }

    /// The tanh-sinh rule in `t`, each row split at `t_i`, of the unsplit integrand
    /// `(4/π) ω σ K(m) L_j(t) / sqrt(1 - t²)`: checks the splitting of the logarithm and the
    /// product weights on thin rings too (`c/b` down to `1 + 1e-4`) and long bands.
    #[test]
    fn agrees_with_the_tanh_sinh_rows_in_t() {
        let rule = TanhSinhRule::new(1.0 / 64.0);
        let bands = [
            (0.9999, 1.0),
            (0.999, 1.001),
            (0.5, 1.0),
            (1e-4, 1.0),
            (1e-8, 1.0),
        ];
        for (inner, outer) in bands {
            let half = 0.5 * f64::ln(outer / inner);
            for n in [6, 17, 40] {
                let nodes = ChebyshevNodes::new(n);
                let fast = band_matrix(inner, outer, &nodes)
                    .expect("a rule for this band")
                    .matrix;
                let mut reference = DMatrix::zeros(n, n);
                let mut basis = vec![0.0; n];
                for (i, &ti) in nodes.points.iter().enumerate() {
                    for (lo, hi) in [(-1.0, ti), (ti, 1.0)] {
                        for node in rule.panel(lo, hi) {
                            let t = node.position;
                            let (from_lo, from_hi) = (node.from_lo, node.from_hi);
                            let one_plus_t = if lo == -1.0 { from_lo } else { 1.0 + t };
                            let one_minus_t = if hi == 1.0 { from_hi } else { 1.0 - t };
                            let delta = if hi == ti { -from_hi } else { from_lo };
                            let kernel = Kernel::at(delta, half);
                            let value = node.weight
                                * omega(one_plus_t, one_minus_t, half)
                                * kernel.share
                                * kernel.k
                                / (one_plus_t * one_minus_t).sqrt();
                            nodes.basis_at(t, &mut basis);
                            for (j, &l) in basis.iter().enumerate() {
                                reference[(i, j)] += 4.0 / PI * value * l;
                            }
                        }
                    }
                }
                let difference = column_difference(&fast, &reference);
                assert!(
                    difference < 1e-12,
                    "band [{inner}, {outer}], N = {n}: relative difference {difference:e}"
                );
            }
        }
    }

    #[test]
    fn points_grow_with_the_band_s_log_length_and_avoid_the_nodes_parity() {
        let short = point_count(40, 0.01).unwrap();
        let long = point_count(40, (1e4_f64).ln()).unwrap();
        assert!(short < long, "{short} {long}");
        assert!(long < 130, "{long}");
        for n in [5, 6, 40, 41] {
            assert_eq!((point_count(n, 3.0).unwrap() + n) % 2, 1);
        }
        assert!(point_count(40, 1e3).is_none());
    }
}
