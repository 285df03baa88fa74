//! The programs in `examples/` run as tests, so that what a new user reads first keeps working.

#[path = "../examples/own_profile.rs"]
#[allow(dead_code)]
mod own_profile;

use ringcontact::methods::{self, Method};
use ringcontact::punch::PunchKind;
use ringcontact::scene::SceneSpec;

/// A user's own sphere solves as the built-in sphere does: the same ring-BEM numbers to 1e-12,
/// the FEM's within its estimate; and the own FEM lies within its estimate of the own ring BEM
/// (an independent method, checked against closed forms in `tests/ring_bem_references.rs`).
#[test]
fn own_profile_solves_as_the_builtin_sphere() {
    let own = own_profile::solve_own_sphere().unwrap();
    let ring_bem = &own[0];
    assert_eq!(ring_bem.method, "ring-bem");
    for solution in &own {
        let tolerance = (solution.method == "fem").then_some(1e-6);
        let mut spec = SceneSpec::default().shape(PunchKind::SPHERE).depth(1.5);
        if let Some(tolerance) = tolerance {
            spec = spec.tolerance(tolerance);
        }
        let scene = spec.validate().unwrap();
        let method = if solution.method == "fem" {
            Method::Fem
        } else {
            Method::RingBem
        };
        let builtin = methods::solve(&scene, method).unwrap();
        let estimate = solution.error_estimate.unwrap();
        let allowed = if method == Method::RingBem {
            1e-12
        } else {
            estimate
        };
        for (what, mine, theirs, exact) in [
            ("force", solution.force, builtin.force, ring_bem.force),
            ("eps", solution.eps, builtin.eps, ring_bem.eps),
        ] {
            println!(
                "{} {what}: own {mine}, built-in {theirs}, own ring BEM {exact}",
                solution.method
            );
            assert!(
                (mine - theirs).abs() <= allowed * theirs.abs().max(1.0),
                "{} {what}: own {mine} against built-in {theirs}",
                solution.method
            );
            let bound = estimate + ring_bem.error_estimate.unwrap();
            assert!(
                (mine - exact).abs() <= bound * exact.abs().max(1.0),
                "{} {what}: own {mine} against the ring BEM's {exact} (bound {bound:.1e})",
                solution.method
            );
        }
    }
}
