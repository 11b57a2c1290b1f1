//! What may be replaced: a target inside an output set, a directory or file not ours.

use super::*;

/// The directory holding `path`; `.` for a bare name.
pub(crate) fn parent_of(path: &Path) -> PathBuf {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// Refuses a target inside an existing output set: adding to it would make that set carry
/// an entry its manifest does not list, and a later run would (rightly) refuse to replace it.
pub(crate) fn check_not_inside_set(target: &Path) -> Result<(), OutputError> {
    let abs = std::path::absolute(target).map_err(io_err(target, "resolving the path"))?;
    for a in abs.ancestors().skip(1) {
        if fs::symlink_metadata(a.join(MANIFEST)).is_ok() {
            return Err(OutputError::InsideOutputSet { path: target.to_path_buf(), set: a.to_path_buf() });
        }
    }
    Ok(())
}

/// Checks that `target` may be replaced by an output directory: absent, an empty directory,
/// or a directory carrying our manifest and nothing it does not list.
pub(crate) fn check_replaceable_dir(target: &Path) -> Result<(), OutputError> {
    let m = match fs::symlink_metadata(target) {
        Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(()),
        Err(e) => return Err(io_err(target, "inspecting the output directory")(e)),
        Ok(m) => m,
    };
    if !m.is_dir() {
        return Err(OutputError::NotADirectory { path: target.to_path_buf(), kind: describe(m.file_type()) });
    }
    match read_manifest(target)? {
        Some(manifest) => check_only_listed(target, &manifest),
        None => {
            let mut it = fs::read_dir(target).map_err(io_err(target, "listing the output directory"))?;
            if it.next().is_none() {
                Ok(())
            } else {
                Err(OutputError::Foreign { path: target.to_path_buf() })
            }
        }
    }
}

/// Checks that `target` may be replaced by an output file: absent, or a regular file that is
/// empty or ours (carries [`FILE_MARK`] within its first [`FILE_MARK_WINDOW`] bytes).
pub(crate) fn check_replaceable_file(target: &Path) -> Result<(), OutputError> {
    let m = match fs::symlink_metadata(target) {
        Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(()),
        Err(e) => return Err(io_err(target, "inspecting the output file")(e)),
        Ok(m) => m,
    };
    if !m.is_file() {
        return Err(OutputError::NotRegularFile { path: target.to_path_buf(), kind: describe(m.file_type()) });
    }
    if m.len() == 0 {
        return Ok(());
    }
    let mut head = Vec::with_capacity(FILE_MARK_WINDOW);
    File::open(target)
        .and_then(|f| io::Read::read_to_end(&mut io::Read::take(f, FILE_MARK_WINDOW as u64), &mut head))
        .map_err(io_err(target, "reading the start of the existing output file"))?;
    if head.windows(FILE_MARK.len()).any(|w| w == FILE_MARK.as_bytes()) {
        Ok(())
    } else {
        Err(OutputError::ForeignFile { path: target.to_path_buf() })
    }
}
