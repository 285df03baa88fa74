//! Quadrature rules on the reference triangle `{ξ >= 0, η >= 0, ξ + η <= 1}` (area 1/2).
//!
//! The stiffness rules are fixed and named, so that another code (FEniCSx) can use the very same
//! points: the hoop strain `u_r/r` makes the integrand non-polynomial, and two different rules of
//! the same degree differ by more than solver tolerance.

use crate::mesh::triangulation::Degree;
pub(crate) use crate::numerics::gauss_legendre::gauss_legendre;

/// A rule: points `(ξ, η)` and weights summing to 1/2.
#[derive(Clone, Debug)]
pub struct TriangleRule {
    pub points: Vec<[f64; 2]>,
    pub weights: Vec<f64>,
    /// Polynomial degree integrated exactly.
    pub degree: usize,
}

impl TriangleRule {
    /// Degree-2, 3-point interior rule (Strang and Fix): points `(1/6, 1/6)`, `(2/3, 1/6)`,
    /// `(1/6, 2/3)`, weights `1/6`. This is basix's default rule for degree 2.
    pub fn degree2() -> Self {
        let (a, b) = (1.0 / 6.0, 2.0 / 3.0);
        Self {
            points: vec![[a, a], [b, a], [a, b]],
            weights: vec![1.0 / 6.0; 3],
            degree: 2,
        }
    }

    /// Degree-4, 6-point symmetric rule (Dunavant 1985; Strang and Fix), basix's default for
    /// degree 4.
    pub fn degree4() -> Self {
        let (a, wa) = (0.445_948_490_915_965, 0.223_381_589_678_011 / 2.0);
        let (b, wb) = (0.091_576_213_509_771, 0.109_951_743_655_322 / 2.0);
        Self {
            points: vec![
                [a, a],
                [1.0 - 2.0 * a, a],
                [a, 1.0 - 2.0 * a],
                [b, b],
                [1.0 - 2.0 * b, b],
                [b, 1.0 - 2.0 * b],
            ],
            weights: vec![wa, wa, wa, wb, wb, wb],
            degree: 4,
        }
    }

    /// Degree-6, 12-point symmetric rule (Dunavant 1985, rule 6): orbits `(a, a, 1 - 2a)` with
    /// `a = 0.249286745170910` and `0.063089014491502`, and the six permutations of
    /// `(0.053145049844817, 0.310352451033784, 0.636502499121399)`.
    pub fn degree6() -> Self {
        let orbits3 = [
            (0.249_286_745_170_910, 0.116_786_275_726_379),
            (0.063_089_014_491_502, 0.050_844_906_370_207),
        ];
        let (p, q, w6) = (
            0.053_145_049_844_817,
            0.310_352_451_033_784,
            0.082_851_075_618_374,
        );
        let mut points = Vec::new();
        let mut weights = Vec::new();
        for (a, w) in orbits3 {
            for pt in [[a, a], [1.0 - 2.0 * a, a], [a, 1.0 - 2.0 * a]] {
                points.push(pt);
                weights.push(w / 2.0);
            }
        }
        let r = 1.0 - p - q;
        for pt in [[p, q], [q, p], [p, r], [r, p], [q, r], [r, q]] {
            points.push(pt);
            weights.push(w6 / 2.0);
        }
        Self {
            points,
            weights,
            degree: 6,
        }
    }

    /// Collapsed Gauss-Legendre product rule with `n x n` points (Duffy transform), exact for
    /// degree `2n - 2`; used for error norms, where accuracy matters more than cost.
    pub fn collapsed_gauss(n: usize) -> Self {
        let (x, w) = gauss_legendre(n);
        let mut points = Vec::with_capacity(n * n);
        let mut weights = Vec::with_capacity(n * n);
        for i in 0..n {
            for j in 0..n {
                // (u, v) in [0,1]², ξ = u, η = v (1 - u), Jacobian (1 - u).
                let (u, v) = (x[i], x[j]);
                points.push([u, v * (1.0 - u)]);
                weights.push(w[i] * w[j] * (1.0 - u));
            }
        }
        Self {
            points,
            weights,
            degree: 2 * n - 2,
        }
    }
}

/// The quadrature rule of the stiffness: degree 2 (3 points) for linear, degree 4 (6 points)
/// for quadratic, degree 6 (12 points) for cubic elements (degree `2p`: exact for the
/// polynomial part `∇N·∇N r` of the integrand up to one degree of the `r` factor).
pub fn stiffness_rule(degree: Degree) -> TriangleRule {
    match degree {
        Degree::Linear => TriangleRule::degree2(),
        Degree::Quadratic => TriangleRule::degree4(),
        Degree::Cubic => TriangleRule::degree6(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn integrate(rule: &TriangleRule, f: impl Fn(f64, f64) -> f64) -> f64 {
        rule.points
            .iter()
            .zip(&rule.weights)
            .map(|(p, w)| w * f(p[0], p[1]))
            .sum()
    }

    #[test]
    fn rules_integrate_monomials_of_their_degree() {
        // ∫ ξ^i η^j = i! j! / (i + j + 2)!
        let fact = |n: u32| (1..=n).map(f64::from).product::<f64>();
        for rule in [
            TriangleRule::degree2(),
            TriangleRule::degree4(),
            TriangleRule::degree6(),
            TriangleRule::collapsed_gauss(5),
        ] {
            for i in 0..=rule.degree as u32 {
                for j in 0..=(rule.degree as u32 - i) {
                    let exact = fact(i) * fact(j) / fact(i + j + 2);
                    let got = integrate(&rule, |x, y| x.powi(i as i32) * y.powi(j as i32));
                    assert!(
                        (got - exact).abs() < 1e-14,
                        "degree {} x^{i} y^{j}",
                        rule.degree
                    );
                }
            }
        }
    }
}
