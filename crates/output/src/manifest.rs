//! The manifest of an output set: what it lists, reading it, verifying a set against it.

use super::*;

/// Checks an artifact path and returns it as `a/b/c`: relative, without `..`, not empty,
/// UTF-8 (the manifest records it as text) and not the manifest's own name.
pub(crate) fn normalize(path: &Path) -> Result<String, OutputError> {
    let bad = |why| Err(OutputError::UnsafePath { path: path.to_path_buf(), why });
    let mut parts = Vec::new();
    for c in path.components() {
        match c {
            Component::Prefix(_) | Component::RootDir => return bad("it is absolute"),
            Component::ParentDir => return bad("it has a '..' component"),
            Component::CurDir => {}
            Component::Normal(s) => match s.to_str() {
                Some(s) => parts.push(s),
                None => return bad("it is not valid UTF-8"),
            },
        }
    }
    if parts.is_empty() {
        return bad("it is empty");
    }
    if parts == [MANIFEST] {
        return bad("the name is reserved for the output manifest");
    }
    Ok(parts.join("/"))
}

#[derive(Debug, Serialize, Deserialize)]
pub(crate) struct Manifest {
    pub(crate) program: String,
    pub(crate) version: String,
    pub(crate) files: Vec<ManifestEntry>,
}

#[derive(Debug, Clone, Serialize, Deserialize)]
pub(crate) struct ManifestEntry {
    pub(crate) path: String,
    pub(crate) size: u64,
    pub(crate) sha256: String,
}

/// Reads the manifest of an output directory; `Ok(None)` if it has none.
pub(crate) fn read_manifest(dir: &Path) -> Result<Option<Manifest>, OutputError> {
    let path = dir.join(MANIFEST);
    match fs::symlink_metadata(&path) {
        Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(None),
        Err(e) => return Err(io_err(&path, "reading the output manifest")(e)),
        Ok(m) if !m.is_file() => {
            return Err(OutputError::BadManifest { path, why: "the manifest is not a regular file".into() })
        }
        Ok(_) => {}
    }
    let text = fs::read(&path).map_err(io_err(&path, "reading the output manifest"))?;
    let m: Manifest = serde_json::from_slice(&text)
        .map_err(|e| OutputError::BadManifest { path: path.clone(), why: format!("not an impact manifest ({e})") })?;
    if m.program != "impact" {
        return Err(OutputError::BadManifest { path, why: format!("written by {:?}, not impact", m.program) });
    }
    Ok(Some(m))
}

/// The files an output directory's manifest lists: relative path, size in bytes, SHA-256
/// (hex); streamed files included.
pub fn listed_files(dir: &Path) -> Result<Vec<(String, u64, String)>, OutputError> {
    let m = read_manifest(dir)?.ok_or_else(|| OutputError::Foreign { path: dir.to_path_buf() })?;
    Ok(m.files.into_iter().map(|f| (f.path, f.size, f.sha256)).collect())
}

/// Every entry under `dir`, relative and in `a/b` form, with its file type; symlinks are
/// reported as such, never followed.
pub(crate) fn walk(dir: &Path, rel: &str, out: &mut Vec<(String, fs::FileType)>) -> Result<(), OutputError> {
    let here = if rel.is_empty() { dir.to_path_buf() } else { dir.join(rel) };
    for e in fs::read_dir(&here).map_err(io_err(&here, "listing the directory"))? {
        let e = e.map_err(io_err(&here, "listing the directory"))?;
        let ft = e.file_type().map_err(io_err(&e.path(), "reading the file type"))?;
        let name = e.file_name().to_string_lossy().into_owned();
        let r = if rel.is_empty() { name } else { format!("{rel}/{name}") };
        out.push((r.clone(), ft));
        if ft.is_dir() {
            walk(dir, &r, out)?;
        }
    }
    Ok(())
}

/// Checks that the output directory `dir` is complete and consistent: every file its
/// manifest lists is present with the listed size and SHA-256, and nothing else is there.
/// Returns the number of files listed.
pub fn verify_set(dir: &Path) -> Result<usize, OutputError> {
    let m = read_manifest(dir)?.ok_or_else(|| OutputError::Foreign { path: dir.to_path_buf() })?;
    for f in &m.files {
        let p = dir.join(&f.path);
        let bytes = fs::read(&p).map_err(io_err(&p, "reading a listed output file"))?;
        if bytes.len() as u64 != f.size || sha256_hex(&bytes) != f.sha256 {
            return Err(OutputError::BadManifest { path: p, why: "the content differs from the manifest".into() });
        }
    }
    check_only_listed(dir, &m)?;
    Ok(m.files.len())
}

