//! Every stored result's `reproduce` command of our side, run as written (with this build's
//! `verify` in place of `cargo run --release --quiet --`), gives the stored number:
//!
//! - a stored FEniCSx result (`verify/fenicsx/`): our solve of the identical discrete problem
//!   (same mesh, remade by gmsh from its stored parameters when it is not cached; same degree,
//!   quadrature, fixed far arc) within 1e-8 of FEniCSx's force (an independent code);
//! - a stored Tamaas or ContactMechanics result (`verify/peers/`): our grid BEM on the same
//!   grid within 1e-6 of the peer's force (the same discretisation, an independent code);
//! - a stored pull-off simulation of ours (`verify/pulloff/`): the same numbers to 1e-10.
//!
//! The largest meshes (`verify/fenicsx/large/`, 6e5-1.4e6 unknowns) and the pull-off
//! simulations (20 s to 3.5 min each) are ignored tests, run by the nightly run
//! (`cargo test --release --test reproduce -- --include-ignored`). The results on meshes only
//! gmsh makes are a test of their own, reported as ignored when the build found no gmsh.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::Value;

/// The prefix every stored command of ours starts with.
const OURS: &str = "cargo run --release --quiet -- ";

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Every stored JSON record under `verify/<dir>` (recursively), by relative path.
fn records(dir: &str) -> BTreeMap<String, Value> {
    fn walk(dir: &Path, base: &Path, out: &mut BTreeMap<String, Value>) {
        for entry in std::fs::read_dir(dir).unwrap().filter_map(|e| e.ok()) {
            let path = entry.path();
            if path.is_dir() {
                walk(&path, base, out);
            } else if path.extension().is_some_and(|x| x == "json") {
                let text = std::fs::read_to_string(&path).unwrap();
                let value = serde_json::from_str(&text)
                    .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
                let name = path.strip_prefix(base).unwrap().display().to_string();
                out.insert(name, value);
            }
        }
    }
    let mut out = BTreeMap::new();
    let base = root().join("verify");
    walk(&base.join(dir), &base, &mut out);
    out
}

