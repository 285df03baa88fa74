//! The far-field condition (Boussinesq's point-force field on the far arc plus the exterior's
//! energy) against the classical fixed arc, on the committed meshes: the reference is Boussinesq's
//! flat punch `γ(0) = 1` (exact), and the ring BEM for the cone.

use crate::common;

use ringcontact::discretisation::far_field::FarField;
use ringcontact::fem::solver::{self, FemLoad, FemOptions, FemState};
use ringcontact::mesh::triangulation::Degree;
use ringcontact::methods::RingBem;
use ringcontact::punch::PunchKind;

fn solve_on(mesh: &str, kind: PunchKind, load: FemLoad, far_field: FarField) -> FemState {
    let options = FemOptions {
        linear_solver: common::linear_solver(),
        trace: false,
        data: Default::default(),
        progress: Default::default(),
        degree: Degree::Quadratic,
        // A single mesh: the tolerance only gates the domain check.
        tolerance: 0.9,
        mesh: Some(solver::mesh_directory().join(mesh)),
        poisson_ratio: 0.0,
        far_field,
    };
    solver::solve(kind, 0.0, load, &options).unwrap()
}

#[test]
fn a_small_domain_with_the_boussinesq_far_field_is_nearly_unbiased() {
    // R = 5a: the fixed arc is too stiff by about 1.2 a/R = 24 %; the far-field condition leaves
    // the discretisation error of this coarse mesh and an O((a/R)²) remainder.
    let fixed = solve_on(
        "small-domain-R5.msh",
        PunchKind::FLAT,
        FemLoad::Flat,
        FarField::Fixed,
    );
    let far = solve_on(
        "small-domain-R5.msh",
        PunchKind::FLAT,
        FemLoad::Flat,
        FarField::Boussinesq,
    );
    let (e_fixed, e_far) = (fixed.gamma.unwrap() - 1.0, far.gamma.unwrap() - 1.0);
    println!("R = 5a: fixed arc {e_fixed:.3e}, Boussinesq far field {e_far:.3e}");
    assert!((e_fixed - 1.2 / 5.0).abs() < 0.05, "{e_fixed}");
    assert!(e_far.abs() < 5e-3, "{e_far}");
}

#[test]
fn the_far_field_removes_the_one_over_r_bias_on_the_default_domain() {
    // R = 1e5 a: the two treatments differ by the fixed arc's bias, about 1e-5, and the
    // far-field result is closer to the exact value on every level of the committed family.
    for level in 0..3 {
        let mesh = format!("disk-L{level}.msh");
        let fixed = solve_on(&mesh, PunchKind::FLAT, FemLoad::Flat, FarField::Fixed);
        let far = solve_on(&mesh, PunchKind::FLAT, FemLoad::Flat, FarField::Boussinesq);
        let shift = fixed.gamma.unwrap() - far.gamma.unwrap();
        println!(
            "L{level}: fixed {:.3e}, Boussinesq {:.3e}, shift {shift:.3e}",
            fixed.gamma.unwrap() - 1.0,
            far.gamma.unwrap() - 1.0
        );
        assert!(shift > 0.5e-5 && shift < 1.5e-5, "{shift}");
        assert!((far.gamma.unwrap() - 1.0).abs() < (fixed.gamma.unwrap() - 1.0).abs());
        assert!(far.truncation_bias < fixed.truncation_bias / 4.0);
    }
    // The cone at d = 2h on the finest committed level, against the ring BEM.
    let bem = RingBem::new()
        .concave_at_depth(&PunchKind::CONE, 2.0, 1e-11)
        .unwrap()
        .gamma2
        .unwrap();
    let error = |far_field| {
        let s = solve_on(
            "disk-L2.msh",
            PunchKind::CONE,
            FemLoad::ConcaveDepth(2.0),
            far_field,
        );
        (s.gamma2.unwrap() - bem) / bem
    };
    let (e_fixed, e_far) = (error(FarField::Fixed), error(FarField::Boussinesq));
    println!("cone d = 2h, L2: fixed {e_fixed:.3e}, Boussinesq {e_far:.3e}");
    assert!(e_far.abs() < e_fixed.abs() - 5e-6);
}

#[test]
fn the_cubic_field_satisfies_the_full_systems_bubble_equations() {
    // The solver condenses every cubic cell's bubble node and recovers its displacement after
    // the solve (after the far-field arc is restored). The bubble lies inside its cell, with no
    // load or constraint: its rows of the full, uncondensed `K u` must vanish. Checked against
    // `assemble_stiffness` (no condensation) with the field the solver returns.
    use ringcontact::discretisation::assembly::assemble_stiffness;
    use ringcontact::discretisation::element::Lame;
    use ringcontact::discretisation::quadrature::stiffness_rule;
    for far_field in [FarField::Boussinesq, FarField::Fixed] {
        let options = FemOptions {
            linear_solver: common::linear_solver(),
            trace: false,
            data: Default::default(),
            progress: Default::default(),
            degree: Degree::Cubic,
            tolerance: 0.9,
            mesh: Some(solver::mesh_directory().join("small-domain-R5.msh")),
            poisson_ratio: 0.3,
            far_field,
        };
        let state = solver::solve(PunchKind::FLAT, 0.0, FemLoad::Flat, &options).unwrap();
        let mesh = &state.field.mesh;
        let u = &state.field.displacement;
        assert_eq!(u.len(), 2 * mesh.nodes.len());
        // The solver's material: E* = 1 whatever ν is.
        let nu: f64 = 0.3;
        let material = Lame::from_young_poisson(1.0 - nu * nu, nu);
        let k = assemble_stiffness(mesh, &material, &stiffness_rule(Degree::Cubic)).unwrap();
        let mut ku = vec![0.0; u.len()];
        let mut scale = vec![0.0_f64; u.len()];
        for (col, column) in k.col_iter().enumerate() {
            for (&row, &value) in column.row_indices().iter().zip(column.values()) {
                ku[row] += value * u[col];
                scale[row] = scale[row].max((value * u[col]).abs());
            }
        }
        let mut bubbles = 0;
        for c in 0..mesh.cell_count() {
            let b = mesh.cell(c)[9];
            for dof in [2 * b, 2 * b + 1] {
                bubbles += 1;
                assert!(
                    ku[dof].abs() <= 1e-10 * scale[dof],
                    "{far_field:?}: bubble dof {dof}: (K u) = {:e} against terms of {:e}",
                    ku[dof],
                    scale[dof]
                );
            }
        }
        assert!(bubbles > 100, "{bubbles} bubble dofs");
    }
}
