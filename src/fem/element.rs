//! Axisymmetric linear elasticity on straight-sided triangles in `(r, z)`.
//!
//! Strain vector `ε = (ε_rr, ε_zz, ε_θθ, γ_rz) = (∂u_r/∂r, ∂u_z/∂z, u_r/r, ∂u_r/∂z + ∂u_z/∂r)`,
//! stress `σ = D ε` with `D` the isotropic Lamé matrix, element stiffness
//! `K_e = ∫ Bᵀ D B 2π r dA` (the `2π` makes nodal reactions total ring forces, so the punch force
//! is their plain sum). Degrees of freedom are ordered `(u_r, u_z)` per node.

use super::mesh::Degree;
use super::quadrature::TriangleRule;

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
pub struct AffineTriangle {
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
    pub fn gradient(&self, dxi: f64, deta: f64) -> [f64; 2] {
        [
            self.inverse[0][0] * dxi + self.inverse[1][0] * deta,
            self.inverse[0][1] * dxi + self.inverse[1][1] * deta,
        ]
    }
}

/// Element stiffness `K_e` (row-major, `2k x 2k` for `k` nodes) of an axisymmetric triangle.
///
/// For nodes `a`, `b` with shape gradients `(g_r, g_z)`, hoop term `h = N/r` and `t = g_r + h`
/// (the trace of the strain of a unit radial displacement), the 2 x 2 block of `Bᵀ D B` is
/// `rr = λ t_a t_b + 2μ (g_r,a g_r,b + h_a h_b) + μ g_z,a g_z,b`,
/// `rz = λ t_a g_z,b + μ g_z,a g_r,b`, `zr = λ g_z,a t_b + μ g_r,a g_z,b`,
/// `zz = (λ + 2μ) g_z,a g_z,b + μ g_r,a g_r,b`: the product with the zeros of the strain vectors
/// `(ε_rr, ε_zz, ε_θθ, γ_rz)` left out (a sixth of the operations of the full product).
/// Blocks with `a <= b` are summed over the rule, the rest mirrored.
pub fn stiffness(
    degree: Degree,
    vertices: [[f64; 2]; 3],
    material: &Lame,
    rule: &TriangleRule,
    out: &mut [f64],
) {
    let k = degree.nodes_per_cell();
    let size = 2 * k;
    out[..size * size].iter_mut().for_each(|v| *v = 0.0);
    let tri = AffineTriangle::new(vertices[0], vertices[1], vertices[2]);
    let (lambda, mu) = (material.lambda, material.mu);
    let (mut n, mut dxi, mut deta) = ([0.0; 10], [0.0; 10], [0.0; 10]);
    let (mut gr, mut gz, mut h, mut t) = ([0.0; 10], [0.0; 10], [0.0; 10], [0.0; 10]);
    for (p, &w) in rule.points.iter().zip(&rule.weights) {
        shape(degree, p[0], p[1], &mut n, &mut dxi, &mut deta);
        let r = tri.map(p[0], p[1])[0];
        for a in 0..k {
            let g = tri.gradient(dxi[a], deta[a]);
            gr[a] = g[0];
            gz[a] = g[1];
            h[a] = n[a] / r;
            t[a] = g[0] + h[a];
        }
        let scale = w * tri.det * 2.0 * std::f64::consts::PI * r;
        for a in 0..k {
            let (sgr, sgz, sh, st) = (scale * gr[a], scale * gz[a], scale * h[a], scale * t[a]);
            let (row_r, row_z) = out[2 * a * size..(2 * a + 2) * size].split_at_mut(size);
            for b in a..k {
                row_r[2 * b] +=
                    lambda * st * t[b] + 2.0 * mu * (sgr * gr[b] + sh * h[b]) + mu * sgz * gz[b];
                row_r[2 * b + 1] += lambda * st * gz[b] + mu * sgz * gr[b];
                row_z[2 * b] += lambda * sgz * t[b] + mu * sgr * gz[b];
                row_z[2 * b + 1] += (lambda + 2.0 * mu) * sgz * gz[b] + mu * sgr * gr[b];
            }
        }
    }
    for i in 0..size {
        for j in 0..i {
            out[i * size + j] = out[j * size + i];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::solver::stiffness_rule;

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
