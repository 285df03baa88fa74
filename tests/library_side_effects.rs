//! The library sets nothing process-wide: no global allocator, no allocator options, no
//! transparent-huge-page or thread-affinity calls, no environment variable set at run time, no
//! global parallelism of `faer`, no panic hook (a program's hook may ask
//! `mesh::msh::inside_mesh_parser` to stay silent on a malformed mesh), nothing leaked and no
//! first-call-wins data directory. Those choices belong to a program (`src/bin/verify.rs`), so a program that links `ringcontact` gets none of them.
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
        "Box::leak",
        "mem::forget",
        "set_data_directory",
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

/// The library reads no environment variable: every setting is an explicit value (the backend,
/// the trace, the data's location and gmsh in `FemOptions`/`MethodOptions`, the progress lines'
/// interval, the native backend's split threshold), which a program fills from its own
/// environment. The one read is `PATH` in `mesh/gmsh.rs`, to find gmsh's file as the operating
/// system finds a program.
#[test]
fn the_library_reads_no_environment_variable() {
    let root = common::library_root();
    let mut readers = Vec::new();
    for file in &library_sources() {
        let relative = file.strip_prefix(&root).unwrap();
        let whole = std::fs::read_to_string(file).unwrap();
        let text = whole.split("#[cfg(test)]").next().unwrap_or_default();
        let reads = text.matches("env::var").count();
        let path_reads = text.matches("env::var_os(\"PATH\")").count();
        if reads > path_reads || (path_reads > 0 && !relative.ends_with("mesh/gmsh.rs")) {
            readers.push(relative.to_string_lossy().replace('\\', "/"));
        }
    }
    assert!(
        readers.is_empty(),
        "{} read an environment variable: the library takes its settings as explicit values (a \
         program reads the environment)",
        readers.join(", ")
    );
}
