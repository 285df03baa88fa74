//! The programs in `examples/` run as tests, so that what a new user reads first keeps working.

#[path = "../../examples/own_profile.rs"]
#[allow(dead_code)]
mod own_profile;

#[path = "../../examples/every_method.rs"]
#[allow(dead_code)]
mod every_method;

#[path = "../../examples/convergence_ladder.rs"]
#[allow(dead_code)]
mod convergence_ladder;

use ringcontact::methods::{self, Method};
use ringcontact::punch::PunchKind;
use ringcontact::scene::SceneSpec;

/// A user's own sphere solves as the built-in sphere does: the same ring-BEM numbers to 1e-12,
/// the FEM's within its estimate; and the own FEM lies within its estimate of the own ring BEM
/// (an independent method, checked against closed forms in `tests/suite/ring_bem_references.rs`).
#[test]
fn own_profile_solves_as_the_builtin_sphere_in_the_ring_bem() {
    own_profile_solves_as_the_builtin_sphere(Method::RingBem, None);
}

/// As above in the FEM at 1e-6, which needs meshes gmsh makes (none is committed that fine).
#[test]
#[cfg_attr(gmsh_missing, ignore = "needs gmsh: bash scripts/install_gmsh.sh")]
fn own_profile_solves_as_the_builtin_sphere_in_the_fem() {
    own_profile_solves_as_the_builtin_sphere(Method::Fem, Some(1e-6));
}

/// The own sphere in `method` at `tolerance` against the built-in sphere and the own ring BEM.
fn own_profile_solves_as_the_builtin_sphere(method: Method, tolerance: Option<f64>) {
    let ring_bem = own_profile::solve_own_sphere(Method::RingBem, None).unwrap();
    let solution = own_profile::solve_own_sphere(method, tolerance).unwrap();
    assert_eq!(solution.method, method.name());
    let mut spec = SceneSpec::default().shape(PunchKind::SPHERE).depth(1.5);
    if let Some(tolerance) = tolerance {
        spec = spec.tolerance(tolerance);
    }
    let builtin = methods::solve(&spec.validate().unwrap(), method).unwrap();
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

/// Every method's force on the flat annulus lies within its own estimate (plus the ring BEM's)
/// of the ring BEM, which is checked against closed forms in `tests/suite/ring_bem_references.rs`.
#[test]
fn every_method_agrees_with_the_ring_bem_within_its_estimate() {
    let solutions = every_method::solve_every_method().unwrap();
    assert_eq!(solutions.len(), 4);
    let ring_bem = solutions.iter().find(|s| s.method == "ring-bem").unwrap();
    let ring_estimate = ring_bem.error_estimate.unwrap();
    let mut checked = 0;
    for solution in &solutions {
        let Some(estimate) = solution.error_estimate else {
            continue;
        };
        let difference = (solution.force - ring_bem.force).abs() / ring_bem.force;
        println!(
            "{}: {difference:.1e} within {estimate:.1e}?",
            solution.method
        );
        assert!(
            difference <= estimate + ring_estimate,
            "{}",
            solution.method
        );
        checked += 1;
    }
    assert!(
        checked >= 3,
        "ring BEM, FEM and grid BEM all carry an estimate"
    );
}

/// On every rung of the ladder the FEM's estimate bounds its true error against the ring BEM at
/// 1e-12, and tightening the tolerance tightens the estimate.
#[test]
fn convergence_ladder_estimates_bound_the_true_error() {
    check_the_ladder(&[1e-2, 1e-3]);
}

/// As above below 1e-3, where the FEM climbs into meshes gmsh makes.
#[test]
#[cfg_attr(gmsh_missing, ignore = "needs gmsh: bash scripts/install_gmsh.sh")]
fn convergence_ladder_estimates_bound_the_true_error_below_1e3() {
    check_the_ladder(&[1e-3, 1e-4, 1e-5]);
}

fn check_the_ladder(tolerances: &[f64]) {
    let rungs = convergence_ladder::climb_the_ladder(tolerances).unwrap();
    for rung in &rungs {
        println!("{rung:?}");
        assert!(rung.true_error <= rung.estimate, "{rung:?}");
        assert!(rung.estimate <= rung.tolerance, "{rung:?}");
    }
    assert!(rungs.windows(2).all(|w| w[1].estimate < w[0].estimate));
}
