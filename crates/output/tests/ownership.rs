//! Ownership of staging areas across processes: a stage is removed only when its owner is
//! provably dead (its lock can be taken), never because its process id looks dead, which it
//! does for a run in another PID namespace, a container or on another host; and a commit
//! checks what is on disk before it reports success.

use std::fs;
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use output::{verify_set, Artifacts, OutputDir, OutputError};

/// Set in the child re-executed from this test binary: the directory it works in.
const CHILD_ENV: &str = "OUTPUT_OWNERSHIP_CHILD_DIR";

fn leftovers(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.contains(".impact-"))
        .collect();
    v.sort();
    v
}

fn dead_pid() -> u32 {
    let mut c = Command::new("true").spawn().unwrap();
    let pid = c.id();
    c.wait().unwrap();
    pid
}

fn wait_for(what: &str, mut done: impl FnMut() -> bool) {
    let start = Instant::now();
    while !done() {
        assert!(start.elapsed() < Duration::from_secs(60), "timed out waiting for {what}");
        std::thread::sleep(Duration::from_millis(10));
    }
}

fn one_file(name: &str, text: &str) -> Artifacts {
    let mut a = Artifacts::new();
    a.add(name, text);
    a
}

/// `flock(1)` holding `lock` in a child process until killed; `None` (with the reason
/// printed) where the tool is missing.
fn hold_lock(lock: &Path) -> Option<Child> {
    // -o: the lock stays with flock itself, not with the command, so killing flock frees it.
    let child = Command::new("flock").arg("-o").arg(lock).args(["sleep", "120"]).stdout(Stdio::null()).spawn();
    let Ok(child) = child else {
        eprintln!("skipped: flock(1) is not available to hold a lock from another process");
        return None;
    };
    // Held once a try from here fails.
    wait_for("the child to take the lock", || {
        !Command::new("flock").args(["-n"]).arg(lock).arg("true").status().unwrap().success()
    });
    Some(child)
}

/// A stage of a run whose recorded pid is dead here (as that of a run in another namespace or
/// on another host is) but whose lock is held by a live process is kept; once the holder is
/// gone, the next run removes it.
#[test]
fn held_lock_keeps_a_stage_whose_pid_looks_dead() {
    let dir = tempfile::tempdir().unwrap();
    let token = format!("{}-0-{:016x}", dead_pid(), 0xfeed);
    let stage = dir.path().join(format!(".out.impact-stage-{token}"));
    let lock = dir.path().join(format!(".out.impact-lock-{token}"));
    fs::create_dir(&stage).unwrap();
    fs::write(stage.join("rows.csv"), "1,2\n").unwrap();
    fs::write(&lock, "").unwrap();
    let Some(mut holder) = hold_lock(&lock) else { return };
    one_file("a.txt", "a").write_all(&dir.path().join("other")).unwrap();
    let kept = fs::read_to_string(stage.join("rows.csv"));
    holder.kill().unwrap();
    holder.wait().unwrap();
    assert_eq!(kept.ok().as_deref(), Some("1,2\n"), "a stage whose lock is held was deleted");
    assert!(lock.exists());
    one_file("b.txt", "b").write_all(&dir.path().join("other")).unwrap();
    assert_eq!(leftovers(dir.path()), Vec::<String>::new(), "the dead run's stage and lock are removed");
}

/// The child's side of [`live_run_in_another_pid_namespace`]: prepares `first`, streams a
/// file, says it is ready, waits to be told to go on, and commits.
#[test]
fn namespace_child() {
    let Some(dir) = std::env::var_os(CHILD_ENV).map(PathBuf::from) else { return };
    let mut out = OutputDir::prepare(dir.join("first")).unwrap();
    let mut f = out.stream("rows/features.csv").unwrap();
    writeln!(f, "a,b\n1,2").unwrap();
    fs::write(dir.join("ready"), "").unwrap();
    wait_for("the parent's go", || dir.join("go").exists());
    out.finish_stream(f).unwrap();
    out.commit(&one_file("index.md", "# first\n")).unwrap();
    assert_eq!(verify_set(&dir.join("first")).unwrap(), 2);
}

/// A live run in another PID namespace (`unshare -p -f --mount-proc`: its pid means nothing
/// here) keeps its stage while a run here prepares and commits beside it, and commits whole.
#[test]
fn live_run_in_another_pid_namespace() {
    let probe = Command::new("unshare").args(["-p", "-f", "--mount-proc", "true"]).output();
    match probe {
        Ok(o) if o.status.success() => {}
        Ok(o) => {
            let why = String::from_utf8_lossy(&o.stderr);
            return eprintln!("skipped: unshare -p -f --mount-proc fails here: {}", why.trim());
        }
        Err(e) => return eprintln!("skipped: unshare cannot be run here: {e}"),
    }
    let dir = tempfile::tempdir().unwrap();
    let exe = std::env::current_exe().unwrap();
    let child = Command::new("unshare")
        .args(["-p", "-f", "--mount-proc"])
        .arg(exe)
        .args(["--exact", "namespace_child", "--nocapture", "--test-threads=1"])
        .env(CHILD_ENV, dir.path())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    wait_for("the child's stage", || dir.path().join("ready").exists());
    one_file("a.txt", "a").write_all(&dir.path().join("second")).unwrap();
    fs::write(dir.path().join("go"), "").unwrap();
    let o = child.wait_with_output().unwrap();
    let said = format!("{}{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr));
    assert!(o.status.success(), "the run in the other namespace failed:\n{said}");
    assert_eq!(verify_set(&dir.path().join("first")).unwrap(), 2);
    assert_eq!(leftovers(dir.path()), Vec::<String>::new());
}

/// A streamed file removed from the stage before the commit fails the commit, which names
/// it, instead of a success that lists a file that is not there.
#[test]
fn commit_fails_naming_a_staged_file_removed_before_it() {
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("out");
    one_file("old.txt", "old").write_all(&target).unwrap();
    let mut out = OutputDir::prepare(&target).unwrap();
    let mut f = out.stream("rows/features.csv").unwrap();
    writeln!(f, "1,2").unwrap();
    out.finish_stream(f).unwrap();
    let stage = leftovers(dir.path()).into_iter().find(|n| n.contains(".impact-stage-")).expect("a stage");
    fs::remove_file(dir.path().join(stage).join("rows/features.csv")).unwrap();
    let e = out.commit(&one_file("index.md", "# new\n")).unwrap_err();
    let msg = e.to_string();
    assert!(matches!(e, OutputError::Unverified { .. }), "{msg}");
    assert!(msg.contains("rows/features.csv") && msg.contains("missing"), "{msg}");
    assert_eq!(fs::read_to_string(target.join("old.txt")).unwrap(), "old");
    assert_eq!(verify_set(&target).unwrap(), 1);
    assert_eq!(leftovers(dir.path()), Vec::<String>::new());
}
