//! Staging entries beside a target: their names, the lock that proves their owner alive, and
//! the removal of the entries of runs that are provably dead.
//!
//! A process id says nothing about a run in another PID namespace, in a container or on
//! another host sharing the file system: such a run looks dead to a process-table check.
//! Ownership is therefore an advisory lock (`flock`) on a lock file beside the entries, held
//! for the run's whole life and released by the kernel (or, on NFS, by the lock manager) when
//! the owner dies however it dies. An entry is removed only after its lock has been taken.

use super::*;

/// The lock file of a run's entries: `.<name>.impact-lock-<token>`.
pub(crate) const LOCK_TAG: &str = ".impact-lock-";

/// The identity of the running process as it appears in staging names: pid and start time.
/// It only helps a person reading the names; ownership is decided by the lock.
pub(crate) fn owner_tag() -> String {
    let pid = std::process::id();
    format!("{pid}-{}", start_time(pid).unwrap_or(0))
}

/// The start time of process `pid` in clock ticks since boot (field 22 of /proc/pid/stat).
fn start_time(pid: u32) -> Option<u64> {
    let s = fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    // The command name (field 2) may contain spaces and parentheses; it ends at the last ')'.
    let rest = &s[s.rfind(')')? + 1..];
    rest.split_whitespace().nth(19)?.parse().ok()
}

pub(crate) fn random_suffix() -> String {
    use std::hash::{BuildHasher, Hasher};
    use std::sync::atomic::{AtomicU64, Ordering};
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let mut h = std::collections::hash_map::RandomState::new().build_hasher();
    h.write_u64(COUNTER.fetch_add(1, Ordering::Relaxed));
    if let Ok(d) = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH) {
        h.write_u128(d.as_nanos());
    }
    format!("{:016x}", h.finish())
}

/// The name `.<name><tag><token>` of an entry beside `name`.
pub(crate) fn entry_name(name: &OsStr, tag: &str, token: &str) -> OsString {
    let mut s = OsString::from(".");
    s.push(name);
    s.push(tag);
    s.push(token);
    s
}

/// Parses a staging entry's name into (tag, target name, token), the token being
/// `<pid>-<start>-<16 hex digits>`.
pub(crate) fn parse_sibling(name: &str) -> Option<(&'static str, &str, &str)> {
    let rest = name.strip_prefix('.')?;
    for tag in [STAGE_TAG, OLD_TAG, TMP_TAG, LOCK_TAG] {
        if let Some(i) = rest.rfind(tag) {
            let token = &rest[i + tag.len()..];
            let mut f = token.split('-');
            let (pid, start, rand) = (f.next()?, f.next()?, f.next()?);
            let digits = |s: &str| !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit());
            if f.next().is_some()
                || !digits(pid)
                || !digits(start)
                || rand.len() != 16
                || !rand.bytes().all(|b| b.is_ascii_hexdigit())
            {
                return None;
            }
            return Some((tag, &rest[..i], token));
        }
    }
    None
}

/// What an attempt to take a lock found.
#[derive(Debug, PartialEq, Eq)]
pub(crate) enum Lock {
    /// Taken: nobody else holds it.
    Taken,
    /// Held by another open file: its owner is alive.
    Busy,
    /// The file system does not lock: nothing can be proven either way.
    Unsupported,
}

/// Tries once, without waiting, to take `file`'s exclusive lock.
pub(crate) fn try_lock(file: &File) -> Lock {
    #[cfg(unix)]
    {
        use rustix::fs::{flock, FlockOperation};
        use rustix::io::Errno;
        match flock(file, FlockOperation::NonBlockingLockExclusive) {
            Ok(()) => Lock::Taken,
            Err(Errno::WOULDBLOCK | Errno::INTR) => Lock::Busy,
            Err(_) => Lock::Unsupported,
        }
    }
    #[cfg(not(unix))]
    {
        let _ = file;
        Lock::Unsupported
    }
}

/// Whether the open `file` is still the one named `path` (a lock file removed and recreated
/// under the same name is another lock).
fn same_file(file: &File, path: &Path) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        match (file.metadata(), fs::symlink_metadata(path)) {
            (Ok(a), Ok(b)) => a.dev() == b.dev() && a.ino() == b.ino(),
            _ => false,
        }
    }
    #[cfg(not(unix))]
    {
        let _ = (file, path);
        true
    }
}

fn open_lock(path: &Path, create: bool) -> io::Result<File> {
    let mut o = OpenOptions::new();
    // Read and write: NFS emulates flock with byte-range locks, whose exclusive kind needs a
    // file open for writing.
    o.read(true).write(true);
    if create {
        o.create_new(true);
    }
    o.open(path)
}

