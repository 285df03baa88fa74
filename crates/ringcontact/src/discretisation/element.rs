//! Axisymmetric linear elasticity on straight-sided triangles in `(r, z)`.
//!
//! Strain vector `ε = (ε_rr, ε_zz, ε_θθ, γ_rz) = (∂u_r/∂r, ∂u_z/∂z, u_r/r, ∂u_r/∂z + ∂u_z/∂r)`,
//! stress `σ = D ε` with `D` the isotropic Lamé matrix, element stiffness
//! `K_e = ∫ Bᵀ D B 2π r dA` (the `2π` makes nodal reactions total ring forces, so the punch force
//! is their plain sum). Degrees of freedom are ordered `(u_r, u_z)` per node.

use crate::discretisation::quadrature::TriangleRule;
use crate::mesh::triangulation::Degree;

/// Isotropic material as Lamé constants.
#[derive(Clone, Copy, Debug)]
pub struct Lame {
    pub lambda: f64,
    pub mu: f64,
}

impl Lame {
    /// From Young's modulus and Poisson's ratio.
    pub fn from_young_poisson(e: f64, nu: f64) -> Self {
        Self {
            lambda: e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)),
            mu: e / (2.0 * (1.0 + nu)),
        }
    }

    /// `σ = D ε` for the axisymmetric strain vector.
    #[inline]
    pub fn stress(&self, strain: [f64; 4]) -> [f64; 4] {
        let trace = strain[0] + strain[1] + strain[2];
        let (l, m) = (self.lambda, self.mu);
        [
            l * trace + 2.0 * m * strain[0],
            l * trace + 2.0 * m * strain[1],
            l * trace + 2.0 * m * strain[2],
            m * strain[3],
        ]
    }
}

/// Shape functions and their reference gradients at `(ξ, η)`, with barycentric coordinates
/// `L1 = 1 - ξ - η`, `L2 = ξ`, `L3 = η`:
/// P1 `N_i = L_i`; P2 `L_i (2 L_i - 1)` and `4 L_i L_j`; P3 `½ L_i (3 L_i - 1)(3 L_i - 2)`,
/// `9/2 L_i L_j (3 L_i - 1)` (edge node nearer `i`) and `27 L1 L2 L3`.
pub fn shape(degree: Degree, xi: f64, eta: f64, n: &mut [f64], dxi: &mut [f64], deta: &mut [f64]) {
    let l = [1.0 - xi - eta, xi, eta];
    // dL/dξ and dL/dη.
    const DXI: [f64; 3] = [-1.0, 1.0, 0.0];
    const DETA: [f64; 3] = [-1.0, 0.0, 1.0];
    // A shape function as f(L) with its gradient in L; chain rule to (ξ, η).
    let mut put = |k: usize, value: f64, grad: [f64; 3]| {
        n[k] = value;
        dxi[k] = (0..3).map(|i| grad[i] * DXI[i]).sum();
        deta[k] = (0..3).map(|i| grad[i] * DETA[i]).sum();
    };
    let unit = |i: usize, v: f64| {
        let mut g = [0.0; 3];
        g[i] = v;
        g
    };
    match degree {
        Degree::Linear => {
            for (i, &li) in l.iter().enumerate() {
                put(i, li, unit(i, 1.0));
            }
        }
        Degree::Quadratic => {
            for (i, &li) in l.iter().enumerate() {
                put(i, li * (2.0 * li - 1.0), unit(i, 4.0 * li - 1.0));
            }
            for (k, (i, j)) in [(0, 1), (1, 2), (2, 0)].into_iter().enumerate() {
                let mut g = [0.0; 3];
                g[i] = 4.0 * l[j];
                g[j] = 4.0 * l[i];
                put(3 + k, 4.0 * l[i] * l[j], g);
            }
        }
        Degree::Cubic => {
            for (i, &li) in l.iter().enumerate() {
                put(
                    i,
                    0.5 * li * (3.0 * li - 1.0) * (3.0 * li - 2.0),
                    unit(i, 0.5 * (27.0 * li * li - 18.0 * li + 2.0)),
                );
            }
            for (e, (i, j)) in [(0, 1), (1, 2), (2, 0)].into_iter().enumerate() {
                // Node nearer i, then nearer j: 9/2 L_i L_j (3 L_near - 1).
                for (slot, (near, far)) in [(i, j), (j, i)].into_iter().enumerate() {
                    let (a, b) = (l[near], l[far]);
                    let mut g = [0.0; 3];
                    g[near] = 4.5 * b * (6.0 * a - 1.0);
                    g[far] = 4.5 * a * (3.0 * a - 1.0);
                    put(3 + 2 * e + slot, 4.5 * a * b * (3.0 * a - 1.0), g);
                }
            }
            put(
                9,
                27.0 * l[0] * l[1] * l[2],
                [27.0 * l[1] * l[2], 27.0 * l[0] * l[2], 27.0 * l[0] * l[1]],
            );
        }
    }
}

