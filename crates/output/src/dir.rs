//! An output directory written whole or not at all.

use super::*;

/// An output directory made ready for a run: the target checked and a staging directory
/// created beside it, with a lock file held for the run's life. [`OutputDir::commit`] checks
/// the staged set against what was written and swaps it in; dropping an uncommitted
/// `OutputDir` removes the stage and leaves the target as it was.
#[derive(Debug)]
pub struct OutputDir {
    target: PathBuf,
    parent: PathBuf,
    /// The lock that keeps other runs from judging the stage dead; released after the stage.
    owner: Option<Owner>,
    pub(crate) stage: Option<PathBuf>,
    /// Files streamed into the stage ([`OutputDir::stream`]): their paths, and their manifest
    /// entries once finished.
    streams: Vec<(String, Option<ManifestEntry>)>,
}

/// A file written straight into an [`OutputDir`]'s stage as it is produced, for output too
/// large to hold in memory (an ensemble's feature rows). It is hashed as it is written,
/// becomes part of the set only through [`OutputDir::finish_stream`], and disappears with
/// the stage if the run fails.
#[derive(Debug)]
pub struct StreamedFile {
    rel: String,
    path: PathBuf,
    writer: io::BufWriter<File>,
    hash: Sha256,
    size: u64,
}

impl StreamedFile {
    /// Bytes written so far.
    pub fn size(&self) -> u64 {
        self.size
    }
}

impl Write for StreamedFile {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        let n = self.writer.write(buf)?;
        self.hash.update(&buf[..n]);
        self.size += n as u64;
        Ok(n)
    }
    fn flush(&mut self) -> io::Result<()> {
        self.writer.flush()
    }
}

impl OutputDir {
    /// Checks that `target` can be replaced (absent, empty, or an earlier impact output with
    /// nothing foreign in it; not inside another output set), creates its parent directories,
    /// removes the staging entries of provably dead runs there, and creates this run's lock
    /// and stage, which also proves the parent writable. Call it before the computation.
    pub fn prepare(target: impl AsRef<Path>) -> Result<OutputDir, OutputError> {
        let target = named_target(target.as_ref())?;
        let name = target.file_name().ok_or_else(|| OutputError::Unnamed { path: target.clone() })?.to_owned();
        let parent = parent_of(&target);
        check_not_inside_set(&target)?;
        fs::create_dir_all(&parent).map_err(io_err(&parent, "creating the parent directory of the output"))?;
        check_replaceable_dir(&target)?;
        clean_stale(&parent);
        let (owner, stage, ()) = claim(&parent, &name, &target, STAGE_TAG, |p| fs::create_dir(p))?;
        Ok(OutputDir { target, parent, owner: Some(owner), stage: Some(stage), streams: Vec::new() })
    }

    fn stage(&self) -> PathBuf {
        self.stage.clone().expect("an OutputDir holds its stage until committed")
    }

    /// Opens the file `rel` (a relative path, as for [`Artifacts::add`]) in the stage for
    /// writing as the run goes. It joins the set when passed to [`OutputDir::finish_stream`];
    /// a stream never finished makes [`OutputDir::commit`] fail, and no artifact may take
    /// its path.
    pub fn stream(&mut self, rel: &str) -> Result<StreamedFile, OutputError> {
        let rel = normalize(Path::new(rel))?;
        if self.streams.iter().any(|(p, _)| *p == rel) {
            return Err(OutputError::UnsafePath { path: rel.into(), why: "it is given twice" });
        }
        let stage = self.stage();
        let path = stage.join(&rel);
        create_staged_dirs(&stage, &path)?;
        let file = staged_options().open(&path).map_err(io_err(&path, "creating a staged file"))?;
        self.streams.push((rel.clone(), None));
        Ok(StreamedFile {
            rel,
            path,
            writer: io::BufWriter::with_capacity(1 << 16, file),
            hash: Sha256::new(),
            size: 0,
        })
    }

    /// Completes a streamed file: flushes it (synced with the rest of the stage on commit)
    /// and records it for the manifest.
    pub fn finish_stream(&mut self, mut file: StreamedFile) -> Result<(), OutputError> {
        file.writer.flush().map_err(io_err(&file.path, "writing a staged file"))?;
        if PER_FILE_SYNC {
            file.writer.get_ref().sync_all().map_err(io_err(&file.path, "syncing a staged file"))?;
        }
        let entry = ManifestEntry { path: file.rel.clone(), size: file.size, sha256: file.hash.hex() };
        match self.streams.iter_mut().find(|(p, _)| *p == file.rel) {
            Some(slot) => slot.1 = Some(entry),
            None => {
                return Err(OutputError::UnsafePath { path: file.rel.into(), why: "it was not opened by this output" })
            }
        }
        Ok(())
    }

