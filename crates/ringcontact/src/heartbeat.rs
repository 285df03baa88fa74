//! Plain progress lines on standard error for long work that has no count of steps (a FEM
//! ladder's meshes and models): a watcher thread writes `<label>: <elapsed> s: <step>` every
//! interval a [`Progress`] gives while the work runs, so that it is never silent for longer,
//! and work shorter than that writes nothing. A program chooses the interval (`verify` reads
//! `RINGCONTACT_PROGRESS_S`); the library reads nothing.

use std::sync::{mpsc, Arc, Mutex};
use std::time::{Duration, Instant};

/// Seconds between plain progress lines by default ([`Progress::default`]).
pub const PLAIN_INTERVAL_S: f64 = 10.0;

/// How often long work reports on standard error.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Progress {
    /// A line every this long while the work runs.
    Every(Duration),
    /// No lines.
    Silent,
}

impl Default for Progress {
    /// A line every [`PLAIN_INTERVAL_S`] seconds.
    fn default() -> Self {
        Progress::Every(Duration::from_secs_f64(PLAIN_INTERVAL_S))
    }
}

/// A watcher thread reporting the step a piece of work is at; stops when dropped.
pub struct Heartbeat {
    step: Arc<Mutex<String>>,
    stop: Option<mpsc::Sender<()>>,
    watcher: Option<std::thread::JoinHandle<()>>,
}

impl Heartbeat {
    /// Start reporting under `label` as `progress` says (the first line after one interval).
    pub fn start(label: &str, progress: Progress) -> Self {
        let step = Arc::new(Mutex::new("starting".to_string()));
        let (stop, stopped) = mpsc::channel::<()>();
        let shared = Arc::clone(&step);
        let label = label.to_string();
        let started = Instant::now();
        let watcher = match progress {
            Progress::Silent => None,
            Progress::Every(interval) => std::thread::Builder::new()
                .name("heartbeat".into())
                .spawn(move || {
                    while let Err(mpsc::RecvTimeoutError::Timeout) = stopped.recv_timeout(interval)
                    {
                        let step = shared.lock().map(|s| s.clone()).unwrap_or_default();
                        eprintln!("{label}: {:.0} s: {step}", started.elapsed().as_secs_f64());
                    }
                })
                .ok(),
        };
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
