//! Files a command writes, staged in memory and committed together.
//!
//! A command computes everything first and only then writes. Two kinds of target exist:
//!
//! * An output **directory** ([`OutputDir`]) appears as a whole or not at all. The set is
//!   written into a sibling staging directory `.<name>.impact-stage-<owner>-<random>`, a
//!   manifest ([`MANIFEST`]: relative paths, sizes, SHA-256, program version; no timestamps,
//!   so output stays deterministic) is written last, everything is fsynced, and only then is
//!   the stage swapped in: renamed to the target if there is none, otherwise exchanged with it
//!   atomically (Linux `renameat2(RENAME_EXCHANGE)`), after which the old set (now at the
//!   stage path) is deleted. A reader, or a crash, therefore sees the complete old set or the
//!   complete new set, never a mixture.
//! * A single output **file** ([`OutputFile`]) is written to a temporary sibling and renamed
//!   over the target; `-` means standard output.
//!
//! Nothing that is not ours is ever replaced: an existing directory is replaced only if it is
//! empty or carries our manifest and holds nothing the manifest does not list; an existing
//! file only if it is a regular file that is empty or carries our mark ([`FILE_MARK`], the
//! opening of the provenance every file of ours carries near its start). Symlinks are not
//! followed, so `/dev/null`, FIFOs and links to `/proc/self/fd/1` are refused rather than
//! turned into regular files.
//!
//! Before the swap, every file the manifest lists is read back from the stage and checked
//! against its size and SHA-256: a file removed or altered during the run fails the commit,
//! naming it, instead of being reported as written.
//!
//! A run owns its entries beside the target through an advisory lock (`flock`) on a lock file
//! `.<name>.impact-lock-<token>`, held for the run's whole life and released by the kernel (on
//! NFS by its lock manager) however the run ends. Every run first removes the entries of runs
//! whose lock it can take, which are provably dead, and keeps every other: those of a live run
//! on this machine, in another PID namespace or container, or on another host sharing the file
//! system, and those without a lock file. A program stopped by a signal removes its own entries
//! with [`abandon_all`] before it exits.

//! ```
//! use output::{verify_set, Artifacts, OutputDir};
//! let parent = std::env::temp_dir().join(format!("output-doc-{}", std::process::id()));
//! let mut files = Artifacts::new();
//! files.add("index.md", "# a report\n");
//! files.add("rows/table.csv", "x_m\n0.1\n");
//! let out = OutputDir::prepare(parent.join("set")).unwrap();
//! out.commit(&files).unwrap();
//! assert_eq!(verify_set(&parent.join("set")).unwrap(), 2);
//! std::fs::remove_dir_all(&parent).unwrap();
//! ```

use std::ffi::{OsStr, OsString};
use std::fs::{self, File, OpenOptions};
use std::io::{self, Write};
use std::path::{Component, Path, PathBuf};

use serde::{Deserialize, Serialize};

mod checks;
mod dir;
mod file;
mod hash;
mod live;
mod manifest;
mod stage;
#[cfg(test)]
mod tests;

use checks::*;
use dir::*;
pub use dir::{OutputDir, StreamedFile};
pub use file::OutputFile;
pub use hash::{sha256_hex, Sha256};
pub use live::abandon_all;
use live::*;
use manifest::*;
pub use manifest::{listed_files, verify_set};
pub use stage::clean_stale;
use stage::*;

/// The manifest every output directory carries; its presence marks the directory as ours.
pub const MANIFEST: &str = ".impact-manifest.json";

/// The mark of a single output file of ours: the opening of the compact JSON of
/// `report::provenance::Provenance` (its first field is the program's name), which a JSON
/// document carries as its first key and a `.vtu` in a comment before its root element. A
/// single file has no room for a manifest; this is its signature instead.
pub const FILE_MARK: &str = "{\"program\":\"impact\",";
/// How far into an existing file [`FILE_MARK`] is looked for: the provenance comes first, so
/// it lies within the first few hundred bytes of every file of ours.
pub const FILE_MARK_WINDOW: usize = 4096;

/// Name tags of the entries a run creates beside its target (see [`clean_stale`]).
pub(crate) const STAGE_TAG: &str = ".impact-stage-";
pub(crate) const OLD_TAG: &str = ".impact-old-";
pub(crate) const TMP_TAG: &str = ".impact-tmp-";