/// Run a stored command of ours and parse its JSON output.
fn run_ours(command: &str) -> Value {
    let args = command
        .strip_prefix(OURS)
        .unwrap_or_else(|| panic!("not a command of ours: {command}"));
    let out = Command::new(env!("CARGO_BIN_EXE_verify"))
        .args(args.split_whitespace())
        .current_dir(root())
        .output()
        .expect("run verify");
    assert!(
        out.status.success(),
        "`{command}` failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout)
        .unwrap_or_else(|e| panic!("`{command}` printed no JSON: {e}"))
}

/// The stored `reproduce` of each record: present, one of ours, no placeholder.
fn reproduce_of(name: &str, record: &Value) -> String {
    let command = record
        .get("reproduce")
        .and_then(Value::as_str)
        .unwrap_or_else(|| panic!("{name}: no reproduce command"));
    assert!(command.starts_with(OURS), "{name}: `{command}` is not ours");
    command.to_string()
}

/// Run each record's command (each distinct command once) and compare `quantity` within
/// `tolerance` (relative above 1, absolute below).
fn check_forces(records: &BTreeMap<String, Value>, tolerance: f64) {
    let mut ran: BTreeMap<String, f64> = BTreeMap::new();
    let mut checked = 0;
    for (name, record) in records {
        let command = reproduce_of(name, record);
        let ours = *ran
            .entry(command.clone())
            .or_insert_with(|| run_ours(&command)["force"].as_f64().expect("force"));
        let stored = record["force"].as_f64().expect("stored force");
        let difference = (ours - stored).abs() / stored.abs().max(1.0);
        println!("{name}: ours {ours:.15} stored {stored:.15} ({difference:.1e})");
        assert!(
            difference <= tolerance,
            "{name}: `{command}` gives {ours}, the stored force is {stored} ({difference:.1e} \
             apart, tolerance {tolerance:e})"
        );
        checked += 1;
    }
    assert!(checked > 0, "nothing was reproduced");
}

/// The stored FEniCSx results (but the operator comparisons) whose directory and mesh are
/// chosen by `keep(name, command)`.
fn fenicsx_records(keep: impl Fn(&str, &str) -> bool) -> BTreeMap<String, Value> {
    records("fenicsx")
        .into_iter()
        .filter(|(name, record)| {
            !name.contains("operators/") && keep(name, &reproduce_of(name, record))
        })
        .collect()
}

/// Whether a stored command solves on a mesh gmsh makes from parameters.
fn needs_gmsh(command: &str) -> bool {
    command.contains("--mesh-parameters")
}

/// The stored FEniCSx results of the default set on committed meshes (`generated` false) or
/// on meshes gmsh makes (true), at least ten, reproduced to 1e-8.
fn check_default_fenicsx_results(generated: bool) {
    let records = fenicsx_records(|name, command| {
        !name.contains("large/") && needs_gmsh(command) == generated
    });
    assert!(
        records.len() >= 10,
        "found {} FEniCSx records",
        records.len()
    );
    check_forces(&records, 1e-8);
}

#[test]
fn the_stored_fenicsx_results_on_committed_meshes_are_reproduced_by_their_commands() {
    check_default_fenicsx_results(false);
}

#[test]
#[cfg_attr(gmsh_missing, ignore = "needs gmsh: bash scripts/install_gmsh.sh")]
fn the_stored_fenicsx_results_on_generated_meshes_are_reproduced_by_their_commands() {
    check_default_fenicsx_results(true);
}

#[test]
#[ignore = "long (6e5-1.4e6 unknowns): the nightly run, or --include-ignored"]
fn the_largest_stored_fenicsx_results_are_reproduced_by_their_commands() {
    let records = fenicsx_records(|name, _| name.contains("large/"));
    assert!(!records.is_empty(), "found no large FEniCSx records");
    check_forces(&records, 1e-8);
}

#[test]
fn the_stored_grid_peer_results_are_reproduced_by_their_commands() {
    let records: BTreeMap<String, Value> = records("peers")
        .into_iter()
        .filter(|(name, _)| {
            !name.starts_with("peers/adhesion/") && !name.starts_with("peers/dugdale/")
        })
        .collect();
    assert!(records.len() >= 26, "found {} peer records", records.len());
    // Every punch with a stored peer result: the four of the paper, the power law, the torus.
    for punch in ["flat", "flat-annulus", "cone", "sphere", "power", "torus"] {
        assert!(
            records.values().any(|r| r["punch"] == punch),
            "no stored peer result for the {punch}"
        );
    }
    check_forces(
        &records,
        ringcontact_verify::harness::records::peers::PEER_AGREEMENT,
    );
}

/// The numbers of a pull-off record that must come out again.
fn pulloff_numbers(result: &Value) -> Vec<f64> {
    let mut out: Vec<f64> = result["sequence"]
        .as_array()
        .map(|s| {
            s.iter()
                .filter_map(|e| e["pulloff_over_f0"].as_f64())
                .collect()
        })
        .unwrap_or_default();
    out.extend(result["extrapolated_over_f0"].as_f64());
    out
}

/// The stored pull-off simulations (at least 15), each with its command of ours.
fn pulloff_records() -> Vec<(String, Value, String)> {
    let records = records("pulloff");
    assert!(
        records.len() >= 15,
        "found {} pull-off records",
        records.len()
    );
    records
        .into_iter()
        .map(|(name, record)| {
            let command = reproduce_of(&name, &record);
            (name, record, command)
        })
        .collect()
}

/// Each stored pull-off simulation names the command of ours that made it (the ignored test
/// below runs them).
#[test]
fn the_stored_pulloff_simulations_name_their_commands() {
    pulloff_records();
}

#[test]
#[ignore = "long (20 s to 3.5 min each): the nightly run, or --include-ignored"]
fn the_stored_pulloff_simulations_are_reproduced_by_their_commands() {
    for (name, record, command) in &pulloff_records() {
        let args = command.strip_prefix(OURS).unwrap();
        let out = Command::new(env!("CARGO_BIN_EXE_verify"))
            .args(args.split_whitespace())
            .current_dir(root())
            .output()
            .expect("run verify");
        match (&record.get("result"), out.status.success()) {
            (Some(stored), true) => {
                let fresh: Value = serde_json::from_slice(&out.stdout).unwrap();
                let (a, b) = (pulloff_numbers(&fresh), pulloff_numbers(stored));
                assert_eq!(a.len(), b.len(), "{name}: {a:?} against {b:?}");
                for (x, y) in a.iter().zip(&b) {
                    assert!((x - y).abs() <= 1e-10, "{name}: {x} against the stored {y}");
                }
            }
            (None, false) => {} // declined, as stored
            (stored, ok) => panic!(
                "{name}: stored {} but the command {}",
                if stored.is_some() {
                    "a result"
                } else {
                    "a decline"
                },
                if ok { "gave a result" } else { "declined" }
            ),
        }
        println!("{name}: reproduced");
    }
}

/// The records of the operator comparisons and of Tamaas's pull-offs are reproduced by the
/// peer's own script (it needs FEniCSx or Tamaas); their commands must name a script of the
/// repository and a mesh that exists or can be made, never a placeholder.
#[test]
fn the_peer_commands_are_runnable_as_written() {
    for (name, record) in records("fenicsx/operators")
        .into_iter()
        .chain(records("peers/adhesion"))
        .chain(
            records("fenicsx")
                .into_iter()
                .filter(|(n, _)| !n.contains("operators/")),
        )
        .chain(records("peers"))
    {
        let Some(command) = record
            .get("peer_reproduce")
            .or_else(|| {
                (!name.starts_with("fenicsx/") || name.contains("operators/"))
                    .then(|| &record["reproduce"])
            })
            .and_then(Value::as_str)
        else {
            continue;
        };
        if command.starts_with(OURS) {
            continue;
        }
        let script = command
            .split_whitespace()
            .find(|w| w.starts_with("scripts/"))
            .unwrap_or_else(|| panic!("{name}: `{command}` runs no script of the repository"));
        assert!(root().join(script).is_file(), "{name}: {script} is missing");
        let words: Vec<&str> = command.split_whitespace().collect();
        for pair in words.windows(2) {
            if pair[0] == "--mesh" {
                assert!(
                    root().join(pair[1]).is_file(),
                    "{name}: mesh {} is missing",
                    pair[1]
                );
            }
            assert!(
                !matches!(pair[1], "F" | "O" | "DIR" | "FILE"),
                "{name}: `{command}` has a placeholder"
            );
        }
    }
}
