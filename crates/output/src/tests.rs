//! The writer's own checks: whole sets, refusals, stale stages, streamed files.

use super::*;
use std::cell::Cell;

thread_local! {
    /// What a test does to the stage between its writing and its verification.
    static BEFORE_VERIFY: Cell<Option<fn(&Path)>> = const { Cell::new(None) };
}

/// Called by [`OutputDir::commit`] once the stage is written and synced.
pub(crate) fn before_verify(stage: &Path) {
    if let Some(f) = BEFORE_VERIFY.get() {
        f(stage)
    }
}

/// A staging entry of kind `tag` for target `out` in `dir`, owned by a dead run: its token
/// names a pid that has exited, and its lock file exists and is free.
fn dead_entry(dir: &Path, out: &str, tag: &str, n: u64) -> PathBuf {
    let token = format!("{}-0-{n:016x}", dead_pid());
    fs::write(dir.join(entry_name(OsStr::new(out), LOCK_TAG, &token)), "").unwrap();
    dir.join(entry_name(OsStr::new(out), tag, &token))
}

/// Entries beside a target that a run creates and must not leave behind.
fn staging_leftovers(dir: &Path) -> Vec<String> {
    fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.contains(".impact-"))
        .collect()
}

fn dead_pid() -> u32 {
    let mut c = std::process::Command::new("true").spawn().unwrap();
    let pid = c.id();
    c.wait().unwrap();
    pid
}