    /// The target directory.
    pub fn path(&self) -> &Path {
        &self.target
    }

    /// Writes `artifacts` into the stage, writes the manifest last, syncs, reads every listed
    /// file back against its size and SHA-256, and swaps the stage in for the target. On error
    /// (a staged file missing or altered is one, named) the target is unchanged (the old set
    /// or nothing) and the stage is removed. Returns the paths of the written files under the
    /// target.
    pub fn commit(mut self, artifacts: &Artifacts) -> Result<Vec<PathBuf>, OutputError> {
        let stage = self.stage();
        let files = artifacts.checked()?;
        let streamed = self.finished_streams(&files)?;
        let mut entries = Vec::with_capacity(files.len() + streamed.len());
        for (rel, bytes) in &files {
            let p = stage.join(rel);
            create_staged_dirs(&stage, &p)?;
            write_staged(&p, bytes, PER_FILE_SYNC)?;
            entries.push(ManifestEntry { path: rel.clone(), size: bytes.len() as u64, sha256: sha256_hex(bytes) });
        }
        entries.extend(streamed.iter().cloned());
        entries.sort_by(|a, b| a.path.cmp(&b.path));
        let manifest = Manifest { program: "impact".into(), version: env!("CARGO_PKG_VERSION").into(), files: entries };
        let mut json = serde_json::to_string_pretty(&manifest).expect("a manifest serializes");
        json.push('\n');
        // Written last: a stage with a manifest is complete.
        write_staged(&stage.join(MANIFEST), json.as_bytes(), PER_FILE_SYNC)?;
        sync_stage(&stage)?;
        #[cfg(test)]
        tests::before_verify(&stage);
        // What is on disk, not what was meant to be: a file removed or altered while the run
        // went on must fail the run, not be reported as written.
        verify_stage(&stage, &self.target, &manifest, json.as_bytes())?;
        {
            let live = live();
            live.check(&self.target)?;
            // The target may have changed during the computation; check it again.
            check_replaceable_dir(&self.target)?;
            let aside = self.owner.as_ref().expect("an OutputDir holds its lock until committed").entry(OLD_TAG);
            swap_in(&stage, &self.target, &aside)?;
        }
        // The stage path now holds the old set, or nothing.
        self.release();
        sync_dir(&self.parent).map_err(io_err(&self.parent, "syncing the output's parent directory"))?;
        Ok(files
            .iter()
            .map(|(rel, _)| rel)
            .chain(streamed.iter().map(|e| &e.path))
            .map(|rel| self.target.join(rel))
            .collect())
    }

    /// The manifest entries of the streamed files, once every stream is finished and none
    /// clashes with an artifact.
    fn finished_streams(&self, files: &[(String, &[u8])]) -> Result<Vec<ManifestEntry>, OutputError> {
        let mut streamed = Vec::with_capacity(self.streams.len());
        for (rel, entry) in &self.streams {
            let Some(entry) = entry else {
                return Err(OutputError::UnsafePath {
                    path: rel.into(),
                    why: "its stream was opened but not finished",
                });
            };
            // A streamed file is a file: no artifact may take its path or use it as a directory.
            if files
                .iter()
                .any(|(p, _)| p == rel || p.starts_with(&format!("{rel}/")) || rel.starts_with(&format!("{p}/")))
            {
                return Err(OutputError::UnsafePath {
                    path: rel.into(),
                    why: "it is streamed and also given as a file",
                });
            }
            streamed.push(entry.clone());
        }
        Ok(streamed)
    }

    /// Removes what the stage path holds, then the lock.
    fn release(&mut self) {
        if let Some(owner) = self.owner.take() {
            release(owner, self.stage.take().as_deref());
        }
    }
}

impl Drop for OutputDir {
    fn drop(&mut self) {
        self.release();
    }
}

/// The target with a trailing `.` resolved (`--out .` inside an empty directory names that
/// directory), since the stage is created beside the target under the target's own name.
fn named_target(target: &Path) -> Result<PathBuf, OutputError> {
    // Rebuilt from its components: `a/.` and `a/./` become `a`, a leading `.` stays.
    let t: PathBuf = target.components().collect();
    if matches!(t.components().next_back(), Some(Component::CurDir | Component::ParentDir)) {
        return fs::canonicalize(&t).map_err(io_err(target, "resolving the output directory"));
    }
    Ok(t)
}

/// Creates the directories between `stage` and the file `path` one level at a time: never the
/// stage itself, so that a stage removed from under the run (a signal) is not recreated.
fn create_staged_dirs(stage: &Path, path: &Path) -> Result<(), OutputError> {
    let Some(dir) = path.parent() else { return Ok(()) };
    let Ok(rel) = dir.strip_prefix(stage) else { return Ok(()) };
    let mut d = stage.to_path_buf();
    for c in rel.components() {
        d.push(c);
        match fs::create_dir(&d) {
            Err(e) if e.kind() != io::ErrorKind::AlreadyExists => {
                return Err(io_err(&d, "creating a staged directory")(e));
            }
            _ => {}
        }
    }
    Ok(())
}