/// Geometry of one affine triangle: vertices and the inverse Jacobian.
#[derive(Clone, Copy, Debug)]
pub(crate) struct AffineTriangle {
    origin: [f64; 2],
    jacobian: [[f64; 2]; 2],
    inverse: [[f64; 2]; 2],
    /// `|det J|` (twice the area).
    pub det: f64,
}

impl AffineTriangle {
    /// From the three vertices `(r, z)`.
    pub fn new(p0: [f64; 2], p1: [f64; 2], p2: [f64; 2]) -> Self {
        let j = [
            [p1[0] - p0[0], p2[0] - p0[0]],
            [p1[1] - p0[1], p2[1] - p0[1]],
        ];
        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        let inverse = [
            [j[1][1] / det, -j[0][1] / det],
            [-j[1][0] / det, j[0][0] / det],
        ];
        Self {
            origin: p0,
            jacobian: j,
            inverse,
            det: det.abs(),
        }
    }

    /// Physical point of `(ξ, η)`.
    #[inline]
    pub fn map(&self, xi: f64, eta: f64) -> [f64; 2] {
        [
            self.origin[0] + self.jacobian[0][0] * xi + self.jacobian[0][1] * eta,
            self.origin[1] + self.jacobian[1][0] * xi + self.jacobian[1][1] * eta,
        ]
    }

    /// Physical gradient `(∂/∂r, ∂/∂z)` from the reference gradient: `J^{-T} ∇_ξ`.
    #[inline]
    pub(crate) fn gradient(&self, dxi: f64, deta: f64) -> [f64; 2] {
        [
            self.inverse[0][0] * dxi + self.inverse[1][0] * deta,
            self.inverse[0][1] * dxi + self.inverse[1][1] * deta,
        ]
    }
}

/// Element stiffness `K_e` (row-major, `2k x 2k` for `k` nodes) of an axisymmetric triangle
/// ([`ElementKernel::stiffness`]; builds the kernel's tables at every call, so assemblies make
/// one [`ElementKernel`] instead).
pub fn stiffness(
    degree: Degree,
    vertices: [[f64; 2]; 3],
    material: &Lame,
    rule: &TriangleRule,
    out: &mut [f64],
) {
    ElementKernel::new(degree, rule).stiffness(vertices, material, out);
}

/// The element stiffness of one degree and quadrature rule, with the rule's sums over the
/// reference triangle done once.
///
/// For nodes `a`, `b` with physical gradients `(g_r, g_z)`, hoop term `h = N/r` and `t = g_r + h`,
/// the 2 x 2 block of `K_e = Σ_q w_q |J| 2π r_q Bᵀ D B` is
/// `rr = λ t_a t_b + 2μ (g_r,a g_r,b + h_a h_b) + μ g_z,a g_z,b`,
/// `rz = λ t_a g_z,b + μ g_z,a g_r,b`, `zr = λ g_z,a t_b + μ g_r,a g_z,b`,
/// `zz = (λ + 2μ) g_z,a g_z,b + μ g_r,a g_r,b`, each weighted by `r`. On an affine triangle
/// `g = J⁻ᵀ ∇_ξ N` and `r_q = Σ_v r_v L_v(q)` (barycentric `L`), so the rule's sums regroup into
/// reference tables: `Σ_q w_q r_q ∂_k N_a ∂_l N_b = Σ_v r_v A^v_{ab,kl}`,
/// `Σ_q w_q r_q h_a ∂_l N_b = Σ_q w_q N_a ∂_l N_b` (the `r` cancels), and only
/// `Σ_q w_q N_a N_b / r_q` is summed cell by cell. The same finite sums as the rule applied
/// point by point (equal to rounding), at a quarter to a third of the operations.
#[derive(Clone, Debug)]
pub(crate) struct ElementKernel {
    nodes: usize,
    /// The node pairs `(a, b)`, `a <= b`.
    pairs: Vec<(usize, usize)>,
    /// `A^v_{ab,kl} = Σ_q w_q L_v(q) ∂_k N_a ∂_l N_b` at `[v × pairs + pair]`, `kl` in the order
    /// `ξξ, ξη, ηξ, ηη`.
    gradient_products: Vec<[f64; 4]>,
    /// `[Σ w N_a ∂_ξ N_b, Σ w N_a ∂_η N_b, Σ w N_b ∂_ξ N_a, Σ w N_b ∂_η N_a]` per pair.
    value_gradient_products: Vec<[f64; 4]>,
    /// `w_q N_a(q) N_b(q)` at `[q × pairs + pair]`.
    value_products: Vec<f64>,
    /// Barycentric coordinates of each point of the rule.
    barycentric: Vec<[f64; 3]>,
}

