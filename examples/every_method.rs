//! One scene, every method: the flat annular punch (`b/a = 0.5`, `d = 1`, `a = E* = 1`) solved by
//! the analytic reference, the ring BEM, the FEM and the 3-D grid BEM, each with its own error
//! estimate, against the ring BEM (the most accurate method here, tolerance 1e-9).
//!
//! Run: `cargo run --release --example every_method`

use ringcontact::methods::{Fem, GridBem, Reference, RingBem, Solver};
use ringcontact::punch::PunchKind;
use ringcontact::scene::SceneSpec;
use ringcontact::solution::Solution;

/// The flat annulus `b/a = 0.5` pressed to `d = 1`, solved by each method in turn (each with
/// its default options; `GridBem { cells: 512, ..Default::default() }` would set the grid).
pub fn solve_every_method() -> ringcontact::Result<Vec<Solution>> {
    let scene = SceneSpec::default()
        .shape(PunchKind::FLAT_ANNULUS)
        .inner_ratio(0.5)
        .depth(1.0)
        .validate()?;
    let solvers: [Box<dyn Solver>; 4] = [
        Box::new(Reference),
        Box::new(RingBem::new()),
        Box::new(Fem::default()),
        Box::new(GridBem::default()),
    ];
    solvers.iter().map(|solver| solver.solve(&scene)).collect()
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let solutions = solve_every_method()?;
    let ring_bem = solutions.iter().find(|s| s.method == "ring-bem").unwrap();
    println!(
        "method        force F/(E* a d)   own estimate   |F - F_ring-bem|/F   unknowns   wall s"
    );
    for solution in &solutions {
        let estimate = solution
            .error_estimate
            .map_or("none".to_string(), |e| format!("{e:.1e}"));
        let difference = (solution.force - ring_bem.force).abs() / ring_bem.force;
        println!(
            "{:<13} {:<18.12} {:<14} {:<20.1e} {:<10} {:.3}",
            solution.method,
            solution.force,
            estimate,
            difference,
            solution.unknowns,
            solution.wall_s
        );
    }
    Ok(())
}
