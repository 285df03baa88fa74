//! Fresh runs of the peers and of the pull-off simulations against the committed baselines.
//!
//! The nightly run writes fresh results (FEniCSx, Tamaas and ContactMechanics, Tamaas's
//! pull-offs, our pull-off simulations) into its report directory (`DIR/fresh/...`, the layout
//! of `verify/`) and never into the checkout; `verify compare --fresh DIR` matches each fresh
//! file with the committed one of the same relative path under `verify/` and compares the
//! numbers that matter. A difference beyond the tolerance is a regression (a failed check); a
//! fresh error record (`NAME.error.json`) is one too. Refreshing a baseline stays a reviewed
//! commit.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use serde_json::Value;

use crate::harness::report::table::{verdict, Cell, Column, Format, Table};
use ringcontact::error::{Error, Result};

/// One number of a fresh result against its baseline.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct BaselineCheck {
    /// Path relative to the fresh directory (and to `verify/`).
    pub file: String,
    /// The JSON path of the number compared (`force`, `result.extrapolated_over_f0`, ...).
    pub quantity: String,
    pub committed: Option<f64>,
    pub fresh: Option<f64>,
    /// `|fresh - committed| / max(|committed|, 1)` (absolute below 1, relative above).
    pub difference: Option<f64>,
    pub tolerance: f64,
    /// `compared`, `new` (no committed baseline: listed, not a failure), `error` (the fresh run
    /// failed: its error record's message) or `missing` (a number the baseline has is absent).
    pub status: String,
    pub note: Option<String>,
    pub passed: bool,
}

/// The numbers compared and their tolerances, by the kind of result (the first directory of
/// the relative path): FEniCSx and the grid-BEM peers solve the same discrete problem again
/// (1e-8), the pull-off simulations are ours (1e-10; their pull-offs and extrapolate), Tamaas's
/// pull-off is iterated to 1e-9 (1e-6).
fn quantities(relative: &str) -> (&'static [&'static str], f64) {
    let first = relative.split('/').next().unwrap_or_default();
    let second = relative.split('/').nth(1).unwrap_or_default();
    match (first, second) {
        ("fenicsx", "operators") => (&["stiffness_difference", "load_difference"], 1e-12),
        ("fenicsx", _) => (&["force"], 1e-8),
        ("peers", "adhesion") => (&["pulloff_over_f0"], 1e-6),
        ("peers", _) => (&["force"], 1e-8),
        ("pulloff", _) => (
            &[
                "result.extrapolated_over_f0",
                "result.sequence.pulloff_over_f0",
            ],
            1e-10,
        ),
        _ => (&[], 0.0),
    }
}

/// The numbers at a dotted path (`a.b.c`; arrays on the way contribute one number per element).
fn numbers_at(value: &Value, path: &str) -> Vec<f64> {
    let mut current = vec![value];
    for key in path.split('.') {
        current = current
            .into_iter()
            .flat_map(|v| match v {
                Value::Array(items) => items.iter().filter_map(|i| i.get(key)).collect(),
                _ => v.get(key).into_iter().collect::<Vec<_>>(),
            })
            .collect();
    }
    current.into_iter().filter_map(Value::as_f64).collect()
}

/// Every `*.json` under `dir`, as paths relative to it, sorted.
fn json_files(dir: &Path, prefix: &Path, out: &mut Vec<PathBuf>) -> Result<()> {
    let entries = std::fs::read_dir(dir).map_err(|e| Error::file("read the directory", dir, e))?;
    for entry in entries.filter_map(|e| e.ok()) {
        let path = entry.path();
        let relative = prefix.join(entry.file_name());
        if path.is_dir() {
            json_files(&path, &relative, out)?;
        } else if path.extension().is_some_and(|x| x == "json") {
            out.push(relative);
        }
    }
    Ok(())
}

fn read_json(path: &Path) -> Result<Value> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::file("read", path, e))?;
    serde_json::from_str(&text).map_err(|e| Error::file("parse", path, e))
}

/// Compare every fresh result under `fresh` with its committed baseline under `committed`
/// (the repository's `verify/`).
pub fn compare(fresh: &Path, committed: &Path) -> Result<Vec<BaselineCheck>> {
    if !fresh.is_dir() {
        return Err(Error::file(
            "compare the fresh results in",
            fresh,
            "not a directory",
        ));
    }
    let mut files = Vec::new();
    json_files(fresh, Path::new(""), &mut files)?;
    files.sort();
    let mut checks = Vec::new();
    for relative in files {
        let name = relative.to_string_lossy().replace('\\', "/");
        let check = |quantity: &str, status: &str, tolerance: f64| BaselineCheck {
            file: name.clone(),
            quantity: quantity.to_string(),
            committed: None,
            fresh: None,
            difference: None,
            tolerance,
            status: status.to_string(),
            note: None,
            passed: false,
        };
        if let Some(stem) = name.strip_suffix(".error.json") {
            let record = read_json(&fresh.join(&relative))?;
            let why = ["declined", "error"]
                .iter()
                .find_map(|k| record.get(*k).and_then(Value::as_str))
                .unwrap_or("the run failed")
                .to_string();
            checks.push(BaselineCheck {
                note: Some(format!("{stem}.json kept; the fresh run failed: {why}")),
                ..check("-", "error", 0.0)
            });
            continue;
        }
        let (names, tolerance) = quantities(&name);
        if names.is_empty() {
            continue;
        }
        let baseline = committed.join(&relative);
        if !baseline.is_file() {
            checks.push(BaselineCheck {
                passed: true,
                note: Some("no committed baseline".into()),
                ..check("-", "new", tolerance)
            });
            continue;
        }
        let (new, old) = (read_json(&fresh.join(&relative))?, read_json(&baseline)?);
        for quantity in names {
            let (a, b) = (numbers_at(&new, quantity), numbers_at(&old, quantity));
            if b.is_empty() && a.is_empty() {
                continue;
            }
            if a.len() != b.len() {
                checks.push(BaselineCheck {
                    note: Some(format!("{} numbers fresh, {} committed", a.len(), b.len())),
                    ..check(quantity, "missing", tolerance)
                });
                continue;
            }
            // The largest difference over the numbers at this path.
            let (worst, x, y) = a
                .iter()
                .zip(&b)
                .map(|(&x, &y)| ((x - y).abs() / y.abs().max(1.0), x, y))
                .fold((0.0, f64::NAN, f64::NAN), |best, item| {
                    if item.0 >= best.0 {
                        item
                    } else {
                        best
                    }
                });
            checks.push(BaselineCheck {
                committed: Some(y),
                fresh: Some(x),
                difference: Some(worst),
                passed: worst <= tolerance,
                ..check(quantity, "compared", tolerance)
            });
        }
    }
    Ok(checks)
}

