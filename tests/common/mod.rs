//! Helpers shared by the integration tests.

/// Run the `verify` binary with `args` (standard input empty).
#[allow(dead_code)]
pub fn verify(args: &[&str]) -> std::process::Output {
    verify_with_input(args, "")
}

/// Run the `verify` binary with `args` and return its standard output, failing the test with
/// its standard error unless it succeeds.
#[allow(dead_code)]
pub fn verify_succeeding(args: &[&str]) -> Vec<u8> {
    let out = verify(args);
    assert!(
        out.status.success(),
        "verify {args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    out.stdout
}

/// Run the `verify` binary with `args`, `input` on its standard input.
#[allow(dead_code)]
pub fn verify_with_input(args: &[&str], input: &str) -> std::process::Output {
    use std::io::Write;
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_verify"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("verify runs");
    child
        .stdin
        .take()
        .expect("stdin")
        .write_all(input.as_bytes())
        .expect("input written");
    child.wait_with_output().expect("verify finishes")
}

/// A fresh scratch directory for a test (under the target directory).
#[allow(dead_code)]
pub fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch directory");
    dir
}

/// A convergence study's JSON (`verify convergence --json`): its levels' errors against the
/// yardstick fall level by level, the finest is below `finest`, and the finest level's error bar
/// bounds its actual error (`bar_bounds_error`). `label` names the study in failures.
#[allow(dead_code)]
pub fn assert_study_converges(json: &serde_json::Value, label: &str, finest: f64) {
    assert_eq!(json["bar_bounds_error"], true, "{label}: {json}");
    let errors: Vec<f64> = json["levels"]
        .as_array()
        .unwrap_or_else(|| panic!("{label}: no levels in {json}"))
        .iter()
        .map(|l| l["error"].as_f64().unwrap().abs())
        .collect();
    assert!(
        errors.windows(2).all(|p| p[1] < p[0]),
        "{label}: {errors:?}"
    );
    assert!(
        errors.last().is_some_and(|e| *e < finest),
        "{label}: {errors:?}"
    );
}

/// The FEM's sparse Cholesky for the tests: `RINGCONTACT_LINEAR_SOLVER` (set by `.ci/run` to run
/// the FEM's tests once more on `faer`), else the library's built-in one. The library reads no
/// environment variable: a test passes its choice explicitly.
#[allow(dead_code)]
pub fn linear_solver() -> ringcontact::sparse::Backend {
    match std::env::var(ringcontact::sparse::ENVIRONMENT_VARIABLE) {
        Ok(name) => name
            .parse()
            .unwrap_or_else(|e| panic!("{}: {e}", ringcontact::sparse::ENVIRONMENT_VARIABLE)),
        Err(_) => ringcontact::sparse::Backend::default(),
    }
}

/// The library's sources (`crates/ringcontact/src`, the crate without a command line).
#[allow(dead_code)]
pub fn library_root() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("crates/ringcontact/src")
}

/// The harness's and the command line's sources (`src`, the root crate with `verify`).
#[allow(dead_code)]
pub fn program_root() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// Every `.rs` file below `dir`, for the tests that read the sources.
#[allow(dead_code)]
pub fn rust_sources(dir: &std::path::Path) -> Vec<std::path::PathBuf> {
    let mut out = Vec::new();
    let mut pending = vec![dir.to_path_buf()];
    while let Some(dir) = pending.pop() {
        for entry in std::fs::read_dir(&dir).unwrap().filter_map(|e| e.ok()) {
            let path = entry.path();
            if path.is_dir() {
                pending.push(path);
            } else if path.extension().is_some_and(|x| x == "rs") {
                out.push(path);
            }
        }
    }
    out.sort();
    out
}
