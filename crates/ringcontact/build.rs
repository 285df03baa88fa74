//! Records the git commit the library is built from (`RINGCONTACT_COMMIT`, with `-dirty` when
//! the sources differ from it), for the provenance of the results the tool writes
//! (`ringcontact::provenance`). Outside a git checkout the commit is `unknown`.

use std::path::PathBuf;
use std::process::Command;

fn git(arguments: &[&str]) -> Option<String> {
    let output = Command::new("git").args(arguments).output().ok()?;
    output
        .status
        .success()
        .then(|| String::from_utf8_lossy(&output.stdout).trim().to_string())
}

/// The checkout's files whose change changes what the program computes: the library, the
/// harness and the command line, and the manifests.
const SOURCES: [&str; 4] = ["src", "crates", "Cargo.toml", "Cargo.lock"];

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    let Some(top) = git(&["rev-parse", "--show-toplevel"]).map(PathBuf::from) else {
        println!("cargo:rerun-if-changed=src");
        println!("cargo:rustc-env=RINGCONTACT_COMMIT=unknown");
        return;
    };
    // Rerun when the sources change or the checked-out commit moves (not on every build): the
    // watched git files are only those that exist, since cargo reruns a build script on every
    // build while a watched path is missing (a checkout may have no packed-refs).
    for watched in SOURCES {
        println!("cargo:rerun-if-changed={}", top.join(watched).display());
    }
    if let Some(git_dir) = git(&["rev-parse", "--absolute-git-dir"]) {
        let git_dir = PathBuf::from(git_dir);
        let mut files = vec![git_dir.join("HEAD"), git_dir.join("packed-refs")];
        if let Some(reference) = git(&["symbolic-ref", "-q", "HEAD"]) {
            files.push(git_dir.join(reference));
        }
        for file in files.iter().filter(|file| file.is_file()) {
            println!("cargo:rerun-if-changed={}", file.display());
        }
    }
    let commit = match git(&["rev-parse", "HEAD"]) {
        Some(hash) if !hash.is_empty() => {
            let mut status = vec!["-C", top.to_str().unwrap_or("."), "status", "--porcelain"];
            status.extend(["--untracked-files=no", "--"]);
            status.extend(SOURCES);
            let dirty = git(&status).is_some_and(|changes| !changes.is_empty());
            if dirty {
                format!("{hash}-dirty")
            } else {
                hash
            }
        }
        _ => "unknown".to_string(),
    };
    println!("cargo:rustc-env=RINGCONTACT_COMMIT={commit}");
}
