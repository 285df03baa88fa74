//! Finding and running gmsh at run time (never at build time).
//!
//! Looked for, in order: the executable [`DataPaths::gmsh`] names (a program's choice, `verify`
//! reads `RINGCONTACT_GMSH`); the project's own environment `.venv-gmsh` (PyPI `gmsh`, made by
//! `scripts/install_gmsh.sh`; its `bin/gmsh` is a Python script, run with the environment's
//! interpreter); a `gmsh` executable on `PATH` (Debian's `gmsh`, or any other), resolved as the
//! operating system resolves a program. When none is found, the error names the one command that
//! installs it. The version each probe finds is remembered in the mesh cache
//! (`gmsh-version-*.txt`) until the files behind the command change.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::{Mutex, OnceLock};

use crate::error::{Error, Result};
use crate::mesh::files::{sha256_hex, DataPaths};

/// Longest a single gmsh run may take before it is stopped (the finest adapted level takes
/// about 5 s on 2 cores).
const MESHING_TIME_LIMIT_S: u64 = 300;

/// The command that installs gmsh for this project (quoted in errors).
pub(crate) const INSTALL_COMMAND: &str = "bash scripts/install_gmsh.sh";

/// A runnable gmsh: program plus leading arguments, and its version.
#[derive(Clone, Debug)]
pub struct Gmsh {
    program: PathBuf,
    prefix: Vec<String>,
    /// `gmsh --version`, e.g. `4.15.2`.
    pub version: String,
}

fn gmsh_error(message: String) -> Error {
    Error::Unsupported {
        method: "fem".into(),
        reason: message,
    }
}

/// Whether `text` reads as a version number (`4.15.2`): it starts with a digit and holds no
/// whitespace.
fn is_version(text: &str) -> bool {
    text.starts_with(|c: char| c.is_ascii_digit()) && !text.contains(char::is_whitespace)
}

/// Whether a file may be run (any execute bit on Unix).
fn is_executable(meta: &std::fs::Metadata) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        meta.is_file() && meta.permissions().mode() & 0o111 != 0
    }
    #[cfg(not(unix))]
    {
        meta.is_file()
    }
}

/// The file `program` names: itself when it holds a path, else the first executable of that
/// name in a directory of `PATH`.
fn resolve_program(program: &Path) -> Option<PathBuf> {
    if program.components().count() > 1 {
        return Some(program.to_path_buf());
    }
    std::env::split_paths(&std::env::var_os("PATH")?)
        .map(|dir| dir.join(program))
        .find(|candidate| std::fs::metadata(candidate).is_ok_and(|m| is_executable(&m)))
}

/// What identifies a gmsh command between runs: for the program (resolved on `PATH`) and each
/// leading argument that is a file, its canonical path (symbolic links followed), size and
/// modification time in nanoseconds. An upgrade or reinstall rewrites the files and changes it.
/// `None` when the program cannot be found.
fn command_identity(program: &Path, prefix: &[String]) -> Option<String> {
    let describe = |path: &Path| -> Option<String> {
        let canonical = std::fs::canonicalize(path).ok()?;
        let meta = std::fs::metadata(&canonical).ok()?;
        let modified = meta
            .modified()
            .ok()?
            .duration_since(std::time::UNIX_EPOCH)
            .ok()?
            .as_nanos();
        Some(format!("{} {} {modified}", canonical.display(), meta.len()))
    };
    let mut parts = vec![describe(&resolve_program(program)?)?];
    for arg in prefix {
        let path = Path::new(arg);
        parts.push(if path.is_file() {
            describe(path)?
        } else {
            arg.clone()
        });
    }
    Some(parts.join(" | "))
}

impl Gmsh {
    fn command(&self) -> Command {
        let mut c = Command::new(&self.program);
        c.args(&self.prefix);
        c
    }

    fn probe(program: PathBuf, prefix: Vec<String>) -> Option<Gmsh> {
        let mut probe = Gmsh {
            program,
            prefix,
            version: String::new(),
        };
        let output = probe.command().arg("--version").output().ok()?;
        if !output.status.success() {
            return None;
        }
        // gmsh prints its version on stderr (older) or stdout (newer).
        let text = format!(
            "{}{}",
            String::from_utf8_lossy(&output.stdout),
            String::from_utf8_lossy(&output.stderr)
        );
        let version = text.split_whitespace().next()?.to_string();
        if !is_version(&version) {
            return None;
        }
        probe.version = version;
        Some(probe)
    }

