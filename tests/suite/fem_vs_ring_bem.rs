//! Solution verification of the finite-element solver against the ring BEM (converged to 1e-10,
//! an independent discretisation of the same problem): with default settings the FEM agrees
//! within 1e-3, with `--tol 1e-4` within 1e-4, and its error estimate bounds its actual error.

use crate::common;

use ringcontact::fem::solver::{self, FemLoad, FemOptions, FemState};
use ringcontact::mesh::triangulation::Degree;
use ringcontact::methods::{RingBem, RingState};
use ringcontact::punch::PunchKind;
use ringcontact::Error;

fn fem(kind: PunchKind, eps: f64, load: FemLoad, tolerance: f64) -> FemState {
    fem_of_degree(Degree::Quadratic, kind, eps, load, tolerance)
}

/// Options of a ladder solve (meshes made for the scene) of `degree` at `tolerance`.
fn ladder_options(degree: Degree, tolerance: f64) -> FemOptions {
    FemOptions {
        linear_solver: common::linear_solver(),
        trace: false,
        data: Default::default(),
        progress: Default::default(),
        degree,
        tolerance,
        mesh: None,
        poisson_ratio: 0.0,
        far_field: ringcontact::discretisation::far_field::FarField::Boussinesq,
    }
}

fn fem_of_degree(
    degree: Degree,
    kind: PunchKind,
    eps: f64,
    load: FemLoad,
    tolerance: f64,
) -> FemState {
    let options = ladder_options(degree, tolerance);
    solver::solve(kind.clone(), eps, load, &options)
        .unwrap_or_else(|e| panic!("{kind} {load:?}: {e}"))
}

/// `(relative error of the force-like output, absolute error of eps)` against the ring BEM.
/// The ring BEM's state at 1e-10, or at 1e-9 where 1e-10 is beyond its rounding: near closure
/// the contact ratio moves 30 times a relative change of the depth (the sphere at `d/h =
/// 2.9999`: `dγ2/deps = 0.033`), so values that scatter by 1e-12 leave it 2e-10 uncertain. Either
/// is 100 times finer than the FEM's finest tolerance on a concave punch here (1e-7).
fn reference(solve: impl Fn(f64) -> ringcontact::Result<RingState>) -> RingState {
    solve(1e-10).or_else(|_| solve(1e-9)).unwrap()
}

fn errors(kind: PunchKind, eps: f64, load: FemLoad, state: &FemState) -> (f64, f64) {
    let bem = RingBem::new();
    match load {
        FemLoad::Flat => {
            let g = bem.flat(eps, 1e-10).unwrap().gamma.unwrap();
            ((state.gamma.unwrap() - g).abs() / g, 0.0)
        }
        FemLoad::ConcaveDepth(d) => {
            let r = reference(|tol| bem.concave_at_depth(&kind, d, tol));
            let g2 = r.gamma2.unwrap();
            (
                (state.gamma2.unwrap() - g2).abs() / g2,
                (state.eps - r.eps).abs(),
            )
        }
        FemLoad::ConcaveForce(f) => {
            let r = reference(|tol| bem.concave_at_force(&kind, f, tol));
            let g1 = r.gamma1.unwrap();
            (
                (state.gamma1.unwrap() - g1).abs() / g1,
                (state.eps - r.eps).abs(),
            )
        }
    }
}

fn check(cases: &[(PunchKind, f64, FemLoad)], tolerance: f64) {
    check_degree(Degree::Quadratic, cases, tolerance)
}

fn check_degree(degree: Degree, cases: &[(PunchKind, f64, FemLoad)], tolerance: f64) {
    check_degree_with_margin(degree, cases, tolerance, 1.0);
}

