//! Running the `impact` binary as a user does, keeping what it printed for the checks.
//!
//! `impact(args)` sets up one run; `.arg`, `.env`, `.current_dir` and `.stdin` add to it; it
//! starts with `.run()` (any exit), `.success()`, `.fails()` or `.fails_with(code)`, the last
//! three panicking with the command line and its standard error when the exit is not the
//! one expected. `.within(seconds)` kills a run that outlives its time and fails the test, so
//! that a test of a bounded run cannot hang CI.

use std::ffi::OsStr;
use std::io::Write as _;
use std::path::Path;
use std::process::{Command, ExitStatus, Stdio};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// The binary under test, built by Cargo for the integration tests.
pub const BIN: &str = env!("CARGO_BIN_EXE_impact");

/// `impact` with `args`; see the module's description.
pub fn impact<S: AsRef<OsStr>>(args: impl IntoIterator<Item = S>) -> Impact {
    Impact { command: Command::new(BIN), shown: vec!["impact".into()], dir: None, stdin: None, limit: None }.args(args)
}

/// One run of `impact`, not yet started.
pub struct Impact {
    command: Command,
    /// The command line as a user would type it, for the panic messages.
    shown: Vec<String>,
    /// The working directory, if not the test's.
    dir: Option<String>,
    stdin: Option<Vec<u8>>,
    /// The longest the run may take before it is killed and the test fails.
    limit: Option<Duration>,
}

/// What a run of `impact` did.
pub struct Run {
    /// The command line, environment and working directory, as the panic messages show them.
    pub command: String,
    pub status: ExitStatus,
    pub stdout: Vec<u8>,
    /// Standard error, lossily UTF-8 (the checks read it as text).
    pub stderr: String,
}

impl Impact {
    pub fn arg(mut self, arg: impl AsRef<OsStr>) -> Self {
        self.shown.push(arg.as_ref().to_string_lossy().into_owned());
        self.command.arg(arg);
        self
    }

    pub fn args<S: AsRef<OsStr>>(self, args: impl IntoIterator<Item = S>) -> Self {
        args.into_iter().fold(self, Impact::arg)
    }

    pub fn env(mut self, key: &str, value: &str) -> Self {
        self.shown.insert(0, format!("{key}={value}"));
        self.command.env(key, value);
        self
    }

    pub fn current_dir(mut self, dir: &Path) -> Self {
        self.dir = Some(dir.display().to_string());
        self.command.current_dir(dir);
        self
    }

    /// Feeds `bytes` to the program's standard input (by default it reads end of file).
    pub fn stdin(mut self, bytes: impl Into<Vec<u8>>) -> Self {
        self.stdin = Some(bytes.into());
        self
    }

    /// Kills the run, failing the test, if it has not ended after `seconds`.
    pub fn within(mut self, seconds: u64) -> Self {
        self.limit = Some(Duration::from_secs(seconds));
        self
    }

    /// Runs to the end, whatever the exit.
    pub fn run(mut self) -> Run {
        let mut command = self.shown.join(" ");
        if let Some(dir) = &self.dir {
            command += &format!(" (in {dir})");
        }
        let mut child = self
            .command
            .stdin(if self.stdin.is_some() { Stdio::piped() } else { Stdio::null() })
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap_or_else(|e| panic!("`{command}` did not start: {e}"));
        // A program that exits without reading all of its input closes the pipe: not an error
        // of the run, whose exit the caller checks.
        let writer = self.stdin.take().map(|bytes| {
            let mut pipe = child.stdin.take().expect("a piped standard input");
            std::thread::spawn(move || {
                let _ = pipe.write_all(&bytes);
            })
        });
        let started = Instant::now();
        let ended = Arc::new(AtomicBool::new(false));
        if let Some(limit) = self.limit {
            watchdog(child.id(), limit, ended.clone());
        }
        let output = child.wait_with_output().unwrap_or_else(|e| panic!("`{command}`: {e}"));
        ended.store(true, Ordering::SeqCst);
        if let Some(limit) = self.limit.filter(|l| started.elapsed() >= *l) {
            panic!("`{command}` did not end within {} s and was killed", limit.as_secs());
        }
        if let Some(w) = writer {
            w.join().expect("the standard input writer");
        }
        Run::new(command, output)
    }

    /// Runs, and panics unless the program exits with 0.
    #[track_caller]
    pub fn success(self) -> Run {
        let r = self.run();
        if !r.status.success() {
            r.unexpected("success");
        }
        r
    }

    /// Runs, and panics if the program exits with 0.
    #[track_caller]
    pub fn fails(self) -> Run {
        let r = self.run();
        if r.status.success() {
            r.unexpected("failure");
        }
        r
    }

    /// Runs, and panics unless the program exits with `code`.
    #[track_caller]
    pub fn fails_with(self, code: i32) -> Run {
        let r = self.run();
        if r.status.code() != Some(code) {
            r.unexpected(&format!("exit code {code}"));
        }
        r
    }
}

/// Kills process `pid` with SIGKILL once `limit` has passed, unless `ended` is set first.
fn watchdog(pid: u32, limit: Duration, ended: Arc<AtomicBool>) {
    std::thread::spawn(move || {
        let started = Instant::now();
        while started.elapsed() < limit {
            if ended.load(Ordering::SeqCst) {
                return;
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        if !ended.load(Ordering::SeqCst) {
            let _ = Command::new("kill").args(["-KILL", &pid.to_string()]).status();
        }
    });
}

impl Run {
    fn new(command: String, o: std::process::Output) -> Self {
        Run { command, status: o.status, stdout: o.stdout, stderr: String::from_utf8_lossy(&o.stderr).into_owned() }
    }

    #[track_caller]
    fn unexpected(&self, expected: &str) -> ! {
        panic!(
            "`{}` ended with {}, expected {expected}; its standard error:\n{}",
            self.command, self.status, self.stderr
        )
    }

    /// Standard output, lossily UTF-8.
    pub fn stdout_text(&self) -> String {
        String::from_utf8_lossy(&self.stdout).into_owned()
    }

    /// Standard output parsed as JSON; panics showing it if it is not.
    #[track_caller]
    pub fn json(&self) -> serde_json::Value {
        match serde_json::from_slice(&self.stdout) {
            Ok(v) => v,
            Err(e) => panic!("`{}` printed no JSON ({e}):\n{}", self.command, self.stdout_text()),
        }
    }
}