    /// [`Self::probe`], its version remembered in `memo_dir` for as long as the files behind the
    /// command are unchanged ([`command_identity`]): a probe of the project's gmsh starts Python
    /// and loads gmsh's library, 30-70 ms that every solve on cached meshes paid before it could
    /// look up its mesh (the cache key holds gmsh's version). A gmsh whose files cannot all be
    /// found is probed every time.
    fn probe_remembered(program: PathBuf, prefix: Vec<String>, memo_dir: &Path) -> Option<Gmsh> {
        let Some(identity) = command_identity(&program, &prefix) else {
            return Gmsh::probe(program, prefix);
        };
        let memo = memo_dir.join(format!(
            "gmsh-version-{}.txt",
            &sha256_hex(identity.as_bytes())[..16]
        ));
        let remembered = std::fs::read_to_string(&memo).ok().and_then(|text| {
            let mut lines = text.lines();
            // The identity is stored too: a hash collision is never taken for a match.
            (lines.next() == Some(identity.as_str()))
                .then(|| lines.next())
                .flatten()
                .map(str::trim)
                .filter(|v| is_version(v))
                .map(str::to_string)
        });
        if let Some(version) = remembered {
            return Some(Gmsh {
                program,
                prefix,
                version,
            });
        }
        let probed = Gmsh::probe(program, prefix)?;
        // Best effort: a cache that cannot be written only costs the next run a probe. Written
        // under a unique name, then renamed: a concurrent run never reads half a file.
        let partial = memo.with_extension(format!("{}.partial", std::process::id()));
        if std::fs::create_dir_all(memo_dir).is_ok()
            && std::fs::write(&partial, format!("{identity}\n{}\n", probed.version)).is_ok()
        {
            let _ = std::fs::rename(&partial, &memo);
        }
        Some(probed)
    }

    /// Find gmsh (see the module documentation) for the data of `data`, each probe's version
    /// remembered in its mesh cache ([`Self::probe_remembered`]).
    pub fn find(data: &DataPaths) -> Option<Gmsh> {
        let memo_dir = &data.cache;
        if let Some(path) = &data.gmsh {
            return Gmsh::probe_remembered(path.clone(), Vec::new(), memo_dir);
        }
        let venv = data.root.join(".venv-gmsh");
        let (python, script) = (venv.join("bin/python"), venv.join("bin/gmsh"));
        if python.exists() && script.exists() {
            if let Some(g) =
                Gmsh::probe_remembered(python, vec![script.display().to_string()], memo_dir)
            {
                return Some(g);
            }
        }
        Gmsh::probe_remembered(PathBuf::from("gmsh"), Vec::new(), memo_dir)
    }

    /// The gmsh of `data` (found once per data location in a process, then remembered), or the
    /// error that says how to get one; `why` says what the mesh was for.
    pub fn get(data: &DataPaths, why: &str) -> Result<Gmsh> {
        static FOUND: OnceLock<Mutex<HashMap<DataPaths, Option<Gmsh>>>> = OnceLock::new();
        let found = FOUND.get_or_init(Mutex::default);
        let known = found.lock().ok().and_then(|map| map.get(data).cloned());
        let gmsh = known.unwrap_or_else(|| {
            let probed = Gmsh::find(data);
            if let Ok(mut map) = found.lock() {
                map.insert(data.clone(), probed.clone());
            }
            probed
        });
        gmsh.ok_or_else(|| {
            let named = data
                .gmsh
                .as_ref()
                .map_or(String::new(), |p| format!("{}, ", p.display()));
            gmsh_error(format!(
                "{why} needs a mesh that is not committed, and gmsh was not found (looked for \
                 {named}{}/.venv-gmsh and `gmsh` on PATH); install it with `{INSTALL_COMMAND}`",
                data.root.display()
            ))
        })
    }

