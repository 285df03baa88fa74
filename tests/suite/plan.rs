//! The plan of jobs (`verify plan`, `run --shard`, `merge`): a sharded run merged from files
//! gives the single-process report, number for number; every job lands in exactly one shard;
//! a failed or missing job is named, never silently left out.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use ringcontact::methods::Method;
use ringcontact::punch::PunchKind;
use ringcontact_verify::harness::plan::Plan;
use ringcontact_verify::harness::report_jobs::{self, Part};

fn verify(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_verify"))
        .args(args)
        .output()
        .expect("run verify")
}

/// `verify run --plan PLAN [--shard SHARD] --results RESULTS`.
fn run_shard(plan: &Path, shard: Option<&str>, results: &Path) -> Output {
    let mut args = vec!["run", "--plan", plan.to_str().unwrap()];
    if let Some(s) = shard {
        args.extend(["--shard", s]);
    }
    args.extend(["--results", results.to_str().unwrap()]);
    verify(&args)
}

/// `verify merge --plan PLAN --results RESULTS --report REPORT [EXTRA...]`.
fn merge(plan: &Path, results: &Path, report: &Path, extra: &[&str]) -> Output {
    let mut args = vec![
        "merge",
        "--plan",
        plan.to_str().unwrap(),
        "--results",
        results.to_str().unwrap(),
        "--report",
        report.to_str().unwrap(),
    ];
    args.extend(extra);
    verify(&args)
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("ringcontact-plan-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// Keys whose values are wall times or follow from them (the Pareto front), and dates.
const TIMING_KEYS: [&str; 7] = [
    "wall_s",
    "fem_wall_s",
    "wall_s_range",
    "our_wall_s",
    "wall_time_ratio",
    "on_pareto_front",
    "date",
];

/// Every difference between two JSON values outside the timing keys, as `path: a != b`.
fn differences(a: &serde_json::Value, b: &serde_json::Value, path: &str, out: &mut Vec<String>) {
    use serde_json::Value;
    match (a, b) {
        (Value::Object(x), Value::Object(y)) => {
            let keys: BTreeMap<&String, ()> = x.keys().chain(y.keys()).map(|k| (k, ())).collect();
            for k in keys.keys() {
                if TIMING_KEYS.contains(&k.as_str()) {
                    continue;
                }
                // A timed point's number of runs follows from its run times (a budget).
                if k.as_str() == "runs" && x.get(*k).is_some_and(|v| v.is_number()) {
                    continue;
                }
                match (x.get(*k), y.get(*k)) {
                    (Some(u), Some(v)) => differences(u, v, &format!("{path}/{k}"), out),
                    _ => out.push(format!("{path}/{k}: present in one report only")),
                }
            }
        }
        (Value::Array(x), Value::Array(y)) if x.len() == y.len() => {
            for (i, (u, v)) in x.iter().zip(y).enumerate() {
                differences(u, v, &format!("{path}[{i}]"), out);
            }
        }
        _ if a == b => {}
        _ => out.push(format!("{path}: {a} != {b}")),
    }
}

fn report_json(dir: &Path) -> serde_json::Value {
    let text = std::fs::read_to_string(dir.join("report.json")).expect("report.json");
    serde_json::from_str(&text).expect("report.json parses")
}

#[test]
fn sharded_run_merges_into_the_single_process_report() {
    let dir = scratch("same");
    let plan = dir.join("default.plan");
    let results = dir.join("results");
    let out = verify(&["plan", "--out", plan.to_str().unwrap()]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    for i in 1..=3 {
        let shard = format!("{i}/3");
        let out = run_shard(&plan, Some(&shard), &results);
        assert!(out.status.success(), "shard {shard}: {}", text(&out.stderr));
    }
    let merged = dir.join("merged");
    let out_merged = merge(&plan, &results, &merged, &[]);
    assert!(out_merged.status.success(), "{}", text(&out_merged.stderr));
    let single = dir.join("single");
    let out_single = verify(&["compare", "--report", single.to_str().unwrap()]);
    assert!(out_single.status.success(), "{}", text(&out_single.stderr));

    let (a, b) = (report_json(&single), report_json(&merged));
    let mut diffs = Vec::new();
    differences(&a, &b, "", &mut diffs);
    assert!(
        diffs.is_empty(),
        "{} differences between the single-process and the merged report, e.g.:\n{}",
        diffs.len(),
        diffs[..diffs.len().min(10)].join("\n")
    );
    // The comparison holds numbers and verdicts of every section.
    assert!(a["extras"]["verdicts"]
        .as_array()
        .is_some_and(|v| !v.is_empty()));
    assert!(a["comparison"]["rows"]
        .as_array()
        .is_some_and(|v| v.len() > 20));
    // The same charts and tables.
    let names = |d: &Path| -> Vec<String> {
        let mut n: Vec<String> = std::fs::read_dir(d)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        n.sort();
        n
    };
    assert_eq!(names(&single), names(&merged));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_plan_is_the_same_from_run_to_run_and_parses_back() {
    for args in [
        vec!["plan"],
        vec!["plan", "--nightly"],
        vec![
            "plan",
            "--convergence",
            "--punch",
            "flat-annulus",
            "--eps",
            "0.3",
            "--method",
            "grid-bem",
            "--levels",
            "5",
        ],
    ] {
        let (a, b) = (verify(&args), verify(&args));
        assert!(a.status.success(), "{args:?}: {}", text(&a.stderr));
        assert_eq!(a.stdout, b.stdout, "{args:?}");
        let plan = Plan::parse(&text(&a.stdout), "stdout").expect("the plan parses");
        for job in &plan.jobs {
            assert_eq!(Part::from_id(&job.part.id()).unwrap(), job.part);
            assert!(job.command.starts_with("verify part "));
        }
    }
}

#[test]
fn every_job_is_in_exactly_one_shard_and_the_shards_are_balanced() {
    let plan = Plan::new(
        "test",
        report_jobs::nightly_parts(1e-9, &[1e-3, 1e-4, 1e-6, 1e-8]),
    );
    let total: f64 = plan.jobs.iter().map(|j| j.expected_s).sum();
    let longest = plan.jobs.iter().map(|j| j.expected_s).fold(0.0, f64::max);
    for n in 1..=7 {
        let mut seen = vec![0usize; plan.jobs.len()];
        for i in 1..=n {
            let shard = plan.shard(i, n).unwrap();
            let load: f64 = shard.iter().map(|j| j.expected_s).sum();
            // Greedy longest-first: no shard exceeds the mean by more than the longest job.
            assert!(
                load <= total / n as f64 + longest + 1e-9,
                "shard {i}/{n}: {load} s of {total} s"
            );
            for job in shard {
                let k = plan.jobs.iter().position(|j| j == job).unwrap();
                seen[k] += 1;
            }
        }
        assert!(seen.iter().all(|&c| c == 1), "N = {n}: {seen:?}");
    }
    assert!(plan.shard(0, 3).is_err() && plan.shard(4, 3).is_err() && plan.shard(1, 0).is_err());
}

#[test]
fn malformed_ids_and_plans_are_refused_with_the_reason() {
    for (id, says) in [
        ("speed:cone-3", "no speed-accuracy problem"),
        ("comparison", "needs `tol=`"),
        ("comparison:tol=abc", "not a number"),
        (
            "convergence:sphere:fem:eps=0:depth=1.5:level=x:of=3",
            "not a count",
        ),
        ("nonsense", "unknown kind"),
        ("pulloff:plate:d0h=1", "no punch"),
        // A job names a table by its hash: only the report's own table can be one.
        ("adhesion:table-000000000000", "must be the report's"),
        (
            "comparison:tol=0.000001",
            "write it as `comparison:tol=1e-6`",
        ),
    ] {
        let e = Part::from_id(id).expect_err(id).to_string();
        assert!(e.contains(says), "{id}: {e}");
    }
    let good = Plan::new("t", vec![Part::Operators, Part::Peers]).to_text();
    let tampered = good.replace("verify part peers", "verify part peers; rm -rf /");
    let e = Plan::parse(&tampered, "p").unwrap_err().to_string();
    assert!(e.contains("line 5") && e.contains("must write"), "{e}");
    let doubled = format!("{good}{}", good.lines().last().unwrap());
    assert!(Plan::parse(&doubled, "p")
        .unwrap_err()
        .to_string()
        .contains("twice"));
    assert!(Plan::parse("id\tx\n", "p")
        .unwrap_err()
        .to_string()
        .contains("not a plan file"));
    let out = verify(&[
        "run",
        "--plan",
        "/nonexistent.plan",
        "--shard",
        "1/2",
        "--results",
        "/tmp/x",
    ]);
    assert!(!out.status.success() && text(&out.stderr).contains("/nonexistent.plan"));
    let out = verify(&[
        "run",
        "--plan",
        "/nonexistent.plan",
        "--shard",
        "3/2",
        "--results",
        "/tmp/x",
    ]);
    assert!(
        text(&out.stderr).contains("1 <= I <= N"),
        "{}",
        text(&out.stderr)
    );
}

#[test]
fn a_failed_job_leaves_an_error_record_and_merge_names_failed_and_missing_jobs() {
    let dir = scratch("fail");
    // The ring BEM has no concave convergence study: this job fails when it runs.
    let failing = Part::ConvergenceLevel {
        punch: PunchKind::SPHERE,
        method: Method::RingBem,
        eps: 0.0,
        depth: 1.5,
        level: 0,
        levels: 2,
    };
    let plan = Plan::new("t", vec![Part::Operators, failing.clone(), Part::Peers]);
    let path = dir.join("p.plan");
    std::fs::write(&path, plan.to_text()).unwrap();
    let results = dir.join("r");
    let out = run_shard(&path, None, &results);
    assert!(!out.status.success());
    assert!(text(&out.stdout).contains(&format!("FAILED: {}", failing.id())));
    let record = std::fs::read_to_string(results.join(failing.output_file())).unwrap();
    assert!(
        record.contains("\"error\"") && record.contains("ring-bem"),
        "{record}"
    );
    std::fs::remove_file(results.join(Part::Peers.output_file())).unwrap();
    let out = merge(&path, &results, &dir.join("rep"), &[]);
    let err = text(&out.stderr);
    assert!(!out.status.success());
    assert!(err.contains("2 of 3 jobs"), "{err}");
    assert!(err.contains(&format!("{}: failed", failing.id())), "{err}");
    assert!(err.contains("peers: missing"), "{err}");
    assert!(!dir.join("rep").join("report.json").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_convergence_plan_merges_into_the_study() {
    let dir = scratch("conv");
    let path = dir.join("c.plan");
    let out = verify(&[
        "plan",
        "--convergence",
        "--punch",
        "flat",
        "--method",
        "grid-bem",
        "--levels",
        "3",
        "--out",
        path.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let results = dir.join("r");
    for i in 1..=2 {
        let out = run_shard(&path, Some(&format!("{i}/2")), &results);
        assert!(out.status.success(), "{}", text(&out.stderr));
    }
    let out = merge(&path, &results, &dir.join("out"), &["--json"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let merged: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let single = verify(&[
        "convergence",
        "--punch",
        "flat",
        "--method",
        "grid-bem",
        "--levels",
        "3",
        "--out",
        dir.join("single").to_str().unwrap(),
        "--json",
    ]);
    let single: serde_json::Value = serde_json::from_slice(&single.stdout).unwrap();
    let mut diffs = Vec::new();
    differences(&single, &merged[0], "", &mut diffs);
    assert!(diffs.is_empty(), "{diffs:?}");
    for file in ["flat-grid-bem.csv", "flat-grid-bem.svg"] {
        assert!(dir.join("out").join(file).exists(), "{file}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
