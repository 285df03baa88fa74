//! The command-line contract that scripts rely on (`verify solve ... --json`).

use std::process::Command;

fn verify(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_verify"))
        .args(args)
        .output()
        .expect("run verify")
}

fn json(args: &[&str]) -> serde_json::Value {
    let out = verify(args);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("one JSON object")
}

#[test]
fn flat_annulus_json_has_the_documented_keys() {
    let v = json(&["solve", "--punch", "flat-annulus", "--eps", "0.5", "--json"]);
    for key in [
        "punch",
        "method",
        "eps",
        "depth",
        "force",
        "gamma",
        "wall_s",
        "error_estimate",
    ] {
        assert!(v.get(key).is_some(), "missing {key}");
    }
    assert_eq!(v["punch"], "flat-annulus");
    assert_eq!(v["method"], "ring-bem");
    // Defaults a = 1, E* = 1, d = 1: F = 2 γ.
    let gamma = v["gamma"].as_f64().unwrap();
    assert!((v["force"].as_f64().unwrap() - 2.0 * gamma).abs() < 1e-14);
}

#[test]
fn concave_json_has_gamma1_and_gamma2() {
    let v = json(&["solve", "--punch", "cone", "--depth", "2", "--json"]);
    for key in [
        "punch",
        "method",
        "eps",
        "depth",
        "force",
        "gamma1",
        "gamma2",
        "wall_s",
        "error_estimate",
    ] {
        assert!(v.get(key).is_some(), "missing {key}");
    }
    assert!((v["gamma1"].as_f64().unwrap() - 2.0).abs() < 1e-9);
    let eps = v["eps"].as_f64().unwrap();
    assert!(eps > 0.0 && eps < 1.0);
}

#[test]
fn reference_method_and_scene_files() {
    let v = json(&[
        "solve",
        "--punch",
        "flat-annulus",
        "--eps",
        "0.1",
        "--method",
        "reference",
        "--json",
    ]);
    assert_eq!(v["method"], "reference:collins-series");
    let scenes = std::fs::read_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/verify/scenes")).unwrap();
    let mut count = 0;
    for entry in scenes {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "toml") {
            let v = json(&["solve", "--scene", path.to_str().unwrap(), "--json"]);
            assert!(v["force"].as_f64().unwrap() > 0.0, "{}", path.display());
            count += 1;
        }
    }
    assert!(count >= 3, "expected the example scenes in verify/scenes");
}

