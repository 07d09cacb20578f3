//! Progress spinners on stderr for long work: shown only when stderr is a terminal and the
//! global `--quiet` flag is off; cleared when the work is done.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;

static QUIET: AtomicBool = AtomicBool::new(false);

/// Silences all progress output (the `--quiet` flag).
pub fn set_quiet(quiet: bool) {
    QUIET.store(quiet, Ordering::Relaxed);
}

/// Whether notes and progress should be printed.
pub fn quiet() -> bool {
    QUIET.load(Ordering::Relaxed)
}

/// Prints a note on stderr unless `--quiet`.
pub fn note(msg: impl AsRef<str>) {
    if !quiet() {
        eprintln!("note: {}", msg.as_ref());
    }
}

/// `eprintln!` unless `--quiet`: the summary lines of a command ("refined ...", "wrote ...").
#[macro_export]
macro_rules! say {
    ($($arg:tt)*) => {
        if !$crate::progress::quiet() {
            eprintln!($($arg)*);
        }
    };
}

/// A spinner naming the current stage of a long task. It starts hidden and appears after a
/// second, so short work leaves no trace; it is cleared when dropped.
#[derive(Debug)]
pub struct Progress {
    bar: Option<(ProgressBar, Arc<Mutex<bool>>)>,
}

impl Progress {
    /// Starts a spinner (a no-op without a terminal or with `--quiet`).
    pub fn start(msg: impl Into<String>) -> Progress {
        if quiet() || !std::io::stderr().is_terminal() {
            return Progress { bar: None };
        }
        let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::hidden());
        bar.set_style(
            ProgressStyle::with_template("{spinner} {msg} [{elapsed}]")
                .unwrap_or_else(|_| ProgressStyle::default_spinner()),
        );
        bar.set_message(msg.into());
        let done = Arc::new(Mutex::new(false));
        let (b, d) = (bar.clone(), done.clone());
        std::thread::spawn(move || {
            std::thread::sleep(Duration::from_secs(1));
            if let Ok(done) = d.lock() {
                if !*done {
                    b.set_draw_target(ProgressDrawTarget::stderr());
                    b.enable_steady_tick(Duration::from_millis(120));
                }
            }
        });
        Progress {
            bar: Some((bar, done)),
        }
    }

    /// Names the next stage.
    pub fn stage(&self, msg: impl Into<String>) {
        if let Some((b, _)) = &self.bar {
            b.set_message(msg.into());
        }
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        if let Some((b, done)) = &self.bar {
            if let Ok(mut d) = done.lock() {
                *d = true;
            }
            b.finish_and_clear();
        }
    }
}
