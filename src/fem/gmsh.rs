//! Finding and running gmsh at run time (never at build time).
//!
//! Looked for, in order: the executable named by `RINGCONTACT_GMSH`; the project's own
//! environment `.venv-gmsh` (PyPI `gmsh`, made by `scripts/install_gmsh.sh`; its `bin/gmsh` is a
//! Python script, run with the environment's interpreter); a `gmsh` executable on `PATH`
//! (Debian's `gmsh`, or any other). When none is found, the error names the one command that
//! installs it.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use crate::error::{Error, Result};

/// Longest a single gmsh run may take before it is stopped (the finest adapted level takes
/// about 5 s on 2 cores).
pub const MESHING_TIME_LIMIT_S: u64 = 300;

/// The command that installs gmsh for this project (quoted in errors).
pub const INSTALL_COMMAND: &str = "bash scripts/install_gmsh.sh";

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
        if !version.starts_with(|c: char| c.is_ascii_digit()) {
            return None;
        }
        probe.version = version;
        Some(probe)
    }

    /// Find gmsh (see the module documentation); `project` is the project's root directory.
    pub fn find(project: &Path) -> Option<Gmsh> {
        if let Some(path) = std::env::var_os("RINGCONTACT_GMSH") {
            return Gmsh::probe(PathBuf::from(path), Vec::new());
        }
        let venv = project.join(".venv-gmsh");
        let (python, script) = (venv.join("bin/python"), venv.join("bin/gmsh"));
        if python.exists() && script.exists() {
            if let Some(g) = Gmsh::probe(python, vec![script.display().to_string()]) {
                return Some(g);
            }
        }
        Gmsh::probe(PathBuf::from("gmsh"), Vec::new())
    }

    /// The gmsh of this process (found once and remembered), or the error that says how to get
    /// one; `why` says what the mesh was for.
    pub fn get(project: &Path, why: &str) -> Result<Gmsh> {
        static FOUND: OnceLock<Option<Gmsh>> = OnceLock::new();
        FOUND
            .get_or_init(|| Gmsh::find(project))
            .clone()
            .ok_or_else(|| {
                gmsh_error(format!(
                    "{why} needs a mesh that is not committed, and gmsh was not found (looked for \
                     $RINGCONTACT_GMSH, {}/.venv-gmsh and `gmsh` on PATH); install it with `{INSTALL_COMMAND}`",
                    project.display()
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