#[test]
fn bad_input_exits_non_zero_with_a_message_naming_the_problem() {
    let cases: &[(&[&str], &str)] = &[
        (
            &["solve", "--punch", "flat-annulus", "--eps", "1.2"],
            "b < a",
        ),
        (
            &["solve", "--punch", "flat-annulus", "--eps", "-0.1"],
            "0 <= b < a",
        ),
        (&["solve", "--punch", "cone"], "needs one of depth"),
        (&["solve", "--punch", "cone", "--depth", "nan"], "finite"),
        (
            &["solve", "--punch", "sphere", "--depth", "-1"],
            "load.depth",
        ),
        (
            &["solve", "--punch", "flat", "--eps", "0.3"],
            "flat-annulus",
        ),
        (&["solve", "--punch", "hexagon"], "invalid value"),
        (
            &["solve", "--punch", "cone", "--depth", "1", "--force", "1"],
            "cannot be used with",
        ),
        (&["solve", "--punch", "cone", "--depth", "60"], "infinity"),
        (
            &["solve", "--scene", "/nonexistent/scene.toml"],
            "cannot read scene file",
        ),
        (
            &["mesh", "--eps", "0.3", "--free-edge", "0.2"],
            "lies in the hole of the contact line",
        ),
        // A ring narrower than the mesh's last contact-node spacing (1.4e-4 a at the rim of
        // disk-L1; the cone's ring at d = 1e-4 h is narrower than 1e-4 a): named, not returned
        // as b/a = 1.
        (
            &[
                "solve",
                "--punch",
                "cone",
                "--depth",
                "1e-4",
                "--method",
                "fem",
                "--mesh",
                "meshes/disk-L1.msh",
            ],
            "narrower than the contact-node spacing at the rim",
        ),
    ];
    for (args, needle) in cases {
        let out = verify(args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{args:?} succeeded");
        assert!(
            stderr.contains(needle),
            "{args:?}: stderr {stderr:?} lacks {needle:?}"
        );
        assert!(!stderr.contains("panicked"), "{args:?} panicked");
    }
}

#[test]
fn fit_and_jkr_json_carry_the_documented_keys() {
    let v = json(&["fit", "--json"]);
    for name in [
        "flat",
        "cone_gamma1",
        "cone_gamma2",
        "sphere_gamma1",
        "sphere_gamma2",
    ] {
        let entry = &v[name];
        for key in [
            "params",
            "paper_params",
            "max_rel_err",
            "paper_max_rel_err",
            "best_form",
            "best_max_rel_err",
        ] {
            assert!(entry.get(key).is_some(), "fit {name}: missing {key}");
        }
    }
    let v = json(&["jkr", "--punch", "flat-annulus", "--eps", "0.5", "--json"]);
    for key in [
        "dc_outer",
        "dc_inner",
        "fc_outer",
        "fc_inner",
        "governing_edge",
    ] {
        assert!(v.get(key).is_some(), "jkr flat-annulus: missing {key}");
    }
    assert_eq!(v["governing_edge"], "outer");
    let v = json(&["jkr", "--punch", "cone", "--d0h", "1", "--json"]);
    for regime in ["fixed_load", "fixed_grips"] {
        for key in ["force", "depth", "eps", "governing_edge"] {
            assert!(
                v[regime].get(key).is_some(),
                "jkr cone {regime}: missing {key}"
            );
        }
    }
    let out = verify(&["jkr", "--punch", "sphere"]);
    assert!(!out.status.success() && String::from_utf8_lossy(&out.stderr).contains("--d0h"));
}

/// Run `verify` from `dir` with `args`.
fn verify_in(dir: &std::path::Path, args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_verify"))
        .current_dir(dir)
        .args(args)
        .output()
        .expect("run verify")
}

fn stderr_of(out: &std::process::Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

#[test]
fn overflowing_and_hostile_values_are_errors_not_numbers() {
    // Every case exits non-zero with a message naming the problem,
    // never a panic, never `inf`/`null` with exit 0, never 300 digits.
    let cases: [(&[&str], &str); 9] = [
        (
            &["solve", "--punch", "flat", "--depth", "1e308"],
            "impossible state",
        ),
        (
            &["solve", "--punch", "cone", "--depth", "1e308"],
            "1.000000e308",
        ),
        (
            &["solve", "--punch", "sphere", "--depth", "1e308", "--json"],
            "impossible state",
        ),
        (
            &["jkr", "--punch", "cone", "--d0h", "1e-310"],
            "must lie in",
        ),
        (
            &["solve", "--punch", "cone", "--depth", "2", "--tol", "-1"],
            "tolerance",
        ),
        (&["jkr", "--punch", "sphere", "--d0h", "-2"], "d0h"),
        (
            &[
                "solve", "--punch", "flat", "--method", "grid-bem", "--grid", "4096",
            ],
            "2048",
        ),
        (
            &[
                "convergence",
                "--punch",
                "flat",
                "--method",
                "grid-bem",
                "--levels",
                "8",
            ],
            "at most 6 levels",
        ),
        (
            &["solve", "--punch", "flat-annulus", "--eps", "1e300"],
            "1.000000e300",
        ),
    ];
    for (args, needle) in cases {
        let out = verify(args);
        let err = stderr_of(&out);
        assert!(
            !out.status.success(),
            "{args:?} succeeded: {}",
            String::from_utf8_lossy(&out.stdout)
        );
        assert!(
            err.contains(needle),
            "{args:?}: expected {needle:?} in {err:?}"
        );
        assert!(!err.contains("panicked"), "{args:?} panicked: {err}");
        assert!(err.len() < 600, "{args:?}: message too long: {err}");
    }
}

#[test]
fn output_to_a_closed_pipe_or_a_full_device_is_not_a_panic() {
    use std::process::Stdio;
    // A reader that has gone before the child starts (closed here, not after the spawn: a
    // loaded machine could let the child finish writing into the pipe's buffer first): the
    // child sees EPIPE on its first write.
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    let out = Command::new(env!("CARGO_BIN_EXE_verify"))
        .args(["solve", "--punch", "cone", "--depth", "2", "--json"])
        .stdout(writer)
        .stderr(Stdio::piped())
        .output()
        .unwrap();
    assert!(!stderr_of(&out).contains("panicked"), "{}", stderr_of(&out));
    assert_eq!(out.status.code(), Some(141));
    if let Ok(full) = std::fs::OpenOptions::new().write(true).open("/dev/full") {
        let out = Command::new(env!("CARGO_BIN_EXE_verify"))
            .args(["solve", "--punch", "cone", "--depth", "2", "--json"])
            .stdout(full)
            .output()
            .unwrap();
        let err = stderr_of(&out);
        assert_eq!(out.status.code(), Some(1), "{err}");
        assert!(err.contains("cannot write to standard output"), "{err}");
    }
}

#[test]
fn the_data_directory_is_found_from_where_the_tool_runs_never_compiled_in() {
    // Outside any checkout: the commands that need the data say what they need.
    let outside = std::env::temp_dir();
    let out = verify_in(&outside, &["fenicsx"]);
    let err = stderr_of(&out);
    assert!(!out.status.success());
    assert!(err.contains("--data-dir"), "{err}");
    // The ring BEM needs no data and works anywhere.
    assert!(
        verify_in(&outside, &["solve", "--punch", "cone", "--depth", "2"])
            .status
            .success()
    );
    // --data-dir points it at a checkout.
    let root = env!("CARGO_MANIFEST_DIR");
    let out = verify_in(&outside, &["--data-dir", root, "fenicsx", "--json"]);
    assert!(out.status.success(), "{}", stderr_of(&out));
    // A copy of the data elsewhere is read, not the original: an empty copy compares nothing.
    let copy = std::env::temp_dir().join(format!("ringcontact-copy-{}", std::process::id()));
    std::fs::create_dir_all(copy.join("meshes")).unwrap();
    std::fs::create_dir_all(copy.join("verify/fenicsx")).unwrap();
    std::fs::copy(
        std::path::Path::new(root).join("meshes/half_space.geo"),
        copy.join("meshes/half_space.geo"),
    )
    .unwrap();
    let out = verify_in(&copy, &["fenicsx"]);
    assert!(!out.status.success(), "compared nothing, yet succeeded");
    assert!(String::from_utf8_lossy(&out.stdout).contains("NOTHING COMPARED"));
    let _ = std::fs::remove_dir_all(&copy);
}

#[test]
fn scene_and_mesh_errors_say_where() {
    // A scene error names the line, the column and the text there.
    let dir = std::env::temp_dir().join(format!("ringcontact-where-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let scene = dir.join("bad.toml");
    std::fs::write(
        &scene,
        "[punch]\nshape = \"cone\"\n[load]\ndepth = \"deep\"\n",
    )
    .unwrap();
    let err = stderr_of(&verify(&["solve", "--scene", scene.to_str().unwrap()]));
    assert!(err.contains("line 4"), "{err}");
    assert!(err.contains("depth"), "{err}");
    // A truncated mesh says where parsing stopped and that the file ends early.
    let original = std::fs::read(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("meshes/small-domain-R5.msh"),
    )
    .unwrap();
    let mesh = dir.join("truncated.msh");
    std::fs::write(&mesh, &original[..original.len() * 3 / 4]).unwrap();
    let err = stderr_of(&verify(&[
        "solve",
        "--punch",
        "flat",
        "--method",
        "fem",
        "--mesh",
        mesh.to_str().unwrap(),
    ]));
    assert!(err.contains("element section"), "{err}");
    assert!(err.contains("truncated"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn export_writes_the_three_files_and_refuses_bad_input() {
    let dir = std::env::temp_dir().join(format!("ringcontact-cli-export-{}", std::process::id()));
    crate::common::verify_succeeding(&[
        "export",
        "--mesh",
        "meshes/small-domain-R5.msh",
        "--degree",
        "1",
        "--out",
        dir.to_str().unwrap(),
    ]);
    for file in ["stiffness.mtx", "load.mtx", "dofs.csv"] {
        assert!(dir.join(file).exists(), "{file} missing");
    }
    let header = std::fs::read_to_string(dir.join("dofs.csv")).unwrap();
    assert!(header.starts_with("index,node_tag,r,z,component\n"));
    let missing = verify(&[
        "export",
        "--mesh",
        "/nonexistent.msh",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(!missing.status.success());
    assert!(String::from_utf8_lossy(&missing.stderr).contains("/nonexistent.msh"));
    let json_alone = verify(&[
        "export",
        "--mesh",
        "meshes/small-domain-R5.msh",
        "--out",
        dir.to_str().unwrap(),
        "--json",
    ]);
    assert!(!json_alone.status.success());
    assert!(String::from_utf8_lossy(&json_alone.stderr).contains("--compare"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_fixed_annulus_sweep_writes_its_csv_with_the_documented_columns() {
    let dir = std::env::temp_dir().join(format!("ringcontact-sweep-{}", std::process::id()));
    let out = verify(&[
        "jkr",
        "--punch",
        "flat-annulus",
        "--sweep",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("critical depths (units d0)"), "{stdout}");
    let csv = std::fs::read_to_string(dir.join("critical-flat-annulus.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next(),
        Some("eps,dc_outer,fc_outer,dc_inner,fc_inner,governing_edge,collins_dc,collins_fc,argatov_dc,argatov_fc")
    );
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 40);
    for r in &rows {
        let eps: f64 = r[0].parse().unwrap();
        let fc_outer: f64 = r[2].parse().unwrap();
        assert!(eps > 0.0 && eps < 1.0 && fc_outer < 0.0, "{r:?}");
        assert!(r[5] == "outer" || r[5] == "inner", "{r:?}");
    }
    assert!(dir.join("critical-flat-annulus.svg").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

/// `verify jkr` and `verify pulloff` refuse a flag of the other punch family instead of ignoring
/// it.
#[test]
fn a_flag_of_the_other_punch_family_is_refused() {
    for command in ["jkr", "pulloff"] {
        for (flags, named) in [
            (["flat-annulus", "--eps", "0.5", "--d0h", "1"], "--d0h"),
            (["cone", "--d0h", "1", "--eps", "0.5"], "--eps"),
        ] {
            let mut args = vec![command, "--punch"];
            args.extend(flags);
            let out = verify(&args);
            let stderr = String::from_utf8_lossy(&out.stderr);
            assert!(!out.status.success(), "{args:?} succeeded");
            assert!(stderr.contains(named), "{args:?}: {stderr}");
        }
    }
}

/// The flags that make the stored results reproducible refuse what they cannot do, naming it,
/// before any work: a far field or a mesh for a method that has none, parameters the geometry
/// file does not take or cannot mesh, a comparison of fresh results without a report.
#[test]
fn the_reproduction_flags_refuse_bad_input_with_a_reason() {
    for (args, named) in [
        (
            &["solve", "--punch", "flat", "--far-field", "fixed"][..],
            "--far-field",
        ),
        (
            &["solve", "--punch", "flat", "--mesh-parameters", "a=1"][..],
            "--mesh-parameters",
        ),
        (
            &[
                "solve",
                "--punch",
                "flat",
                "--method",
                "fem",
                "--mesh-parameters",
                "a=x",
            ][..],
            "not a finite number",
        ),
        (
            &[
                "solve",
                "--punch",
                "flat",
                "--method",
                "fem",
                "--mesh-parameters",
                "zz=1",
            ][..],
            "unknown parameter 'zz'",
        ),
        (&["mesh", "--parameters", "b=2"][..], "need 0 <= b < a < R"),
        (
            &["compare", "--no-report", "--fresh", "/nonexistent"][..],
            "--fresh",
        ),
        (
            &["compare", "--fresh", "/nonexistent"][..],
            "not a directory",
        ),
    ] {
        let out = verify(args);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{args:?} succeeded");
        assert!(stderr.contains(named), "{args:?}: {stderr}");
        assert!(out.stdout.is_empty(), "{args:?} printed a result");
    }
}

/// `--far-field fixed` is FEniCSx's model: on the committed disk (P2) the force is the stored
/// FEniCSx force (an independent code) to 1e-8, and the default Boussinesq far field is not.
#[test]
fn the_fixed_far_field_solves_fenicsxs_problem() {
    let stored: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(
            std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("verify/fenicsx/flat-disk-L1-P2.json"),
        )
        .unwrap(),
    )
    .unwrap();
    let fenicsx = stored["force"].as_f64().unwrap();
    let force = |far: &str| {
        json(&[
            "solve",
            "--punch",
            "flat",
            "--method",
            "fem",
            "--mesh",
            "meshes/disk-L1.msh",
            "--degree",
            "2",
            "--far-field",
            far,
            "--json",
        ])["force"]
            .as_f64()
            .unwrap()
    };
    assert!(((force("fixed") - fenicsx) / fenicsx).abs() < 1e-8);
    assert!(((force("boussinesq") - fenicsx) / fenicsx).abs() > 1e-6);
}
