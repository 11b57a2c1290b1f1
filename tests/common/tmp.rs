//! A temporary directory for one test's scene files and output, removed when dropped.

use std::path::{Path, PathBuf};

/// A fresh temporary directory.
pub fn tmp() -> Tmp {
    Tmp(tempfile::tempdir().expect("a temporary directory"))
}

/// A temporary directory; see [`tmp`].
pub struct Tmp(tempfile::TempDir);

impl Tmp {
    pub fn path(&self) -> &Path {
        self.0.path()
    }

    /// `name` inside the directory (nothing is created).
    pub fn join(&self, name: impl AsRef<Path>) -> PathBuf {
        self.0.path().join(name)
    }

    /// Writes `contents` to `name` inside the directory and returns its path.
    pub fn write(&self, name: impl AsRef<Path>, contents: impl AsRef<[u8]>) -> PathBuf {
        let path = self.join(name);
        std::fs::write(&path, contents).unwrap_or_else(|e| panic!("writing {}: {e}", path.display()));
        path
    }
}

/// The entries a run creates beside its target (stages, lock files) and must not leave
/// behind: every name in `dir` that holds ".impact-".
pub fn leftovers(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.contains(".impact-"))
        .collect()
}
