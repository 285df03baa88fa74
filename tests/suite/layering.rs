//! The library's layout keeps its layers (docs/architecture.md): each top-level module of the
//! library (`crates/ringcontact/src`) and of the program's crate (`src`: the harness, the
//! command line) belongs to a layer, and no file imports a module of a higher layer; no files
//! import each other, directly or around a circle; no folder holds more than twelve files; `unsafe` code and
//! `faer`'s internal supernodal layouts stay inside the native linear-algebra backend
//! (`sparse/native/`; the one CPU prefetch hint in `numerics/prefetch.rs` aside). The library
//! depends on no command-line crate (its manifest).
//! Read from the sources (`crate::` paths outside comments and unit tests).

use crate::common;

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// Layer of each top-level module, from the ground up.
const LAYERS: [(&str, u8); 24] = [
    ("choice", 0),
    ("error", 0),
    ("finite_guard", 0),
    ("heartbeat", 0),
    ("numerics", 0),
    ("provenance", 0),
    ("sparse", 1),
    ("punch", 1),
    ("mesh", 2),
    ("discretisation", 3),
    ("fem", 4),
    ("bem", 4),
    ("reference", 4),
    ("scene", 6),
    ("solution", 6),
    ("methods", 6),
    ("fit", 7),
    ("adhesion", 7),
    ("cohesive", 7),
    ("dugdale", 7),
    ("harness", 8),
    ("cli", 9),
    ("lib", 10),
    ("bin", 10),
];

/// `src/a/b.rs` -> `a::b`, `src/a/mod.rs` -> `a`.
fn module_of(src: &Path, file: &Path) -> String {
    let relative = file.strip_prefix(src).unwrap().with_extension("");
    let parts: Vec<String> = relative
        .components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .filter(|p| p != "mod")
        .collect();
    parts.join("::")
}

/// The code of a file without its unit tests and comments.
fn code_of(file: &Path) -> String {
    let whole = std::fs::read_to_string(file).unwrap();
    let code = whole.split("#[cfg(test)]").next().unwrap_or_default();
    code.lines()
        .map(|line| line.split("//").next().unwrap_or_default())
        .collect::<Vec<_>>()
        .join("\n")
}

/// The modules `code` names through `crate::` paths (the longest path that is a module).
fn imports(code: &str, modules: &BTreeSet<String>) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    for (i, _) in code.match_indices("crate::") {
        let rest = &code[i + "crate::".len()..];
        let path: String = rest
            .chars()
            .take_while(|c| c.is_ascii_alphanumeric() || *c == '_' || *c == ':')
            .collect();
        let parts: Vec<&str> = path.split("::").filter(|p| !p.is_empty()).collect();
        for k in (1..=parts.len()).rev() {
            let candidate = parts[..k].join("::");
            if modules.contains(&candidate) {
                out.insert(candidate);
                break;
            }
        }
    }
    out
}

fn layer(module: &str) -> u8 {
    let top = module.split("::").next().unwrap();
    LAYERS
        .iter()
        .find(|(name, _)| *name == top)
        .unwrap_or_else(|| panic!("module {module} has no layer in tests/suite/layering.rs"))
        .1
}

#[test]
fn no_import_runs_up_a_layer_and_no_files_import_each_other() {
    check_layers(&common::library_root());
    check_layers(&common::program_root());
}

/// The layers of one crate whose sources are below `src` (`crate::` paths name its modules).
fn check_layers(src: &Path) {
    let files = common::rust_sources(src);
    let modules: BTreeSet<String> = files.iter().map(|f| module_of(src, f)).collect();
    let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for file in &files {
        let module = module_of(src, file);
        let mut uses = imports(&code_of(file), &modules);
        uses.remove(&module);
        for used in &uses {
            assert!(
                layer(used) <= layer(&module),
                "{module} imports {used}, a higher layer"
            );
        }
        graph.insert(module, uses);
    }
    // A circle: a module reached again from itself.
    for start in graph.keys() {
        let mut stack: Vec<(String, Vec<String>)> = vec![(start.clone(), vec![start.clone()])];
        let mut seen = BTreeSet::new();
        while let Some((module, path)) = stack.pop() {
            for next in graph.get(&module).into_iter().flatten() {
                if next == start {
                    panic!("import circle: {} -> {start}", path.join(" -> "));
                }
                if seen.insert(next.clone()) {
                    let mut longer = path.clone();
                    longer.push(next.clone());
                    stack.push((next.clone(), longer));
                }
            }
        }
    }
}

#[test]
fn folders_are_small_and_unsafe_code_stays_in_the_native_backend() {
    let src = common::library_root();
    let mut files = common::rust_sources(&src);
    files.extend(common::rust_sources(&common::program_root()));
    let mut per_folder: BTreeMap<PathBuf, usize> = BTreeMap::new();
    for file in &files {
        *per_folder
            .entry(file.parent().unwrap().to_path_buf())
            .or_default() += 1;
    }
    for (folder, count) in per_folder {
        assert!(count <= 12, "{} holds {count} files", folder.display());
    }
    let native = src.join("sparse").join("native");
    let faer_internals = [
        "supernodal::",
        "EliminationTreeRef",
        "SymbolicSupernodalCholesky",
    ];
    for file in &files {
        if file.starts_with(&native) {
            continue;
        }
        let code = code_of(file);
        if !file.ends_with("numerics/prefetch.rs") {
            assert!(
                !code.contains("unsafe"),
                "{} holds unsafe code outside the native backend",
                file.display()
            );
        }
        for word in faer_internals {
            assert!(
                !code.contains(word),
                "{} reads faer's internal layout ({word}) outside the native backend",
                file.display()
            );
        }
    }
}