    /// Mesh `geo` in 2-D with `-setnumber` parameters, writing `out` (`.msh` 4.1).
    pub fn mesh(&self, geo: &Path, parameters: &[(String, f64)], out: &Path) -> Result<()> {
        let mut command = self.command();
        command.arg(geo).args(["-2", "-v", "1", "-format", "msh41"]);
        for (name, value) in parameters {
            command.args(["-setnumber", name, &format!("{value:e}")]);
        }
        command.arg("-o").arg(out);
        // stdout is not read (a full pipe would block gmsh); -v 1 keeps stderr to errors.
        command
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::piped());
        let mut child = command
            .spawn()
            .map_err(|e| gmsh_error(format!("cannot run gmsh: {e}")))?;
        // gmsh can stall on extreme size ratios instead of failing: never wait forever.
        let limit = std::time::Duration::from_secs(MESHING_TIME_LIMIT_S);
        let start = std::time::Instant::now();
        loop {
            match child.try_wait() {
                Ok(Some(_)) => break,
                Ok(None) if start.elapsed() > limit => {
                    let _ = child.kill();
                    let _ = child.wait();
                    let _ = std::fs::remove_file(out);
                    return Err(gmsh_error(format!(
                        "gmsh did not finish meshing {} within {MESHING_TIME_LIMIT_S} s \
                         (parameters {parameters:?}); stopped",
                        geo.display()
                    )));
                }
                Ok(None) => std::thread::sleep(std::time::Duration::from_millis(20)),
                Err(e) => return Err(gmsh_error(format!("cannot wait for gmsh: {e}"))),
            }
        }
        let output = child
            .wait_with_output()
            .map_err(|e| gmsh_error(format!("cannot read gmsh's output: {e}")))?;
        if !output.status.success() || !out.exists() {
            return Err(gmsh_error(format!(
                "gmsh failed on {} ({}): {}",
                geo.display(),
                output.status,
                String::from_utf8_lossy(&output.stderr)
                    .lines()
                    .take(5)
                    .collect::<Vec<_>>()
                    .join(" | ")
            )));
        }
        Ok(())
    }
}

#[cfg(all(test, unix))]
mod tests {
    use super::*;
    use std::os::unix::fs::PermissionsExt;

    /// A stand-in gmsh: a shell script that prints `version` and counts its runs in `runs`.
    fn fake_gmsh(dir: &Path, version: &str) -> PathBuf {
        let script = dir.join("gmsh");
        let runs = dir.join("runs");
        std::fs::write(
            &script,
            format!(
                "#!/bin/sh\necho x >> '{}'\necho {version}\n",
                runs.display()
            ),
        )
        .unwrap();
        std::fs::set_permissions(&script, std::fs::Permissions::from_mode(0o755)).unwrap();
        script
    }

    /// An empty scratch directory `ringcontact-gmsh-<name>-<pid>` under the system's temporary
    /// directory.
    fn scratch_dir(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("ringcontact-gmsh-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    fn runs(dir: &Path) -> usize {
        std::fs::read_to_string(dir.join("runs"))
            .map(|t| t.lines().count())
            .unwrap_or(0)
    }

    /// The version is probed once and remembered while the program's file is unchanged; a
    /// changed program (another size) is probed again and its new version reported.
    #[test]
    fn a_probed_version_is_remembered_until_the_program_changes() {
        let dir = scratch_dir("memo");
        let memo = dir.join("memo");
        let script = fake_gmsh(&dir, "4.15.2");
        let first = Gmsh::probe_remembered(script.clone(), Vec::new(), &memo).unwrap();
        let second = Gmsh::probe_remembered(script.clone(), Vec::new(), &memo).unwrap();
        assert_eq!(
            (first.version.as_str(), second.version.as_str()),
            ("4.15.2", "4.15.2")
        );
        assert_eq!(runs(&dir), 1, "the second probe ran the program again");
        fake_gmsh(&dir, "4.16.10");
        let third = Gmsh::probe_remembered(script, Vec::new(), &memo).unwrap();
        assert_eq!(third.version, "4.16.10");
        assert_eq!(runs(&dir), 2, "the changed program was not probed again");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// A program that prints no version is not gmsh, and nothing is remembered for it.
    #[test]
    fn a_program_without_a_version_is_not_gmsh() {
        let dir = scratch_dir("none");
        let script = fake_gmsh(&dir, "usage:");
        assert!(Gmsh::probe_remembered(script, Vec::new(), &dir.join("memo")).is_none());
        assert!(!dir.join("memo").exists());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
