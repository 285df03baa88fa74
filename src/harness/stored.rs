//! Stored external results: small JSON files, one per run, in a directory of the repository.

use std::path::{Path, PathBuf};

use serde::de::DeserializeOwned;

use crate::error::{Error, Result};

/// Read every `*.json` in `dir` as a `T`, sorted by file name; `what` names the kind of result in
/// errors. A missing directory is an empty list.
pub fn load_json_dir<T: DeserializeOwned>(dir: &Path, what: &str) -> Result<Vec<(String, T)>> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|entries| {
            entries
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| p.extension().is_some_and(|x| x == "json"))
                .collect()
        })
        .unwrap_or_default();
    files.sort();
    files
        .into_iter()
        .map(|path| {
            let text = std::fs::read_to_string(&path).map_err(|e| Error::SceneFile {
                path: path.display().to_string(),
                message: e.to_string(),
            })?;
            let result = serde_json::from_str(&text).map_err(|e| Error::SceneFile {
                path: path.display().to_string(),
                message: format!("not a {what}: {e}"),
            })?;
            let name = path
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default();
            Ok((name, result))
        })
        .collect()
}
