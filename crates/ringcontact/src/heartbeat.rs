//! Plain progress lines on standard error for long work that has no count of steps (a FEM
//! ladder's meshes and models): a watcher thread writes `<label>: <elapsed> s: <step>` every
//! [`plain_interval`] while the work runs, so that it is never silent for longer, and work
//! shorter than that writes nothing. The harness's counted sweeps use the same interval for
//! their plain lines (`crate::harness::progress`).

use std::sync::{mpsc, Arc, Mutex};
use std::time::{Duration, Instant};

/// Seconds between plain progress lines, unless `RINGCONTACT_PROGRESS_S` gives another
/// positive number ([`plain_interval`]).
pub const PLAIN_INTERVAL_S: f64 = 10.0;

/// [`PLAIN_INTERVAL_S`], or the positive number of seconds `RINGCONTACT_PROGRESS_S` gives.
pub fn plain_interval() -> Duration {
    let seconds = std::env::var("RINGCONTACT_PROGRESS_S")
        .ok()
        .and_then(|v| v.trim().parse::<f64>().ok())
        .filter(|s| s.is_finite() && *s > 0.0 && *s < 1e6)
        .unwrap_or(PLAIN_INTERVAL_S);
    Duration::from_secs_f64(seconds)
}

/// A watcher thread reporting the step a piece of work is at; stops when dropped.
pub struct Heartbeat {
    step: Arc<Mutex<String>>,
    stop: Option<mpsc::Sender<()>>,
    watcher: Option<std::thread::JoinHandle<()>>,
}

impl Heartbeat {
    /// Start reporting under `label` (the first line after one [`plain_interval`]).
    pub fn start(label: &str) -> Self {
        let step = Arc::new(Mutex::new("starting".to_string()));
        let (stop, stopped) = mpsc::channel::<()>();
        let shared = Arc::clone(&step);
        let label = label.to_string();
        let started = Instant::now();
        let interval = plain_interval();
        let watcher = std::thread::Builder::new()
            .name("heartbeat".into())
            .spawn(move || {
                while let Err(mpsc::RecvTimeoutError::Timeout) = stopped.recv_timeout(interval) {
                    let step = shared.lock().map(|s| s.clone()).unwrap_or_default();
                    eprintln!("{label}: {:.0} s: {step}", started.elapsed().as_secs_f64());
                }
            })
            .ok();
        Self {
            step,
            stop: Some(stop),
            watcher,
        }
    }

    /// The step the work is at, for the next line.
    pub fn set(&self, step: String) {
        if let Ok(mut current) = self.step.lock() {
            *current = step;
        }
    }
}

impl Drop for Heartbeat {
    fn drop(&mut self) {
        drop(self.stop.take());
        if let Some(watcher) = self.watcher.take() {
            let _ = watcher.join();
        }
    }
}