/// A run's claim on the entries it creates beside one target: the lock file, held locked
/// until the claim is dropped. Dropping it removes the lock file, so the entries it covers
/// must be gone first.
#[derive(Debug)]
pub(crate) struct Owner {
    parent: PathBuf,
    name: OsString,
    token: String,
    lock_path: PathBuf,
    _lock: File,
}

impl Owner {
    /// Creates and locks a fresh lock file beside `name` in `parent`. On a file system without
    /// locks the run goes on unlocked: no other run can take the lock either, so nothing of it
    /// is ever judged dead.
    pub(crate) fn acquire(parent: &Path, name: &OsStr) -> Result<Owner, OutputError> {
        let mut attempt = 0;
        loop {
            attempt += 1;
            let token = format!("{}-{}", owner_tag(), random_suffix());
            let lock_path = parent.join(entry_name(name, LOCK_TAG, &token));
            let file = match open_lock(&lock_path, true) {
                Ok(f) => f,
                Err(e) if e.kind() == io::ErrorKind::AlreadyExists && attempt < 8 => continue,
                Err(e) => return Err(io_err(&lock_path, "creating the lock file of the staging area")(e)),
            };
            // Between its creation and the lock, another run's cleaning could have found the
            // file free and removed it: then the name is no longer ours, and we start again.
            if try_lock(&file) != Lock::Busy && same_file(&file, &lock_path) {
                return Ok(Owner {
                    parent: parent.to_path_buf(),
                    name: name.to_owned(),
                    token,
                    lock_path,
                    _lock: file,
                });
            }
            if attempt >= 8 {
                return Err(io_err(&lock_path, "locking the staging area")(io::Error::other(
                    "the lock file was taken or removed by another process at every attempt",
                )));
            }
        }
    }

    /// The path of this run's entry of kind `tag` beside the target.
    pub(crate) fn entry(&self, tag: &str) -> PathBuf {
        self.parent.join(entry_name(&self.name, tag, &self.token))
    }

    pub(crate) fn lock_path(&self) -> &Path {
        &self.lock_path
    }
}

impl Drop for Owner {
    fn drop(&mut self) {
        // Removed while still locked: a cleaner that opened it meanwhile finds, once it gets
        // the lock, that the name no longer leads to this file, and leaves it.
        let _ = fs::remove_file(&self.lock_path);
    }
}

/// Removes the entries in `dir` of runs that are provably dead (their lock file can be
/// locked), and puts back an old set a dead run had moved aside (the fallback swap) if its
/// target is missing. An entry whose owner cannot be proven dead is kept: one with a held lock,
/// one without a lock file (an older version's, or a lock file removed by hand), one on a
/// file system without locks. Best effort: a failure here leaves an entry for a later run and
/// does not stop this one.
pub fn clean_stale(dir: &Path) {
    let Ok(entries) = fs::read_dir(dir) else { return };
    let mut runs: std::collections::BTreeMap<(String, String), Vec<(&'static str, PathBuf)>> = Default::default();
    for e in entries.flatten() {
        let name = e.file_name();
        let Some((tag, target, token)) = name.to_str().and_then(parse_sibling) else { continue };
        runs.entry((target.to_owned(), token.to_owned())).or_default().push((tag, e.path()));
    }
    for ((target, token), entries) in runs {
        let lock_path = dir.join(entry_name(OsStr::new(&target), LOCK_TAG, &token));
        let Ok(lock) = open_lock(&lock_path, false) else { continue };
        if try_lock(&lock) != Lock::Taken || !same_file(&lock, &lock_path) {
            continue;
        }
        for (tag, path) in entries {
            if tag == LOCK_TAG {
                continue;
            }
            if tag == OLD_TAG {
                // Recovery rule of the fallback swap: the old set was moved aside and the run
                // died before the new set took its place, so the old set is restored.
                let t = dir.join(&target);
                if matches!(fs::symlink_metadata(&t), Err(ref e) if e.kind() == io::ErrorKind::NotFound)
                    && fs::rename(&path, &t).is_ok()
                {
                    let _ = sync_dir(dir);
                    continue;
                }
            }
            remove_entry(&path);
        }
        // Last, and still locked: while it exists, a half-removed entry stays provably dead.
        let _ = fs::remove_file(&lock_path);
    }
}

/// Removes a file or directory tree without following symlinks; errors are ignored.
pub(crate) fn remove_entry(path: &Path) {
    match fs::symlink_metadata(path) {
        Ok(m) if m.is_dir() => {
            let _ = fs::remove_dir_all(path);
        }
        Ok(_) => {
            let _ = fs::remove_file(path);
        }
        Err(_) => {}
    }
}

pub(crate) fn sync_dir(dir: &Path) -> io::Result<()> {
    File::open(dir)?.sync_all()
}
