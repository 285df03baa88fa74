//! Progress on standard error: a bar redrawn in place on a terminal; elsewhere (pipes, CI logs,
//! scripts) a plain line at most every [`PLAIN_INTERVAL_S`] seconds, so that long runs are never
//! silent.

use std::io::{IsTerminal, Write};

/// Seconds between plain progress lines when standard error is not a terminal.
pub const PLAIN_INTERVAL_S: f64 = 10.0;

/// Progress of a sweep of known length.
pub struct Progress {
    label: String,
    total: usize,
    done: usize,
    enabled: bool,
    started: std::time::Instant,
    reported: std::time::Instant,
}

impl Progress {
    /// A bar for `total` steps, shown only on a terminal.
    pub fn new(label: &str, total: usize) -> Self {
        Self {
            label: label.to_string(),
            total: total.max(1),
            done: 0,
            enabled: std::io::stderr().is_terminal(),
            started: std::time::Instant::now(),
            reported: std::time::Instant::now(),
        }
    }

    /// One step done; `what` names it.
    pub fn tick(&mut self, what: &str) {
        self.done = (self.done + 1).min(self.total);
        if !self.enabled {
            if self.reported.elapsed().as_secs_f64() >= PLAIN_INTERVAL_S && self.done < self.total {
                self.reported = std::time::Instant::now();
                eprintln!(
                    "{}: {}/{} done after {:.0} s ({})",
                    self.label,
                    self.done,
                    self.total,
                    self.started.elapsed().as_secs_f64(),
                    what.chars().take(60).collect::<String>()
                );
            }
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
