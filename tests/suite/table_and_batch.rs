//! `verify table` (many states of one punch, one row each) and `verify solve --batch` (JSON
//! lines of scenes): rows against closed forms, provenance, bad lists and bad lines named.

use crate::common;

use common::{scratch, verify, verify_with_input};

/// The CSV of `verify table` as a header and rows of fields.
fn csv(text: &str) -> (Vec<String>, Vec<Vec<String>>) {
    let mut lines = text.lines();
    let header = lines
        .next()
        .expect("a header")
        .split(',')
        .map(String::from)
        .collect();
    let rows = lines
        .map(|l| l.split(',').map(String::from).collect())
        .collect();
    (header, rows)
}

/// The number in column `key` of `row`.
fn field(header: &[String], row: &[String], key: &str) -> f64 {
    let c = header
        .iter()
        .position(|h| h == key)
        .unwrap_or_else(|| panic!("no column {key} in {header:?}"));
    row[c]
        .parse()
        .unwrap_or_else(|_| panic!("{key} = {:?}", row[c]))
}

fn stdout_of(out: &std::process::Output) -> String {
    assert!(
        out.status.success(),
        "stderr: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout.clone()).unwrap()
}

#[test]
fn table_rows_follow_the_closed_forms_in_the_order_listed() {
    // Boussinesq's flat punch: F = 2 E* a d (E* = a = 1).
    let text = stdout_of(&verify(&["table", "--punch", "flat", "--depth", "0.5,2,1"]));
    let (header, rows) = csv(&text);
    assert_eq!(rows.len(), 3, "{text}");
    for (row, d) in rows.iter().zip([0.5, 2.0, 1.0]) {
        assert_eq!(field(&header, row, "given_depth"), d);
        let force = field(&header, row, "force");
        assert!((force - 2.0 * d).abs() < 1e-12 * d, "F({d}) = {force}");
        assert!(field(&header, row, "error_estimate") <= 1e-9);
    }
    // The sphere in full contact (d >= 3h): F = 2 E* a (d - h/3), so gamma2 = d/h - 1/3.
    let text = stdout_of(&verify(&[
        "table", "--punch", "sphere", "--depth", "3:5:0.5",
    ]));
    let (header, rows) = csv(&text);
    assert_eq!(rows.len(), 5, "{text}");
    assert!(!header.contains(&"gamma".to_string()), "{header:?}");
    for row in &rows {
        let d = field(&header, row, "given_depth");
        let gamma2 = field(&header, row, "gamma2");
        assert!(
            (gamma2 - (d - 1.0 / 3.0)).abs() < 1e-12,
            "gamma2({d}) = {gamma2}"
        );
        assert_eq!(field(&header, row, "eps"), 0.0);
    }
}

#[test]
fn a_table_of_a_dimensional_scene_is_linear_in_the_depth() {
    // The flat annulus's contact is fixed, so F is proportional to d (units of the scene: mm, N).
    let text = stdout_of(&verify(&[
        "table",
        "--scene",
        "verify/scenes/flat-annulus-half.toml",
        "--depth",
        "0.01,0.03",
    ]));
    let (header, rows) = csv(&text);
    let f1 = field(&header, &rows[0], "force");
    let f3 = field(&header, &rows[1], "force");
    assert!((f3 / f1 - 3.0).abs() < 1e-12, "{f1} {f3}");
    assert_eq!(field(&header, &rows[0], "eps"), 0.5);
}

#[test]
fn table_json_carries_the_provenance_and_one_row_per_state() {
    let dir = scratch("table_json");
    let out_file = dir.join("cone.json");
    let out = verify(&[
        "table",
        "--punch",
        "cone",
        "--eps",
        "0.2:0.8:0.2",
        "--json",
        "--out",
        out_file.to_str().unwrap(),
    ]);
    assert!(stdout_of(&out).contains("4 rows written"));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&out_file).unwrap()).unwrap();
    let provenance = &json["provenance"];
    assert!(provenance["command"]
        .as_str()
        .unwrap()
        .starts_with("verify table --punch cone --eps 0.2:0.8:0.2 --json"));
    assert!(!provenance["commit"].as_str().unwrap().is_empty());
    assert_eq!(provenance["ringcontact_version"], env!("CARGO_PKG_VERSION"));
    let rows = json["rows"].as_array().unwrap();
    let eps: Vec<f64> = rows.iter().map(|r| r["eps"].as_f64().unwrap()).collect();
    assert_eq!(eps, vec![0.2, 0.4, 0.6, 0.8]);
    // gamma1 grows as the hole shrinks (d/h = gamma1(eps) falls with eps).
    assert!(rows
        .windows(2)
        .all(|w| w[0]["gamma1"].as_f64() > w[1]["gamma1"].as_f64()));
    assert!(rows.iter().all(|r| r["unknowns"].is_u64()));
}

