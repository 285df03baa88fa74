//! Where the project's data lives and how files are named by their content: the data directory
//! (`--data-dir`, `RINGCONTACT_DATA_DIR`, else found upward from the current directory), the
//! committed meshes' and the mesh cache's directories, and SHA-256 digests.

use std::path::{Path, PathBuf};

use sha2::{Digest, Sha256};

use crate::error::{Error, Result};

/// Environment variable naming the project's data directory (`verify --data-dir` sets it).
pub const DATA_DIR_VARIABLE: &str = "RINGCONTACT_DATA_DIR";

/// The data directory a program chose (`verify --data-dir`), set once before any lookup.
static DATA_DIRECTORY: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();

/// Make `dir` the project's data directory for the rest of the process (what `verify
/// --data-dir` does; it takes precedence over `RINGCONTACT_DATA_DIR`). The first call wins.
pub fn set_data_directory(dir: PathBuf) {
    let _ = DATA_DIRECTORY.set(dir);
}

/// The project's data directory (the one holding `meshes/half_space.geo` and `verify/`):
/// `RINGCONTACT_DATA_DIR` (or `verify --data-dir`), else the first directory upward from the
/// current one that holds `meshes/half_space.geo`. Never a path compiled into the binary: a copy
/// of the checkout, a moved one or an installed binary reads the data of where it runs.
pub fn find_project_root() -> Result<PathBuf> {
    let marker = "meshes/half_space.geo";
    let chosen = DATA_DIRECTORY
        .get()
        .cloned()
        .or_else(|| std::env::var_os(DATA_DIR_VARIABLE).map(PathBuf::from));
    if let Some(dir) = chosen {
        if dir.join(marker).is_file() {
            return Ok(dir);
        }
        return Err(Error::file(
            "use as the data directory",
            &dir,
            format!("it has no {marker} (set by --data-dir or {DATA_DIR_VARIABLE})"),
        ));
    }
    let cwd = std::env::current_dir().map_err(|e| Error::file("find", Path::new("."), e))?;
    cwd.ancestors()
        .find(|dir| dir.join(marker).is_file())
        .map(Path::to_path_buf)
        .ok_or_else(|| {
            Error::file(
                "find the project's data from",
                &cwd,
                format!(
                    "no {marker} here or in any parent directory; run inside a checkout of the \
                     project, or pass --data-dir DIR (or set {DATA_DIR_VARIABLE}) to one"
                ),
            )
        })
}

/// [`find_project_root`], or the current directory when there is none (the error then surfaces
/// where a file is missing).
pub fn project_root() -> PathBuf {
    find_project_root().unwrap_or_else(|_| std::env::current_dir().unwrap_or_default())
}

/// Directory of the committed meshes (`RINGCONTACT_MESHES` overrides).
pub fn mesh_directory() -> PathBuf {
    std::env::var_os("RINGCONTACT_MESHES")
        .map(PathBuf::from)
        .unwrap_or_else(|| project_root().join("meshes"))
}

/// Directory of generated meshes.
pub fn cache_directory() -> PathBuf {
    cache_directory_of(&project_root())
}

/// Directory of generated meshes of the project at `root` (`RINGCONTACT_MESH_CACHE`
/// overrides); it also remembers gmsh's version (`crate::mesh::gmsh::Gmsh::find`).
pub fn cache_directory_of(root: &Path) -> PathBuf {
    std::env::var_os("RINGCONTACT_MESH_CACHE")
        .map(PathBuf::from)
        .unwrap_or_else(|| root.join(".mesh-cache"))
}

/// SHA-256 of a file, hex.
pub fn sha256_file(path: &Path) -> Result<String> {
    let bytes = std::fs::read(path).map_err(|e| Error::InvalidMesh {
        path: path.display().to_string(),
        message: format!("cannot read: {e}"),
    })?;
    Ok(sha256_hex(&bytes))
}

/// SHA-256 of `bytes`, hex.
pub fn sha256_hex(bytes: &[u8]) -> String {
    hex(&Sha256::digest(bytes))
}

/// Lower-case hexadecimal of `bytes` (a digest's usual spelling).
pub(crate) fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}