/// Number of failed checks (differences beyond tolerance, failed fresh runs).
pub fn failures(checks: &[BaselineCheck]) -> usize {
    checks.iter().filter(|c| !c.passed).count()
}

/// The fresh results against the committed baselines, one row per number.
pub fn table(checks: &[BaselineCheck]) -> Table {
    let mut t = Table::new(
        "Fresh peer and pull-off runs against the committed baselines (verify/)",
        vec![
            Column::text("file", "fresh result"),
            Column::text("quantity", "quantity"),
            Column::number("committed", "committed", Format::Scientific(12)),
            Column::number("fresh", "fresh", Format::Scientific(12)),
            Column::number("difference", "difference", Format::Scientific(1)),
            Column::number("tolerance", "tolerance", Format::Scientific(0)),
            Column::text("verdict", "verdict"),
        ],
    );
    for c in checks {
        let verdict_cell = match c.status.as_str() {
            "compared" => verdict(c.passed, "REGRESSION"),
            "new" => Cell::Text("new: no committed baseline".into()),
            _ => Cell::Flag(format!(
                "{}: {}",
                c.status.to_uppercase(),
                c.note.clone().unwrap_or_default()
            )),
        };
        t.push(vec![
            c.file.clone().into(),
            c.quantity.clone().into(),
            c.committed.into(),
            c.fresh.into(),
            c.difference.into(),
            c.tolerance.into(),
            verdict_cell,
        ]);
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    fn write(dir: &Path, name: &str, value: Value) {
        let path = dir.join(name);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, value.to_string()).unwrap();
    }

    /// Fresh results are matched by relative path, compared within their kind's tolerance; a
    /// failed fresh run is a failure, a result with no baseline is listed and not one.
    #[test]
    fn fresh_results_are_compared_with_their_baselines() {
        let root =
            std::env::temp_dir().join(format!("ringcontact-baselines-{}", std::process::id()));
        let (fresh, committed) = (root.join("fresh"), root.join("verify"));
        let _ = std::fs::remove_dir_all(&root);
        write(
            &committed,
            "fenicsx/a.json",
            serde_json::json!({"force": 2.0}),
        );
        write(
            &fresh,
            "fenicsx/a.json",
            serde_json::json!({"force": 2.0 + 1e-9}),
        );
        write(
            &committed,
            "fenicsx/b.json",
            serde_json::json!({"force": 2.0}),
        );
        write(
            &fresh,
            "fenicsx/b.json",
            serde_json::json!({"force": 2.001}),
        );
        write(
            &fresh,
            "fenicsx/new.json",
            serde_json::json!({"force": 1.0}),
        );
        write(
            &committed,
            "pulloff/p.json",
            serde_json::json!({"result": {"extrapolated_over_f0": 1.0,
                "sequence": [{"pulloff_over_f0": 0.9}, {"pulloff_over_f0": 0.95}]}}),
        );
        write(
            &fresh,
            "pulloff/p.json",
            serde_json::json!({"result": {"extrapolated_over_f0": 1.0,
                "sequence": [{"pulloff_over_f0": 0.9}, {"pulloff_over_f0": 0.950001}]}}),
        );
        write(
            &fresh,
            "pulloff/q.error.json",
            serde_json::json!({"declined": "gmsh missing"}),
        );
        let checks = compare(&fresh, &committed).unwrap();
        let find = |file: &str, quantity: &str| {
            checks
                .iter()
                .find(|c| c.file == file && c.quantity == quantity)
                .unwrap_or_else(|| panic!("{file} {quantity}: {checks:?}"))
        };
        assert!(find("fenicsx/a.json", "force").passed);
        assert!(!find("fenicsx/b.json", "force").passed);
        assert_eq!(find("fenicsx/new.json", "-").status, "new");
        assert!(find("pulloff/p.json", "result.extrapolated_over_f0").passed);
        let sequence = find("pulloff/p.json", "result.sequence.pulloff_over_f0");
        assert!(!sequence.passed);
        assert!((sequence.difference.unwrap() - 1e-6).abs() < 1e-9);
        let error = find("pulloff/q.error.json", "-");
        assert!(!error.passed && error.note.as_ref().unwrap().contains("gmsh missing"));
        assert_eq!(failures(&checks), 3);
        let _ = std::fs::remove_dir_all(&root);
    }
}
