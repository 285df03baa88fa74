//! The table punch (`--punch table --profile FILE`): a concave punch whose profile is a CSV table
//! of `(r/a, g/h)` points, interpolated by monotone cubics (PCHIP).
//!
//! Independent check: tables sampled from the sphere's profile `1 - (r/a)²` at 6 to 41 points,
//! solved by the FEM at `--tol 1e-7`, tend to the sphere's converged ring-BEM state (1e-12) as
//! the table is refined. Two facts bound the difference: the contact problem is monotone in the
//! gap, so a gap within `δ` of the sphere's changes `γ2 = F/(2 E* h a)` at a given depth by at
//! most `δ` (the force's slope in the depth is at most `2 E* a`), and `δ` falls at least as the
//! square of the spacing (the interpolant's order next to the axis, `src/punch/table.rs`).
//! The ring BEM refuses tables by name, and bad tables are errors naming the line.

mod common;
use common::gmsh_available;

use std::path::{Path, PathBuf};
use std::process::Command;

use ringcontact::bem::ring_contact::RingBemSolver;
use ringcontact::punch::{PunchKind, PunchName};

/// A table of the sphere's profile at `points` equally spaced radii, written to a fresh file.
fn sphere_table(dir: &Path, points: usize) -> PathBuf {
    let mut text = String::from("r/a,g/h\n");
    for k in 0..points {
        let r = k as f64 / (points - 1) as f64;
        text.push_str(&format!("{r},{}\n", 1.0 - r * r));
    }
    let path = dir.join(format!("sphere-{points}.csv"));
    std::fs::write(&path, text).unwrap();
    path
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("ringcontact-table-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn verify(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_verify"))
        .args(args)
        .output()
        .unwrap()
}

/// Largest difference between the table's interpolant and the sphere's profile.
fn profile_error(kind: PunchKind) -> f64 {
    (0..=20000)
        .map(|k| k as f64 / 20000.0)
        .map(|rho| (kind.gap_shape(rho) - (1.0 - rho * rho)).abs())
        .fold(0.0, f64::max)
}

#[test]
fn sampled_sphere_tends_to_the_sphere_as_the_table_is_refined() {
    if !gmsh_available("sampled_sphere_tends_to_the_sphere_as_the_table_is_refined") {
        return;
    }
    let dir = scratch("convergence");
    let sphere = RingBemSolver::new()
        .concave_at_depth(PunchKind::Sphere, 1.0, 1e-12)
        .unwrap();
    let reference = sphere.gamma2.unwrap();
    let mut errors = Vec::new();
    for points in [6, 11, 21, 41] {
        let path = sphere_table(&dir, points);
        let kind = PunchName::Table.with_parameters(None, Some(&path)).unwrap();
        let out = verify(&[
            "solve",
            "--punch",
            "table",
            "--profile",
            path.to_str().unwrap(),
            "--depth",
            "1",
            "--method",
            "fem",
            "--tol",
            "1e-7",
            "--json",
        ]);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        assert_eq!(json["punch"], "table");
        assert_eq!(json["profile_file"], path.to_str().unwrap());
        assert_eq!(json["profile_sha256"].as_str().map(str::len), Some(64));
        let gamma2 = json["gamma2"].as_f64().unwrap();
        let estimate = json["error_estimate"].as_f64().unwrap();
        let error = (gamma2 - reference).abs();
        let bound = profile_error(kind) + estimate * reference;
        eprintln!("{points} points: γ2 off by {error:.2e}, bound {bound:.2e}, FEM estimate {estimate:.1e}");
        assert!(estimate <= 1e-7, "{json}");
        assert!(error <= bound, "{points} points: {error:e} > {bound:e}");
        errors.push(error);
    }
    for pair in errors.windows(2) {
        // Halving the spacing: at least the interpolant's second order (measured: 13 to 20).
        assert!(pair[0] / pair[1] > 4.0, "{errors:?}");
    }
}

#[test]
fn auto_picks_the_fem_for_a_table() {
    if !gmsh_available("auto_picks_the_fem_for_a_table") {
        return;
    }
    let out = verify(&[
        "solve",
        "--punch",
        "table",
        "--profile",
        "verify/profiles/sphere-21.csv",
        "--force",
        "1",
        "--method",
        "auto",
        "--tol",
        "1e-4",
        "--json",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let selection = json["selection"].as_str().unwrap();
    assert!(
        selection.contains("auto: fem") && selection.contains("ring-bem: method"),
        "{selection}"
    );
}

#[test]
fn the_ring_bem_refuses_a_table_by_name() {
    let out = verify(&[
        "solve",
        "--punch",
        "table",
        "--profile",
        "verify/profiles/sphere-21.csv",
        "--depth",
        "1",
    ]);
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("piecewise cubics") && stderr.contains("--method fem"),
        "{stderr}"
    );
}

#[test]
fn bad_tables_and_misplaced_flags_are_named() {
    let dir = scratch("bad");
    let unsorted = dir.join("unsorted.csv");
    std::fs::write(&unsorted, "r/a,g/h\n0,1\n0.6,0.5\n0.4,0.7\n1,0\n").unwrap();
    let unsorted = unsorted.to_str().unwrap();
    let cases: [(&[&str], &str); 5] = [
        (&["--punch", "table", "--profile", unsorted], "line 4"),
        (&["--punch", "table"], "needs its profile"),
        (
            &["--punch", "cone", "--profile", unsorted],
            "applies only to shape = table",
        ),
        (
            &["--punch", "table", "--profile", "no/such/file.csv"],
            "cannot read",
        ),
        (
            &["--punch", "table", "--profile", unsorted, "--exponent", "2"],
            "exponent",
        ),
    ];
    for (flags, expected) in cases {
        let mut args = vec!["solve"];
        args.extend_from_slice(flags);
        args.extend(["--depth", "1", "--method", "grid-bem", "--grid", "32"]);
        let out = verify(&args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(
            !out.status.success() && stderr.contains(expected),
            "{flags:?}: {stderr}"
        );
        assert!(!stderr.contains("panicked"), "{stderr}");
    }
}

#[test]
fn a_scene_file_reads_its_profile_beside_itself() {
    let dir = scratch("scene");
    sphere_table(&dir, 11);
    let scene = dir.join("tip.toml");
    std::fs::write(
        &scene,
        "[punch]\nshape = \"table\"\nprofile = \"sphere-11.csv\"\nhole_depth = 0.5\n\
         [load]\ndepth = 0.5\n",
    )
    .unwrap();
    let out = verify(&[
        "solve",
        "--scene",
        scene.to_str().unwrap(),
        "--method",
        "grid-bem",
        "--grid",
        "64",
        "--json",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(json["punch"], "table");
    // d = h: the sphere's γ1 = 1 state, force 2 E* h a γ2 with γ2 = 0.756 (ring BEM), within
    // the 64² grid's discretisation error (a few per cent).
    let gamma2 = json["gamma2"].as_f64().unwrap();
    assert!((gamma2 - 0.7563).abs() < 0.05 * 0.7563, "{json}");
}