#[test]
fn sha256_known_vectors() {
    assert_eq!(sha256_hex(b""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
    assert_eq!(sha256_hex(b"abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
    assert_eq!(
        sha256_hex(b"abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
        "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1"
    );
    assert_eq!(sha256_hex(&vec![b'a'; 1_000_000]), "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

#[test]
fn writes_all_files_and_replaces_duplicates() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let mut a = Artifacts::new();
    a.add("a.txt", "one");
    a.add("sub/b.txt", "two");
    a.add("a.txt", "three");
    let written = a.write_all(&out).unwrap();
    assert_eq!(written, vec![out.join("sub/b.txt"), out.join("a.txt")]);
    assert_eq!(fs::read_to_string(out.join("a.txt")).unwrap(), "three");
    assert_eq!(fs::read_to_string(out.join("sub/b.txt")).unwrap(), "two");
    assert_eq!(verify_set(&out).unwrap(), 2);
    assert!(staging_leftovers(dir.path()).is_empty());
}

/// The manifest depends on the content only: the same set gives the same bytes.
#[test]
fn manifest_is_deterministic() {
    let dir = tempfile::tempdir().unwrap();
    let mut a = Artifacts::new();
    a.add("z.csv", "1,2\n");
    a.add("m/a.svg", "<svg/>");
    a.write_all(&dir.path().join("one")).unwrap();
    a.write_all(&dir.path().join("two")).unwrap();
    let one = fs::read(dir.path().join("one").join(MANIFEST)).unwrap();
    assert_eq!(one, fs::read(dir.path().join("two").join(MANIFEST)).unwrap());
    let text = String::from_utf8(one).unwrap();
    assert!(text.find("m/a.svg").unwrap() < text.find("z.csv").unwrap(), "{text}");
    assert!(text.contains(env!("CARGO_PKG_VERSION")));
}

#[test]
fn unsafe_paths_are_rejected() {
    let mut a = Artifacts::new();
    for p in ["/etc/passwd", "../x", "a/../../b", "", ".", MANIFEST] {
        let e = a.try_add(p, "x").unwrap_err();
        assert!(matches!(e, OutputError::UnsafePath { .. }), "{p}: {e}");
    }
    assert!(a.is_empty());
    a.try_add("./ok/b.txt", "x").unwrap();
    assert_eq!(a.len(), 1);
    // Checked again at commit, for paths added unchecked; the target is not touched.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    for bad in [vec!["../escape"], vec!["a", "a/b"], vec!["a", "./a"], vec!["a-b", "a", "a/c"]] {
        let mut a = Artifacts::new();
        for p in &bad {
            a.add(*p, "x");
        }
        let e = a.write_all(&out).unwrap_err();
        assert!(matches!(e, OutputError::UnsafePath { .. }), "{bad:?}: {e}");
        assert!(!out.exists() && !dir.path().join("escape").exists());
    }
    assert!(staging_leftovers(dir.path()).is_empty());
}

#[test]
fn replaces_own_output_and_refuses_foreign() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let mut a = Artifacts::new();
    a.add("old.txt", "old");
    a.add("d/old.txt", "old");
    a.write_all(&out).unwrap();
    let mut b = Artifacts::new();
    b.add("new.txt", "new");
    b.write_all(&out).unwrap();
    // The old set is gone as a whole, not merged with the new one.
    assert!(!out.join("old.txt").exists() && !out.join("d").exists());
    assert_eq!(verify_set(&out).unwrap(), 1);

    // Something a user put into our output is not deleted with it.
    fs::write(out.join("notes.md"), "mine").unwrap();
    let e = b.write_all(&out).unwrap_err();
    assert!(matches!(e, OutputError::ForeignEntry { .. }), "{e}");
    assert!(e.to_string().contains("notes.md"), "{e}");
    assert_eq!(fs::read_to_string(out.join("notes.md")).unwrap(), "mine");

    // A directory without our manifest is refused unless empty.
    let foreign = dir.path().join("foreign");
    fs::create_dir(&foreign).unwrap();
    fs::write(foreign.join("thesis.tex"), "years of work").unwrap();
    let e = OutputDir::prepare(&foreign).unwrap_err();
    assert!(matches!(e, OutputError::Foreign { .. }), "{e}");
    assert!(e.to_string().contains("foreign") && e.to_string().contains(MANIFEST), "{e}");
    let empty = dir.path().join("empty");
    fs::create_dir(&empty).unwrap();
    b.write_all(&empty).unwrap();
    assert_eq!(verify_set(&empty).unwrap(), 1);

    // A manifest that is not ours does not make a directory ours.
    let fake = dir.path().join("fake");
    fs::create_dir(&fake).unwrap();
    fs::write(fake.join(MANIFEST), r#"{"program":"other","version":"1","files":[]}"#).unwrap();
    assert!(matches!(OutputDir::prepare(&fake).unwrap_err(), OutputError::BadManifest { .. }));
    assert!(staging_leftovers(dir.path()).is_empty());
}

#[test]
fn refuses_targets_inside_an_output_set_and_unnamed_targets() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let mut a = Artifacts::new();
    a.add("a.txt", "a");
    a.write_all(&out).unwrap();
    let e = OutputDir::prepare(out.join("nested")).unwrap_err();
    assert!(matches!(e, OutputError::InsideOutputSet { .. }), "{e}");
    assert!(matches!(OutputFile::prepare(out.join("x.json")).unwrap_err(), OutputError::InsideOutputSet { .. }));
    assert_eq!(verify_set(&out).unwrap(), 1);
    assert!(matches!(OutputDir::prepare("/").unwrap_err(), OutputError::Unnamed { .. }));
    // A path ending in '.' or '..' names the directory it resolves to (`--out .` in an empty
    // directory), staged beside it under its own name.
    let empty = dir.path().join("empty");
    fs::create_dir(&empty).unwrap();
    for p in [empty.join("."), empty.join("./")] {
        let prepared = OutputDir::prepare(&p).unwrap();
        prepared.commit(&a).unwrap();
        assert_eq!(verify_set(&empty).unwrap(), 1);
    }
    assert!(staging_leftovers(dir.path()).is_empty());
}

/// A commit that fails part-way through staging (a real I/O error, even for root: a name
/// longer than the file system allows) leaves the earlier output exactly as it was.
#[test]
fn failed_commit_leaves_earlier_output() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let mut a = Artifacts::new();
    a.add("a.txt", "old");
    a.write_all(&out).unwrap();
    let before = fs::read(out.join(MANIFEST)).unwrap();
    let prepared = OutputDir::prepare(&out).unwrap();
    let mut b = Artifacts::new();
    b.add("a.txt", "new");
    b.add("x".repeat(300), "too long a name");
    let e = prepared.commit(&b).unwrap_err();
    assert!(matches!(e, OutputError::Io { .. }), "{e}");
    assert!(std::error::Error::source(&e).is_some());
    assert_eq!(fs::read_to_string(out.join("a.txt")).unwrap(), "old");
    assert_eq!(fs::read(out.join(MANIFEST)).unwrap(), before);
    assert_eq!(verify_set(&out).unwrap(), 1);
    assert!(staging_leftovers(dir.path()).is_empty());
}

#[test]
fn dropping_a_prepared_output_removes_its_stage() {
    let dir = tempfile::tempdir().unwrap();
    let p = OutputDir::prepare(dir.path().join("out")).unwrap();
    // The stage and its lock file.
    assert_eq!(staging_leftovers(dir.path()).len(), 2);
    drop(p);
    assert!(staging_leftovers(dir.path()).is_empty());
    assert!(!dir.path().join("out").exists());
    let f = OutputFile::prepare(dir.path().join("f.json")).unwrap();
    assert_eq!(staging_leftovers(dir.path()).len(), 2);
    drop(f);
    assert!(staging_leftovers(dir.path()).is_empty());
    assert!(!dir.path().join("f.json").exists());
}

#[test]
fn stale_entries_of_dead_runs_are_removed_and_live_ones_kept() {
    let dir = tempfile::tempdir().unwrap();
    let stale_stage = dead_entry(dir.path(), "out", STAGE_TAG, 1);
    fs::create_dir(&stale_stage).unwrap();
    fs::write(stale_stage.join("half.csv"), "1,").unwrap();
    let stale_tmp = dead_entry(dir.path(), "f.json", TMP_TAG, 2);
    fs::write(&stale_tmp, "partial").unwrap();
    // A lock file whose run died before it made anything.
    let orphan_lock = dead_entry(dir.path(), "g", LOCK_TAG, 3);
    // A live run (this process) preparing another target in the same directory.
    let live = OutputDir::prepare(dir.path().join("other")).unwrap();
    // A name that only looks similar is not ours to delete.
    let lookalike = dir.path().join(".out.impact-stage-notes");
    fs::write(&lookalike, "keep").unwrap();
    let mut a = Artifacts::new();
    a.add("a.txt", "a");
    a.write_all(&dir.path().join("out")).unwrap();
    assert!(!stale_stage.exists() && !stale_tmp.exists() && !orphan_lock.exists());
    assert!(live.stage.as_ref().unwrap().exists());
    assert!(lookalike.exists());
    live.commit(&a).unwrap();
    fs::remove_file(&lookalike).unwrap();
    assert!(staging_leftovers(dir.path()).is_empty());
}

/// A stage whose owner cannot be proven dead is kept: without a lock file (an older version's,
/// or one removed by hand) nothing shows that its run has ended, whatever its pid says.
#[test]
fn stage_without_a_lock_file_is_kept() {
    let dir = tempfile::tempdir().unwrap();
    let token = format!("{}-0-{:016x}", dead_pid(), 4);
    let stage = dir.path().join(entry_name(OsStr::new("out"), STAGE_TAG, &token));
    fs::create_dir(&stage).unwrap();
    fs::write(stage.join("a.csv"), "1\n").unwrap();
    let mut a = Artifacts::new();
    a.add("a.txt", "a");
    a.write_all(&dir.path().join("out")).unwrap();
    assert_eq!(fs::read_to_string(stage.join("a.csv")).unwrap(), "1\n");
}

/// The fallback swap, and its recovery rule: an old set moved aside by a run that died
/// before moving the new set in is put back.
#[test]
fn fallback_swap_and_recovery() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let mut a = Artifacts::new();
    a.add("a.txt", "old");
    a.write_all(&out).unwrap();
    let stage = dir.path().join("stage");
    fs::create_dir(&stage).unwrap();
    fs::write(stage.join("b.txt"), "new").unwrap();
    let aside = dir.path().join("aside");
    swap_aside(&stage, &out, &aside).unwrap();
    assert_eq!(fs::read_to_string(out.join("b.txt")).unwrap(), "new");
    assert!(!stage.exists() && !aside.exists() && staging_leftovers(dir.path()).is_empty());

    // A crash between the two renames: no target, the old set aside under a dead owner.
    let aside = dead_entry(dir.path(), "out", OLD_TAG, 3);
    fs::rename(&out, &aside).unwrap();
    clean_stale(dir.path());
    assert_eq!(fs::read_to_string(out.join("b.txt")).unwrap(), "new");
    assert!(staging_leftovers(dir.path()).is_empty());
    // With the target in place, a dead run's aside copy is just removed.
    let aside = dead_entry(dir.path(), "out", OLD_TAG, 4);
    fs::create_dir(&aside).unwrap();
    clean_stale(dir.path());
    assert!(!aside.exists() && out.join("b.txt").exists());
    assert!(staging_leftovers(dir.path()).is_empty());
}

#[test]
fn staging_names_parse() {
    let dir = tempfile::tempdir().unwrap();
    let owner = Owner::acquire(dir.path(), OsStr::new("my-out.d")).unwrap();
    let n = owner.entry(STAGE_TAG);
    let (tag, target, token) = parse_sibling(n.file_name().unwrap().to_str().unwrap()).unwrap();
    assert_eq!((tag, target), (STAGE_TAG, "my-out.d"));
    assert!(token.starts_with(&format!("{}-", std::process::id())));
    let lock = owner.lock_path().file_name().unwrap().to_str().unwrap().to_owned();
    assert_eq!(parse_sibling(&lock), Some((LOCK_TAG, "my-out.d", token)));
    // Held by this run: another open file cannot take it.
    assert_eq!(try_lock(&File::options().read(true).write(true).open(owner.lock_path()).unwrap()), Lock::Busy);
    drop(owner);
    assert!(staging_leftovers(dir.path()).is_empty());
    assert!(parse_sibling(".x.impact-stage-12-0-zz").is_none());
    assert!(parse_sibling(".x.impact-stage-a-0-0123456789abcdef").is_none());
    assert!(parse_sibling("x.impact-tmp-12-0-0123456789abcdef").is_none());
}

/// A staged file removed, altered or added between its writing and the swap fails the commit,
/// naming it, and leaves the earlier output as it was.
#[test]
fn commit_verifies_the_stage() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let mut a = Artifacts::new();
    a.add("a.csv", "old\n");
    a.write_all(&out).unwrap();
    let mut b = Artifacts::new();
    b.add("a.csv", "new\n");
    b.add("sub/b.csv", "2\n");
    type Tamper = fn(&Path);
    let cases: [(Tamper, &str, &str); 4] = [
        (|s| fs::remove_file(s.join("sub/b.csv")).unwrap(), "sub/b.csv", "is missing"),
        (|s| fs::write(s.join("a.csv"), "NEW\n").unwrap(), "a.csv", "differs from what was written"),
        (|s| fs::write(s.join("a.csv"), "longer\n").unwrap(), "a.csv", "holds 7 bytes where 4 were written"),
        (|s| fs::write(s.join("extra.csv"), "x").unwrap(), "extra.csv", "was not written by this run"),
    ];
    for (tamper, file, why) in cases {
        BEFORE_VERIFY.set(Some(tamper));
        let e = OutputDir::prepare(&out).unwrap().commit(&b).unwrap_err();
        BEFORE_VERIFY.set(None);
        let msg = e.to_string();
        assert!(matches!(&e, OutputError::Unverified { file: f, .. } if f == file), "{msg}");
        assert!(msg.contains(why) && msg.contains("not committed"), "{msg}");
        assert_eq!(fs::read_to_string(out.join("a.csv")).unwrap(), "old\n");
        assert_eq!(verify_set(&out).unwrap(), 1);
        assert!(staging_leftovers(dir.path()).is_empty());
    }
}

/// Every write error, a full disk among them, names the file being written.
#[test]
fn write_errors_name_the_file() {
    let full = Path::new("/dev/full");
    let Ok(f) = File::options().write(true).open(full) else {
        eprintln!("skipped: /dev/full cannot be opened here");
        return;
    };
    let e = write_synced(f, full, &[0u8; 1 << 16], true).unwrap_err();
    let msg = e.to_string();
    assert!(msg.starts_with("/dev/full: writing a staged file"), "{msg}");
    assert!(matches!(&e, OutputError::Io { source, .. } if source.raw_os_error() == Some(28)), "{msg}");
}

/// After [`abandon_all`] (a signal), this process's stages and locks are gone and nothing more
/// is staged or swapped in. Run alone in a child: it stops the whole process's output.
#[test]
fn abandon_all_removes_the_stages() {
    if std::env::var_os("OUTPUT_ABANDON_CHILD").is_none() {
        let exe = std::env::current_exe().unwrap();
        let o = std::process::Command::new(exe)
            .args(["--exact", "tests::abandon_all_removes_the_stages", "--test-threads=1"])
            .env("OUTPUT_ABANDON_CHILD", "1")
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stdout));
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let mut d = OutputDir::prepare(dir.path().join("out")).unwrap();
    let mut s = d.stream("rows/a.csv").unwrap();
    writeln!(s, "1").unwrap();
    let f = OutputFile::prepare(dir.path().join("f.json")).unwrap();
    assert_eq!(staging_leftovers(dir.path()).len(), 4);
    assert_eq!(abandon_all(), 2);
    assert!(staging_leftovers(dir.path()).is_empty());
    // Whatever step of the run meets the removed stage first fails it.
    assert!(d.finish_stream(s).and_then(|()| d.commit(&Artifacts::new())).is_err());
    assert!(matches!(f.commit(b"x").unwrap_err(), OutputError::Stopped { .. }));
    assert!(matches!(OutputDir::prepare(dir.path().join("o2")).unwrap_err(), OutputError::Stopped { .. }));
    assert!(staging_leftovers(dir.path()).is_empty() && !dir.path().join("out").exists());
}

