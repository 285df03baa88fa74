//! Body-force load vectors and error norms against an exact field (code verification).
//!
//! `L2`: `‖u_h - u‖ = sqrt(∫ |u_h - u|² 2π r dA)`;
//! energy: `‖u_h - u‖_E = sqrt(∫ (ε_h - ε)ᵀ D (ε_h - ε) 2π r dA)`.

use std::f64::consts::PI;

use crate::discretisation::element::{shape, AffineTriangle, Lame};
use crate::discretisation::quadrature::TriangleRule;
use crate::mesh::triangulation::Mesh;

/// Consistent load vector `f_i = ∫ N_a b_c 2π r dA` of a body force `b(r, z)`.
pub fn body_force_vector(
    mesh: &Mesh,
    rule: &TriangleRule,
    body: impl Fn(f64, f64) -> [f64; 2],
) -> Vec<f64> {
    let mut f = vec![0.0; 2 * mesh.nodes.len()];
    let (mut n, mut dxi, mut deta) = ([0.0; 10], [0.0; 10], [0.0; 10]);
    for c in 0..mesh.cell_count() {
        let cell = mesh.cell(c);
        let tri = AffineTriangle::new(
            mesh.nodes[cell[0]],
            mesh.nodes[cell[1]],
            mesh.nodes[cell[2]],
        );
        for (p, &w) in rule.points.iter().zip(&rule.weights) {
            shape(mesh.degree, p[0], p[1], &mut n, &mut dxi, &mut deta);
            let x = tri.map(p[0], p[1]);
            let b = body(x[0], x[1]);
            let scale = w * tri.det * 2.0 * PI * x[0];
            for (a, &node) in cell.iter().enumerate() {
                f[2 * node] += scale * n[a] * b[0];
                f[2 * node + 1] += scale * n[a] * b[1];
            }
        }
    }
    f
}

/// Exact displacement and strain vector `(ε_rr, ε_zz, ε_θθ, γ_rz)` at `(r, z)`.
pub trait ExactField {
    fn displacement(&self, r: f64, z: f64) -> [f64; 2];
    fn strain(&self, r: f64, z: f64) -> [f64; 4];
}

/// `(L2 error, energy-norm error)` of the nodal field `u` (dofs `(u_r, u_z)` per node).
pub fn errors(mesh: &Mesh, u: &[f64], exact: &impl ExactField, material: &Lame) -> (f64, f64) {
    let rule = TriangleRule::collapsed_gauss(8);
    let (mut l2, mut energy) = (0.0, 0.0);
    let (mut n, mut dxi, mut deta) = ([0.0; 10], [0.0; 10], [0.0; 10]);
    for c in 0..mesh.cell_count() {
        let cell = mesh.cell(c);
        let tri = AffineTriangle::new(
            mesh.nodes[cell[0]],
            mesh.nodes[cell[1]],
            mesh.nodes[cell[2]],
        );
        for (p, &w) in rule.points.iter().zip(&rule.weights) {
            shape(mesh.degree, p[0], p[1], &mut n, &mut dxi, &mut deta);
            let x = tri.map(p[0], p[1]);
            let r = x[0];
            let (mut uh, mut eps) = ([0.0; 2], [0.0; 4]);
            for (a, &node) in cell.iter().enumerate() {
                let (ur, uz) = (u[2 * node], u[2 * node + 1]);
                let g = tri.gradient(dxi[a], deta[a]);
                uh[0] += n[a] * ur;
                uh[1] += n[a] * uz;
                eps[0] += g[0] * ur;
                eps[1] += g[1] * uz;
                eps[2] += n[a] * ur / r;
                eps[3] += g[1] * ur + g[0] * uz;
            }
            let ue = exact.displacement(r, x[1]);
            let ee = exact.strain(r, x[1]);
            let de = [
                eps[0] - ee[0],
                eps[1] - ee[1],
                eps[2] - ee[2],
                eps[3] - ee[3],
            ];
            let s = material.stress(de);
            let scale = w * tri.det * 2.0 * PI * r;
            l2 += scale * ((uh[0] - ue[0]).powi(2) + (uh[1] - ue[1]).powi(2));
            energy += scale * (s[0] * de[0] + s[1] * de[1] + s[2] * de[2] + s[3] * de[3]);
        }
    }
    (l2.sqrt(), energy.sqrt())
}
