//! `verify grade`: other codes' results against the converged references. The grading's
//! arithmetic against closed forms (Boussinesq's flat punch, the sphere in full contact), the
//! worked examples of docs/tasks.md (the paper's fits, our own coarse runs against their own
//! estimates, Tamaas's stored results) and bad files named by line and column.

use crate::common;

use common::{scratch, verify};
use ringcontact_verify::harness::grade::input::{parse, Quantity, ResultRow};

fn graded(args: &[&str]) -> (Option<i32>, serde_json::Value) {
    let out = verify(&[&["grade", "--json"], args].concat());
    let stderr = String::from_utf8_lossy(&out.stderr);
    let json = serde_json::from_slice(&out.stdout)
        .unwrap_or_else(|e| panic!("{args:?}: {e}; stderr: {stderr}"));
    (out.status.code(), json)
}

/// The graded rows of `quantity` of `punch`.
fn rows_of<'a>(
    json: &'a serde_json::Value,
    punch: &str,
    quantity: &str,
) -> Vec<&'a serde_json::Value> {
    json["rows"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|r| r["punch"] == punch && r["quantity"] == quantity)
        .collect()
}

fn largest(rows: &[&serde_json::Value]) -> f64 {
    rows.iter()
        .map(|r| r["relative_error"].as_f64().unwrap())
        .fold(0.0, f64::max)
}

#[test]
fn relative_errors_against_closed_forms() {
    let dir = scratch("grade_closed_forms");
    let file = dir.join("mine.csv");
    // Boussinesq: gamma = 1, F = 2 E* a d (here E* = 2, a = 3, d = 0.1: F = 1.2). The sphere in
    // full contact (d >= 3h): gamma2 = d/h - 1/3.
    std::fs::write(
        &file,
        "punch,depth,gamma,gamma2,E_star,a,force,code\n\
         flat,1,1.01,,,,,mine\n\
         flat,0.1,,,2,3,1.2012,mine\n\
         sphere,4,,3.6666666666666665,,,,mine\n",
    )
    .unwrap();
    let (status, json) = graded(&["--results", file.to_str().unwrap(), "--tol", "0.005"]);
    assert_eq!(status, Some(1), "1 % is beyond 0.5 %");
    assert_eq!(json["tolerance"], 0.005);
    let rows = json["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 3);
    let expected = [(1.01, 1.0, 0.01, false), (1.2012, 1.2, 1e-3, true)];
    for (row, (value, reference, error, within)) in rows.iter().zip(expected) {
        assert_eq!(row["value"], value);
        assert!((row["reference"].as_f64().unwrap() - reference).abs() < 1e-12);
        assert!((row["relative_error"].as_f64().unwrap() - error).abs() < 1e-11);
        assert_eq!(row["within"], within);
        assert!(row["reference_error"].as_f64().unwrap() <= 1e-12);
        assert_eq!(row["resolved"], true);
    }
    // The sphere's value is the closed form: closer to the reference than the reference can
    // resolve, and said so.
    assert!(rows[2]["relative_error"].as_f64().unwrap() < 1e-12);
    assert_eq!(rows[2]["resolved"], false);
    assert!(rows[2]["note"].as_str().unwrap().contains("not resolved"));
    assert!((json["max_relative_error"].as_f64().unwrap() - 0.01).abs() < 1e-11);
    // At 2 %: every value passes.
    let (status, _) = graded(&["--results", file.to_str().unwrap(), "--tol", "0.02"]);
    assert_eq!(status, Some(0));
}

#[test]
fn the_papers_fits_show_their_known_errors() {
    // The fits of the paper tabulated by an independent script (scripts/grade/paper_fits.py);
    // their largest errors against converged solutions (README, `verify fit`): 2.5 % for the
    // flat annulus, 25 % for the cone's gamma2 near b/a = 1.
    let (status, json) = graded(&["--results", "verify/grade/paper-fits.csv", "--tol", "0.03"]);
    assert_eq!(status, Some(1), "the cone's fits are beyond 3 %");
    let flat = largest(&rows_of(&json, "flat-annulus", "gamma"));
    assert!((0.02..0.03).contains(&flat), "flat annulus: {flat}");
    let cone = rows_of(&json, "cone", "gamma2");
    let worst = cone
        .iter()
        .max_by(|a, b| {
            a["relative_error"]
                .as_f64()
                .partial_cmp(&b["relative_error"].as_f64())
                .unwrap()
        })
        .unwrap();
    let error = worst["relative_error"].as_f64().unwrap();
    assert!((0.2..0.3).contains(&error), "cone gamma2: {error}");
    assert_eq!(worst["state_value"], 0.99);
    assert!(json["summary"].as_array().unwrap().len() == 5);
}

#[test]
fn our_coarse_runs_are_graded_against_their_own_estimates() {
    // The FEM at 1e-3 carries an estimate per state: each holds against the ring BEM.
    let (status, json) = graded(&["--results", "verify/grade/fem-sphere-1e-3.json"]);
    assert_eq!(status, Some(0));
    let rows = json["rows"].as_array().unwrap();
    assert!(rows.len() >= 9);
    assert!(rows.iter().all(|r| r["claim_holds"] == true), "{rows:#?}");
    assert_eq!(json["claims_broken"], 0);
    // The grid BEM on 64 cells, a few percent off at the first order of the grid, with the
    // estimate from 32 and 16 cells: each holds.
    let (status, json) = graded(&[
        "--results",
        "verify/grade/grid-bem-sphere-64.json",
        "--tol",
        "0.05",
    ]);
    assert_eq!(status, Some(0));
    let force = largest(&rows_of(&json, "sphere", "force"));
    assert!((1e-3..0.05).contains(&force), "grid BEM force: {force}");
    let rows = json["rows"].as_array().unwrap();
    assert!(rows.iter().all(|r| r["claim_holds"] == true), "{rows:#?}");
    assert_eq!(json["claims_broken"], 0);
    // The stored file is what its command makes today.
    let stored: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(
            std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("verify/grade/grid-bem-sphere-64.json"),
        )
        .unwrap(),
    )
    .unwrap();
    let command = stored["provenance"]["command"].as_str().unwrap();
    let words: Vec<&str> = command.split_whitespace().skip(1).collect();
    let fresh = verify(&words);
    let fresh: serde_json::Value = serde_json::from_slice(&fresh.stdout).unwrap();
    for (a, b) in stored["rows"]
        .as_array()
        .unwrap()
        .iter()
        .zip(fresh["rows"].as_array().unwrap())
    {
        for key in ["eps", "force", "gamma2", "error_estimate"] {
            let (x, y) = (a[key].as_f64().unwrap(), b[key].as_f64().unwrap());
            assert!(
                (x - y).abs() <= 1e-12 * y.abs(),
                "{key}: {x} stored, {y} now"
            );
        }
    }
}