/// Fails with [`OutputError::ForeignEntry`] if `dir` holds anything its manifest does not
/// account for: an unlisted file, a symlink or other special file, or an unlisted directory.
pub(crate) fn check_only_listed(dir: &Path, m: &Manifest) -> Result<(), OutputError> {
    let files: std::collections::HashSet<&str> = m.files.iter().map(|f| f.path.as_str()).collect();
    let dirs: std::collections::HashSet<&str> =
        m.files.iter().flat_map(|f| f.path.match_indices('/').map(|(i, _)| &f.path[..i])).collect();
    let mut entries = Vec::new();
    walk(dir, "", &mut entries)?;
    for (rel, ft) in entries {
        let ok = if ft.is_dir() {
            dirs.contains(rel.as_str())
        } else if ft.is_file() {
            rel == MANIFEST || files.contains(rel.as_str())
        } else {
            false
        };
        if !ok {
            let entry = if ft.is_dir() && fs::symlink_metadata(dir.join(&rel).join(MANIFEST)).is_ok() {
                PathBuf::from(format!("{rel} (another impact output set)"))
            } else {
                PathBuf::from(rel)
            };
            return Err(OutputError::ForeignEntry { path: dir.to_path_buf(), entry });
        }
    }
    Ok(())
}

/// What a path is, for messages about targets we refuse to replace.
pub(crate) fn describe(ft: fs::FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if ft.is_fifo() {
            return "a FIFO";
        }
        if ft.is_socket() {
            return "a socket";
        }
        if ft.is_char_device() {
            return "a character device";
        }
        if ft.is_block_device() {
            return "a block device";
        }
    }
    if ft.is_symlink() {
        "a symbolic link"
    } else if ft.is_dir() {
        "a directory"
    } else if ft.is_file() {
        "a regular file"
    } else {
        "not a regular file"
    }
}

/// Size and SHA-256 of the file at `path`, read in pieces (a streamed file may be large).
fn hash_file(path: &Path) -> io::Result<(u64, String)> {
    let mut f = File::open(path)?;
    let (mut h, mut size, mut buf) = (Sha256::new(), 0u64, vec![0u8; 1 << 16]);
    loop {
        match io::Read::read(&mut f, &mut buf) {
            Ok(0) => return Ok((size, h.hex())),
            Ok(n) => {
                h.update(&buf[..n]);
                size += n as u64;
            }
            Err(e) if e.kind() == io::ErrorKind::Interrupted => {}
            Err(e) => return Err(e),
        }
    }
}

/// Checks the stage on disk against the manifest `m` (whose text is `json`) before it is
/// swapped in for `target`: every listed file present with its size and SHA-256, the
/// manifest as written, nothing else. The error names the first file that differs.
pub(crate) fn verify_stage(stage: &Path, target: &Path, m: &Manifest, json: &[u8]) -> Result<(), OutputError> {
    let fail = |file: &str, why: String| OutputError::Unverified {
        target: target.to_path_buf(),
        file: file.to_string(),
        staged: stage.join(file),
        why,
    };
    for f in &m.files {
        let (size, sha) = hash_file(&stage.join(&f.path)).map_err(|e| match e.kind() {
            io::ErrorKind::NotFound => fail(&f.path, "is missing: something removed it during the run".into()),
            _ => fail(&f.path, format!("cannot be read back ({e})")),
        })?;
        if size != f.size {
            return Err(fail(&f.path, format!("holds {size} bytes where {} were written", f.size)));
        }
        if sha != f.sha256 {
            return Err(fail(&f.path, format!("differs from what was written (SHA-256 {sha}, not {})", f.sha256)));
        }
    }
    match fs::read(stage.join(MANIFEST)) {
        Ok(b) if b == json => {}
        Ok(_) => return Err(fail(MANIFEST, "differs from what was written".into())),
        Err(e) => return Err(fail(MANIFEST, format!("cannot be read back ({e})"))),
    }
    check_only_listed(stage, m).map_err(|e| match e {
        OutputError::ForeignEntry { entry, .. } => {
            fail(&entry.to_string_lossy(), "was not written by this run (found in its stage)".into())
        }
        other => other,
    })
}
