//! Chebyshev points of the first kind and barycentric Lagrange interpolation on them.
//!
//! Nodes `t_j = cos((2j+1)π/(2N))`, barycentric weights `w_j = (-1)^j sin((2j+1)π/(2N))`
//! (Berrut and Trefethen 2004). Interpolation through these nodes converges geometrically for
//! functions analytic on the interval and is evaluated stably in `O(N)` per point.

use std::f64::consts::PI;

/// The `N` Chebyshev points of the first kind on `[-1, 1]` with their barycentric weights.
#[derive(Clone, Debug)]
pub struct ChebyshevNodes {
    /// Nodes in decreasing order, `t_j = cos((2j+1)π/(2N))`.
    pub points: Vec<f64>,
    weights: Vec<f64>,
}

impl ChebyshevNodes {
    /// Nodes for an interpolant of degree `count - 1`.
    pub fn new(count: usize) -> Self {
        let n = count as f64;
        let mut points = Vec::with_capacity(count);
        let mut weights = Vec::with_capacity(count);
        for j in 0..count {
            let angle = (2 * j + 1) as f64 * PI / (2.0 * n);
            points.push(angle.cos());
            let sign = if j % 2 == 0 { 1.0 } else { -1.0 };
            weights.push(sign * angle.sin());
        }
        Self { points, weights }
    }

    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// Whether there are no nodes.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// Values `L_j(t)` of all Lagrange basis polynomials at `t`, written into `out`: the terms of
    /// [`Self::scaled_basis_at`] times its factor.
    pub(crate) fn basis_at(&self, t: f64, out: &mut [f64]) {
        let factor = self.scaled_basis_at(t, out);
        out.iter_mut().for_each(|v| *v *= factor);
    }

    /// The unnormalised barycentric terms `w_j / (t - t_j)` into `out`, returning the factor
    /// `1 / Σ_j w_j / (t - t_j)` that makes them the Lagrange basis `L_j(t)` of
    /// [`Self::basis_at`]: a caller that scales the terms anyway saves the normalising pass, and
    /// the loop has no branch and no running sum, so it vectorises. At a node (`t = t_j`), the
    /// basis itself and the factor 1.
    pub(crate) fn scaled_basis_at(&self, t: f64, out: &mut [f64]) -> f64 {
        for ((o, &tj), &wj) in out.iter_mut().zip(&self.points).zip(&self.weights) {
            *o = wj / (t - tj);
        }
        // Four partial sums: independent additions instead of one chain.
        let mut partial = [0.0; 4];
        let mut chunks = out.chunks_exact(4);
        for c in &mut chunks {
            for (p, &v) in partial.iter_mut().zip(c) {
                *p += v;
            }
        }
        let total = chunks.remainder().iter().sum::<f64>()
            + ((partial[0] + partial[1]) + (partial[2] + partial[3]));
        if total.is_finite() {
            return 1.0 / total;
        }
        // At a node (a term divided by zero): that node's basis function is 1, the others 0.
        match self.points.iter().position(|&tj| tj == t) {
            Some(j) => {
                out.iter_mut().for_each(|v| *v = 0.0);
                out[j] = 1.0;
                1.0
            }
            None => 1.0 / total,
        }
    }

    /// Interpolated value at `t` of the function with values `values` at the nodes:
    /// `Σ_j L_j(t) f_j` with the Lagrange basis of [`Self::basis_at`] (normalised before it
    /// multiplies the values, so values near the largest `f64` do not overflow, as the unnormalised
    /// barycentric sum `Σ_j w_j f_j / (t - t_j)` did).
    pub(crate) fn interpolate(&self, values: &[f64], t: f64) -> f64 {
        let n = self.points.len();
        let combine = |basis: &mut [f64]| -> f64 {
            self.basis_at(t, basis);
            basis.iter().zip(values).map(|(l, f)| l * f).sum()
        };
        // The basis on the stack for the usual node counts: this runs once per quadrature node.
        if n <= BASIS_ON_STACK {
            combine(&mut [0.0; BASIS_ON_STACK][..n])
        } else {
            combine(&mut vec![0.0; n])
        }
    }

