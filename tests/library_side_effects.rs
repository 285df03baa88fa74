//! The library sets nothing process-wide: no global allocator, no allocator options, no
//! transparent-huge-page or thread-affinity calls, no environment variable set at run time, no
//! global parallelism of `faer`, and no panic hook (a program's hook may ask
//! `mesh::msh::inside_mesh_parser` to stay silent on a malformed mesh). Those choices belong to a program (`src/bin/`), so a program that links `ringcontact`
//! gets none of them. Checked on the sources, where a regression would be written.

mod common;

use std::path::{Path, PathBuf};

/// The library's sources: every file below `src/` but the programs in `src/bin/`.
fn library_sources(src: &Path) -> Vec<PathBuf> {
    common::rust_sources(src)
        .into_iter()
        .filter(|file| !file.strip_prefix(src).unwrap().starts_with("bin"))
        .collect()
}

#[test]
fn the_library_sets_no_process_state() {
    let files = library_sources(&PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("src"));
    assert!(files.len() > 50, "found {} sources", files.len());
    let forbidden = [
        "#[global_allocator]",
        "mi_option_set",
        "PR_SET_THP_DISABLE",
        "sched_setaffinity",
        "env::set_var",
        "env::remove_var",
        "set_global_parallelism",
    ];
    for file in &files {
        let whole = std::fs::read_to_string(file).unwrap();
        // The code, without its unit tests (which may set a hook to observe one).
        let text = whole.split("#[cfg(test)]").next().unwrap_or_default();
        for word in forbidden {
            assert!(
                !text.contains(word),
                "{} uses {word}: a process setting belongs to a program, not the library",
                file.display()
            );
        }
        let hooks = text.matches("panic::set_hook").count();
        assert!(
            hooks == 0,
            "{} sets the panic hook {hooks} times",
            file.display()
        );
    }
}

/// The library's core (everything but the harness, the command line and the programs in
/// `src/bin/`, which become the program's own crate) reads no environment variable outside
/// the files listed here, each a setting not yet passed as an explicit value: the progress
/// lines' interval, the mesh and data locations, gmsh's executable and the native solver's
/// split threshold. The linear-solver backend and the FEM's trace are explicit options
/// (`FemOptions::linear_solver`, `FemOptions::trace`, and the same in `MethodOptions`): no core
/// file may read them.
#[test]
fn the_core_reads_environment_variables_only_where_listed() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("src");
    let files = library_sources(&root);
    let program_side = ["harness", "cli"];
    let still_reading = [
        "heartbeat.rs",
        "mesh/provider.rs",
        "mesh/files.rs",
        "mesh/gmsh.rs",
        "sparse/mod.rs",
    ];
    let mut readers = Vec::new();
    for file in &files {
        let relative = file.strip_prefix(&root).unwrap();
        if program_side.iter().any(|p| relative.starts_with(p)) {
            continue;
        }
        let whole = std::fs::read_to_string(file).unwrap();
        let text = whole.split("#[cfg(test)]").next().unwrap_or_default();
        if text.contains("env::var") {
            readers.push(relative.to_string_lossy().replace('\\', "/"));
        }
    }
    for reader in &readers {
        assert!(
            still_reading.contains(&reader.as_str()),
            "src/{reader} reads an environment variable: the library takes its settings as \
             explicit values (a program reads the environment)"
        );
    }
    let sparse = std::fs::read_to_string(root.join("sparse/mod.rs")).unwrap();
    assert!(
        !sparse.contains("env::var(ENVIRONMENT_VARIABLE)"),
        "the library reads RINGCONTACT_LINEAR_SOLVER: the backend is an explicit option"
    );
}
