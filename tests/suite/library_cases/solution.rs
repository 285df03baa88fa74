use ringcontact::punch::PunchKind;
use ringcontact::solution::{FemProvenance, Solution};

/// The FEM's part is written as the solution's own keys (the JSON of `verify solve --json`
/// before it had a part of its own), absent for other methods, and read back as it was.
#[test]
fn fem_provenance_keys_are_the_solutions_own() {
    let other = state(PunchKind::SPHERE, 0.2, 1.5, 2.0);
    let json = serde_json::to_value(&other).unwrap();
    assert!(json.get("dofs").is_none() && json.get("fem").is_none());
    let back: Solution = serde_json::from_value(json).unwrap();
    assert!(back.fem.is_none());
    let fem = Solution {
        fem: Some(FemProvenance {
            dofs: 1234,
            mesh: "meshes/disk-L2.msh".into(),
            mesh_sha256: "ab".repeat(32),
            mesh_origin: ringcontact::mesh::provider::MeshOrigin::Committed,
            gmsh_version: None,
            mesh_refinement: None,
            far_field: ringcontact::discretisation::far_field::FarField::Boussinesq,
            fem_timings: Default::default(),
            degree: 2,
            edge_conditioning: Some(0.5),
        }),
        ..other
    };
    let json = serde_json::to_value(&fem).unwrap();
    assert_eq!(json["dofs"], 1234);
    assert_eq!(json["mesh"], "meshes/disk-L2.msh");
    assert_eq!(json["far_field"], "boussinesq");
    assert_eq!(json["degree"], 2);
    assert_eq!(json["edge_conditioning"], 0.5);
    assert!(json.get("fem").is_none() && json.get("gmsh_version").is_none());
    let back: Solution = serde_json::from_value(json).unwrap();
    let part = back.fem.expect("the FEM's keys read back into its part");
    assert_eq!((part.dofs, part.degree), (1234, 2));
    assert_eq!(part.edge_conditioning, Some(0.5));
}

fn state(punch: PunchKind, eps: f64, depth: f64, force: f64) -> Solution {
    Solution {
        punch,
        method: "test".into(),
        eps,
        depth,
        force,
        inner_radius: eps,
        rim_radius: 1.0,
        outer_radius: 1.0,
        tube_radius: None,
        gamma: None,
        gamma1: Some(depth),
        gamma2: Some(0.5 * force),
        stress_intensity_rim: None,
        stress_intensity_inner: None,
        error_estimate: Some(1e-4),
        wall_s: 0.0,
        unknowns: 0,
        iterations: 0,
        fem: None,
        complementarity_residual: None,
        grid_bem: None,
        selection: None,
        pressure: Vec::new(),
        provenance: String::new(),
    }
}

/// The linear gap's hole bound ([`ringcontact::punch::Profile::hole_lower_bound`]) stays below the
/// ring BEM's hole and within 20 % of it at depths not in its table. (At 1e-9: the ring BEM's
/// values scatter by about 1e-10 of themselves at the holes of 1e-4 a near d/h = 15.)
#[test]
fn the_cone_hole_bound_is_below_the_ring_bems_hole() {
    let bem = ringcontact::methods::RingBem::new();
    for depth in [2.0, 3.0, 4.0, 6.0, 8.0, 10.5, 12.0, 13.0, 14.0, 15.0] {
        let hole = bem
            .concave_at_depth(&PunchKind::CONE, depth, 1e-9)
            .unwrap()
            .eps;
        let bound = PunchKind::CONE.profile().hole_lower_bound(depth).unwrap();
        assert!(
            bound <= hole && bound >= 0.8 * hole,
            "d/h = {depth}: bound {bound:e}, hole {hole:e}"
        );
    }
    assert!(PunchKind::SPHERE.profile().hole_lower_bound(2.0).is_none());
}

#[test]
fn an_underflowed_force_is_refused_with_short_numbers_and_the_cause() {
    let mut tiny = state(PunchKind::CONE, 0.45, 2e-301, 0.0);
    tiny.gamma2 = Some(1.8);
    let message = tiny.check_plausible().unwrap_err().to_string();
    assert!(message.contains("force underflows"), "{message}");
    assert!(message.contains("2.000000e-301"), "{message}");
    assert!(message.len() < 400, "{message}");
}

#[test]
fn impossible_states_are_refused() {
    assert!(state(PunchKind::CONE, 0.45, 2.0, 3.6)
        .check_plausible()
        .is_ok());
    // A coarse mesh that lost its whole contact: eps = 1 with a positive force.
    assert!(state(PunchKind::CONE, 1.0, 2.0, 3.6)
        .check_plausible()
        .is_err());
    // Overflow.
    assert!(state(PunchKind::SPHERE, 0.3, 1.0, f64::INFINITY)
        .check_plausible()
        .is_err());
    // Force and depth of opposite signs.
    assert!(state(PunchKind::CONE, 0.45, 2.0, -3.6)
        .check_plausible()
        .is_err());
    // Full contact where it cannot exist: the linear gap with an estimate smaller than its hole
    // there (or without an estimate), and the parabolic gap below d = 3h.
    assert!(state(PunchKind::CONE, 0.0, 5.0, 10.0)
        .check_plausible()
        .is_err());
    assert!(state(PunchKind::CONE, 0.0, 50.0, 100.0)
        .check_plausible()
        .is_ok());
    let mut without_estimate = state(PunchKind::CONE, 0.0, 50.0, 100.0);
    without_estimate.error_estimate = None;
    assert!(without_estimate.check_plausible().is_err());
    // At 13h the hole is 4.8e-4 a (ring BEM): closed within 8.2e-4 holds it (the FEM's P2
    // answer at --tol 1e-3), closed within 1e-4 does not; nor, at 5h (a hole of 7.8e-2 a),
    // closed within 5e-2.
    let mut closed_at_13 = state(PunchKind::CONE, 0.0, 13.0, 25.6);
    closed_at_13.error_estimate = Some(8.2e-4);
    assert!(closed_at_13.check_plausible().is_ok());
    closed_at_13.error_estimate = Some(1e-4);
    assert!(closed_at_13.check_plausible().is_err());
    let mut closed_at_5 = state(PunchKind::CONE, 0.0, 5.0, 10.0);
    closed_at_5.error_estimate = Some(5e-2);
    assert!(closed_at_5.check_plausible().is_err());
    // Deeper than the ring BEM's table: at 20h the hole is about 5.6e-6 a (asymptote).
    let mut closed_at_20 = state(PunchKind::CONE, 0.0, 20.0, 40.0);
    closed_at_20.error_estimate = Some(1e-5);
    assert!(closed_at_20.check_plausible().is_ok());
    closed_at_20.error_estimate = Some(1e-6);
    assert!(closed_at_20.check_plausible().is_err());
    assert!(state(PunchKind::SPHERE, 0.0, 2.5, 5.0)
        .check_plausible()
        .is_err());
    assert!(state(PunchKind::SPHERE, 0.0, 3.5, 6.3)
        .check_plausible()
        .is_ok());
}