impl ElementKernel {
    /// Tabulate the rule's sums for `degree`'s shape functions ([`shape`]).
    pub fn new(degree: Degree, rule: &TriangleRule) -> Self {
        let k = degree.nodes_per_cell();
        let pairs: Vec<(usize, usize)> = (0..k).flat_map(|a| (a..k).map(move |b| (a, b))).collect();
        let np = pairs.len();
        let mut gradient_products = vec![[0.0; 4]; 3 * np];
        let mut value_gradient_products = vec![[0.0; 4]; np];
        let mut value_products = vec![0.0; rule.points.len() * np];
        let mut barycentric = Vec::with_capacity(rule.points.len());
        let (mut n, mut dxi, mut deta) = ([0.0; 10], [0.0; 10], [0.0; 10]);
        for (q, (p, &w)) in rule.points.iter().zip(&rule.weights).enumerate() {
            shape(degree, p[0], p[1], &mut n, &mut dxi, &mut deta);
            let l = [1.0 - p[0] - p[1], p[0], p[1]];
            barycentric.push(l);
            for (i, &(a, b)) in pairs.iter().enumerate() {
                let grad = |c: usize| [dxi[c], deta[c]];
                let (ga, gb) = (grad(a), grad(b));
                for (v, &lv) in l.iter().enumerate() {
                    let entry = &mut gradient_products[v * np + i];
                    entry[0] += w * lv * ga[0] * gb[0];
                    entry[1] += w * lv * ga[0] * gb[1];
                    entry[2] += w * lv * ga[1] * gb[0];
                    entry[3] += w * lv * ga[1] * gb[1];
                }
                let entry = &mut value_gradient_products[i];
                entry[0] += w * n[a] * gb[0];
                entry[1] += w * n[a] * gb[1];
                entry[2] += w * n[b] * ga[0];
                entry[3] += w * n[b] * ga[1];
                value_products[q * np + i] = w * n[a] * n[b];
            }
        }
        Self {
            nodes: k,
            pairs,
            gradient_products,
            value_gradient_products,
            value_products,
            barycentric,
        }
    }

