//! Stored external results: small JSON files, one per run, in a directory of the repository.

use std::path::{Path, PathBuf};

use serde::de::DeserializeOwned;

use ringcontact::error::{Error, Result};

/// Read every `*.json` in `dir` as a `T`, sorted by file name; `what` names the kind of result in
/// errors. A missing or unreadable directory is an error (a comparison must not silently compare
/// nothing).
pub fn load_json_dir<T: DeserializeOwned>(dir: &Path, what: &str) -> Result<Vec<(String, T)>> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(|e| Error::file(&format!("read the directory of each {what} in"), dir, e))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .collect();
    files.sort();
    files
        .into_iter()
        .map(|path| {
            let text = std::fs::read_to_string(&path).map_err(|e| Error::file("read", &path, e))?;
            let result = serde_json::from_str(&text)
                .map_err(|e| Error::file("parse", &path, format!("not a {what}: {e}")))?;
            let name = path
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default();
            Ok((name, result))
        })
        .collect()
}