/// [`check_degree`], the estimate asked to exceed both errors `margin` times.
fn check_degree_with_margin(
    degree: Degree,
    cases: &[(PunchKind, f64, FemLoad)],
    tolerance: f64,
    margin: f64,
) {
    for (kind, eps, load) in cases.iter().cloned() {
        let state = fem_of_degree(degree, kind.clone(), eps, load, tolerance);
        let (force_error, eps_error) = errors(kind.clone(), eps, load, &state);
        let estimate = state.error_estimate.unwrap();
        println!(
            "{kind} {load:?}: force error {force_error:.2e}, eps error {eps_error:.2e}, estimate {estimate:.1e}, \
             {} dofs on {}, {:.2} s",
            state.dofs, state.mesh, state.wall_s
        );
        assert!(
            force_error <= tolerance && eps_error <= tolerance,
            "{kind} {load:?}: beyond {tolerance:e}"
        );
        assert!(
            estimate <= tolerance,
            "{kind} {load:?}: estimate {estimate:e} above the tolerance"
        );
        assert!(
            margin * force_error <= estimate && margin * eps_error <= estimate,
            "{kind} {load:?}: the estimate {estimate:.2e} does not bound the errors ({force_error:.2e}, \
             {eps_error:.2e}) {margin} times"
        );
    }
}

const FLAT: [(PunchKind, f64, FemLoad); 3] = [
    (PunchKind::FLAT, 0.0, FemLoad::Flat),
    (PunchKind::FLAT_ANNULUS, 0.5, FemLoad::Flat),
    (PunchKind::FLAT_ANNULUS, 0.9, FemLoad::Flat),
];

#[test]
fn default_settings_agree_with_the_ring_bem_within_1e3() {
    let mut cases = FLAT.to_vec();
    for d in [0.5, 2.0, 4.0] {
        cases.push((PunchKind::CONE, 0.0, FemLoad::ConcaveDepth(d)));
    }
    for d in [0.5, 1.5, 2.8] {
        cases.push((PunchKind::SPHERE, 0.0, FemLoad::ConcaveDepth(d)));
    }
    cases.push((PunchKind::CONE, 0.0, FemLoad::ConcaveForce(1.0)));
    check(&cases, solver::DEFAULT_TOLERANCE);
}

#[test]
fn sphere_past_full_contact_follows_mdr() {
    // d >= 3h: F = 2 E* a (d - h/3) (method of dimensionality reduction), full contact.
    let state = fem(PunchKind::SPHERE, 0.0, FemLoad::ConcaveDepth(3.5), 1e-3);
    assert_eq!(state.eps, 0.0);
    let exact = 3.5 - 1.0 / 3.0;
    assert!((state.gamma2.unwrap() - exact).abs() / exact <= 1e-3);
}

#[test]
#[cfg_attr(gmsh_missing, ignore = "needs gmsh: bash scripts/install_gmsh.sh")]
fn tolerance_1e4_is_met() {
    // Climbs past the committed levels into meshes made by gmsh.
    let mut cases = FLAT.to_vec();
    cases.push((PunchKind::CONE, 0.0, FemLoad::ConcaveDepth(2.0)));
    cases.push((PunchKind::SPHERE, 0.0, FemLoad::ConcaveDepth(1.5)));
    check(&cases, 1e-4);
}

#[test]
fn linear_elements_converge_toward_the_ring_bem() {
    let bem = RingBem::new().flat(0.5, 1e-10).unwrap().gamma.unwrap();
    let dir = solver::mesh_directory();
    let errors: Vec<f64> = (0..3)
        .map(|level| {
            let options = FemOptions {
                linear_solver: common::linear_solver(),
                trace: false,
                data: Default::default(),
                progress: Default::default(),
                degree: Degree::Linear,
                tolerance: 1e-3,
                mesh: Some(dir.join(format!("annulus-0.5-L{level}.msh"))),
                poisson_ratio: 0.3,
                far_field: ringcontact::discretisation::far_field::FarField::Boussinesq,
            };
            let s = solver::solve(PunchKind::FLAT_ANNULUS, 0.5, FemLoad::Flat, &options).unwrap();
            assert!(s.error_estimate.is_none(), "a single mesh has no estimate");
            (s.gamma.unwrap() - bem) / bem
        })
        .collect();
    // Too stiff, and each level (sizes halved) cuts the error by more than 3.
    assert!(errors.iter().all(|&e| e > 0.0), "{errors:?}");
    assert!(
        errors[1] < errors[0] / 3.0 && errors[2] < errors[1] / 3.0,
        "{errors:?}"
    );
}

