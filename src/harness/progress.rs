//! Progress on standard error: on a terminal an `indicatif` bar with rate and ETA, redrawn in
//! place; elsewhere (pipes, CI logs, scripts) a plain line at most every [`plain_interval`]
//! ([`PLAIN_INTERVAL_S`] seconds unless `RINGCONTACT_PROGRESS_S` says otherwise), so that long
//! runs are never silent (indicatif hides its bar there).

use std::io::IsTerminal;

use indicatif::{ProgressBar, ProgressStyle};

pub use ringcontact::heartbeat::PLAIN_INTERVAL_S;

/// [`PLAIN_INTERVAL_S`], or the positive number of seconds `RINGCONTACT_PROGRESS_S` gives.
pub fn plain_interval() -> std::time::Duration {
    let seconds = std::env::var("RINGCONTACT_PROGRESS_S")
        .ok()
        .and_then(|v| v.trim().parse::<f64>().ok())
        .filter(|s| s.is_finite() && *s > 0.0 && *s < 1e6)
        .unwrap_or(PLAIN_INTERVAL_S);
    std::time::Duration::from_secs_f64(seconds)
}

/// The progress lines this program's FEM solves write: every [`plain_interval`].
pub fn fem_progress() -> ringcontact::heartbeat::Progress {
    ringcontact::heartbeat::Progress::Every(plain_interval())
}

/// Progress of a sweep of known length.
pub(crate) struct Progress {
    label: String,
    total: usize,
    done: usize,
    bar: Option<ProgressBar>,
    started: std::time::Instant,
    reported: std::time::Instant,
    interval: std::time::Duration,
}

impl Progress {
    /// A bar for `total` steps (plain lines when standard error is not a terminal).
    pub fn new(label: &str, total: usize) -> Self {
        let total = total.max(1);
        let bar = std::io::stderr().is_terminal().then(|| {
            let bar = ProgressBar::new(total as u64);
            if let Ok(style) = ProgressStyle::with_template(
                "{prefix} [{bar:30}] {pos}/{len} ({per_sec}, ETA {eta}) {wide_msg}",
            ) {
                bar.set_style(style.progress_chars("#>."));
            }
            bar.set_prefix(label.to_string());
            bar
        });
        Self {
            label: label.to_string(),
            total,
            done: 0,
            bar,
            started: std::time::Instant::now(),
            reported: std::time::Instant::now(),
            interval: plain_interval(),
        }
    }

    /// `extra` more steps than announced (a sweep that found it needs them).
    pub fn grow(&mut self, extra: usize) {
        self.total += extra;
        if let Some(bar) = &self.bar {
            bar.set_length(self.total as u64);
        }
    }

    /// One step done; `what` names it.
    pub(crate) fn tick(&mut self, what: &str) {
        self.done = (self.done + 1).min(self.total);
        if let Some(bar) = &self.bar {
            bar.set_message(what.chars().take(60).collect::<String>());
            bar.inc(1);
            if self.done == self.total {
                bar.finish();
            }
            return;
        }
        if self.reported.elapsed() >= self.interval && self.done < self.total {
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
    }
}
