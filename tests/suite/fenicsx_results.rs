//! The stored FEniCSx results (verify/fenicsx/, produced by scripts/fenicsx/run_all.sh with
//! dolfinx) against our FEM on the identical discrete problem: every committed result must belong
//! to the committed meshes (SHA-256), agree in force within 1e-8 and have the same active contact
//! set. A result whose mesh changed is caught as stale and not used.

use ringcontact::methods::RingBem;
use ringcontact_verify::harness::records::fenicsx::{
    self, compare, large_results_directory, load_results, results_directory, FORCE_AGREEMENT,
};

/// The stored results on committed meshes (`generated` false) or on meshes gmsh remakes from
/// their stored parameters (`generated` true), at least `minimum` of them, against our FEM.
fn check_stored_results(generated: bool, minimum: usize) {
    let ring = RingBem::new();
    let rows = load_results(&results_directory())
        .unwrap()
        .iter()
        .filter(|(_, stored)| stored.mesh_parameters.is_some() == generated)
        .map(|(file, stored)| compare(file, stored, &ring).unwrap())
        .collect::<Vec<_>>();
    assert!(
        rows.len() >= minimum,
        "expected the default suite of stored results, found {}",
        rows.len()
    );
    for row in &rows {
        assert_eq!(
            row.status, "current",
            "{}: mesh {} changed since the result was stored, or could not be remade",
            row.file, row.stored.mesh
        );
        let diff = row.relative_difference.unwrap();
        assert!(
            diff.abs() <= FORCE_AGREEMENT,
            "{}: force differs by {diff:e}",
            row.file
        );
        assert_eq!(
            row.same_active_set,
            Some(true),
            "{}: active sets differ",
            row.file
        );
        let reproduce = &row.stored.reproduce;
        assert!(
            reproduce.starts_with("cargo run --release --quiet -- solve ")
                && reproduce.contains(" --method fem")
                && reproduce.contains(" --punch "),
            "{}: no reproduce line of our FEM",
            row.file
        );
        assert!(!row.stored.dolfinx_version.is_empty() && !row.stored.petsc_version.is_empty());
    }
}

#[test]
fn every_result_on_a_committed_mesh_matches_it_and_our_fem() {
    check_stored_results(false, 10);
}

#[test]
#[cfg_attr(gmsh_missing, ignore = "needs gmsh: bash scripts/install_gmsh.sh")]
fn every_result_on_a_generated_mesh_matches_the_remade_mesh_and_our_fem() {
    check_stored_results(true, 10);
}

/// The results on the largest meshes are compared only on request (`verify fenicsx --large`: a
/// minute of solves): here they must parse, be large, and carry what remakes and reruns them.
#[test]
fn the_stored_results_on_the_largest_meshes_can_be_remade_and_compared() {
    let large = load_results(&large_results_directory()).unwrap();
    assert!(large.len() >= 3, "found {} large results", large.len());
    for (file, result) in &large {
        assert!(result.dofs >= 500_000, "{file}: {} dofs", result.dofs);
        assert!(
            result.mesh_parameters.is_some(),
            "{file}: no gmsh parameters to remake its mesh"
        );
        assert!(
            result
                .reproduce
                .starts_with("cargo run --release --quiet -- solve --punch"),
            "{file}"
        );
        assert!(result.force.is_finite() && result.force > 0.0 && result.wall_s > 0.0);
    }
}

/// The first stored result on a committed mesh (those on gmsh-made meshes need gmsh to remake it).
fn committed_mesh_result() -> (String, fenicsx::FenicsxResult) {
    load_results(&results_directory())
        .unwrap()
        .into_iter()
        .find(|(_, r)| r.mesh_parameters.is_none())
        .unwrap()
}

#[test]
fn a_result_whose_mesh_changed_is_stale_and_not_used() {
    let (file, mut stored) = committed_mesh_result();
    stored.mesh_sha256 = "0".repeat(64);
    let row = compare(&file, &stored, &RingBem::new()).unwrap();
    assert_eq!(row.status, "stale");
    assert!(row.our_force.is_none() && !row.passed);
    // Not compared is a failure: the stale row, and a run that compared nothing.
    assert_eq!(
        fenicsx::failures(std::slice::from_ref(&row)),
        2,
        "a stale result is a failure, and so is comparing nothing"
    );
    assert!(fenicsx::coverage(std::slice::from_ref(&row)).contains("not compared"));
    assert!(fenicsx::render(&[row]).contains("STALE"));
}

#[test]
fn a_disagreeing_result_fails() {
    // The check must be able to fail: a force off by 1e-6 is a disagreement.
    let (file, mut stored) = committed_mesh_result();
    stored.force *= 1.0 + 1e-6;
    let row = compare(&file, &stored, &RingBem::new()).unwrap();
    assert_eq!(row.status, "current");
    assert!(!row.passed);
    assert_eq!(fenicsx::failures(&[row]), 1);
}