#[test]
fn incremental_hash_is_the_one_shot_hash() {
    // Pieces that straddle the 64-byte blocks and the padding boundary (55/56 bytes).
    let data: Vec<u8> = (0..1000u32).map(|i| (i * 7 % 251) as u8).collect();
    for cut in [0, 1, 55, 56, 63, 64, 65, 500, 1000] {
        let mut h = Sha256::new();
        h.update(&data[..cut]);
        h.update(&data[cut..]);
        assert_eq!(h.hex(), sha256_hex(&data), "cut {cut}");
    }
}

#[test]
fn streamed_files_join_the_manifest() {
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("out");
    let mut out = OutputDir::prepare(&target).unwrap();
    let mut f = out.stream("rows/features.csv").unwrap();
    for i in 0..10_000 {
        writeln!(f, "{i},{}", i * i).unwrap();
    }
    let size = f.size();
    out.finish_stream(f).unwrap();
    let mut a = Artifacts::new();
    a.add("index.md", "report");
    let written = out.commit(&a).unwrap();
    assert_eq!(written.len(), 2);
    assert_eq!(fs::metadata(target.join("rows/features.csv")).unwrap().len(), size);
    // The manifest lists the streamed file with its hash: the set verifies.
    assert_eq!(verify_set(&target).unwrap(), 2);
    // An unfinished stream or a clash with an artifact fails the commit, leaving the set.
    let mut out = OutputDir::prepare(&target).unwrap();
    let _open = out.stream("a.csv").unwrap();
    assert!(out.commit(&Artifacts::new()).is_err());
    let mut out = OutputDir::prepare(&target).unwrap();
    let f = out.stream("a.csv").unwrap();
    out.finish_stream(f).unwrap();
    let mut a = Artifacts::new();
    a.add("a.csv", "x");
    assert!(out.commit(&a).is_err());
    assert_eq!(verify_set(&target).unwrap(), 2);
    assert!(staging_leftovers(dir.path()).is_empty());
}