    /// `K_e` (row-major, `2k x 2k`) of the triangle with `vertices` `(r, z)`.
    pub fn stiffness(&self, vertices: [[f64; 2]; 3], material: &Lame, out: &mut [f64]) {
        let size = 2 * self.nodes;
        let tri = AffineTriangle::new(vertices[0], vertices[1], vertices[2]);
        let (lambda, mu) = (material.lambda, material.mu);
        // ∂/∂r = c_r · (∂_ξ, ∂_η), ∂/∂z = c_z · (∂_ξ, ∂_η): the columns of J⁻ᵀ.
        let c_r = [tri.inverse[0][0], tri.inverse[1][0]];
        let c_z = [tri.inverse[0][1], tri.inverse[1][1]];
        let radii = [vertices[0][0], vertices[1][0], vertices[2][0]];
        let scale = tri.det * 2.0 * std::f64::consts::PI;
        let np = self.pairs.len();
        let inverse_radii: Vec<f64> = self
            .barycentric
            .iter()
            .map(|l| 1.0 / (l[0] * radii[0] + l[1] * radii[1] + l[2] * radii[2]))
            .collect();
        for (i, &(a, b)) in self.pairs.iter().enumerate() {
            let mut s = [0.0; 4];
            for (v, &rv) in radii.iter().enumerate() {
                let table = &self.gradient_products[v * np + i];
                for (sk, tk) in s.iter_mut().zip(table) {
                    *sk += rv * tk;
                }
            }
            // u_k = Σ_l S_kl c_r,l and v_k = Σ_l S_kl c_z,l; then contract k.
            let u = [s[0] * c_r[0] + s[1] * c_r[1], s[2] * c_r[0] + s[3] * c_r[1]];
            let v = [s[0] * c_z[0] + s[1] * c_z[1], s[2] * c_z[0] + s[3] * c_z[1]];
            let grgr = c_r[0] * u[0] + c_r[1] * u[1];
            let gzgr = c_z[0] * u[0] + c_z[1] * u[1];
            let grgz = c_r[0] * v[0] + c_r[1] * v[1];
            let gzgz = c_z[0] * v[0] + c_z[1] * v[1];
            let vg = &self.value_gradient_products[i];
            let hgr = c_r[0] * vg[0] + c_r[1] * vg[1];
            let hgz = c_z[0] * vg[0] + c_z[1] * vg[1];
            let grh = c_r[0] * vg[2] + c_r[1] * vg[3];
            let gzh = c_z[0] * vg[2] + c_z[1] * vg[3];
            let hh: f64 = inverse_radii
                .iter()
                .enumerate()
                .map(|(q, inv_r)| self.value_products[q * np + i] * inv_r)
                .sum();
            let rr = lambda * (grgr + grh + hgr + hh) + 2.0 * mu * (grgr + hh) + mu * gzgz;
            let rz = lambda * (grgz + hgz) + mu * gzgr;
            let zr = lambda * (gzgr + gzh) + mu * grgz;
            let zz = (lambda + 2.0 * mu) * gzgz + mu * grgr;
            let (ra, za, rb, zb) = (2 * a, 2 * a + 1, 2 * b, 2 * b + 1);
            // The block (a, b) and its mirror (b, a); on the diagonal (a = b) `zr` equals `rz`
            // but for rounding, and the upper entry is mirrored so that `K_e` is exactly
            // symmetric.
            let zr = if a == b { rz } else { zr };
            out[ra * size + rb] = scale * rr;
            out[ra * size + zb] = scale * rz;
            out[za * size + rb] = scale * zr;
            out[za * size + zb] = scale * zz;
            out[rb * size + ra] = scale * rr;
            out[zb * size + ra] = scale * rz;
            out[rb * size + za] = scale * zr;
            out[zb * size + za] = scale * zz;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::discretisation::quadrature::stiffness_rule;

    /// `K_e` by the definition: `Σ_q w_q 2π r_q B_qᵀ D B_q |det J|` with the full strain vectors.
    fn stiffness_by_definition(
        degree: Degree,
        vertices: [[f64; 2]; 3],
        material: &Lame,
        rule: &TriangleRule,
    ) -> Vec<f64> {
        let k = degree.nodes_per_cell();
        let size = 2 * k;
        let mut out = vec![0.0; size * size];
        let tri = AffineTriangle::new(vertices[0], vertices[1], vertices[2]);
        let (mut n, mut dxi, mut deta) = ([0.0; 10], [0.0; 10], [0.0; 10]);
        for (p, &w) in rule.points.iter().zip(&rule.weights) {
            shape(degree, p[0], p[1], &mut n, &mut dxi, &mut deta);
            let r = tri.map(p[0], p[1])[0];
            let mut b = vec![[0.0; 4]; size];
            for a in 0..k {
                let g = tri.gradient(dxi[a], deta[a]);
                b[2 * a] = [g[0], 0.0, n[a] / r, g[1]];
                b[2 * a + 1] = [0.0, g[1], 0.0, g[0]];
            }
            let scale = w * tri.det * 2.0 * std::f64::consts::PI * r;
            for i in 0..size {
                let s = material.stress(b[i]);
                for j in 0..size {
                    out[i * size + j] += scale * (0..4).map(|c| s[c] * b[j][c]).sum::<f64>();
                }
            }
        }
        out
    }

    #[test]
    fn the_element_stiffness_equals_the_full_product_of_its_definition() {
        // A compressible material (λ ≠ 0) and a triangle off the axis and on it.
        let material = Lame::from_young_poisson(2.5, 0.3);
        for vertices in [
            [[0.7, -0.2], [1.3, -0.1], [0.9, 0.4]],
            [[0.0, 0.0], [0.5, -0.3], [0.0, -0.6]],
        ] {
            for degree in [Degree::Linear, Degree::Quadratic, Degree::Cubic] {
                let rule = stiffness_rule(degree);
                let size = 2 * degree.nodes_per_cell();
                let mut fast = vec![0.0; size * size];
                stiffness(degree, vertices, &material, &rule, &mut fast);
                let reference = stiffness_by_definition(degree, vertices, &material, &rule);
                let scale = reference.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
                for (i, (x, y)) in fast.iter().zip(&reference).enumerate() {
                    assert!(
                        (x - y).abs() <= 1e-13 * scale,
                        "{degree:?} entry {i}: {x} against {y}"
                    );
                }
            }
        }
    }
}
