//! The commands of the README and of the guide's task pages run as written, so the
//! documentation cannot drift from the program: every `verify ...` line of their `sh` blocks is
//! run in a fresh directory (the project's `meshes/`, `verify/`, `benches/` and gmsh linked in,
//! so that relative paths resolve and outputs stay in that directory), must exit with status 0,
//! and must print the text after its `# expect:` comment.
//!
//! Left out: lines marked `# long` (the nightly run's), the two commands of the README's front
//! door (`cargo run --release --bin verify` is `.ci/run`'s smoke run, `cargo test --release` is
//! this suite), and lines that run scripts (`bash`, `python3`: `tests/suite/scripts.rs` runs the
//! scripts). Commands whose comment names gmsh are a test of their own, reported as ignored
//! when the build found no gmsh; a command that needs gmsh without saying so fails.

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
    /// Its comment says it needs gmsh.
    needs_gmsh: bool,
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
            needs_gmsh: comment.contains("gmsh"),
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

/// Run the commands of `file` that need gmsh (`gmsh`) or those that do not; at least `minimum`.
fn run_all(file: &str, gmsh: bool, minimum: usize) {
    let commands: Vec<DocCommand> = commands_in(file)
        .into_iter()
        .filter(|c| c.needs_gmsh == gmsh)
        .collect();
    assert!(
        commands.len() >= minimum,
        "{file}: found {} commands",
        commands.len()
    );
    let dir = fresh_directory(&format!("{}-gmsh-{gmsh}", file.replace('/', "-")));
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
        println!("{}: verify {} -> {}", c.place, c.args.join(" "), out.status);
        if !out.status.success() && !gmsh && text.contains("install_gmsh") {
            failures.push(format!(
                "{}: needs gmsh, and its comment does not say so: {}",
                c.place,
                text.trim()
            ));
        } else if !out.status.success() {
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
    run_all("README.md", false, 10);
}

#[test]
#[cfg_attr(gmsh_missing, ignore = "needs gmsh: bash scripts/install_gmsh.sh")]
fn the_readme_commands_that_need_gmsh_run() {
    run_all("README.md", true, 3);
}

/// The task pages run without gmsh (a command there that needs it would need a test like the
/// README's).
#[test]
fn the_task_pages_commands_run() {
    let marked: Vec<String> = commands_in("docs/tasks.md")
        .into_iter()
        .filter(|c| c.needs_gmsh)
        .map(|c| c.place)
        .collect();
    assert!(marked.is_empty(), "commands that need gmsh: {marked:?}");
    run_all("docs/tasks.md", false, 15);
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
