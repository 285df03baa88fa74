use ringcontact::mesh::triangulation::Degree;
use ringcontact::methods::{solve, GridBem, Method, MethodOptions, RingBem, Solver};
use ringcontact::punch::PunchKind;
use ringcontact::scene::SceneSpec;

/// Each method's flags go to that method alone: another method refuses them by name.
#[test]
fn a_flag_of_another_method_is_refused_by_name() {
    let grid = MethodOptions {
        grid: Some(64),
        ..MethodOptions::default()
    };
    let refused = Method::Fem.solver(&grid).err().unwrap().to_string();
    assert!(refused.contains("--grid"), "{refused}");
    let mesh = MethodOptions {
        degree: Some(Degree::Linear),
        ..MethodOptions::default()
    };
    assert!(Method::RingBem.solver(&mesh).is_err());
    assert_eq!(Method::GridBem.solver(&grid).unwrap().name(), "grid-bem");
}

/// A typed grid BEM with a square extent declines a punch whose grid is its own `[-a, a]²`.
#[test]
fn the_grid_extent_is_refused_on_a_punch_with_a_rim() {
    let scene = SceneSpec::default()
        .shape(PunchKind::CONE)
        .depth(1.5)
        .validate()
        .unwrap();
    let solver = GridBem {
        cells: 32,
        extent: Some(2.0),
        with_estimate: false,
        max_iterations: None,
    };
    let refused = solver.solve(&scene).unwrap_err().to_string();
    assert!(refused.contains("--grid-extent"), "{refused}");
}

/// The typed solver and the command line's route give the same solution.
#[test]
fn a_typed_solver_solves_as_the_named_method() {
    let scene = SceneSpec::default()
        .shape(PunchKind::SPHERE)
        .depth(1.5)
        .validate()
        .unwrap();
    let typed = RingBem::new().solve(&scene).unwrap();
    let named = solve(&scene, Method::RingBem).unwrap();
    assert_eq!(typed.method, "ring-bem");
    assert_eq!(typed.force, named.force);
    assert_eq!(typed.eps, named.eps);
}
