//! Code verification of the axisymmetric elasticity discretisation by the method of manufactured
//! solutions (docs/methods.md): observed orders of the L2 and energy-norm errors must be within
//! 0.1 of theory (2 and 1 for linear, 3 and 2 for quadratic triangles).
//!
//! Manufactured field (regular on the axis: `u_r` odd in `r`, `u_z` even):
//! `u_r = r sin z`, `u_z = e^z cos r`, on `[0, 1] x [-1, 0]`. Strains
//! `ε_rr = ε_θθ = sin z`, `ε_zz = e^z cos r`, `γ_rz = r cos z - e^z sin r`; the body force
//! `b = -div σ` in cylindrical coordinates (derivation in the comments below) makes it an exact
//! solution; `u = u*` is prescribed on the top, side and bottom, `u_r = 0` on the axis.

use crate::common;

use ringcontact::discretisation::assembly::assemble_stiffness;
use ringcontact::discretisation::element::Lame;
use ringcontact::discretisation::norms::{body_force_vector, errors, ExactField};
use ringcontact::discretisation::quadrature::TriangleRule;
use ringcontact::mesh::triangulation::{structured_rectangle, tags, Degree, Mesh};
use ringcontact::sparse::constrained::ConstrainedCholesky;

struct Manufactured;

impl ExactField for Manufactured {
    fn displacement(&self, r: f64, z: f64) -> [f64; 2] {
        [r * z.sin(), z.exp() * r.cos()]
    }
    fn strain(&self, r: f64, z: f64) -> [f64; 4] {
        [
            z.sin(),
            z.exp() * r.cos(),
            z.sin(),
            r * z.cos() - z.exp() * r.sin(),
        ]
    }
}

/// `b = -div σ`:
/// `b_r = -(∂σ_rr/∂r + ∂σ_rz/∂z + (σ_rr - σ_θθ)/r) = λ e^z sin r + μ (r sin z + e^z sin r)`,
/// `b_z = -(∂σ_rz/∂r + ∂σ_zz/∂z + σ_rz/r)
///      = -(2μ cos z + μ e^z cos r + λ (2 cos z + e^z cos r) - μ e^z sin(r)/r)`.
fn body_force(m: &Lame, r: f64, z: f64) -> [f64; 2] {
    let (l, mu) = (m.lambda, m.mu);
    let sinc = if r == 0.0 { 1.0 } else { r.sin() / r };
    [
        l * z.exp() * r.sin() + mu * (r * z.sin() + z.exp() * r.sin()),
        -(2.0 * mu * z.cos() + mu * z.exp() * r.cos() + l * (2.0 * z.cos() + z.exp() * r.cos())
            - mu * z.exp() * sinc),
    ]
}

fn solve(cells: usize, degree: Degree, material: &Lame) -> (f64, f64, f64) {
    solve_with(cells, degree, material, |r, z| body_force(material, r, z))
}

fn solve_with(
    cells: usize,
    degree: Degree,
    material: &Lame,
    body: impl Fn(f64, f64) -> [f64; 2],
) -> (f64, f64, f64) {
    let mesh: Mesh = structured_rectangle(1.0, 1.0, cells, cells, 11, 12, 13).with_degree(degree);
    let rule = match degree {
        Degree::Linear => TriangleRule::degree2(),
        Degree::Quadratic => TriangleRule::degree4(),
        Degree::Cubic => TriangleRule::degree6(),
    };
    let k = assemble_stiffness(&mesh, material, &rule).unwrap();
    // Body force integrated with a high-order rule so that its quadrature error is negligible.
    let f = body_force_vector(&mesh, &TriangleRule::collapsed_gauss(6), body);
    let dofs = 2 * mesh.nodes.len();
    let mut constrained = vec![false; dofs];
    let mut prescribed = vec![0.0; dofs];
    for tag in [11, 12, 13] {
        for node in mesh.boundary_nodes(tag) {
            let [r, z] = mesh.nodes[node];
            let u = Manufactured.displacement(r, z);
            for c in 0..2 {
                constrained[2 * node + c] = true;
                prescribed[2 * node + c] = u[c];
            }
        }
    }
    for node in mesh.boundary_nodes(tags::AXIS) {
        constrained[2 * node] = true;
        prescribed[2 * node] = 0.0;
    }
    let mut solver = ConstrainedCholesky::with_backend(&k, common::linear_solver()).unwrap();
    let u = solver.solve(&f, &constrained, &prescribed).unwrap();
    let (l2, energy) = errors(&mesh, &u, &Manufactured, material);
    (1.0 / cells as f64, l2, energy)
}

/// Least-squares slope of `ln(error)` against `ln(h)`.
fn observed_order(points: &[(f64, f64)]) -> f64 {
    let n = points.len() as f64;
    let (sx, sy) = points
        .iter()
        .fold((0.0, 0.0), |(a, b), &(h, e)| (a + h.ln(), b + e.ln()));
    let (mx, my) = (sx / n, sy / n);
    let (num, den) = points.iter().fold((0.0, 0.0), |(a, b), &(h, e)| {
        (a + (h.ln() - mx) * (e.ln() - my), b + (h.ln() - mx).powi(2))
    });
    num / den
}

fn check_orders(degree: Degree, meshes: &[usize], expected_l2: f64, expected_energy: f64) {
    for nu in [0.0, 0.3, 0.45] {
        let material = Lame::from_young_poisson(1.0, nu);
        let results: Vec<(f64, f64, f64)> = meshes
            .iter()
            .map(|&n| solve(n, degree, &material))
            .collect();
        let l2: Vec<(f64, f64)> = results.iter().map(|&(h, e, _)| (h, e)).collect();
        let energy: Vec<(f64, f64)> = results.iter().map(|&(h, _, e)| (h, e)).collect();
        let (p_l2, p_energy) = (observed_order(&l2), observed_order(&energy));
        println!("{degree:?} nu = {nu}: observed order L2 {p_l2:.3}, energy {p_energy:.3}");
        assert!(
            (p_l2 - expected_l2).abs() <= 0.1 && (p_energy - expected_energy).abs() <= 0.1,
            "{degree:?}, nu = {nu}: observed orders L2 {p_l2:.3} (expected {expected_l2}), \
             energy {p_energy:.3} (expected {expected_energy}); errors {results:?}"
        );
    }
}

#[test]
fn linear_triangles_converge_at_orders_two_and_one() {
    check_orders(Degree::Linear, &[16, 32, 64], 2.0, 1.0);
}

#[test]
fn quadratic_triangles_converge_at_orders_three_and_two() {
    check_orders(Degree::Quadratic, &[8, 16, 32], 3.0, 2.0);
}

#[test]
fn cubic_triangles_converge_at_orders_four_and_three() {
    check_orders(Degree::Cubic, &[4, 8, 16], 4.0, 3.0);
}

#[test]
fn a_wrong_body_force_is_detected() {
    // The test must be able to fail: with the hoop term μ e^z sin(r)/r of b_z dropped, the
    // discrete solutions converge to something else and the error stalls.
    let material = Lame::from_young_poisson(1.0, 0.3);
    let wrong = |r: f64, z: f64| {
        let b = body_force(&material, r, z);
        [
            b[0],
            b[1] - material.mu * z.exp() * if r == 0.0 { 1.0 } else { r.sin() / r },
        ]
    };
    let errors: Vec<(f64, f64)> = [8, 16, 32]
        .iter()
        .map(|&n| {
            let (h, l2, _) = solve_with(n, Degree::Quadratic, &material, wrong);
            (h, l2)
        })
        .collect();
    assert!(observed_order(&errors) < 1.0, "{errors:?}");
}
