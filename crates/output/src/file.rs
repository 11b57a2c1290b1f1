//! A single output file renamed over its target.

use super::*;

/// A single output file made ready for a run, or standard output (`-`). The file is written
/// to a temporary sibling and renamed over the target on commit; dropping an uncommitted
/// `OutputFile` removes the temporary file.
///
/// An existing target is replaced only if it is a regular file that is empty or was written
/// by impact (it carries [`FILE_MARK`] near its start), so `--out FILE` overwrites one's own
/// earlier result but never a scene file or anything else of the user's. Devices, FIFOs,
/// sockets, directories and symlinks (not followed) are refused. The bytes committed should
/// carry the mark themselves, or the next run will refuse to replace them.
#[derive(Debug)]
pub struct OutputFile {
    target: Option<PathBuf>,
    parent: PathBuf,
    /// The lock that keeps other runs from judging the temporary file dead.
    owner: Option<Owner>,
    tmp: Option<(PathBuf, File)>,
}

impl OutputFile {
    /// Checks `target` (`-` means standard output), creates its parent directories, removes
    /// stale temporaries of dead runs there, and creates this run's temporary file, which also
    /// proves the directory writable. Call it before the computation.
    pub fn prepare(target: impl AsRef<Path>) -> Result<OutputFile, OutputError> {
        let target = target.as_ref();
        if target == Path::new("-") {
            return Ok(OutputFile { target: None, parent: PathBuf::new(), owner: None, tmp: None });
        }
        let name = match target.components().next_back() {
            Some(Component::Normal(n)) => n.to_owned(),
            _ => return Err(OutputError::Unnamed { path: target.to_path_buf() }),
        };
        let parent = parent_of(target);
        check_not_inside_set(target)?;
        fs::create_dir_all(&parent).map_err(io_err(&parent, "creating the parent directory of the output"))?;
        check_replaceable_file(target)?;
        clean_stale(&parent);
        let (owner, tmp, file) = claim(&parent, &name, target, TMP_TAG, |p| staged_options().open(p))?;
        Ok(OutputFile { target: Some(target.to_path_buf()), parent, owner: Some(owner), tmp: Some((tmp, file)) })
    }

    /// Whether this output is standard output.
    pub fn is_stdout(&self) -> bool {
        self.target.is_none()
    }

    /// The target file; `None` for standard output.
    pub fn path(&self) -> Option<&Path> {
        self.target.as_deref()
    }

    /// Writes `bytes` and puts them in place. Returns the file written, `None` for standard
    /// output. On error an existing target is unchanged.
    pub fn commit(mut self, bytes: &[u8]) -> Result<Option<PathBuf>, OutputError> {
        let Some(target) = self.target.clone() else {
            let mut out = io::stdout().lock();
            out.write_all(bytes).and_then(|()| out.flush()).map_err(io_err(Path::new("-"), "writing to stdout"))?;
            return Ok(None);
        };
        let (tmp, mut file) = self.tmp.take().expect("an OutputFile holds its temporary file until committed");
        let result = (|| {
            file.write_all(bytes).map_err(io_err(&tmp, "writing the output file"))?;
            file.sync_all().map_err(io_err(&tmp, "syncing the output file"))?;
            drop(file);
            let live = live();
            live.check(&target)?;
            check_replaceable_file(&target)?;
            fs::rename(&tmp, &target).map_err(io_err(&target, "moving the output file in"))
        })();
        // After the rename the temporary name holds nothing, and removing it is a no-op.
        if let Some(owner) = self.owner.take() {
            release(owner, Some(&tmp));
        }
        result?;
        sync_dir(&self.parent).map_err(io_err(&self.parent, "syncing the output's directory"))?;
        Ok(Some(target))
    }
}

impl Drop for OutputFile {
    fn drop(&mut self) {
        let tmp = self.tmp.take().map(|(p, _)| p);
        if let Some(owner) = self.owner.take() {
            release(owner, tmp.as_deref());
        }
    }
}