    /// Chebyshev coefficients `c_k` of the interpolant through `values` at the nodes,
    /// `p(t) = Σ_k c_k T_k(t)`: `c_k = (2 - δ_k0)/N Σ_j f_j cos(k θ_j)`, `t_j = cos θ_j`
    /// (the discrete cosine transform of the first-kind points).
    pub(crate) fn coefficients(&self, values: &[f64]) -> Vec<f64> {
        let n = self.points.len();
        (0..n)
            .map(|k| {
                let sum: f64 = values
                    .iter()
                    .enumerate()
                    .map(|(j, f)| f * ((k * (2 * j + 1)) as f64 * PI / (2 * n) as f64).cos())
                    .sum();
                if k == 0 {
                    sum / n as f64
                } else {
                    2.0 * sum / n as f64
                }
            })
            .collect()
    }
}

/// `Σ_k c_k T_k(t)` by Clenshaw's recurrence.
pub(crate) fn chebyshev_series(coefficients: &[f64], t: f64) -> f64 {
    let (mut b1, mut b2) = (0.0, 0.0);
    for &c in coefficients.iter().skip(1).rev() {
        let b0 = 2.0 * t * b1 - b2 + c;
        b2 = b1;
        b1 = b0;
    }
    t * b1 - b2 + coefficients.first().copied().unwrap_or(0.0)
}

/// Node counts up to which [`ChebyshevNodes::interpolate`] keeps its basis on the stack.
const BASIS_ON_STACK: usize = 64;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interpolates_an_analytic_function_to_rounding() {
        let nodes = ChebyshevNodes::new(30);
        let f = |t: f64| (2.0 * t).sin() / (2.0 + t);
        let values: Vec<f64> = nodes.points.iter().map(|&t| f(t)).collect();
        for &t in &[-1.0, -0.3, 0.77, 1.0] {
            assert!((nodes.interpolate(&values, t) - f(t)).abs() < 1e-14);
        }
        // Linear in the values, also near the largest f64 (a depth of 1e300 once gave inf), and
        // also close to a node, where `1/(t - t_j)` is large.
        let huge: Vec<f64> = values.iter().map(|v| v * 1e306).collect();
        for &t in &[-0.999, -0.3, 0.77, 0.999, nodes.points[7] + 1e-9] {
            let scaled = nodes.interpolate(&huge, t) / 1e306;
            assert!(
                (scaled - nodes.interpolate(&values, t)).abs() < 1e-14,
                "t = {t}"
            );
        }
        let mut basis = vec![0.0; 30];
        nodes.basis_at(0.123, &mut basis);
        let sum: f64 = basis.iter().sum();
        assert!((sum - 1.0).abs() < 1e-14);
    }

    #[test]
    fn the_scaled_terms_times_their_factor_are_the_basis() {
        let nodes = ChebyshevNodes::new(37);
        let (mut basis, mut scaled) = (vec![0.0; 37], vec![0.0; 37]);
        for t in [-1.0, -0.999, -0.3, 0.0, 0.123, 0.77, 1.0, nodes.points[5]] {
            // The Lagrange basis by its product formula, `Π_{k≠j} (t - t_k)/(t_j - t_k)`.
            for (j, l) in basis.iter_mut().enumerate() {
                *l = (0..37)
                    .filter(|&k| k != j)
                    .map(|k| (t - nodes.points[k]) / (nodes.points[j] - nodes.points[k]))
                    .product();
            }
            let factor = nodes.scaled_basis_at(t, &mut scaled);
            for (l, s) in basis.iter().zip(&scaled) {
                assert!(
                    (l - factor * s).abs() < 1e-14,
                    "t = {t}: {l} {}",
                    factor * s
                );
            }
        }
    }

    #[test]
    fn the_series_of_the_coefficients_is_the_interpolant() {
        let nodes = ChebyshevNodes::new(30);
        let f = |t: f64| (2.0 * t).sin() / (2.0 + t);
        let values: Vec<f64> = nodes.points.iter().map(|&t| f(t)).collect();
        let c = nodes.coefficients(&values);
        for &t in &[-1.0, -0.999, -0.3, 0.0, 0.77, 1.0] {
            assert!(
                (chebyshev_series(&c, t) - f(t)).abs() < 1e-14,
                "value at {t}"
            );
        }
    }
}