#[test]
fn the_answer_does_not_depend_on_poisson_ratio() {
    // The rigid frictionless punch depends on E* only; the FEM must reproduce that.
    let run = |nu: f64| {
        let options = FemOptions {
            linear_solver: common::linear_solver(),
            trace: false,
            data: Default::default(),
            progress: Default::default(),
            degree: Degree::Quadratic,
            tolerance: 1e-3,
            mesh: Some(solver::mesh_directory().join("disk-L1.msh")),
            poisson_ratio: nu,
            far_field: ringcontact::discretisation::far_field::FarField::Boussinesq,
        };
        solver::solve(PunchKind::SPHERE, 0.0, FemLoad::ConcaveDepth(1.0), &options).unwrap()
    };
    let (a, b) = (run(0.0), run(0.45));
    assert!((a.gamma2.unwrap() - b.gamma2.unwrap()).abs() / a.gamma2.unwrap() < 1e-3);
}

#[test]
fn mismatched_mesh_and_scene_are_errors() {
    let options = FemOptions {
        linear_solver: common::linear_solver(),
        trace: false,
        data: Default::default(),
        progress: Default::default(),
        degree: Degree::Quadratic,
        tolerance: 1e-3,
        mesh: Some(solver::mesh_directory().join("annulus-0.5-L0.msh")),
        poisson_ratio: 0.0,
        far_field: ringcontact::discretisation::far_field::FarField::Boussinesq,
    };
    let e = solver::solve(PunchKind::FLAT_ANNULUS, 0.9, FemLoad::Flat, &options).unwrap_err();
    assert!(matches!(e, Error::InvalidMesh { .. }), "{e}");
}

#[test]
#[cfg_attr(gmsh_missing, ignore = "needs gmsh: bash scripts/install_gmsh.sh")]
fn any_annulus_ratio_and_tolerance_meets_it_on_generated_meshes() {
    // b/a without a committed family, and tolerances past the committed levels: gmsh makes the
    // meshes (graded toward r = a, r = b and the located free edge); the ring BEM is the reference.
    let mut cases = Vec::new();
    for eps in [0.1, 0.3, 0.7, 0.97] {
        cases.push((PunchKind::FLAT_ANNULUS, eps, FemLoad::Flat));
    }
    check(&cases, 1e-3);
    cases.push((PunchKind::CONE, 0.0, FemLoad::ConcaveDepth(0.5)));
    cases.push((PunchKind::CONE, 0.0, FemLoad::ConcaveDepth(4.0)));
    cases.push((PunchKind::SPHERE, 0.0, FemLoad::ConcaveDepth(2.8)));
    cases.push((PunchKind::SPHERE, 0.0, FemLoad::ConcaveDepth(0.7)));
    check(&cases, 1e-4);
    let generated = fem(PunchKind::FLAT_ANNULUS, 0.3, FemLoad::Flat, 1e-3);
    assert!(generated.gmsh_version.is_some() && generated.mesh_sha256.len() == 64);
    // Quadratic elements further down their ladder (levels 2 and 3).
    check(&[(PunchKind::CONE, 0.0, FemLoad::ConcaveDepth(2.0))], 1e-5);
}

