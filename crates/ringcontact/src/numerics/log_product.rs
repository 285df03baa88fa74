//! Product integration of a logarithmic singularity against the Chebyshev weight.
//!
//! For `|x| <= 1` and the Chebyshev polynomials `T_k`,
//!
//! ```text
//! ∫_{-1}^{1} ln|t - x| T_k(t) / sqrt(1 - t²) dt = -π ln 2        (k = 0)
//!                                                = -π T_k(x) / k   (k >= 1)
//! ```
//!
//! (from `ln|cos θ - cos φ| = -ln 2 - 2 Σ_k cos kθ cos kφ / k`). Interpolating a smooth `g` at the
//! `M` Chebyshev points of the first kind `t_m = cos θ_m`, `θ_m = (2m + 1)π / (2M)`, and
//! integrating the interpolant exactly gives the rule
//!
//! ```text
//! ∫_{-1}^{1} ln|t - x| g(t) / sqrt(1 - t²) dt ≈ Σ_m v_m(x) g(t_m),
//! v_m(x) = -(π/M) [ln 2 + 2 Σ_{k=1}^{M-1} T_k(x) T_k(t_m) / k],
//! ```
//!
//! exact for polynomials `g` of degree below `M` and geometric in `M` for analytic `g`. The smooth
//! part of an integrand takes the Gauss-Chebyshev rule on the same points, weights `π/M`, exact to
//! degree `2M - 1`.

use std::f64::consts::{LN_2, PI};

/// The weights `v_m(x_i)` of the logarithmic rule on the `count` points `t_m` (in the order of
/// [`crate::numerics::chebyshev::ChebyshevNodes`]) for every singular point
/// `x_i = cos((2i + 1)π / (2N))`, the `N` Chebyshev points of the first kind (row `i` of length
/// `count` each). Every cosine is `cos(jπ / (2 N M))` for an integer `j`: read from one table.
pub(crate) fn log_weights_at_chebyshev_points(nodes: usize, count: usize) -> Vec<Vec<f64>> {
    // cos(k θ) for θ = (2i + 1)π/(2N) and θ_m = (2m + 1)π/(2M): both are multiples of
    // π/(2NM); the table holds one period, 4NM entries.
    let period = 4 * nodes * count;
    let table: Vec<f64> = (0..period)
        .map(|j| (j as f64 * PI / (2 * nodes * count) as f64).cos())
        .collect();
    let scale = -PI / count as f64;
    (0..nodes)
        .map(|i| {
            let step_i = (2 * i + 1) * count; // θ_i in units of π/(2NM)
            let series: Vec<f64> = (1..count)
                .map(|k| 2.0 * table[(k * step_i) % period] / k as f64)
                .collect();
            (0..count)
                .map(|m| {
                    let step_m = (2 * m + 1) * nodes; // θ_m in the same units
                    let sum: f64 = series
                        .iter()
                        .enumerate()
                        .map(|(k, c)| c * table[((k + 1) * step_m) % period])
                        .sum();
                    scale * (LN_2 + sum)
                })
                .collect()
        })
        .collect()
}

/// The weights `v_m(x)` of the logarithmic rule on `count` points for the singular point
/// `x = cos(angle)`, `0 <= angle <= π`.
#[cfg(test)]
fn log_weights(angle: f64, count: usize) -> Vec<f64> {
    let scale = -PI / count as f64;
    let series: Vec<f64> = (1..count)
        .map(|k| 2.0 * (k as f64 * angle).cos() / k as f64)
        .collect();
    (0..count)
        .map(|m| {
            let theta = (2 * m + 1) as f64 * PI / (2 * count) as f64;
            let sum: f64 = series
                .iter()
                .enumerate()
                .map(|(i, c)| c * ((i + 1) as f64 * theta).cos())
                .sum();
            scale * (LN_2 + sum)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numerics::chebyshev::ChebyshevNodes;

    /// The `m` Chebyshev points of the first kind.
    fn chebyshev_points(m: usize) -> Vec<f64> {
        ChebyshevNodes::new(m).points
    }

    /// `∫ ln|t - x| / sqrt(1 - t²) dt = -π ln 2` for every `x` in `[-1, 1]`, and
    /// `∫ ln|t - x| t / sqrt(1 - t²) dt = -π x` (the `k = 0, 1` formulas): closed forms.
    #[test]
    fn integrates_the_first_chebyshev_polynomials_exactly() {
        let m = 17;
        let points = chebyshev_points(m);
        for &angle in &[0.0, 0.3, 1.0, 2.0, PI] {
            let x: f64 = f64::cos(angle);
            let v = log_weights(angle, m);
            let constant: f64 = v.iter().sum();
            let linear: f64 = v.iter().zip(&points).map(|(w, t)| w * t).sum();
            assert!((constant + PI * LN_2).abs() < 1e-14, "{constant}");
            assert!((linear + PI * x).abs() < 1e-14, "{linear} at x = {x}");
        }
    }

    /// The tabulated weights at Chebyshev points are the directly computed ones.
    #[test]
    fn the_table_of_cosines_gives_the_direct_weights() {
        let (n, m) = (7, 12);
        let tabulated = log_weights_at_chebyshev_points(n, m);
        for (i, row) in tabulated.iter().enumerate() {
            let direct = log_weights((2 * i + 1) as f64 * PI / (2 * n) as f64, m);
            for (a, b) in row.iter().zip(&direct) {
                assert!((a - b).abs() < 1e-14, "{a} {b}");
            }
        }
    }

    /// An analytic integrand, `e^t ln|t - x| / sqrt(1 - t²)`, against a tanh-sinh quadrature split
    /// at `x` (an independent rule), on a point between nodes and on a node of a smaller rule.
    #[test]
    fn converges_geometrically_for_an_analytic_factor() {
        use crate::numerics::tanh_sinh::TanhSinhRule;
        let rule = TanhSinhRule::new(1.0 / 64.0);
        for &angle in &[0.7, PI / 10.0, 3.1] {
            let x: f64 = f64::cos(angle);
            let mut reference = 0.0;
            for (lo, hi) in [(-1.0, x), (x, 1.0)] {
                for node in rule.panel(lo, hi) {
                    let t: f64 = node.position;
                    let (from_lo, from_hi) = (t + 1.0, 1.0 - t);
                    let from_lo = if lo == -1.0 { node.from_lo } else { from_lo };
                    let from_hi = if hi == 1.0 { node.from_hi } else { from_hi };
                    let distance = if hi == x { node.from_hi } else { node.from_lo };
                    reference += node.weight * t.exp() * distance.ln() / (from_lo * from_hi).sqrt();
                }
            }
            let m = 24;
            let value: f64 = log_weights(angle, m)
                .iter()
                .zip(chebyshev_points(m))
                .map(|(w, t)| w * t.exp())
                .sum();
            assert!(
                (value - reference).abs() < 1e-13 * reference.abs(),
                "x = {x}: {value} against {reference}"
            );
        }
    }
}
