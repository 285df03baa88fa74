//! A punch of your own: implement [`Profile`] for your type and every method solves it.
//!
//! The profile here is the spherical concave punch, gap `g = h (1 - (r/a)²)`, written as a user
//! would write it (the built-in `sphere` is not called). It is pressed to the depth `d = 1.5 h`
//! and solved with the ring BEM (its default tolerance, 1e-9) and with the FEM (1e-6); each solution prints as one
//! JSON object with the keys `verify solve --json` uses. The numbers equal the built-in sphere's
//! (`verify solve --punch sphere --depth 1.5 --method ring-bem --json`).
//!
//! Run: `cargo run --release --example own_profile`

use ringcontact::methods::{self, Method};
use ringcontact::punch::{Contact, Profile, PunchKind};
use ringcontact::scene::SceneSpec;
use ringcontact::solution::Solution;

/// Concave spherical cap, dimensionless: `ĝ(ρ) = 1 - ρ²` at `ρ = r/a`.
#[derive(Debug)]
struct MySphere;

impl Profile for MySphere {
    fn name(&self) -> &str {
        "my-sphere"
    }
    /// A sharp rim at `r = a` and a free inner edge `b` the solver finds.
    fn contact(&self) -> Contact {
        Contact::RimAndFreeInner
    }
    fn gap(&self, rho: f64) -> f64 {
        1.0 - rho * rho
    }
    fn slope(&self, rho: f64) -> f64 {
        -2.0 * rho
    }
    /// `ĝ'(0) = 0`: the pressure stays bounded at the axis, so the hole can close.
    fn smooth_at_axis(&self) -> bool {
        true
    }
}

/// The own sphere pressed to `d = 1.5 h` (`a = h = E* = 1`) and solved by `method`, to its
/// default tolerance when `tolerance` is `None`.
pub fn solve_own_sphere(method: Method, tolerance: Option<f64>) -> ringcontact::Result<Solution> {
    let mut spec = SceneSpec::default()
        .shape(PunchKind::new(MySphere))
        .rim_radius(1.0)
        .hole_depth(1.0)
        .depth(1.5);
    if let Some(tolerance) = tolerance {
        spec = spec.tolerance(tolerance);
    }
    methods::solve(&spec.validate()?, method)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // The ring BEM at its default tolerance (1e-9), the FEM at 1e-6 (gmsh makes its meshes).
    for (method, tolerance) in [(Method::RingBem, None), (Method::Fem, Some(1e-6))] {
        let solution = solve_own_sphere(method, tolerance)?;
        let record = serde_json::json!({
            "method": solution.method,
            "punch": solution.punch.name(),
            "depth": solution.depth,
            "force": solution.force,
            "eps": solution.eps,
            "gamma1": solution.gamma1,
            "gamma2": solution.gamma2,
            "error_estimate": solution.error_estimate,
        });
        println!("{record}");
    }
    Ok(())
}