/// 29 states: the 12 targets (cone at `d/h` 0.5, 2, 4; sphere at 0.5, 1.5, 2.8; flat
/// annulus at `b/a` 0.1, 0.3, 0.5, 0.7, 0.9, 0.97), and 17 more (other depths, up to the sphere's
/// full contact at 3h and the cone at 14h, thinner and thicker rings, the disk, force control).
fn many_states() -> Vec<(PunchKind, f64, FemLoad)> {
    let mut cases = Vec::new();
    // Up to the deep cone, whose hole (b/a = 2.5e-4 at 14 h) the first models see as full contact.
    for d in [0.1, 0.5, 1.0, 2.0, 3.0, 4.0, 8.0, 12.0, 14.0] {
        cases.push((PunchKind::CONE, 0.0, FemLoad::ConcaveDepth(d)));
    }
    for d in [0.2, 0.5, 1.0, 1.5, 2.5, 2.8, 2.95] {
        cases.push((PunchKind::SPHERE, 0.0, FemLoad::ConcaveDepth(d)));
    }
    for eps in [0.02, 0.1, 0.2, 0.3, 0.5, 0.7, 0.8, 0.9, 0.97, 0.99] {
        cases.push((PunchKind::FLAT_ANNULUS, eps, FemLoad::Flat));
    }
    cases.push((PunchKind::FLAT, 0.0, FemLoad::Flat));
    cases.push((PunchKind::CONE, 0.0, FemLoad::ConcaveForce(1.0)));
    cases.push((PunchKind::SPHERE, 0.0, FemLoad::ConcaveForce(0.8)));
    cases
}

#[test]
#[cfg_attr(gmsh_missing, ignore = "needs gmsh: bash scripts/install_gmsh.sh")]
fn the_estimate_bounds_the_error_at_29_states_at_1e3_and_1e6() {
    // Meshes made for each scene, the default degree (cubic), against the ring BEM at 1e-10:
    // every state meets the tolerance in force and eps, and its estimate bounds both errors.
    for tolerance in [1e-3, 1e-6] {
        check_degree(
            solver::default_degree(&ringcontact::mesh::files::DataPaths::default(), tolerance),
            &many_states(),
            tolerance,
        );
    }
}

#[test]
#[cfg_attr(gmsh_missing, ignore = "needs gmsh: bash scripts/install_gmsh.sh")]
fn narrow_contact_rings_are_resolved_or_declined() {
    // Rings 1e-3 to 1.5e-4 a wide: the flat annulus near b/a = 1 and the shallow concave punches,
    // whose contact is a thin ring at the rim. The elements at the edges scale with the ring's
    // width; before they did, every level was wrong alike (b/a = 0.9999: a force error of 9e-3
    // under an estimate of 3e-5, the sphere at d = 0.003 h: 4.5e-3 under 1.2e-4).
    let cases = [
        (PunchKind::FLAT_ANNULUS, 0.999, FemLoad::Flat),
        (PunchKind::FLAT_ANNULUS, 0.9999, FemLoad::Flat),
        (PunchKind::CONE, 0.0, FemLoad::ConcaveDepth(0.001)),
        (PunchKind::SPHERE, 0.0, FemLoad::ConcaveDepth(0.003)),
    ];
    check_degree(Degree::Cubic, &cases, 1e-3);
    check_degree(Degree::Cubic, &cases[..2], 1e-6);
    check_degree(
        Degree::Cubic,
        &[(PunchKind::CONE, 0.0, FemLoad::ConcaveDepth(0.03))],
        1e-6,
    );
    // Quadratic elements at 1e-5 on rings 3.2e-4 and 1.6e-4 a wide: with the free edge's
    // elements sized for `a`, not for the ring, the levels shared them, and the force errors
    // (2.5e-6, 6.6e-6) were above the estimates (2.0e-6, 3.8e-6).
    check_degree(
        Degree::Quadratic,
        &[
            (PunchKind::CONE, 0.0, FemLoad::ConcaveDepth(0.002)),
            (PunchKind::SPHERE, 0.0, FemLoad::ConcaveDepth(0.002)),
        ],
        1e-5,
    );
    // A ring whose tolerance would need elements below the smallest the FEM makes is declined,
    // naming the loosest tolerance that would do.
    let options = ladder_options(Degree::Cubic, 1e-8);
    let e = solver::solve(PunchKind::FLAT_ANNULUS, 0.999, FemLoad::Flat, &options).unwrap_err();
    assert!(
        matches!(&e, Error::OutOfRange { reason, .. }
            if reason.contains("0.001 a wide") && reason.contains("at least 1.000000e-7")),
        "{e}"
    );
}