/// The library crate carries no command line, progress bars, markdown renderer or allocator:
/// those belong to the program's crate (the root `Cargo.toml`).
#[test]
fn the_library_depends_on_no_program_crate() {
    let manifest = common::library_root().parent().unwrap().join("Cargo.toml");
    let text = std::fs::read_to_string(&manifest).unwrap();
    let table: toml::Table = text.parse().unwrap();
    let dependencies = table["dependencies"].as_table().unwrap();
    assert!(dependencies.contains_key("faer"), "read the wrong manifest");
    for program_crate in ["clap", "indicatif", "pulldown-cmark", "mimalloc"] {
        assert!(
            !dependencies.contains_key(program_crate),
            "{} depends on {program_crate}: it belongs to the program's crate",
            manifest.display()
        );
    }
}

/// The harness and the command line reach the methods through their types (`methods::RingBem`,
/// `Fem`, `GridBem` with their typed options and states; `methods::Solver`; `Method::ladder` for
/// convergence levels): no file names the BEM's or the FEM's modules, the linear algebra's
/// backends, nor the discretisation but its operator export (`discretisation::export`, what the
/// FEniCSx operator comparison reads).
#[test]
fn the_harness_names_no_bem_or_fem_module() {
    let root = common::program_root();
    let files = common::rust_sources(&root);
    assert!(!files.is_empty(), "no harness sources found");
    let mut naming = Vec::new();
    for file in files {
        let code = code_of(&file).replace("ringcontact::discretisation::export", "");
        for internal in [
            "ringcontact::bem",
            "ringcontact::fem",
            "ringcontact::discretisation",
            "ringcontact::sparse::native",
            "ringcontact::sparse::constrained",
        ] {
            if code.contains(internal) {
                naming.push(format!("{} names {internal}", file.display()));
            }
        }
    }
    assert!(
        naming.is_empty(),
        "{naming:#?}: ask the methods (methods::RingBem, Fem, GridBem, Solver, Method::ladder) \
         instead"
    );
}

/// How far a built-in punch spreads: the files of the library's and the program's sources that
/// name it (in code or prose), at most four: its own, the registry (`punch.rs`), the command
/// line's flag list (`cli/args.rs`) and the harness's case list (`harness/cases.rs`). Everything
/// else asks the profile (its contact, closure, references) or the registry (names by contact),
/// and prose names a profile by its geometry (a fixed annulus, a linear or parabolic gap).
#[test]
fn built_in_punch_names_spread_no_further() {
    // Each name as runs of lower-case words (`PunchKind::FLAT` is `punchkind flat`).
    let names: [(&str, &[&str], usize); 7] = [
        (
            "flat",
            &["flat punch", "punchkind flat", "punchname flat"],
            4,
        ),
        (
            "flat-annulus",
            &[
                "flat annulus",
                "flat annular",
                "flatannulus",
                "flat_annulus",
            ],
            4,
        ),
        ("cone", &["cone", "cones", "conical"], 4),
        ("sphere", &["sphere", "spheres", "spherical"], 4),
        (
            "power",
            &["power law", "punchname power", "punchkind power"],
            4,
        ),
        ("torus", &["torus", "tori"], 3),
        (
            "table",
            &["table punch", "punchname table", "tableprofile"],
            4,
        ),
    ];
    let mut files = common::rust_sources(&common::library_root());
    files.extend(common::rust_sources(&common::program_root()));
    let texts: Vec<(String, String)> = files
        .iter()
        .map(|file| {
            let text = std::fs::read_to_string(file).unwrap().to_lowercase();
            let words: Vec<&str> = text
                .split(|c: char| !c.is_alphanumeric() && c != '_')
                .filter(|w| !w.is_empty())
                .collect();
            (file.display().to_string(), format!(" {} ", words.join(" ")))
        })
        .collect();
    let mut too_far = Vec::new();
    for (punch, patterns, ceiling) in names {
        let naming: Vec<&str> = texts
            .iter()
            .filter(|(_, words)| patterns.iter().any(|p| words.contains(&format!(" {p} "))))
            .map(|(file, _)| file.as_str())
            .collect();
        println!("{punch}: {} files", naming.len());
        if naming.len() > ceiling {
            too_far.push(format!(
                "{punch}: {} files, ceiling {ceiling}: {naming:#?}",
                naming.len()
            ));
        }
    }
    assert!(
        too_far.is_empty(),
        "a built-in punch is named in more files than before (ask the profile, or take the \
         state from harness/cases.rs):\n{}",
        too_far.join("\n")
    );
}
