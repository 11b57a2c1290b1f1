//! Progress on standard error: a bar when standard error is a terminal; otherwise (a batch
//! job's log, Jupyter) one plain line when a stage starts, every few seconds while it runs and
//! when it ends, so that a long command is never silent.

use std::io::{IsTerminal as _, Write as _};
use std::sync::Mutex;
use std::time::{Duration, Instant};
use studies::progress::Progress;

/// Seconds between the plain lines of a stage.
const PLAIN_EVERY: Duration = Duration::from_secs(5);

/// [`Progress`] on standard error.
pub struct Terminal {
    interactive: bool,
    stage: Mutex<Stage>,
}

struct Stage {
    bar: Option<indicatif::ProgressBar>,
    what: String,
    len: usize,
    done: usize,
    started: Instant,
    printed: Instant,
}

impl Terminal {
    /// A bar if standard error is a terminal, plain lines otherwise.
    pub fn new() -> Self {
        let now = Instant::now();
        let stage = Stage { bar: None, what: String::new(), len: 0, done: 0, started: now, printed: now };
        Self { interactive: std::io::stderr().is_terminal(), stage: Mutex::new(stage) }
    }
}

fn line(s: &Stage, state: &str) {
    let _ = writeln!(
        std::io::stderr().lock(),
        "{}: {}/{} {state} ({:.0} s)",
        s.what,
        s.done,
        s.len,
        s.started.elapsed().as_secs_f64()
    );
}

impl Progress for Terminal {
    fn start(&self, len: usize, what: &str) {
        let Ok(mut s) = self.stage.lock() else { return };
        let now = Instant::now();
        *s = Stage { bar: None, what: what.to_string(), len, done: 0, started: now, printed: now };
        if self.interactive {
            let bar = indicatif::ProgressBar::new(len as u64);
            bar.set_style(
                indicatif::ProgressStyle::with_template("{msg:30} [{bar:30}] {pos}/{len} {elapsed}, eta {eta}")
                    .expect("a valid template")
                    .progress_chars("=> "),
            );
            bar.set_message(what.to_string());
            s.bar = Some(bar);
        } else {
            line(&s, "started");
        }
    }

    fn advance(&self, n: usize) {
        let Ok(mut s) = self.stage.lock() else { return };
        s.done += n;
        if let Some(bar) = &s.bar {
            bar.inc(n as u64);
        } else if s.printed.elapsed() >= PLAIN_EVERY {
            s.printed = Instant::now();
            line(&s, "done");
        }
    }

    fn finish(&self) {
        let Ok(mut s) = self.stage.lock() else { return };
        match s.bar.take() {
            Some(bar) => bar.finish_and_clear(),
            None if s.len > 0 => line(&s, "finished"),
            None => {}
        }
    }
}