#[test]
#[cfg_attr(gmsh_missing, ignore = "needs gmsh: bash scripts/install_gmsh.sh")]
fn a_nearly_closed_hole_is_bound_or_declined() {
    // The sphere within 1e-3 h and 1e-4 h of full contact (holes 1.9e-2 a and 6.1e-3 a): its
    // edge moves 29 and 92 times a relative change of the depth (the ring BEM's), so the small
    // error of the displacement field moves it far more than the mesh at the edge does. Before
    // the edge's field component, cubic models at 1e-6 returned edges off by 8.3e-7 and 4.3e-6
    // under estimates of 6.4e-7 and 6.5e-7, and at 1e-7 by 2.1e-7 under 4.2e-8.
    check_degree(
        Degree::Cubic,
        &[
            (PunchKind::SPHERE, 0.0, FemLoad::ConcaveDepth(2.999)),
            (PunchKind::SPHERE, 0.0, FemLoad::ConcaveDepth(2.9999)),
        ],
        1e-6,
    );
    // At 2e-4 h from closure (hole 8.7e-3 a, κ = 52) cubic models at 1e-3 stopped at 14.5 k
    // unknowns with an edge off by 5.4e-4 under an estimate of 5.3e-4: their force estimate came
    // from an observed convergence ratio below the known order's (outside the asymptotic range)
    // and exceeded the actual error by 1.15 times only, so the edge's field share of 0.5 fell
    // short (the edge erred by 0.82 of κ times the actual force error). The whole κ ε is taken
    // there now.
    check_degree(
        Degree::Cubic,
        &[(PunchKind::SPHERE, 0.0, FemLoad::ConcaveDepth(2.9998))],
        1e-3,
    );
    // At 1e-7 the edge of the hole 6.1e-3 a wide needs forces finer than the far field's
    // floor allows: declined, naming the conditioning.
    let options = ladder_options(Degree::Cubic, 1e-7);
    match solver::solve(
        PunchKind::SPHERE,
        0.0,
        FemLoad::ConcaveDepth(2.9999),
        &options,
    ) {
        Err(Error::OutOfRange { reason, .. }) => {
            assert!(reason.contains("ill-conditioned"), "{reason}")
        }
        other => panic!("expected the nearly closed hole at 1e-7 to be declined: {other:?}"),
    }
}

#[test]
#[cfg_attr(gmsh_missing, ignore = "needs gmsh: bash scripts/install_gmsh.sh")]
fn an_edge_under_a_prescribed_force_is_bound_near_closure() {
    // The sphere under F = 5.3 and 5.333 (d = 2.983 h and 2.9998 h by the ring BEM; closed from
    // F = 16/3): cubic models at 1e-3 returned edges off by 5.1e-4 and 1.3e-3 under estimates of
    // 2.5e-4 and 6.5e-4. Under a prescribed force the model's force error is a depth error, which
    // moves the edge by κ times itself, on top of the edge's own error: the estimate now takes
    // the whole shift and adds it.
    check_degree(
        Degree::Cubic,
        &[
            (PunchKind::SPHERE, 0.0, FemLoad::ConcaveForce(2.65)),
            (PunchKind::SPHERE, 0.0, FemLoad::ConcaveForce(2.6665)),
        ],
        1e-3,
    );
}

#[test]
#[cfg_attr(gmsh_missing, ignore = "needs gmsh: bash scripts/install_gmsh.sh")]
fn an_edge_under_a_force_keeps_a_margin_for_its_conditionings_error() {
    // The sphere under F = 5.3328 (d = 2.99973 h by the ring BEM, a hole of 0.0100 a): the
    // located edge moves κ = |db/dd| d times the relative depth error, and the model's own κ
    // errs by up to a third near closure (48.3 here against the ring BEM's 56.3). Taking the
    // whole shift once, the cubic model at 1e-3 answered eps off by 9.3e-4 under an estimate of
    // 9.5e-4: bound by a factor of 1.02, so a neighbouring state with a worse κ would not be.
    // The estimate must keep a margin of 1.25 here (the model's κ a fifth under).
    check_degree_with_margin(
        Degree::Cubic,
        &[(PunchKind::SPHERE, 0.0, FemLoad::ConcaveForce(2.6664))],
        1e-3,
        1.25,
    );
}