/// Why an output could not be written; every message names the path concerned.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    #[error("{}: {what}: {source}", path.display())]
    Io {
        path: PathBuf,
        what: &'static str,
        #[source]
        source: io::Error,
    },
    #[error("{} exists and is not a regular file (it is {kind}); refusing to replace it", path.display())]
    NotRegularFile { path: PathBuf, kind: &'static str },
    #[error("{} exists and is not a directory (it is {kind}); refusing to replace it", path.display())]
    NotADirectory { path: PathBuf, kind: &'static str },
    #[error(
        "{} exists and was not written by impact (no {MANIFEST}); choose another --out or remove it",
        path.display()
    )]
    Foreign { path: PathBuf },
    #[error(
        "{} holds {}, which its {MANIFEST} does not list, so it was not written by impact; \
         refusing to delete it with the old output (move it away or choose another --out)",
        path.display(),
        entry.display()
    )]
    ForeignEntry { path: PathBuf, entry: PathBuf },
    #[error("{}: {why}", path.display())]
    BadManifest { path: PathBuf, why: String },
    #[error(
        "{} lies inside {}, an output set written by impact; writing there would alter that set \
         (choose an --out outside it)",
        path.display(),
        set.display()
    )]
    InsideOutputSet { path: PathBuf, set: PathBuf },
    #[error(
        "{} exists and was not written by impact (its first {FILE_MARK_WINDOW} bytes carry no impact \
         provenance); refusing to replace it (choose another --out or remove it)",
        path.display()
    )]
    ForeignFile { path: PathBuf },
    #[error("{}: the output must be named (not '.', '..' or '/'), because it is staged beside itself", path.display())]
    Unnamed { path: PathBuf },
    #[error("artifact path {} is unsafe: {why}", path.display())]
    UnsafePath { path: PathBuf, why: &'static str },
    #[error(
        "{}: not committed, because the staged file {file} {why} ({}); {} is as it was",
        target.display(),
        staged.display(),
        target.display()
    )]
    Unverified { target: PathBuf, file: String, staged: PathBuf, why: String },
    #[error("{}: not written, because the run is being stopped by a signal", path.display())]
    Stopped { path: PathBuf },
}

pub(crate) fn io_err<'a>(path: &'a Path, what: &'static str) -> impl FnOnce(io::Error) -> OutputError + 'a {
    move |source| OutputError::Io { path: path.to_path_buf(), what, source }
}

/// Files to write, relative to an output directory.
#[derive(Debug, Default)]
pub struct Artifacts {
    files: Vec<(PathBuf, Vec<u8>)>,
}

impl Artifacts {
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds a file; a later file of the same path replaces an earlier one. The path is
    /// checked when the set is committed (or use [`Artifacts::try_add`] to check it now).
    pub fn add(&mut self, path: impl Into<PathBuf>, bytes: impl Into<Vec<u8>>) {
        let path = path.into();
        self.files.retain(|(p, _)| p != &path);
        self.files.push((path, bytes.into()));
    }

    /// Adds a file after checking that its path is relative, has no `..` and is not empty.
    pub fn try_add(&mut self, path: impl Into<PathBuf>, bytes: impl Into<Vec<u8>>) -> Result<(), OutputError> {
        let path = path.into();
        normalize(&path)?;
        self.add(path, bytes);
        Ok(())
    }

    /// Adds every file of `other` under the subdirectory `dir`.
    pub fn nest(&mut self, dir: &str, other: Artifacts) {
        for (p, b) in other.files {
            self.add(Path::new(dir).join(p), b);
        }
    }

    /// Adds every file of `other` at its own path.
    pub fn extend(&mut self, other: Artifacts) {
        for (p, b) in other.files {
            self.add(p, b);
        }
    }

    /// Replaces every file's content by `f(path, content)`.
    pub fn map_files(&mut self, mut f: impl FnMut(&Path, &[u8]) -> Vec<u8>) {
        for (p, b) in &mut self.files {
            *b = f(p, b);
        }
    }

    pub fn paths(&self) -> impl Iterator<Item = &Path> {
        self.files.iter().map(|(p, _)| p.as_path())
    }

    pub fn get(&self, path: &str) -> Option<&[u8]> {
        self.files.iter().find(|(p, _)| p == Path::new(path)).map(|(_, b)| b.as_slice())
    }

    pub fn len(&self) -> usize {
        self.files.len()
    }

    pub fn is_empty(&self) -> bool {
        self.files.is_empty()
    }

    /// Replaces the directory `dir` with exactly these files, as a whole or not at all:
    /// [`OutputDir::prepare`] followed by [`OutputDir::commit`]. Prefer calling those two
    /// directly, `prepare` before the computation, so that an unusable target is reported
    /// before the work is done.
    pub fn write_all(&self, dir: &Path) -> Result<Vec<PathBuf>, OutputError> {
        OutputDir::prepare(dir)?.commit(self)
    }

    /// The files with their paths normalized to `a/b/c` form, after checking that every path
    /// is safe and that no two collide (the same path twice, or a file that is also used as
    /// a directory by another).
    fn checked(&self) -> Result<Vec<(String, &[u8])>, OutputError> {
        let mut out: Vec<(String, &[u8])> = Vec::with_capacity(self.files.len());
        for (p, b) in &self.files {
            out.push((normalize(p)?, b.as_slice()));
        }
        let mut sorted: Vec<&str> = out.iter().map(|(p, _)| p.as_str()).collect();
        sorted.sort_unstable();
        for w in sorted.windows(2) {
            if w[0] == w[1] {
                return Err(OutputError::UnsafePath { path: w[0].into(), why: "it is given twice" });
            }
        }
        // Names such as "a-b" sort between "a" and "a/c", so every later name sharing the
        // prefix is checked, not only the next one.
        for (i, a) in sorted.iter().enumerate() {
            for b in &sorted[i + 1..] {
                if !b.starts_with(a) {
                    break;
                }
                if b.as_bytes().get(a.len()) == Some(&b'/') {
                    return Err(OutputError::UnsafePath {
                        path: (*a).into(),
                        why: "it is a file and also the directory of another file",
                    });
                }
            }
        }
        Ok(out)
    }
}
