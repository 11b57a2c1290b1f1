//! The staging entries this process holds, so that a run stopped by a signal can remove them
//! before it exits (see [`abandon_all`]).

use super::*;
use std::sync::{Mutex, MutexGuard};

/// This process's entries beside its targets, and whether it has been stopped.
#[derive(Debug, Default)]
pub(crate) struct Live {
    stopped: bool,
    entries: Vec<PathBuf>,
    locks: Vec<PathBuf>,
}

static LIVE: Mutex<Live> = Mutex::new(Live { stopped: false, entries: Vec::new(), locks: Vec::new() });

/// The registry, held while an entry is created, swapped in or removed, so that a signal never
/// finds one half made. A panic elsewhere while it was held leaves it usable.
pub(crate) fn live() -> MutexGuard<'static, Live> {
    LIVE.lock().unwrap_or_else(|e| e.into_inner())
}

impl Live {
    /// Fails once the process has been stopped: nothing more may be staged or swapped in.
    pub(crate) fn check(&self, target: &Path) -> Result<(), OutputError> {
        if self.stopped {
            return Err(OutputError::Stopped { path: target.to_path_buf() });
        }
        Ok(())
    }

    pub(crate) fn add_entry(&mut self, path: PathBuf) {
        self.entries.push(path);
    }

    pub(crate) fn add_lock(&mut self, path: PathBuf) {
        self.locks.push(path);
    }

    /// Forgets `path`, an entry or a lock file that its owner has removed or handed over.
    pub(crate) fn forget(&mut self, path: &Path) {
        self.entries.retain(|p| p != path);
        self.locks.retain(|p| p != path);
    }
}

/// Removes every staging entry and lock file this process holds, and makes every later
/// [`OutputDir::prepare`], [`OutputDir::commit`] or [`OutputFile::prepare`] fail: for a
/// program stopped by a signal, which calls it and then exits. Outputs already committed stay.
/// Returns the number of staging entries removed.
pub fn abandon_all() -> usize {
    let mut live = live();
    live.stopped = true;
    let entries = std::mem::take(&mut live.entries);
    for e in &entries {
        // The run may still be writing into the stage; a file it creates between listing and
        // removal makes one pass fail, so a few are tried. New files cannot appear after the
        // stage's directory is gone: staged directories are never created with their parents.
        for _ in 0..5 {
            remove_entry(e);
            if fs::symlink_metadata(e).is_err() {
                break;
            }
        }
    }
    for l in std::mem::take(&mut live.locks) {
        let _ = fs::remove_file(l);
    }
    entries.len()
}

/// Takes a fresh lock beside `name` in `parent` and creates with `create` the run's entry of
/// kind `tag`, both registered for [`abandon_all`] before a signal could find them made.
pub(crate) fn claim<T>(
    parent: &Path,
    name: &OsStr,
    target: &Path,
    tag: &str,
    create: impl FnOnce(&Path) -> io::Result<T>,
) -> Result<(Owner, PathBuf, T), OutputError> {
    let mut live = live();
    live.check(target)?;
    let owner = Owner::acquire(parent, name)?;
    live.add_lock(owner.lock_path().to_path_buf());
    let path = owner.entry(tag);
    match create(&path) {
        Ok(t) => {
            live.add_entry(path.clone());
            Ok((owner, path, t))
        }
        Err(e) => {
            live.forget(owner.lock_path());
            Err(io_err(&path, "creating the staging area beside the output")(e))
        }
    }
}

/// Removes `entry` (if any), then `owner`'s lock file, and forgets both.
pub(crate) fn release(owner: Owner, entry: Option<&Path>) {
    let mut live = live();
    if let Some(e) = entry {
        remove_entry(e);
        live.forget(e);
    }
    live.forget(owner.lock_path());
    drop(owner);
}