#[test]
fn single_file_output() {
    let dir = tempfile::tempdir().unwrap();
    let f = dir.path().join("sub/field.json");
    let ours = |n: u8| format!("{{\"provenance\":{FILE_MARK}\"n\":{n}}}}}").into_bytes();
    assert_eq!(OutputFile::prepare(&f).unwrap().commit(&ours(1)).unwrap(), Some(f.clone()));
    OutputFile::prepare(&f).unwrap().commit(&ours(2)).unwrap();
    assert_eq!(fs::read(&f).unwrap(), ours(2));
    // Not ours: a file without the mark (or with it only beyond the window) is refused
    // and left byte for byte; an empty file holds nothing to lose.
    let mut late = vec![b' '; FILE_MARK_WINDOW];
    late.extend_from_slice(&ours(3));
    for foreign in [b"{}".to_vec(), b"name = \"my scene\"\n".to_vec(), late] {
        fs::write(&f, &foreign).unwrap();
        let e = OutputFile::prepare(&f).unwrap_err();
        assert!(matches!(e, OutputError::ForeignFile { .. }), "{e}");
        assert!(e.to_string().contains("not written by impact"), "{e}");
        assert_eq!(fs::read(&f).unwrap(), foreign);
    }
    fs::write(&f, b"").unwrap();
    OutputFile::prepare(&f).unwrap().commit(&ours(4)).unwrap();
    assert_eq!(fs::read(&f).unwrap(), ours(4));
    // Taken over by someone else between prepare and commit: refused at commit.
    let prepared = OutputFile::prepare(&f).unwrap();
    fs::write(&f, b"theirs").unwrap();
    assert!(matches!(prepared.commit(&ours(5)).unwrap_err(), OutputError::ForeignFile { .. }));
    assert_eq!(fs::read(&f).unwrap(), b"theirs");
    let stdout = OutputFile::prepare("-").unwrap();
    assert!(stdout.is_stdout() && stdout.path().is_none());
    let e = OutputFile::prepare(dir.path()).unwrap_err();
    assert!(matches!(e, OutputError::NotRegularFile { kind: "a directory", .. }), "{e}");
    assert!(staging_leftovers(&dir.path().join("sub")).is_empty());
}
