//! The output of the `impact` binary under a concurrent run in another PID namespace, a
//! signal, a full file system and `--out` onto an empty directory: a live run's stage is
//! never deleted, a stopped run leaves nothing behind, every error names the path.

mod common;

use std::fs;
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use common::{impact, leftovers, tmp, BIN};
use impact::output::verify_set;

/// Waits until `dir` holds a stage of a run; false if `child` ended first.
fn stage_appears(dir: &Path, child: &mut Child) -> bool {
    let start = Instant::now();
    while start.elapsed() < Duration::from_secs(120) {
        if leftovers(dir).iter().any(|n| n.contains(".impact-stage-")) {
            return true;
        }
        if child.try_wait().unwrap().is_some() {
            return false;
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    panic!("no stage appeared in {} within 120 s", dir.display());
}

/// Whether `unshare` with `args` works here; prints why not.
fn unshare_works(args: &[&str]) -> bool {
    match Command::new("unshare").args(args).arg("true").output() {
        Ok(o) if o.status.success() => true,
        Ok(o) => {
            eprintln!("skipped: unshare {} fails here: {}", args.join(" "), String::from_utf8_lossy(&o.stderr).trim());
            false
        }
        Err(e) => {
            eprintln!("skipped: unshare cannot be run here: {e}");
            false
        }
    }
}

/// A long run (`impact signals` on the default scene, some 20 s) stopped by SIGTERM or SIGINT once its
/// stage exists: it removes its stage and lock and exits with 128 + the signal's number,
/// leaving no output.
#[test]
fn a_run_stopped_by_a_signal_removes_its_stage() {
    for (signal, code) in [("TERM", 143), ("INT", 130)] {
        let dir = tmp();
        let out = dir.join("out");
        let mut child = Command::new(BIN)
            .args(["signals", "--out"])
            .arg(&out)
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        assert!(stage_appears(dir.path(), &mut child), "impact signals ended before its stage was seen");
        assert!(Command::new("kill").args([format!("-{signal}"), child.id().to_string()]).status().unwrap().success());
        let o = child.wait_with_output().unwrap();
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(code), "SIG{signal}: {:?}; standard error:\n{stderr}", o.status);
        assert!(stderr.contains(&format!("SIG{signal}")), "{stderr}");
        assert_eq!(leftovers(dir.path()), Vec::<String>::new(), "SIG{signal} left its staging behind");
        assert!(!out.exists(), "SIG{signal}: a half-written output");
    }
}

/// `--out` onto an existing empty directory, also as `--out .` from inside it, is accepted; a
/// non-empty directory that is not an earlier output is still refused, naming it.
#[test]
fn out_onto_an_empty_directory() {
    let dir = tmp();
    let named = dir.join("named");
    fs::create_dir(&named).unwrap();
    impact(["solve", "--out"]).arg(&named).success();
    assert!(verify_set(&named).unwrap() > 0);
    let here = dir.join("here");
    fs::create_dir(&here).unwrap();
    let r = impact(["solve", "--out", "."]).current_dir(&here).success();
    assert!(r.stderr.contains("wrote"), "{}", r.stderr);
    assert!(verify_set(&here).unwrap() > 0);
    let foreign = dir.join("thesis");
    fs::create_dir(&foreign).unwrap();
    fs::write(foreign.join("chapter1.tex"), "years of work").unwrap();
    let r = impact(["solve", "--out", "."]).current_dir(&foreign).fails();
    assert!(r.stderr.contains("thesis") && r.stderr.contains("not written by impact"), "{}", r.stderr);
    assert_eq!(fs::read_to_string(foreign.join("chapter1.tex")).unwrap(), "years of work");
    assert_eq!(leftovers(dir.path()), Vec::<String>::new());
}

/// A live `impact signals` in another PID namespace, whose pid means nothing here, keeps its
/// stage while `impact solve` prepares and commits beside it, and its output is whole.
#[test]
fn a_run_in_another_pid_namespace_keeps_its_stage() {
    live_stage_is_kept_across(&["-p", "-f", "--mount-proc"]);
}

/// The same from another user and PID namespace (`unshare --user --pid --fork`, which needs no
/// privilege where unprivileged user namespaces are allowed): the run's pid and its user id
/// both mean nothing here. Skipped, saying why, where `unshare` is not allowed.
#[test]
fn a_run_in_another_user_and_pid_namespace_keeps_its_stage() {
    live_stage_is_kept_across(&["--user", "--pid", "--fork"]);
}

/// Runs `impact signals` under `unshare <namespaces>` and `impact solve` beside it once its
/// stage exists: the stage is still there after the second run has prepared and committed
/// (while the first still runs), and the first run's output is whole.
fn live_stage_is_kept_across(namespaces: &[&str]) {
    if !unshare_works(namespaces) {
        return;
    }
    let dir = tmp();
    let first = dir.join("first");
    let mut child = Command::new("unshare")
        .args(namespaces)
        .args([BIN, "signals", "--out"])
        .arg(&first)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    assert!(stage_appears(dir.path(), &mut child), "impact signals ended before its stage was seen");
    let stage: Vec<String> = leftovers(dir.path()).into_iter().filter(|n| n.contains(".impact-stage-")).collect();
    impact(["solve", "--out"]).arg(dir.join("second")).within(120).success();
    if child.try_wait().unwrap().is_none() {
        for s in &stage {
            assert!(dir.join(s).exists(), "the live run's stage {s} was removed by the run beside it");
        }
    }
    let o = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "the run in the other namespace failed: {stderr}");
    assert!(verify_set(&first).is_ok(), "{stderr}: {:?}", verify_set(&first));
    assert_eq!(leftovers(dir.path()), Vec::<String>::new());
}

/// A full file system (a 64 KiB tmpfs in a private mount namespace): the run fails naming the
/// file it was writing and the device's error, and leaves nothing behind.
#[test]
fn a_full_file_system_is_reported_with_the_path() {
    if !unshare_works(&["-m"]) {
        return;
    }
    let script = r#"mount -t tmpfs -o size=64k impact-full "$1" || exit 90
"$2" solve --out "$1/out"; code=$?
echo "left: $(ls -A "$1")"
exit $code"#;
    let dir = tmp();
    let o =
        Command::new("unshare").args(["-m", "--", "sh", "-c", script, "sh"]).arg(dir.path()).arg(BIN).output().unwrap();
    let (stdout, stderr) = (String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr));
    if o.status.code() == Some(90) {
        return eprintln!("skipped: a tmpfs cannot be mounted here: {}", stderr.trim());
    }
    assert_eq!(o.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("No space left on device"), "{stderr}");
    let mount = dir.path().to_string_lossy();
    assert!(stderr.contains(&format!("error: {mount}/.out.impact-")), "the message names no path: {stderr}");
    assert!(stdout.trim_end().ends_with("left:"), "{stdout}");
}