/// Puts everything staged on disk before the swap is, or a power cut could leave the new name
/// pointing at incomplete files.
fn sync_stage(stage: &Path) -> Result<(), OutputError> {
    #[cfg(target_os = "linux")]
    {
        // One syncfs costs one journal commit; an fsync per file costs one each (about
        // 2 s instead of a few ms for 300 files on ext4).
        let f = File::open(stage).map_err(io_err(stage, "opening the stage to sync it"))?;
        rustix::fs::syncfs(&f).map_err(|e| io_err(stage, "syncing the stage")(e.into()))?;
    }
    #[cfg(not(target_os = "linux"))]
    {
        let mut entries = Vec::new();
        walk(stage, "", &mut entries)?;
        let mut dirs: Vec<PathBuf> = entries.iter().filter(|(_, t)| t.is_dir()).map(|(r, _)| stage.join(r)).collect();
        dirs.sort();
        for d in dirs.iter().rev().chain(std::iter::once(&stage.to_path_buf())) {
            sync_dir(d).map_err(io_err(d, "syncing a staged directory"))?;
        }
    }
    Ok(())
}

/// Whether staged files are synced one by one; on Linux the whole stage is synced at once.
pub(crate) const PER_FILE_SYNC: bool = cfg!(not(target_os = "linux"));

/// Options for creating a staged file: new only, mode 0644 less the umask.
pub(crate) fn staged_options() -> OpenOptions {
    let mut o = OpenOptions::new();
    o.write(true).create_new(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        o.mode(0o644);
    }
    o
}

/// Creates `path` with `bytes`, and syncs it if `sync`.
pub(crate) fn write_staged(path: &Path, bytes: &[u8], sync: bool) -> Result<(), OutputError> {
    let f = staged_options().open(path).map_err(io_err(path, "creating a staged file"))?;
    write_synced(f, path, bytes, sync)
}

/// Writes `bytes` to the open `f` named `path`; every error (a full disk among them) names it.
pub(crate) fn write_synced(mut f: File, path: &Path, bytes: &[u8], sync: bool) -> Result<(), OutputError> {
    f.write_all(bytes).map_err(io_err(path, "writing a staged file"))?;
    if sync {
        f.sync_all().map_err(io_err(path, "syncing a staged file"))?;
    }
    Ok(())
}

/// Puts the complete stage at `target`: a rename if there is no target, else an atomic
/// exchange, falling back to [`swap_aside`] (through `aside`) where the exchange is not
/// available.
pub(crate) fn swap_in(stage: &Path, target: &Path, aside: &Path) -> Result<(), OutputError> {
    let exists = match fs::symlink_metadata(target) {
        Err(e) if e.kind() == io::ErrorKind::NotFound => false,
        Err(e) => return Err(io_err(target, "inspecting the output directory")(e)),
        Ok(_) => true,
    };
    #[cfg(target_os = "linux")]
    {
        use rustix::fs::{renameat_with, RenameFlags, CWD};
        use rustix::io::Errno;
        let flags = if exists { RenameFlags::EXCHANGE } else { RenameFlags::NOREPLACE };
        match renameat_with(CWD, stage, CWD, target, flags) {
            Ok(()) => return Ok(()),
            // The file system or kernel lacks renameat2 or this flag: use the portable way.
            Err(Errno::INVAL | Errno::NOSYS | Errno::OPNOTSUPP) => {}
            Err(e) => return Err(io_err(target, "swapping the new output in")(e.into())),
        }
    }
    if exists {
        swap_aside(stage, target, aside)
    } else {
        fs::rename(stage, target).map_err(io_err(target, "moving the new output in"))
    }
}

/// The swap without an atomic exchange: move the old set aside to `aside` (a name that marks
/// it as the run's, covered by its lock), move the stage in, delete the old set. A crash
/// between the two renames leaves no target; the next run's [`clean_stale`] then restores the
/// old set from the aside name.
pub(crate) fn swap_aside(stage: &Path, target: &Path, aside: &Path) -> Result<(), OutputError> {
    fs::rename(target, aside).map_err(io_err(aside, "moving the old output aside"))?;
    if let Err(e) = fs::rename(stage, target) {
        // Put the old set back so that a failure leaves the earlier output in place.
        let _ = fs::rename(aside, target);
        return Err(io_err(target, "moving the new output in")(e));
    }
    let _ = sync_dir(&parent_of(target));
    remove_entry(aside);
    Ok(())
}
