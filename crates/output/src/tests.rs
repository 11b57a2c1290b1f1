//! The writer's own checks: whole sets, refusals, stale stages, streamed files.

use super::*;
use dir::swap_aside;

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
    for p in [Path::new("/"), Path::new("."), Path::new("..")] {
        assert!(matches!(OutputDir::prepare(p).unwrap_err(), OutputError::Unnamed { .. }), "{}", p.display());
    }
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
    assert_eq!(staging_leftovers(dir.path()).len(), 1);
    drop(p);
    assert!(staging_leftovers(dir.path()).is_empty());
    assert!(!dir.path().join("out").exists());
    let f = OutputFile::prepare(dir.path().join("f.json")).unwrap();
    assert_eq!(staging_leftovers(dir.path()).len(), 1);
    drop(f);
    assert!(staging_leftovers(dir.path()).is_empty());
    assert!(!dir.path().join("f.json").exists());
}

#[test]
fn stale_entries_of_dead_runs_are_removed_and_live_ones_kept() {
    let dir = tempfile::tempdir().unwrap();
    let dead = dead_pid();
    let stale_stage = dir.path().join(format!(".out{STAGE_TAG}{dead}-0-{:016x}", 1));
    fs::create_dir(&stale_stage).unwrap();
    fs::write(stale_stage.join("half.csv"), "1,").unwrap();
    let stale_tmp = dir.path().join(format!(".f.json{TMP_TAG}{dead}-0-{:016x}", 2));
    fs::write(&stale_tmp, "partial").unwrap();
    // A live run (this process) preparing another target in the same directory.
    let live = OutputDir::prepare(dir.path().join("other")).unwrap();
    // A name that only looks similar is not ours to delete.
    let lookalike = dir.path().join(".out.impact-stage-notes");
    fs::write(&lookalike, "keep").unwrap();
    let mut a = Artifacts::new();
    a.add("a.txt", "a");
    a.write_all(&dir.path().join("out")).unwrap();
    assert!(!stale_stage.exists() && !stale_tmp.exists());
    assert!(live.stage.as_ref().unwrap().exists());
    assert!(lookalike.exists());
    live.commit(&a).unwrap();
    fs::remove_file(&lookalike).unwrap();
    assert!(staging_leftovers(dir.path()).is_empty());
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
    swap_aside(dir.path(), &stage, &out).unwrap();
    assert_eq!(fs::read_to_string(out.join("b.txt")).unwrap(), "new");
    assert!(!stage.exists() && staging_leftovers(dir.path()).is_empty());

    // A crash between the two renames: no target, the old set aside under a dead owner.
    let aside = dir.path().join(format!(".out{OLD_TAG}{}-0-{:016x}", dead_pid(), 3));
    fs::rename(&out, &aside).unwrap();
    clean_stale(dir.path());
    assert_eq!(fs::read_to_string(out.join("b.txt")).unwrap(), "new");
    assert!(staging_leftovers(dir.path()).is_empty());
    // With the target in place, a dead run's aside copy is just removed.
    fs::create_dir(&aside).unwrap();
    clean_stale(dir.path());
    assert!(!aside.exists() && out.join("b.txt").exists());
}

#[test]
fn staging_names_parse() {
    let n = sibling_name(OsStr::new("my-out.d"), STAGE_TAG);
    let (tag, target, pid, _) = parse_sibling(n.to_str().unwrap()).unwrap();
    assert_eq!((tag, target, pid), (STAGE_TAG, "my-out.d", std::process::id()));
    assert!(owner_alive(pid, start_time(pid).unwrap()));
    assert!(!owner_alive(dead_pid(), 0));
    assert!(parse_sibling(".x.impact-stage-12-0-zz").is_none());
    assert!(parse_sibling("x.impact-tmp-12-0-0123456789abcdef").is_none());
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
