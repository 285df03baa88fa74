//! Where the project's data lives and how files are named by their content: the data directory
//! (the one holding `meshes/half_space.geo`), its committed meshes, the mesh cache and gmsh, as
//! one explicit value ([`DataPaths`]) a program chooses; and SHA-256 digests.

use std::path::{Path, PathBuf};

use sha2::{Digest, Sha256};

use crate::error::{Error, Result};

/// The file that marks a directory as the project's data directory.
pub const DATA_MARKER: &str = "meshes/half_space.geo";

/// Where the FEM's data lives: the project's data directory, the committed meshes, the cache of
/// meshes gmsh made, and gmsh itself. A program builds it from its flags (`verify --data-dir`)
/// or its environment; the library never reads either. [`Default`] is the data directory found
/// upward from the current one (a checkout's), with the usual layout below it.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct DataPaths {
    /// The project's data directory (holding `meshes/half_space.geo` and `verify/`).
    pub root: PathBuf,
    /// The committed meshes (`root/meshes`).
    pub meshes: PathBuf,
    /// The meshes gmsh made, and the versions of gmsh probed (`root/.mesh-cache`).
    pub cache: PathBuf,
    /// gmsh's executable when chosen; else `root/.venv-gmsh` (made by
    /// `scripts/install_gmsh.sh`), then `gmsh` on the `PATH`.
    pub gmsh: Option<PathBuf>,
}

impl DataPaths {
    /// The usual layout below the data directory `root`: `meshes/`, `.mesh-cache/`, gmsh found.
    pub fn at(root: PathBuf) -> DataPaths {
        DataPaths {
            meshes: root.join("meshes"),
            cache: root.join(".mesh-cache"),
            gmsh: None,
            root,
        }
    }

    /// The data directory `dir` or the first one upward from it that holds
    /// [`DATA_MARKER`], with the usual layout; an error naming `dir` when there is none.
    pub fn find_from(dir: &Path) -> Result<DataPaths> {
        dir.ancestors()
            .find(|candidate| candidate.join(DATA_MARKER).is_file())
            .map(|root| DataPaths::at(root.to_path_buf()))
            .ok_or_else(|| {
                Error::file(
                    "find the project's data from",
                    dir,
                    format!(
                        "no {DATA_MARKER} here or in any parent directory; run inside a checkout \
                         of the project, or name the data directory (verify --data-dir DIR)"
                    ),
                )
            })
    }

    /// [`Self::find_from`] the current directory.
    pub fn find() -> Result<DataPaths> {
        let cwd = std::env::current_dir().map_err(|e| Error::file("find", Path::new("."), e))?;
        DataPaths::find_from(&cwd)
    }

    /// An error unless the data directory holds [`DATA_MARKER`] (a directory a user named that
    /// is not the project's data).
    pub fn check(&self) -> Result<()> {
        if self.root.join(DATA_MARKER).is_file() {
            return Ok(());
        }
        Err(Error::file(
            "use as the data directory",
            &self.root,
            format!("it has no {DATA_MARKER}"),
        ))
    }

    /// `path` relative to the data directory where it lies below it.
    pub fn display(&self, path: &Path) -> String {
        path.strip_prefix(&self.root)
            .unwrap_or(path)
            .display()
            .to_string()
    }
}

impl Default for DataPaths {
    /// [`DataPaths::find`], or the current directory's layout when no data directory is found
    /// (the error then surfaces where a file is missing, or from [`DataPaths::check`]).
    fn default() -> Self {
        DataPaths::find()
            .unwrap_or_else(|_| DataPaths::at(std::env::current_dir().unwrap_or_default()))
    }
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