#[test]
#[cfg_attr(gmsh_missing, ignore = "needs gmsh: bash scripts/install_gmsh.sh")]
fn full_contact_near_closure_is_bound_certified_or_declined() {
    // Quadratic models near the sphere's closure (holes of 1.9e-2, 6.1e-3 and 4.3e-3 a at
    // d/h = 2.999, 2.9999, 2.99995; closed from d = 3h, where F = 2 E* a (d - h/3)): their
    // axis node alone is often free (a P2 vertex on the axis carries a reaction of the
    // pressure's slope), and that state had been given the axis' spacing, 0, as its edge's
    // bound: eps = 0 was returned for the first three with estimates of 2.3e-4 and 3.4e-5.
    // Full contact is now bounded by the first node off the axis, certified closed only when
    // the contact would open beyond the model's error, and refined when it would open within.
    // The cone never closes, and its apex (a kink) hides a hole at the first node: at 12 h its
    // hole of 9e-4 a lay inside first nodes at 7.5e-4 a, whose margins fell toward the axis, and
    // P2 and P3 at 1e-3 ended in the impossible-state error; the next mesh now refines inside
    // that node. Each must bound its errors against the ring BEM (MDR past closure) or decline.
    let mut answered = 0;
    let sphere = PunchKind::SPHERE;
    let cases = [
        (sphere.clone(), Degree::Quadratic, 2.999, 1e-3),
        (sphere.clone(), Degree::Quadratic, 2.9999, 1e-3),
        (sphere.clone(), Degree::Quadratic, 2.99995, 1e-3),
        (sphere.clone(), Degree::Quadratic, 2.9999, 1e-4),
        (sphere.clone(), Degree::Quadratic, 3.0001, 1e-3),
        (sphere.clone(), Degree::Cubic, 3.0001, 1e-4),
        (sphere, Degree::Cubic, 2.99995, 1e-4),
        (PunchKind::CONE, Degree::Quadratic, 12.0, 1e-3),
        (PunchKind::CONE, Degree::Cubic, 12.0, 1e-3),
        (PunchKind::CONE, Degree::Cubic, 14.0, 1e-3),
    ];
    for (kind, degree, depth, tolerance) in cases.clone() {
        let load = FemLoad::ConcaveDepth(depth);
        let options = ladder_options(degree, tolerance);
        let state = match solver::solve(kind.clone(), 0.0, load, &options) {
            Ok(state) => state,
            Err(e) => {
                println!("{kind} {degree:?} d/h = {depth} at {tolerance:e}: declined: {e}");
                continue;
            }
        };
        answered += 1;
        let (force_error, eps_error) = errors(kind.clone(), 0.0, load, &state);
        let estimate = state.error_estimate.unwrap();
        println!(
            "{kind} {degree:?} d/h = {depth} at {tolerance:e}: eps {:.3e}, force error {force_error:.1e}, \
             eps error {eps_error:.1e}, estimate {estimate:.1e}, {} dofs",
            state.eps, state.dofs
        );
        assert!(
            estimate <= tolerance && force_error <= estimate && eps_error <= estimate,
            "{kind} {degree:?} d/h = {depth} at {tolerance:e}: the estimate {estimate:.1e} does not \
             bound the errors ({force_error:.1e}, {eps_error:.1e})"
        );
    }
    // Declining everything would pass the loop: most of these states were answered when the
    // test was written (all ten).
    assert!(answered >= 8, "only {answered} of {} answered", cases.len());
}

