//! The commands of the README and of the guide's task pages run as written, so the
//! documentation cannot drift from the program: every `verify ...` line of their `sh` blocks is
//! run in a fresh directory (the project's `meshes/`, `verify/`, `benches/` and gmsh linked in,
//! so that relative paths resolve and outputs stay in that directory), must exit with status 0,
//! and must print the text after its `# expect:` comment.
//!
//! Left out: lines marked `# long` (the nightly run's), the two commands of the README's front
//! door (`cargo run --release --bin verify` is `.ci/run`'s smoke run, `cargo test --release` is
//! this suite), and lines that run scripts (`bash`, `python3`: `tests/suite/scripts.rs` runs the
//! scripts). Commands that need gmsh are skipped without it unless `RINGCONTACT_REQUIRE_GMSH`
//! is set (CI sets it).

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// One documented command: where it is, its arguments, the text it must print.
#[derive(Debug)]
struct DocCommand {
    place: String,
    args: Vec<String>,
    expect: Option<String>,
}

/// The `verify` commands in the `sh` blocks of `file`.
fn commands_in(file: &str) -> Vec<DocCommand> {
    let text = std::fs::read_to_string(root().join(file)).unwrap();
    let mut out = Vec::new();
    let mut in_sh = false;
    for (n, line) in text.lines().enumerate() {
        let trimmed = line.trim();
        if trimmed.starts_with("```") {
            in_sh = !in_sh && trimmed == "```sh";
            continue;
        }
        if !in_sh {
            continue;
        }
        let (command, comment) = match trimmed.split_once('#') {
            Some((c, rest)) => (c.trim(), rest.trim()),
            None => (trimmed, ""),
        };
        let args: Vec<String> = if let Some(rest) = command.strip_prefix("verify ") {
            rest.split_whitespace().map(str::to_string).collect()
        } else if let Some(rest) = command.strip_prefix("cargo run --release -- ") {
            rest.split_whitespace().map(str::to_string).collect()
        } else {
            continue;
        };
        if comment.starts_with("long") {
            continue;
        }
        let expect = comment
            .strip_prefix("expect:")
            .map(|e| e.trim().to_string());
        out.push(DocCommand {
            place: format!("{file}:{}", n + 1),
            args,
            expect,
        });
    }
    out
}

/// A fresh directory holding links to the project's data, and the environment to run in it.
fn fresh_directory(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("ringcontact-docs-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    for data in ["meshes", "verify", "benches"] {
        std::os::unix::fs::symlink(root().join(data), dir.join(data)).unwrap();
    }
    // The project's gmsh, where scripts/install_gmsh.sh put it.
    if root().join(".venv-gmsh").is_dir() {
        std::os::unix::fs::symlink(root().join(".venv-gmsh"), dir.join(".venv-gmsh")).unwrap();
    }
    dir
}

fn gmsh_usable() -> bool {
    std::env::var_os("RINGCONTACT_REQUIRE_GMSH").is_some()
        || ringcontact::mesh::provider::gmsh_available(
            &ringcontact::mesh::files::DataPaths::default(),
        )
}

fn run_all(file: &str, minimum: usize) {
    let commands = commands_in(file);
    assert!(
        commands.len() >= minimum,
        "{file}: found {} commands",
        commands.len()
    );
    let dir = fresh_directory(&file.replace('/', "-"));
    let mut failures = Vec::new();
    for c in &commands {
        let mut command = Command::new(env!("CARGO_BIN_EXE_verify"));
        command
            .args(&c.args)
            .current_dir(&dir)
            .env("RINGCONTACT_MESH_CACHE", root().join(".mesh-cache"))
            .env_remove("RINGCONTACT_DATA_DIR");
        let out = command.output().expect("run verify");
        let text = format!(
            "{}{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        );
        if !out.status.success() && text.contains("install_gmsh") && !gmsh_usable() {
            eprintln!("{}: skipped, needs gmsh", c.place);
            continue;
        }
        println!("{}: verify {} -> {}", c.place, c.args.join(" "), out.status);
        if !out.status.success() {
            failures.push(format!("{}: exit {}: {}", c.place, out.status, text.trim()));
        } else if let Some(expect) = &c.expect {
            if !text.contains(expect.as_str()) {
                failures.push(format!("{}: output lacks `{expect}`:\n{text}", c.place));
            }
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

#[test]
fn the_readme_commands_run() {
    run_all("README.md", 10);
}

#[test]
fn the_task_pages_commands_run() {
    run_all("docs/tasks.md", 15);
}

/// The documentation's files exist where the README links them, and the repository's prose
/// names no file outside it.
#[test]
fn the_documentation_is_linked_and_self_contained() {
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    for link in readme.split("](").skip(1) {
        let target = link.split(')').next().unwrap();
        if target.starts_with("http") {
            continue;
        }
        assert!(
            Path::new(&root().join(target)).exists(),
            "README links {target}, which is missing"
        );
    }
    assert!(
        readme.lines().count() <= 200,
        "the README is a guide, not a record"
    );
    for file in [
        "README.md",
        "docs/tasks.md",
        "docs/methods.md",
        "docs/conventions.md",
    ] {
        let text = std::fs::read_to_string(root().join(file)).unwrap();
        assert!(
            !text.contains("shared/docs"),
            "{file} cites a file outside the repository"
        );
    }
}
