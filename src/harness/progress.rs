//! A plain text progress bar on standard error, drawn only when standard error is a terminal
//! (quiet in pipes, CI logs and scripts).

use std::io::{IsTerminal, Write};

/// Progress of a sweep of known length.
pub struct Progress {
    label: String,
    total: usize,
    done: usize,
    enabled: bool,
}

impl Progress {
    /// A bar for `total` steps, shown only on a terminal.
    pub fn new(label: &str, total: usize) -> Self {
        Self {
            label: label.to_string(),
            total: total.max(1),
            done: 0,
            enabled: std::io::stderr().is_terminal(),
        }
    }

    /// One step done; `what` names it.
    pub fn tick(&mut self, what: &str) {
        self.done = (self.done + 1).min(self.total);
        if !self.enabled {
            return;
        }
        let width = 30;
        let filled = width * self.done / self.total;
        let what: String = what.chars().take(40).collect();
        eprint!(
            "\r{} [{}{}] {}/{} {:<40}",
            self.label,
            "#".repeat(filled),
            ".".repeat(width - filled),
            self.done,
            self.total,
            what
        );
        let _ = std::io::stderr().flush();
        if self.done == self.total {
            eprintln!();
        }
    }
}
