//! Where a result comes from: this program's version, the commit it was built from and the
//! command that produced it (written beside the results of `verify table` and the dataset).

use serde::Serialize;

/// The crate's version (`Cargo.toml`).
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// The git commit the library was built from, `-dirty` appended when its sources differed from
/// it, `unknown` outside a git checkout (recorded by `build.rs`).
pub const COMMIT: &str = env!("RINGCONTACT_COMMIT");

/// Version, commit and command of a result.
#[derive(Clone, Debug, Serialize)]
pub struct Provenance {
    /// `ringcontact` version.
    pub ringcontact_version: String,
    /// Commit of the build ([`COMMIT`]).
    pub commit: String,
    /// The command line that produced the result, quoted for a POSIX shell.
    pub command: String,
}

impl Provenance {
    /// The provenance of a result of this process (its own command line).
    pub fn of_this_process() -> Self {
        let words: Vec<String> = std::env::args().collect();
        Self::of_command(&words)
    }

    /// The provenance of a result of the command `words` (program name first; its path is
    /// reduced to the file name).
    pub fn of_command(words: &[String]) -> Self {
        let mut quoted: Vec<String> = words.iter().map(|w| shell_quoted(w)).collect();
        if let Some(program) = words.first() {
            quoted[0] = std::path::Path::new(program)
                .file_name()
                .map(|n| shell_quoted(&n.to_string_lossy()))
                .unwrap_or_else(|| shell_quoted(program));
        }
        Self {
            ringcontact_version: VERSION.to_string(),
            commit: COMMIT.to_string(),
            command: quoted.join(" "),
        }
    }
}

/// `word` as a POSIX shell reads it back: unchanged when it holds only safe characters, else in
/// single quotes (a quote inside written `'\''`).
pub fn shell_quoted(word: &str) -> String {
    let safe = !word.is_empty()
        && word
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || "-_./:,=+@%".contains(c));
    if safe {
        word.to_string()
    } else {
        format!("'{}'", word.replace('\'', r"'\''"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn commands_are_quoted_for_the_shell() {
        let p = Provenance::of_command(&[
            "/tmp/target/release/verify".into(),
            "table".into(),
            "--eps".into(),
            "0.1:0.9:0.1".into(),
            "--scene".into(),
            "my scene's.toml".into(),
        ]);
        assert_eq!(
            p.command,
            r"verify table --eps 0.1:0.9:0.1 --scene 'my scene'\''s.toml'"
        );
        assert_eq!(p.ringcontact_version, VERSION);
        assert!(!p.commit.is_empty());
    }
}
