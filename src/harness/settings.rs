//! The program's choices that the library takes as explicit values: the linear-solver backend
//! of every FEM model the harness and the command line build (`verify --linear-solver`, else
//! the environment's `RINGCONTACT_LINEAR_SOLVER`, else the library's built-in one), and the
//! FEM's trace (`RINGCONTACT_TRACE`), the data's location (`verify --data-dir`, else
//! `RINGCONTACT_DATA_DIR`, else found upward from the current directory; `RINGCONTACT_MESHES`,
//! `RINGCONTACT_MESH_CACHE` and `RINGCONTACT_GMSH` move its parts) and the progress lines'
//! interval (`RINGCONTACT_PROGRESS_S`).

use std::path::PathBuf;
use std::sync::OnceLock;

use ringcontact::error::{Error, Result};
use ringcontact::mesh::files::{DataPaths, DATA_MARKER};
use ringcontact::methods::{Fem, MethodOptions};
use ringcontact::sparse::{Backend, ENVIRONMENT_VARIABLE};

/// Environment variable naming the project's data directory (`verify --data-dir` sets it).
pub const DATA_DIR_VARIABLE: &str = "RINGCONTACT_DATA_DIR";

static DATA_DIRECTORY: OnceLock<PathBuf> = OnceLock::new();

/// Make `dir` this program's data directory (`verify --data-dir`; it takes precedence over
/// `RINGCONTACT_DATA_DIR`), before any lookup. The first call wins.
pub fn choose_data_directory(dir: PathBuf) {
    let _ = DATA_DIRECTORY.set(dir);
}

/// This program's data ([`DataPaths`]): the chosen directory, else `RINGCONTACT_DATA_DIR`, else
/// the first directory upward from the current one holding `meshes/half_space.geo`; its parts
/// moved by `RINGCONTACT_MESHES`, `RINGCONTACT_MESH_CACHE` and `RINGCONTACT_GMSH`. An error
/// names a chosen directory that is not the project's data, or the absence of one. Looked up
/// once per process; a failed lookup is tried again.
pub fn find_data() -> Result<DataPaths> {
    static FOUND: OnceLock<DataPaths> = OnceLock::new();
    if let Some(data) = FOUND.get() {
        return Ok(data.clone());
    }
    let data = locate_data()?;
    Ok(FOUND.get_or_init(|| data).clone())
}

/// [`find_data`]'s lookup.
fn locate_data() -> Result<DataPaths> {
    let chosen = DATA_DIRECTORY
        .get()
        .cloned()
        .or_else(|| std::env::var_os(DATA_DIR_VARIABLE).map(PathBuf::from));
    let mut data = match chosen {
        Some(dir) => {
            let data = DataPaths::at(dir);
            data.check().map_err(|_| {
                Error::file(
                    "use as the data directory",
                    &data.root,
                    format!("it has no {DATA_MARKER} (set by --data-dir or {DATA_DIR_VARIABLE})"),
                )
            })?;
            data
        }
        None => DataPaths::find().map_err(|e| {
            Error::file(
                "find the project's data",
                &std::env::current_dir().unwrap_or_default(),
                format!("{e} (or set {DATA_DIR_VARIABLE})"),
            )
        })?,
    };
    if let Some(meshes) = std::env::var_os("RINGCONTACT_MESHES") {
        data.meshes = PathBuf::from(meshes);
    }
    if let Some(cache) = std::env::var_os("RINGCONTACT_MESH_CACHE") {
        data.cache = PathBuf::from(cache);
    }
    if let Some(gmsh) = std::env::var_os("RINGCONTACT_GMSH") {
        data.gmsh = Some(PathBuf::from(gmsh));
    }
    Ok(data)
}

/// [`find_data`], or the current directory's layout when there is none (the error then
/// surfaces where a file is missing).
pub fn data_paths() -> DataPaths {
    find_data().unwrap_or_else(|_| DataPaths::at(std::env::current_dir().unwrap_or_default()))
}

/// This program's data directory ([`data_paths`]).
pub fn project_root() -> PathBuf {
    data_paths().root
}

/// This program's committed meshes ([`data_paths`]).
pub fn mesh_directory() -> PathBuf {
    data_paths().meshes
}

static LINEAR_SOLVER: OnceLock<Backend> = OnceLock::new();

/// Choose the backend of this program's FEM models (the `verify` binary's `--linear-solver`),
/// before any is built; only the first choice counts. Returns whether it was taken.
pub fn choose_linear_solver(backend: Backend) -> bool {
    let backend = with_split_threshold(backend);
    LINEAR_SOLVER.set(backend).is_ok() || LINEAR_SOLVER.get() == Some(&backend)
}

/// `backend` with the native factorisation's split threshold `RINGCONTACT_SPLIT_MIN_DOFS` when
/// the environment gives one (to compare the split factorisation with the whole one on the
/// same model, `scripts/linear_solver_speed.py`).
fn with_split_threshold(backend: Backend) -> Backend {
    let threshold = std::env::var("RINGCONTACT_SPLIT_MIN_DOFS")
        .ok()
        .and_then(|v| v.trim().parse().ok());
    match (backend, threshold) {
        (Backend::Native { .. }, Some(split_min_dofs)) => Backend::Native { split_min_dofs },
        _ => backend,
    }
}

/// The backend this program's FEM models use: the one chosen, else the environment's
/// `RINGCONTACT_LINEAR_SOLVER` (an unknown name is refused by the binary, ignored here), else
/// [`Backend::BUILT_IN`].
pub fn linear_solver() -> Backend {
    *LINEAR_SOLVER.get_or_init(|| {
        let named = std::env::var(ENVIRONMENT_VARIABLE)
            .ok()
            .and_then(|name| name.parse().ok());
        with_split_threshold(named.unwrap_or_default())
    })
}

/// Whether this program's FEM models trace each model on standard error (`RINGCONTACT_TRACE`
/// set).
pub fn trace() -> bool {
    std::env::var_os("RINGCONTACT_TRACE").is_some()
}

/// Method options with nothing set but this program's [`linear_solver`], [`trace`], data and
/// progress lines.
pub fn method_options() -> MethodOptions {
    MethodOptions {
        linear_solver: Some(linear_solver()),
        trace: trace(),
        data: Some(data_paths()),
        progress: crate::harness::progress::fem_progress(),
        ..MethodOptions::default()
    }
}

/// The FEM with this program's [`linear_solver`], [`trace`], data and progress lines, its other
/// options at their defaults.
pub fn fem() -> Fem {
    Fem {
        linear_solver: Some(linear_solver()),
        trace: trace(),
        data: Some(data_paths()),
        progress: crate::harness::progress::fem_progress(),
        ..Fem::default()
    }
}