/// `verify table --no-grid-estimate` solves each state on the one grid (the same answer as with
/// the estimate, which only adds the coarser grids), with no `error_estimate` column; another
/// method refuses the flag by name.
#[test]
fn a_grid_table_without_its_estimate_solves_the_one_grid() {
    let run = |extra: &[&str]| {
        let mut args = vec![
            "table", "--punch", "sphere", "--depth", "1.5,2", "--method", "grid-bem", "--grid",
            "64",
        ];
        args.extend_from_slice(extra);
        csv(&stdout_of(&verify(&args)))
    };
    let (header, rows) = run(&["--no-grid-estimate"]);
    let (full_header, full_rows) = run(&[]);
    assert!(
        !header.contains(&"error_estimate".to_string()),
        "{header:?}"
    );
    assert!(
        full_header.contains(&"error_estimate".to_string()),
        "{full_header:?}"
    );
    for (row, full) in rows.iter().zip(&full_rows) {
        assert_eq!(
            field(&header, row, "gamma2"),
            field(&full_header, full, "gamma2")
        );
    }
    let out = verify(&[
        "table",
        "--punch",
        "sphere",
        "--depth",
        "1",
        "--no-grid-estimate",
    ]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("applies to --method grid-bem only"));
}

#[test]
fn bad_lists_and_states_are_named_before_any_solve() {
    for (args, says) in [
        (vec!["--punch", "cone", "--eps", "0.9:0.1:0.1"], "--eps"),
        (vec!["--punch", "cone", "--depth", "1,x"], "\"x\""),
        (vec!["--punch", "sphere", "--depth", "1,-2"], "load.depth"),
        (vec!["--punch", "cone", "--eps", "0.5,1.5"], "contact_ratio"),
        (vec!["--depth", "1"], "--punch"),
    ] {
        let out = verify(&[&["table"], args.as_slice()].concat());
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {stderr}");
        assert!(stderr.contains(says), "{args:?}: {stderr}");
        assert!(out.stdout.is_empty(), "{args:?}");
    }
    // Two lists, or none: the command line is refused (status 2).
    for args in [
        vec!["table", "--punch", "cone", "--eps", "0.5", "--depth", "1"],
        vec!["table", "--punch", "cone"],
    ] {
        assert_eq!(verify(&args).status.code(), Some(2), "{args:?}");
    }
}

#[test]
fn a_batch_answers_every_line_in_order_and_names_the_bad_ones() {
    let dir = scratch("batch_lines");
    let batch = dir.join("scenes.jsonl");
    std::fs::write(
        &batch,
        concat!(
            r#"{"punch": {"shape": "flat", "rim_radius": 3}, "material": {"effective_modulus": 2}, "load": {"depth": 0.1}}"#,
            "\n",
            r#"{"punch": {"shape": "sphere"}, "load": {"depth": -1}}"#,
            "\n\n",
            r#"{"punch": {"shape": "sphere"}, "load": {"depth": 4}, "method": "reference"}"#,
            "\n",
            r#"{"punch": {"shape": "table", "profile": "tip.csv"}, "load": {"depth": 1}}"#,
            "\n",
            "{\"punch\": {\"shape\": \"cone\", \"colour\": \"red\"}}\n",
        ),
    )
    .unwrap();
    std::fs::write(dir.join("tip.csv"), "0,1\n0.4,0.84\n0.7,0.51\n1,0\n").unwrap();
    let out = verify(&["solve", "--batch", batch.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1), "a failed line fails the batch");
    let answers: Vec<serde_json::Value> = String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    let lines: Vec<u64> = answers
        .iter()
        .map(|a| a["line"].as_u64().unwrap())
        .collect();
    assert_eq!(lines, vec![1, 2, 4, 5, 6]);
    // Boussinesq, dimensional: F = 2 E* a d = 2 * 2 * 3 * 0.1.
    assert!((answers[0]["force"].as_f64().unwrap() - 1.2).abs() < 1e-12);
    assert!(answers[1]["error"].as_str().unwrap().contains("load.depth"));
    // Full contact of the sphere by the closed form: gamma2 = d/h - 1/3.
    assert!((answers[2]["gamma2"].as_f64().unwrap() - (4.0 - 1.0 / 3.0)).abs() < 1e-12);
    // The profile is found beside the batch file and solved (d = h: gamma1 = 1).
    assert_eq!(answers[3]["punch"], "table", "{}", answers[3]);
    assert!((answers[3]["gamma1"].as_f64().unwrap() - 1.0).abs() < 1e-9);
    assert!(answers[4]["error"].as_str().unwrap().contains("colour"));
}

#[test]
fn a_batch_reads_standard_input_and_applies_the_flags_where_a_line_is_silent() {
    let input = concat!(
        r#"{"punch": {"shape": "flat"}, "load": {"depth": 0.5}}"#,
        "\n",
        r#"{"punch": {"shape": "cone"}, "load": {"depth": 2}, "method": "ring-bem"}"#,
        "\n",
    );
    let out = verify_with_input(&["solve", "--batch", "-", "--method", "reference"], input);
    let text = stdout_of(&out);
    let answers: Vec<serde_json::Value> = text
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(answers.len(), 2);
    assert!(answers[0]["method"]
        .as_str()
        .unwrap()
        .starts_with("reference"));
    assert_eq!(answers[1]["method"], "ring-bem");
    assert_eq!(answers[0]["force"], 1.0);
    let empty = verify_with_input(&["solve", "--batch", "-"], "\n\n");
    assert_eq!(empty.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&empty.stderr).contains("no scene"));
}
