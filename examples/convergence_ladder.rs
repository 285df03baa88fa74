//! A convergence ladder: the FEM asked for tighter and tighter tolerances on the conical concave
//! punch (`d = 1.5 h`), each answer's own error estimate set beside its true error against the
//! ring BEM at 1e-12. An honest estimate bounds the true error on every rung.
//!
//! Run: `cargo run --release --example convergence_ladder`

use ringcontact::methods::{self, Method};
use ringcontact::punch::PunchKind;
use ringcontact::scene::SceneSpec;

/// One rung: the tolerance asked for, the FEM's force, its estimate and its true error.
#[derive(Debug)]
pub struct Rung {
    /// Relative tolerance requested (`--tol`).
    pub tolerance: f64,
    /// Dimensionless force `γ2 = F / (2 E* h a)`.
    pub force: f64,
    /// The FEM's own relative error estimate.
    pub estimate: f64,
    /// `|F - F_ring-bem| / F_ring-bem`, the ring BEM solved to 1e-12.
    pub true_error: f64,
    /// Unknowns of the finest model the FEM solved.
    pub unknowns: usize,
}

/// Solve the cone at `d = 1.5 h` with the FEM at each of `tolerances` (below 1e-3 gmsh makes
/// the meshes; coarser rungs run on the committed ones).
pub fn climb_the_ladder(tolerances: &[f64]) -> ringcontact::Result<Vec<Rung>> {
    let scene = |tolerance: f64| {
        SceneSpec::default()
            .shape(PunchKind::CONE)
            .depth(1.5)
            .tolerance(tolerance)
            .validate()
    };
    let reference = methods::solve(&scene(1e-12)?, Method::RingBem)?.force;
    tolerances
        .iter()
        .map(|&tolerance| {
            let solution = methods::solve(&scene(tolerance)?, Method::Fem)?;
            Ok(Rung {
                tolerance,
                force: solution.force,
                estimate: solution.error_estimate.unwrap_or(f64::NAN),
                true_error: (solution.force - reference).abs() / reference,
                unknowns: solution.unknowns,
            })
        })
        .collect()
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    println!("tol      force gamma2       estimate   true error   unknowns");
    for rung in climb_the_ladder(&[1e-2, 1e-3, 1e-4, 1e-5])? {
        println!(
            "{:<8.0e} {:<18.12} {:<10.1e} {:<12.1e} {}",
            rung.tolerance, rung.force, rung.estimate, rung.true_error, rung.unknowns
        );
    }
    Ok(())
}
