//! Finds the outside programs some tests need and tells the tests which are missing, so that a
//! test that cannot run is reported as ignored (with the reason and the install command), never
//! as passed: `cfg(gmsh_missing)` (gmsh in `.venv-gmsh` or on the `PATH`, as the library finds
//! it), `cfg(chromium_missing)`, `cfg(dolfinx_missing)` (`/usr/bin/python3` with dolfinx),
//! `cfg(python3_missing)` (`/usr/bin/python3`).
//!
//! `RINGCONTACT_REQUIRE_GMSH=1` and `RINGCONTACT_REQUIRE_CHROMIUM=1` (set by `.ci/run`) make the
//! tests run, and fail, without them. The answer is kept until the `PATH`, those variables or a
//! found program changes; `scripts/install_gmsh.sh`, `scripts/install_chromium.sh` and
//! `scripts/fenicsx/setup.sh` touch this file so that the next build sees what they installed
//! (after installing a program by other means, `touch build.rs`).

use std::path::Path;
use std::process::Command;

/// Whether `program args` runs and exits 0.
fn runs(program: &Path, args: &[&str]) -> bool {
    Command::new(program)
        .args(args)
        .output()
        .is_ok_and(|o| o.status.success())
}

/// The executable `name` on the `PATH`, if there is one.
fn on_path(name: &str) -> Option<std::path::PathBuf> {
    let path = std::env::var_os("PATH")?;
    std::env::split_paths(&path)
        .map(|dir| dir.join(name))
        .find(|candidate| candidate.is_file())
}

/// Tell cargo to rerun this script when `file` changes (only files that exist: a missing watched
/// file would rerun it on every build).
fn watch(file: &Path) {
    if file.is_file() {
        println!("cargo:rerun-if-changed={}", file.display());
    }
}

fn gmsh_found(root: &Path) -> bool {
    let venv = root.join(".venv-gmsh/bin");
    let (python, script) = (venv.join("python"), venv.join("gmsh"));
    watch(&script);
    if python.is_file() && script.is_file() {
        let script = script.display().to_string();
        if runs(&python, &[script.as_str(), "--version"]) {
            return true;
        }
    }
    on_path("gmsh").is_some_and(|gmsh| {
        watch(&gmsh);
        runs(&gmsh, &["--version"])
    })
}

fn chromium_found() -> bool {
    if let Some(path) = std::env::var_os("RINGCONTACT_CHROMIUM") {
        return Path::new(&path).is_file();
    }
    ["chromium", "chromium-browser", "google-chrome"]
        .iter()
        .filter_map(|name| on_path(name))
        .any(|browser| {
            watch(&browser);
            runs(&browser, &["--version"])
        })
}

fn dolfinx_found() -> bool {
    let python = Path::new("/usr/bin/python3");
    watch(python);
    python.is_file() && runs(python, &["-c", "import dolfinx"])
}

/// Emit `cfg(name)` unless `found`, or unless the variable `require` is `1`.
fn missing_unless(found: bool, name: &str, require: Option<&str>) {
    println!("cargo:rustc-check-cfg=cfg({name})");
    let required = require.is_some_and(|var| std::env::var(var).as_deref() == Ok("1"));
    if !found && !required {
        println!("cargo:rustc-cfg={name}");
    }
}

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    for var in [
        "PATH",
        "RINGCONTACT_REQUIRE_GMSH",
        "RINGCONTACT_REQUIRE_CHROMIUM",
        "RINGCONTACT_CHROMIUM",
    ] {
        println!("cargo:rerun-if-env-changed={var}");
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    missing_unless(
        gmsh_found(root),
        "gmsh_missing",
        Some("RINGCONTACT_REQUIRE_GMSH"),
    );
    missing_unless(
        chromium_found(),
        "chromium_missing",
        Some("RINGCONTACT_REQUIRE_CHROMIUM"),
    );
    missing_unless(dolfinx_found(), "dolfinx_missing", None);
    missing_unless(
        Path::new("/usr/bin/python3").is_file(),
        "python3_missing",
        None,
    );
}
