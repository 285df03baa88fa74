//! Our assembled operator against FEniCSx's: the stiffness matrix and the
//! unit-pressure load vector, entry by entry, dofs matched by position.
//!
//! References: FEniCSx's own assembly (dolfinx 0.5.2), stored for one small mesh under
//! `verify/fenicsx/operators/small-domain-R5-P1/` (made by `scripts/fenicsx/export.py`), made
//! afresh when `/usr/bin/python3` has dolfinx, and a closed form for the load's total.

use std::path::{Path, PathBuf};
use std::process::Command;

use ringcontact::discretisation::export::{assemble_system, load_mesh, read_matrix, write_system};
use ringcontact::mesh::triangulation::{structured_rectangle, tags, Degree};
use ringcontact_verify::harness::records::operator::{
    compare_operator, load_records, OPERATOR_GOAL,
};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn the_stored_fenicsx_assembly_equals_ours_entry_by_entry() {
    let dir = root().join("verify/fenicsx/operators/small-domain-R5-P1");
    let c = compare_operator(
        &root().join("meshes/small-domain-R5.msh"),
        Degree::Linear,
        &dir,
    )
    .unwrap();
    println!("{c:?}");
    assert_eq!(c.nnz_ours, c.nnz_fenicsx, "different sparsity patterns");
    assert!(c.meets_goal(), "{c:?}");
}

#[test]
fn the_stored_comparisons_on_committed_meshes_are_current_and_meet_the_goal() {
    let records = load_records().unwrap();
    assert!(records.len() >= 5, "found {} records", records.len());
    for r in &records {
        let c = &r.record.comparison;
        if c.mesh.starts_with("meshes/") {
            assert_eq!(r.status, "current", "{}: its mesh changed", r.file);
        }
        assert!(c.stiffness_difference <= OPERATOR_GOAL, "{}: {c:?}", r.file);
        assert!(c.load_difference <= OPERATOR_GOAL, "{}: {c:?}", r.file);
        assert_eq!(c.nnz_ours, c.nnz_fenicsx, "{}", r.file);
    }
}

#[test]
#[cfg_attr(
    dolfinx_missing,
    ignore = "needs dolfinx in /usr/bin/python3: bash scripts/fenicsx/setup.sh"
)]
fn a_fresh_fenicsx_assembly_equals_ours_for_every_degree() {
    let work = std::env::temp_dir().join(format!("ringcontact-operator-{}", std::process::id()));
    for degree in [1u8, 2, 3] {
        let dir = work.join(format!("P{degree}"));
        let status = Command::new("/usr/bin/python3")
            .arg(root().join("scripts/fenicsx/export.py"))
            .args([
                "--mesh",
                "meshes/disk-L0.msh",
                "--degree",
                &degree.to_string(),
            ])
            .arg("--out")
            .arg(&dir)
            .current_dir(root())
            .output()
            .unwrap();
        assert!(
            status.status.success(),
            "{}",
            String::from_utf8_lossy(&status.stderr)
        );
        let c = compare_operator(
            &root().join("meshes/disk-L0.msh"),
            Degree::from_number(degree).unwrap(),
            &dir,
        )
        .unwrap();
        println!("P{degree}: {c:?}");
        assert!(c.meets_goal(), "P{degree}: {c:?}");
    }
    let _ = std::fs::remove_dir_all(&work);
}

#[test]
fn the_load_of_a_unit_pressure_sums_to_minus_pi_a_squared() {
    // Contact line [0, 2] on z = 0: the total of f_z is -∫ 2π r dr = -π · 2² for every degree.
    for degree in [Degree::Linear, Degree::Quadratic, Degree::Cubic] {
        let mesh = structured_rectangle(2.0, 1.0, 5, 3, tags::CONTACT, tags::FREE, tags::FAR)
            .with_degree(degree);
        let system = assemble_system(&mesh).unwrap();
        let total: f64 = system.load.iter().skip(1).step_by(2).sum();
        assert!(
            (total + 4.0 * std::f64::consts::PI).abs() < 1e-12,
            "{degree:?}: {total}"
        );
        assert!(system.load.iter().step_by(2).all(|&v| v == 0.0));
        // A rigid translation along z is in the kernel of K (up to rounding).
        let k = &system.stiffness;
        let largest = k.values().iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let mut ku = vec![0.0; k.nrows()];
        for col in (1..k.ncols()).step_by(2) {
            for idx in k.col_offsets()[col]..k.col_offsets()[col + 1] {
                ku[k.row_indices()[idx]] += k.values()[idx];
            }
        }
        assert!(ku.iter().all(|v| v.abs() < 1e-12 * largest), "{degree:?}");
    }
}

#[test]
fn the_matrix_market_files_read_back_exactly() {
    let mesh = load_mesh(
        Path::new(&root().join("meshes/small-domain-R5.msh")),
        Degree::Quadratic,
    )
    .unwrap();
    let system = assemble_system(&mesh).unwrap();
    let dir = std::env::temp_dir().join(format!("ringcontact-export-{}", std::process::id()));
    write_system(&system, &dir).unwrap();
    let back = read_matrix(&dir.join("stiffness.mtx")).unwrap();
    assert_eq!(back.nnz(), system.stiffness.nnz());
    let k = &system.stiffness;
    for (&value, (row, col)) in back.triplet_iter() {
        let range = k.col_offsets()[col]..k.col_offsets()[col + 1];
        let at = k.row_indices()[range.clone()].binary_search(&row).unwrap();
        assert_eq!(value, k.values()[range.start + at], "({row}, {col})");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn an_export_of_another_mesh_is_a_clear_error() {
    let dir = root().join("verify/fenicsx/operators/small-domain-R5-P1");
    let e = compare_operator(&root().join("meshes/disk-L0.msh"), Degree::Linear, &dir)
        .unwrap_err()
        .to_string();
    assert!(e.contains("556 dofs") && e.contains("924"), "{e}");
}
