//! The project's scripts cannot lose data: they find `verify` the way cargo does, stop before
//! writing anything when they cannot, and a nightly run leaves the checkout as it was (its fresh
//! results go into its report directory, never into the committed `verify/`).

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// `git status --porcelain` of the checkout (empty when git or the repository is absent: the
/// comparison is then of two empty strings and the file checks below still hold).
fn git_status() -> String {
    Command::new("git")
        .args([
            "status",
            "--porcelain",
            "--untracked-files=all",
            "--",
            "verify",
            "meshes",
        ])
        .current_dir(root())
        .output()
        .map(|o| String::from_utf8_lossy(&o.stdout).into_owned())
        .unwrap_or_default()
}

/// A `PATH` with the system's directories and no cargo: `verify` cannot be built or found.
const PATH_WITHOUT_CARGO: &str = "/usr/local/bin:/usr/bin:/bin";

fn run(script: &[&str], env: &[(&str, &Path)], path: Option<&str>) -> std::process::Output {
    let mut command = Command::new(script[0]);
    command.args(&script[1..]).current_dir(root());
    for (key, value) in env {
        command.env(key, value);
    }
    if let Some(path) = path {
        command.env("PATH", path);
    }
    command.output().expect("run the script")
}

/// Without cargo, every script that writes results fails at once, naming the reason, and writes
/// nothing: not into the committed baselines, not into the directory it was given.
#[test]
#[cfg_attr(python3_missing, ignore = "needs /usr/bin/python3")]
fn scripts_without_a_verify_binary_fail_before_writing() {
    let before = git_status();
    let scratch = std::env::temp_dir().join(format!("ringcontact-no-cargo-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&scratch);
    let out_dir = scratch.join("out");
    let out = out_dir.to_str().unwrap();
    for script in [
        vec!["bash", "scripts/nightly.sh", "--quick", "--out", out],
        vec![
            "/usr/bin/python3",
            "scripts/pulloff/run_all.py",
            "--out",
            "verify/pulloff",
            "flat",
        ],
        vec![
            "/usr/bin/python3",
            "scripts/pulloff/run_all.py",
            "--out",
            out,
            "flat",
        ],
        vec!["bash", "scripts/pulloff/run_all.sh", "--out", out],
        vec![
            "/usr/bin/python3",
            "scripts/fenicsx/operators.py",
            "--out",
            out,
        ],
        vec![
            "/usr/bin/python3",
            "scripts/fenicsx/run_all.py",
            "--out",
            out,
        ],
        vec!["/usr/bin/python3", "scripts/fenicsx/speed.py", "--out", out],
    ] {
        let result = run(&script, &[], Some(PATH_WITHOUT_CARGO));
        let stderr = String::from_utf8_lossy(&result.stderr);
        assert!(
            !result.status.success(),
            "{script:?} succeeded without cargo: {stderr}"
        );
        assert!(
            stderr.contains("cargo") || stderr.contains("FEniCSx"),
            "{script:?}: the reason is not named: {stderr}"
        );
        assert!(
            !out_dir.exists(),
            "{script:?} wrote into {out} before failing"
        );
        assert_eq!(git_status(), before, "{script:?} changed the checkout");
    }
    let _ = std::fs::remove_dir_all(&scratch);
}

/// An unknown case or a missing `--out` is refused before anything runs.
#[test]
fn scripts_refuse_bad_arguments() {
    for script in [
        vec![
            "python3",
            "scripts/pulloff/run_all.py",
            "--out",
            "/tmp/x",
            "no-such-case",
        ],
        vec!["python3", "scripts/pulloff/run_all.py"],
        vec!["bash", "scripts/nightly.sh", "--no-such-option"],
        vec!["bash", "scripts/peers/run_peers.sh"],
    ] {
        let result = run(&script, &[], None);
        assert_eq!(
            result.status.code(),
            Some(2),
            "{script:?}: {}",
            String::from_utf8_lossy(&result.stderr)
        );
    }
}

/// `--help` prints the nightly script's usage from its header and exits 0, before it builds.
#[test]
fn the_nightly_script_teaches_its_options() {
    let result = run(&["bash", "scripts/nightly.sh", "--help"], &[], None);
    let text = String::from_utf8_lossy(&result.stdout);
    assert_eq!(result.status.code(), Some(0), "{text}");
    for option in [
        "Usage: bash scripts/nightly.sh",
        "--out DIR",
        "--history FILE",
        "--quick",
    ] {
        assert!(
            text.contains(option),
            "--help does not name {option}: {text}"
        );
    }
    assert!(!text.contains("set -uo"), "--help printed code: {text}");
}

/// A nightly run with `CARGO_TARGET_DIR` set elsewhere finds the binary there, writes its report
/// (and its fresh results) into its own directory, and leaves `verify/` and `meshes/` as they
/// were (`git status` of the whole checkout, untracked files included), its history beside the
/// report, and exits 0 saying every step passed. `--quick` leaves out the long parts. About 1.5 minutes of a whole report: `.ci/run` runs it (`--ignored`).
#[test]
#[ignore = "a whole quick nightly run (about 1.5 min): .ci/run runs it with --ignored"]
fn a_quick_nightly_run_with_another_target_directory_leaves_the_checkout_clean() {
    // The binary under test sits in <target>/release/; point CARGO_TARGET_DIR at <target>
    // through another path, as a user's setting would.
    let binary = PathBuf::from(env!("CARGO_BIN_EXE_verify"));
    let target = binary
        .parent()
        .and_then(Path::parent)
        .unwrap()
        .to_path_buf();
    let scratch = std::env::temp_dir().join(format!("ringcontact-nightly-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&scratch);
    std::fs::create_dir_all(&scratch).unwrap();
    let elsewhere = scratch.join("target-elsewhere");
    std::os::unix::fs::symlink(&target, &elsewhere).unwrap();
    let before = git_status();
    let report = scratch.join("report");
    let result = run(
        &[
            "bash",
            "scripts/nightly.sh",
            "--quick",
            "--out",
            report.to_str().unwrap(),
        ],
        &[("CARGO_TARGET_DIR", &elsewhere)],
        None,
    );
    let stdout = String::from_utf8_lossy(&result.stdout);
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(
        report.join("index.html").is_file() && report.join("report.json").is_file(),
        "no report was written: {stdout}\n{stderr}"
    );
    assert!(
        result.status.success() && stdout.contains("every step passed"),
        "the run failed ({}): {stdout}\n{stderr}",
        result.status
    );
    // The history goes beside the report directory, not into the checkout.
    assert!(
        scratch.join("history.jsonl").is_file(),
        "the history was not written beside the report"
    );
    assert!(
        stdout.contains(&format!("{}", elsewhere.display())),
        "the binary was not taken from CARGO_TARGET_DIR: {stdout}"
    );
    assert_eq!(git_status(), before, "the nightly run changed the checkout");
    let _ = std::fs::remove_dir_all(&scratch);
}