#[test]
#[cfg_attr(gmsh_missing, ignore = "needs gmsh: bash scripts/install_gmsh.sh")]
fn a_closed_cone_within_its_estimate_is_answered() {
    // The cone never closes, but at 13 and 14 h its holes (4.8e-4 and 2.5e-4 a, ring BEM) are
    // below the quadratic models' resolution at 1e-3: their answer, eps = 0 within 8.2e-4, holds
    // them. The harness's plausibility check once refused every closed cone below 15 h (it now
    // compares the estimate with the hole's lower bound at that depth). Through
    // the binary, where the check applies; both bounds against the ring BEM.
    let bem = RingBem::new();
    for depth in [13.0, 14.0] {
        let output = std::process::Command::new(env!("CARGO_BIN_EXE_verify"))
            .args([
                "solve", "--punch", "cone", "--method", "fem", "--degree", "2",
            ])
            .args(["--tol", "1e-3", "--depth", &depth.to_string(), "--json"])
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(output.status.success(), "d/h = {depth}: {stderr}");
        let state: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
        let (eps, gamma2) = (
            state["eps"].as_f64().unwrap(),
            state["gamma2"].as_f64().unwrap(),
        );
        let estimate = state["error_estimate"].as_f64().unwrap();
        // 1e-9: at these holes the free edge's rounding floor is 1e-10 to 2e-10.
        let reference = bem.concave_at_depth(&PunchKind::CONE, depth, 1e-9).unwrap();
        // F = 2 E* h a γ2: the force's relative error is γ2's.
        let force_error = (gamma2 / reference.gamma2.unwrap() - 1.0).abs();
        let eps_error = (eps - reference.eps).abs();
        println!(
            "cone d/h = {depth}: eps {eps:.2e} (ring BEM {:.2e}), force error {force_error:.1e}, \
             estimate {estimate:.1e}",
            reference.eps
        );
        assert!(
            estimate <= 1e-3 && force_error <= estimate && eps_error <= estimate,
            "d/h = {depth}: the estimate {estimate:.1e} does not bound the errors \
             ({force_error:.1e}, {eps_error:.1e})"
        );
    }
}

#[test]
#[cfg_attr(gmsh_missing, ignore = "needs gmsh: bash scripts/install_gmsh.sh")]
fn the_free_edges_conditioning_follows_the_ring_bem() {
    // κ = |db/dd| d of the FEM's final model against the ring BEM's central difference of its
    // located edge over d ± 1e-6 (converged to 1e-10). The FEM's is a difference of its edge's
    // extrapolation from the free nodes' gaps: measured 0.80-1.34 of the ring BEM's at 1e-5
    // (cone d/h = 0.5, 2, 4; sphere 0.5, 1.5, 2.99, 2.999). It only has to tell a
    // well-conditioned edge (κ below 1) from a nearly closed hole (κ of 10-100).
    let bem = RingBem::new();
    for (kind, depth) in [
        (PunchKind::CONE, 2.0),
        (PunchKind::SPHERE, 1.5),
        (PunchKind::SPHERE, 2.99),
    ] {
        let state = fem_of_degree(
            Degree::Cubic,
            kind.clone(),
            0.0,
            FemLoad::ConcaveDepth(depth),
            1e-5,
        );
        let fem_kappa = state
            .edge_conditioning
            .expect("a concave punch's conditioning");
        let edge = |d: f64| bem.concave_at_depth(&kind, d, 1e-10).unwrap().eps;
        let step = 1e-6;
        let bem_kappa = (edge(depth + step) - edge(depth - step)).abs() / (2.0 * step) * depth;
        println!("{kind} d/h = {depth}: κ FEM {fem_kappa:.4}, ring BEM {bem_kappa:.4}");
        assert!(
            (fem_kappa / bem_kappa - 1.0).abs() < 0.5,
            "{kind} d/h = {depth}: κ {fem_kappa} against the ring BEM's {bem_kappa}"
        );
    }
}

#[test]
#[cfg_attr(gmsh_missing, ignore = "needs gmsh: bash scripts/install_gmsh.sh")]
fn tolerance_1e8_is_met_on_a_narrow_ring_and_both_concave_punches() {
    // 1e-8 needs rim elements of 1e-9 a and below, finer than gmsh meshes well (slivers below
    // 1e-8 a): the corner refinement makes them. Before it, b/a = 0.97 stopped at 1.4e-8.
    let cases = [
        (PunchKind::FLAT_ANNULUS, 0.97, FemLoad::Flat),
        (PunchKind::CONE, 0.0, FemLoad::ConcaveDepth(2.0)),
        (PunchKind::SPHERE, 0.0, FemLoad::ConcaveDepth(2.8)),
    ];
    check_degree(Degree::Cubic, &cases, 1e-8);
    let state = fem_of_degree(
        Degree::Cubic,
        cases[0].0.clone(),
        cases[0].1,
        cases[0].2,
        1e-8,
    );
    assert!(
        state.mesh_refinement.is_some(),
        "no corner refinement recorded"
    );
}