#[test]
fn tamaas_stored_results_are_within_their_grid_error() {
    let (status, json) = graded(&["--results", "verify/grade/tamaas.csv", "--tol", "0.01"]);
    assert_eq!(status, Some(0));
    assert_eq!(json["rows"].as_array().unwrap().len(), 13);
    let worst = json["max_relative_error"].as_f64().unwrap();
    assert!(worst > 1e-5 && worst < 1e-2, "{worst}");
}

#[test]
fn the_stored_example_files_are_what_their_scripts_write() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    for (script, file) in [
        (
            vec!["scripts/grade/paper_fits.py"],
            "verify/grade/paper-fits.csv",
        ),
        (
            vec!["scripts/grade/peer_table.py", "tamaas"],
            "verify/grade/tamaas.csv",
        ),
    ] {
        let Ok(out) = std::process::Command::new("python3")
            .args(&script)
            .current_dir(root)
            .output()
        else {
            eprintln!("python3 not found: {file} not checked against its script");
            continue;
        };
        assert!(out.status.success(), "{script:?}");
        let stored = std::fs::read_to_string(root.join(file)).unwrap();
        assert_eq!(String::from_utf8(out.stdout).unwrap(), stored, "{file}");
    }
}

#[test]
fn bad_files_are_named_by_line_and_column() {
    let dir = scratch("grade_bad_files");
    for (name, text, says) in [
        (
            "no-punch.csv",
            "eps,gamma1\n0.5,1\n",
            "missing column `punch`",
        ),
        (
            "unknown.csv",
            "punch,eps,gamma1\nwedge,0.5,1\n",
            "line 2, column punch: unknown punch",
        ),
        (
            "range.csv",
            "punch,eps,gamma1\ncone,0.5,1\ncone,1.5,1\n",
            "line 3, column eps",
        ),
        (
            "depth.csv",
            "punch,depth,force\nsphere,-1,1\n",
            "line 2, column depth",
        ),
        (
            "modulus.csv",
            "punch,depth,gamma,E_star\nflat,1,1,-2\n",
            "line 2, column E_star",
        ),
        (
            "word.csv",
            "punch,eps,gamma1\ncone,0.5,one\n",
            "line 2, column gamma1",
        ),
        ("empty.csv", "", "the file is empty"),
        ("header.csv", "punch,eps,gamma1\n", "no results"),
        ("ragged.csv", "punch,eps,gamma1\ncone,0.5\n", "t.csv"),
        ("bad.json", "{\"rows\": 3}", "rows"),
    ] {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        let out = verify(&["grade", "--results", path.to_str().unwrap()]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{name}: {stderr}");
        let says = if says == "t.csv" { name } else { says };
        assert!(stderr.contains(says), "{name}: {stderr}");
        assert!(!stderr.contains("internal defect"), "{name}: {stderr}");
    }
    let out = verify(&["grade", "--results", "/nonexistent/r.csv"]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("cannot read"));
    let out = verify(&[
        "grade",
        "--results",
        "verify/grade/tamaas.csv",
        "--tol",
        "0",
    ]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("0 < T < 1"));
}

// The results file's parsing, on its own.

/// The rows of a results CSV given as text.
fn parse_csv(text: &str) -> Result<Vec<ResultRow>, String> {
    parse(text, "t.csv", false, None)
}

#[test]
fn the_state_is_the_first_of_depth_force_eps_and_the_rest_is_graded() {
    let rows = parse_csv("punch,eps,gamma1,gamma2,code\ncone,0.5,1.79,1.59,mine\nsphere,,,,x\n");
    let e = rows.unwrap_err();
    assert!(e.contains("line 3") && e.contains("no state"), "{e}");
    let rows = parse_csv("punch,eps,gamma1,gamma2,code\ncone,0.5,1.79,1.59,mine\n").unwrap();
    assert_eq!(rows[0].state, Some((Quantity::Eps, 0.5)));
    assert_eq!(
        rows[0].values,
        vec![(Quantity::Gamma1, 1.79), (Quantity::Gamma2, 1.59)]
    );
    let rows = parse_csv("punch,eps,depth,force,gamma1\nsphere,0.8,1,1.5,1\n").unwrap();
    assert_eq!(rows[0].state, Some((Quantity::Depth, 1.0)));
    assert_eq!(
        rows[0].values,
        vec![(Quantity::Eps, 0.8), (Quantity::Force, 1.5)]
    );
    let rows = parse_csv("punch,eps,depth,force,state\nsphere,0.8,1,1.5,force\n").unwrap();
    assert_eq!(rows[0].state, Some((Quantity::Force, 1.5)));
    assert_eq!(
        rows[0].values,
        vec![(Quantity::Eps, 0.8), (Quantity::Depth, 1.0)]
    );
    let rows = parse_csv("punch,eps,depth,force,state\nsphere,0.8,1,1.5,depth\n").unwrap();
    assert_eq!(rows[0].state, Some((Quantity::Depth, 1.0)));
    assert_eq!(
        rows[0].values,
        vec![(Quantity::Eps, 0.8), (Quantity::Force, 1.5)]
    );
    let rows = parse_csv("punch,eps,gamma\nflat-annulus,0.5,0.98\n").unwrap();
    assert_eq!((rows[0].hole_ratio, rows[0].state), (Some(0.5), None));
}

#[test]
fn bad_rows_name_their_line_and_column() {
    for (text, says) in [
        ("eps,gamma\n0.5,1\n", "missing column `punch`"),
        ("punch,code\ncone,1\n", "no column to grade"),
        (
            "punch,eps,gamma1\nwedge,0.5,1\n",
            "line 2, column punch: unknown punch \"wedge\"",
        ),
        (
            "punch,eps,gamma1\ncone,0.5,abc\n",
            "line 2, column gamma1: \"abc\" is not",
        ),
        ("punch,eps,gamma1\ncone,0.5,inf\n", "column gamma1"),
        (
            "punch,eps,gamma\ncone,0.5,1\n",
            "column gamma: does not apply to the cone",
        ),
        ("punch,eps,gamma1\nflat-annulus,0.5,1\n", "column gamma1"),
        (
            "punch,depth,gamma\nflat-annulus,1,1\n",
            "column eps: the flat-annulus needs",
        ),
        ("punch,eps\ncone,0.5\n", "nothing to grade"),
        ("Punch,eps,gamma1\ncone,0.5,1\n", "missing column `punch`"),
        ("punch,EPS,gamma1\ncone,0.5,1\n", "case-sensitive"),
        ("punch,eps,gamma1,state\ncone,0.5,1,size\n", "column state"),
    ] {
        let e = parse_csv(text).unwrap_err();
        assert!(e.contains(says), "{text:?}: {e}");
    }
}

#[test]
fn json_rows_read_like_csv_rows() {
    let rows = parse(
        r#"{"rows": [{"punch": "cone", "eps": 0.5, "gamma1": 1.79, "note": null}]}"#,
        "t.json",
        true,
        None,
    )
    .unwrap();
    assert_eq!(rows[0].place, "row 1");
    assert_eq!(rows[0].values, vec![(Quantity::Gamma1, 1.79)]);
    assert!(parse("[1]", "t.json", true, None)
        .unwrap_err()
        .contains("row 1"));
    assert!(parse("{\"a\": 1}", "t.json", true, None)
        .unwrap_err()
        .contains("rows"));
}
