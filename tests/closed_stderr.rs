//! A closed standard error (`impact … 2>&1 | head`, a reader that has gone) must not turn a
//! run into a panic (exit code 101): the messages nobody can read are dropped, and the exit
//! code still says how the run ended (1 for an error, 0 for success). (indicatif, which draws
//! the progress bars, ignores its own write errors, and draws nothing where standard error is
//! not a terminal.)

mod common;

use common::{impact, tmp, BIN};
use std::process::{Command, Stdio};

/// Runs `impact args` with standard error a pipe whose read end is already closed, so every
/// write to it fails with EPIPE at once (not by a race with the reader). Returns the exit
/// code; standard output is discarded. The pipe is the standard input of a `true` that has
/// exited: its read end died with that process, and the parent never holds one.
fn with_closed_stderr(args: &[&str]) -> Option<i32> {
    let mut reader = Command::new("true").stdin(Stdio::piped()).spawn().expect("true runs");
    let writer = reader.stdin.take().expect("a pipe");
    assert!(reader.wait().expect("true ends").success());
    let status =
        Command::new(BIN).args(args).stdout(Stdio::null()).stderr(Stdio::from(writer)).status().expect("impact runs");
    status.code()
}

#[test]
fn an_error_with_stderr_closed_exits_1_not_101() {
    let dir = tmp();
    let bad = dir.write("bad.toml", impact::scene::DEFAULT_SCENE.replace("thickness_mm = 8.0", "thickness_mm = -8.0"));
    // Control: with standard error open the same run reports the error and exits 1.
    let o = impact(["solve", "--scene"]).arg(&bad).fails_with(1);
    assert!(o.stderr.contains("thickness_mm = -8"));
    for _ in 0..5 {
        assert_eq!(with_closed_stderr(&["solve", "--scene", bad.to_str().unwrap()]), Some(1));
    }
}

#[test]
fn messages_after_success_with_stderr_closed_exit_0() {
    let dir = tmp();
    let f = dir.join("f.json");
    // "wrote FILE" goes to standard error.
    let args = ["field", "--x-mm", "100", "--z-mm", "100", "--elements", "2", "--out", f.to_str().unwrap()];
    assert_eq!(with_closed_stderr(&args), Some(0));
    assert!(f.exists());
    // The status line of --json goes to standard error; "wrote N files" too.
    let out = dir.join("out");
    assert_eq!(with_closed_stderr(&["solve", "--json", "--out", out.to_str().unwrap()]), Some(0));
    assert!(out.join("results.json").exists());
}
