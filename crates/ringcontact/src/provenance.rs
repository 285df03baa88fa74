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
    /// The provenance of a result of this process: its own command line, or the call that
    /// [`called_as`] names on this thread (a Python call into the library).
    pub fn of_this_process() -> Self {
        if let Some(call) = CALL.with(|c| c.borrow().clone()) {
            return Self {
                ringcontact_version: VERSION.to_string(),
                commit: COMMIT.to_string(),
                command: call,
            };
        }
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

thread_local! {
    /// The call that produces this thread's results, when it is not the process's command line.
    static CALL: std::cell::RefCell<Option<String>> = const { std::cell::RefCell::new(None) };
}

/// Run `work` with `call` (e.g. `ringcontact.dataset(small=True)`, from Python) recorded as the
/// command of the results it writes; the process's command line again afterwards.
pub fn called_as<T>(call: &str, work: impl FnOnce() -> T) -> T {
    /// Puts the previous call back when dropped, even when `work` panics.
    struct Restore(Option<String>);
    impl Drop for Restore {
        fn drop(&mut self) {
            CALL.with(|c| c.replace(self.0.take()));
        }
    }
    let _restore = Restore(CALL.with(|c| c.replace(Some(call.to_string()))));
    work()
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

    #[test]
    fn a_call_named_on_this_thread_is_the_command() {
        let inside = called_as(
            "ringcontact.dataset(small=True)",
            Provenance::of_this_process,
        );
        assert_eq!(inside.command, "ringcontact.dataset(small=True)");
        assert_ne!(Provenance::of_this_process().command, inside.command);
    }
}
