//! Cost of the finite-element pipeline against the number of unknowns, up to 10^6:
//! assembly (`nalgebra-sparse` CSC), symbolic Cholesky analysis (`faer`, AMD ordering, done once),
//! one numeric factorisation + solve, and the primal-dual active-set contact loop (a spherical
//! concave punch pressed into the top of the block, which is the contact line `[0, 1]`; the far
//! side and bottom are fixed), cold (one factorisation per active-set change) and warm (the banded
//! solve from an edge guess off by 2 % of the block: one factorisation plus unit responses of the
//! band nodes). Structured P2 meshes of the unit block, generated in Rust.
//! Run: `cargo bench --bench fem_scaling` (release build; assembly on both cores, `faer` sequential).

use std::time::Instant;

use ringcontact::discretisation::assembly::assemble_stiffness;
use ringcontact::discretisation::element::Lame;
use ringcontact::discretisation::quadrature::TriangleRule;
use ringcontact::fem::contact::ContactModel;
use ringcontact::mesh::triangulation::{structured_rectangle, tags, Degree};
use ringcontact::punch::PunchKind;
use ringcontact::sparse::constrained::ConstrainedCholesky;

fn main() {
    let material = Lame::from_young_poisson(1.0, 0.3);
    let rule = TriangleRule::degree4();
    println!("FEM pipeline, P2 triangles on a structured block, contact line = top edge");
    println!(
        "{:>9} {:>10} {:>11} {:>11} {:>12} {:>10} {:>6} {:>8} {:>9} {:>10}",
        "unknowns",
        "nnz(K)",
        "assembly s",
        "symbolic s",
        "factor+solve",
        "cold s",
        "iters",
        "factors",
        "banded s",
        "responses"
    );
    for cells in [16usize, 32, 64, 128, 256, 354] {
        let mesh =
            structured_rectangle(1.0, 1.0, cells, cells, tags::CONTACT, tags::FAR, tags::FAR)
                .with_degree(Degree::Quadratic);
        let dofs = 2 * mesh.nodes.len();
        let start = Instant::now();
        let k = assemble_stiffness(&mesh, &material, &rule).expect("assembly");
        let assembly = start.elapsed().as_secs_f64();
        let start = Instant::now();
        let mut solver = ConstrainedCholesky::new(&k).expect("symbolic");
        let symbolic = start.elapsed().as_secs_f64();
        let model = ContactModel::new(&mesh, k.nrows()).expect("contact model");
        // One plain flat-punch solve: numeric factorisation + triangular solves.
        let start = Instant::now();
        model.flat(&mut solver, 0.01).expect("flat solve");
        let factor = start.elapsed().as_secs_f64();
        let before = solver.factorisations;
        let start = Instant::now();
        let (solution, _) = model
            .concave(&mut solver, PunchKind::SPHERE, 0.5, None)
            .expect("contact solve");
        let contact = start.elapsed().as_secs_f64();
        let start = Instant::now();
        let guess = solution.inner_radius + 0.02;
        let mut warm_solver = ConstrainedCholesky::new(&k).expect("symbolic");
        let mut system = model.banded_system(&mut warm_solver, PunchKind::SPHERE, guess + 0.04);
        let (banded, _, _) = model
            .concave_with(
                &mut system,
                PunchKind::SPHERE,
                0.5,
                Some(model.active_set_for_radius(guess)),
            )
            .expect("banded contact solve");
        let responses = system.responses_computed();
        let banded_time = start.elapsed().as_secs_f64();
        assert!((banded.force / solution.force - 1.0).abs() < 1e-9);
        println!(
            "{dofs:>9} {:>10} {assembly:>11.3} {symbolic:>11.3} {factor:>12.3} {contact:>10.3} {:>6} {:>8} {banded_time:>9.3} {responses:>10}",
            k.nnz(),
            solution.iterations,
            solver.factorisations - before
        );
    }
}