#[test]
fn a_long_ladder_reports_its_progress() {
    // Every 10 s by default; here every millisecond, so that a short ladder shows its steps.
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_verify"))
        .args(["solve", "--punch", "flat", "--method", "fem"])
        .env("RINGCONTACT_PROGRESS_S", "0.001")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{stderr}");
    assert!(
        stderr
            .lines()
            .any(|l| l.starts_with("fem: ") && l.contains(" unknowns on ")),
        "{stderr}"
    );
    // Without the variable a solve of a second is silent.
    let quiet = std::process::Command::new(env!("CARGO_BIN_EXE_verify"))
        .args(["solve", "--punch", "flat", "--method", "fem"])
        .output()
        .unwrap();
    assert!(quiet.status.success() && quiet.stderr.is_empty());
}

#[test]
fn a_missing_gmsh_is_one_clear_error() {
    // With gmsh pointed at nothing, a scene that needs a generated mesh names the install command.
    let dir = std::env::temp_dir().join(format!("ringcontact-no-gmsh-{}", std::process::id()));
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_verify"))
        .args([
            "solve",
            "--punch",
            "flat-annulus",
            "--eps",
            "0.37",
            "--method",
            "fem",
        ])
        .env("RINGCONTACT_GMSH", "/nonexistent/gmsh")
        .env("RINGCONTACT_MESH_CACHE", &dir)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success());
    assert!(
        stderr.contains("gmsh was not found") && stderr.contains("bash scripts/install_gmsh.sh"),
        "{stderr}"
    );
}

/// The power-law punch `h (1 - (r/a)^n)` at 17 states: fractional, odd and even exponents
/// (up to the steep walls of `n = 50`), annular and full contact, depth and force control. The FEM (meshes made for each scene) meets
/// 1e-6 against the ring BEM at 1e-10 in force and in the free edge, and its estimate bounds
/// both errors. (States of `n > 2` whose contact is a disk and an annulus are left out: the ring
/// BEM refuses them.)
#[test]
#[cfg_attr(gmsh_missing, ignore = "needs gmsh: bash scripts/install_gmsh.sh")]
fn power_law_punches_agree_with_the_ring_bem_to_1e6() {
    let power = |n: f64| PunchKind::power(ringcontact::punch::Exponent::new(n).unwrap());
    let mut cases = Vec::new();
    for (n, depths) in [
        (0.5, vec![0.5, 2.0, 5.0]),
        (1.5, vec![0.5, 2.0, 4.0]),
        (3.0, vec![1.0, 2.0, 2.2]),
        (4.0, vec![1.0, 1.2, 3.0]),
    ] {
        for d in depths {
            cases.push((power(n), 0.0, FemLoad::ConcaveDepth(d)));
        }
    }
    cases.push((power(1.5), 0.0, FemLoad::ConcaveForce(1.0)));
    cases.push((power(3.0), 0.0, FemLoad::ConcaveForce(1.0)));
    // Steep-walled profiles, whose `γ1(ε)` rises again inside the hole: the ring BEM's search
    // wandered there (`n = 20`, `d = 0.9 h`) or refused a state that exists (`n = 6`,
    // `d = 1.8 h`; `n = 50`, `F/(2 E* h a) = 0.5`) until it started from the sphere of the
    // same rim slope.
    cases.push((power(6.0), 0.0, FemLoad::ConcaveDepth(1.8)));
    cases.push((power(20.0), 0.0, FemLoad::ConcaveDepth(0.9)));
    cases.push((power(50.0), 0.0, FemLoad::ConcaveForce(0.5)));
    check_degree(
        solver::default_degree(&ringcontact::mesh::files::DataPaths::default(), 1e-6),
        &cases,
        1e-6,
    );
}
