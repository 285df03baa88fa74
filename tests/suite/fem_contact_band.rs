//! The banded contact solve (one factorisation, the band condensed through unit responses)
//! against the primal-dual active-set loop that refactorises at every iteration: both solve the
//! same discrete problem, so they must agree to rounding (the reference is the independent
//! factorisation-per-iteration route), whatever side of the true free edge the warm start lies.

use crate::common;

use ringcontact::discretisation::assembly::assemble_stiffness;
use ringcontact::discretisation::element::Lame;
use ringcontact::discretisation::quadrature::TriangleRule;
use ringcontact::fem::contact::ContactModel;
use ringcontact::fem::solver;
use ringcontact::mesh::msh::read_msh;
use ringcontact::mesh::triangulation::Degree;
use ringcontact::punch::PunchKind;
use ringcontact::sparse::constrained::ConstrainedCholesky;

fn committed(level: usize) -> ringcontact::mesh::triangulation::Mesh {
    read_msh(&solver::mesh_directory().join(format!("disk-L{level}.msh")))
        .unwrap()
        .with_degree(Degree::Quadratic)
}

fn stiffness(mesh: &ringcontact::mesh::triangulation::Mesh) -> nalgebra_sparse::CscMatrix<f64> {
    assemble_stiffness(
        mesh,
        &Lame::from_young_poisson(1.0, 0.0),
        &TriangleRule::degree4(),
    )
    .unwrap()
}

#[test]
fn the_banded_solve_equals_the_refactorising_loop_with_one_factorisation() {
    let mesh = committed(1);
    let k = stiffness(&mesh);
    let contact = ContactModel::new(&mesh, k.nrows()).unwrap();
    for (kind, depth) in [(PunchKind::CONE, 2.0), (PunchKind::SPHERE, 1.5)] {
        let mut reference_solver =
            ConstrainedCholesky::with_backend(&k, common::linear_solver()).unwrap();
        let (reference, _) = contact
            .concave(&mut reference_solver, kind.clone(), depth, None)
            .unwrap();
        // Warm starts on both sides of the edge, within a band of 0.03 a.
        for offset in [-0.02, -0.005, 0.004, 0.015] {
            let guess = reference.inner_radius + offset;
            let mut solver =
                ConstrainedCholesky::with_backend(&k, common::linear_solver()).unwrap();
            let mut system = contact.banded_system(&mut solver, kind.clone(), guess + 0.03);
            let (banded, _, was_banded) = contact
                .concave_with(
                    &mut system,
                    kind.clone(),
                    depth,
                    Some(contact.active_set_for_radius(guess)),
                )
                .unwrap();
            let responses = system.responses_computed();
            let relative = (banded.force / reference.force - 1.0).abs();
            println!(
                "{kind} d = {depth}, start {offset:+}: force {relative:.1e}, {} factorisations, \
                 {responses} responses, banded {was_banded}",
                solver.factorisations
            );
            assert!(was_banded, "the band held the edge, yet it fell back");
            assert_eq!(solver.factorisations, 1);
            assert!(relative < 1e-11, "{relative}");
            assert_eq!(banded.active_radii, reference.active_radii);
            assert!((banded.inner_radius - reference.inner_radius).abs() < 1e-12);
        }
    }
}

#[test]
fn a_band_that_misses_the_edge_is_moved_or_replaced_never_wrong() {
    let mesh = committed(0);
    let k = stiffness(&mesh);
    let contact = ContactModel::new(&mesh, k.nrows()).unwrap();
    let (kind, depth) = (PunchKind::CONE, 2.0);
    let mut reference_solver =
        ConstrainedCholesky::with_backend(&k, common::linear_solver()).unwrap();
    let (reference, _) = contact
        .concave(&mut reference_solver, kind.clone(), depth, None)
        .unwrap();
    // A core that starts below the true edge (the warm start is far too low, the band narrow):
    // core nodes must be released, and the answer must still be the reference.
    for guess in [0.1, 0.3, 0.44] {
        let mut solver = ConstrainedCholesky::with_backend(&k, common::linear_solver()).unwrap();
        let mut system = contact.banded_system(&mut solver, kind.clone(), guess + 1e-3);
        let (solution, _, _) = contact
            .concave_with(
                &mut system,
                kind.clone(),
                depth,
                Some(contact.active_set_for_radius(guess)),
            )
            .unwrap();
        let relative = (solution.force / reference.force - 1.0).abs();
        println!("start {guess}: force {relative:.1e}");
        assert!(relative < 1e-11, "{relative}");
        assert_eq!(solution.active_radii, reference.active_radii);
    }
}

#[test]
fn a_single_mesh_solve_starts_from_its_linear_model_and_factorises_once() {
    // `verify solve --mesh M` on a concave punch: the free edge is first located on the linear
    // model of the same mesh, then the quadratic or cubic model is solved by the banded route.
    // Reference: the same discrete problem by the refactorising loop from a cold start.
    use ringcontact::discretisation::far_field::FarField;
    use ringcontact::fem::solver::{FemLoad, FemOptions};
    let path = solver::mesh_directory().join("disk-L1.msh");
    let cases = [
        (PunchKind::CONE, 0.5, Degree::Quadratic),
        (PunchKind::CONE, 2.0, Degree::Cubic),
        (PunchKind::CONE, 4.0, Degree::Quadratic),
        (PunchKind::SPHERE, 0.5, Degree::Quadratic),
        (PunchKind::SPHERE, 2.8, Degree::Cubic),
    ];
    for (kind, depth, degree) in cases {
        let mesh = read_msh(&path).unwrap().with_degree(degree);
        let k = assemble_stiffness(
            &mesh,
            &Lame::from_young_poisson(1.0, 0.0),
            &ringcontact::discretisation::quadrature::stiffness_rule(degree),
        )
        .unwrap();
        let contact = ContactModel::new(&mesh, k.nrows()).unwrap();
        let mut reference_solver =
            ConstrainedCholesky::with_backend(&k, common::linear_solver()).unwrap();
        let (reference, _) = contact
            .concave(&mut reference_solver, kind.clone(), depth, None)
            .unwrap();
        let options = FemOptions {
            linear_solver: common::linear_solver(),
            trace: false,
            data: Default::default(),
            progress: Default::default(),
            degree,
            tolerance: 0.9,
            mesh: Some(path.clone()),
            poisson_ratio: 0.0,
            far_field: FarField::Fixed,
        };
        let state =
            solver::solve(kind.clone(), 0.0, FemLoad::ConcaveDepth(depth), &options).unwrap();
        let force = 2.0 * state.gamma2.unwrap();
        let relative = (force / reference.force - 1.0).abs();
        println!(
            "{kind} d = {depth} {degree:?}: force {relative:.1e}, {} factorisations (reference \
             {}), linear locator {:.3} s",
            state.timings.factorisations,
            reference_solver.factorisations,
            state.timings.edge_presolve
        );
        assert!(relative < 1e-11, "{relative}");
        assert_eq!(state.active_radii, reference.active_radii);
        assert_eq!(state.timings.factorisations, 1);
        assert!(reference_solver.factorisations > 1);
        assert!(state.timings.edge_presolve > 0.0);
    }
}
