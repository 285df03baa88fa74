//! The library sets nothing process-wide: no global allocator, no allocator options, no
//! transparent-huge-page or thread-affinity calls, no environment variable set at run time, no
//! global parallelism of `faer`, and no panic hook (a program's hook may ask
//! `mesh::msh::inside_mesh_parser` to stay silent on a malformed mesh). Those choices belong to
//! a program (`src/bin/verify.rs`), so a program that links `ringcontact` gets none of them.
//! Checked on the library's sources (`crates/ringcontact/src`), where a regression would be
//! written.

mod common;

use std::path::PathBuf;

/// The library's sources.
fn library_sources() -> Vec<PathBuf> {
    common::rust_sources(&common::library_root())
}

#[test]
fn the_library_sets_no_process_state() {
    let files = library_sources();
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

/// The library reads no environment variable outside the files listed here, each a setting not
/// yet passed as an explicit value: the progress lines' interval, the mesh and data locations,
/// gmsh's executable and the native solver's split threshold. The linear-solver backend and the FEM's trace are explicit options
/// (`FemOptions::linear_solver`, `FemOptions::trace`, and the same in `MethodOptions`): no core
/// file may read them.
#[test]
fn the_core_reads_environment_variables_only_where_listed() {
    let root = common::library_root();
    let files = library_sources();
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
        let whole = std::fs::read_to_string(file).unwrap();
        let text = whole.split("#[cfg(test)]").next().unwrap_or_default();
        if text.contains("env::var") {
            readers.push(relative.to_string_lossy().replace('\\', "/"));
        }
    }
    for reader in &readers {
        assert!(
            still_reading.contains(&reader.as_str()),
            "{reader} reads an environment variable: the library takes its settings as \
             explicit values (a program reads the environment)"
        );
    }
    let sparse = std::fs::read_to_string(root.join("sparse/mod.rs")).unwrap();
    assert!(
        !sparse.contains("env::var(ENVIRONMENT_VARIABLE)"),
        "the library reads RINGCONTACT_LINEAR_SOLVER: the backend is an explicit option"
    );
}
