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
