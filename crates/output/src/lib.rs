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
//! Staging names carry the owning process's pid and start time. Every run first removes
//! stale staging entries in the target's parent whose owner is no longer alive, and never
//! touches those of a live concurrent run.

use std::ffi::{OsStr, OsString};
use std::fs::{self, File, OpenOptions};
use std::io::{self, Write};
use std::path::{Component, Path, PathBuf};

use serde::{Deserialize, Serialize};

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
const STAGE_TAG: &str = ".impact-stage-";
const OLD_TAG: &str = ".impact-old-";
const TMP_TAG: &str = ".impact-tmp-";

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
}

fn io_err<'a>(path: &'a Path, what: &'static str) -> impl FnOnce(io::Error) -> OutputError + 'a {
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

/// Checks an artifact path and returns it as `a/b/c`: relative, without `..`, not empty,
/// UTF-8 (the manifest records it as text) and not the manifest's own name.
fn normalize(path: &Path) -> Result<String, OutputError> {
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
struct Manifest {
    program: String,
    version: String,
    files: Vec<ManifestEntry>,
}

#[derive(Debug, Clone, Serialize, Deserialize)]
struct ManifestEntry {
    path: String,
    size: u64,
    sha256: String,
}

/// Reads the manifest of an output directory; `Ok(None)` if it has none.
fn read_manifest(dir: &Path) -> Result<Option<Manifest>, OutputError> {
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
fn walk(dir: &Path, rel: &str, out: &mut Vec<(String, fs::FileType)>) -> Result<(), OutputError> {
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
fn check_only_listed(dir: &Path, m: &Manifest) -> Result<(), OutputError> {
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
fn describe(ft: fs::FileType) -> &'static str {
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

/// The directory holding `path`; `.` for a bare name.
fn parent_of(path: &Path) -> PathBuf {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// Refuses a target inside an existing output set: adding to it would make that set carry
/// an entry its manifest does not list, and a later run would (rightly) refuse to replace it.
fn check_not_inside_set(target: &Path) -> Result<(), OutputError> {
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
fn check_replaceable_dir(target: &Path) -> Result<(), OutputError> {
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
fn check_replaceable_file(target: &Path) -> Result<(), OutputError> {
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

/// The identity of the running process as it appears in staging names: pid and start time
/// (so that a recycled pid is not mistaken for the owner).
fn owner_tag() -> String {
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

/// Whether the owner of a staging entry may still be running. Without /proc there is no way
/// to tell, and the answer is yes: leaving a stale entry is harmless, removing a live one not.
fn owner_alive(pid: u32, start: u64) -> bool {
    if !Path::new("/proc/self").exists() {
        return true;
    }
    match start_time(pid) {
        Some(t) => start == 0 || t == start,
        None => Path::new(&format!("/proc/{pid}")).exists(),
    }
}

fn random_suffix() -> String {
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

/// A sibling name `.<name><tag><owner>-<random>` for staging beside `name`.
fn sibling_name(name: &OsStr, tag: &str) -> OsString {
    let mut s = OsString::from(".");
    s.push(name);
    s.push(format!("{tag}{}-{}", owner_tag(), random_suffix()));
    s
}

/// Parses a staging entry's name into (tag, target name, pid, start time).
fn parse_sibling(name: &str) -> Option<(&'static str, &str, u32, u64)> {
    let rest = name.strip_prefix('.')?;
    for tag in [STAGE_TAG, OLD_TAG, TMP_TAG] {
        if let Some(i) = rest.rfind(tag) {
            let mut f = rest[i + tag.len()..].split('-');
            let (pid, start, rand) = (f.next()?, f.next()?, f.next()?);
            if f.next().is_some() || rand.len() != 16 || !rand.bytes().all(|b| b.is_ascii_hexdigit()) {
                return None;
            }
            return Some((tag, &rest[..i], pid.parse().ok()?, start.parse().ok()?));
        }
    }
    None
}

/// Removes the staging entries in `dir` left by runs that died, and puts back an old set a
/// dead run had moved aside (the fallback swap) if its target is missing. Best effort: a
/// failure here leaves an entry for a later run and does not stop this one.
pub fn clean_stale(dir: &Path) {
    let Ok(entries) = fs::read_dir(dir) else { return };
    for e in entries.flatten() {
        let name = e.file_name();
        let Some((tag, target, pid, start)) = name.to_str().and_then(parse_sibling) else { continue };
        if owner_alive(pid, start) {
            continue;
        }
        let path = e.path();
        if tag == OLD_TAG {
            // Recovery rule of the fallback swap: the old set was moved aside and the run died
            // before the new set took its place, so the old set is restored.
            let t = dir.join(target);
            if matches!(fs::symlink_metadata(&t), Err(ref e) if e.kind() == io::ErrorKind::NotFound)
                && fs::rename(&path, &t).is_ok()
            {
                let _ = sync_dir(dir);
                continue;
            }
        }
        remove_entry(&path);
    }
}

/// Removes a file or directory tree without following symlinks; errors are ignored.
fn remove_entry(path: &Path) {
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

fn sync_dir(dir: &Path) -> io::Result<()> {
    File::open(dir)?.sync_all()
}

/// Creates a new entry beside `target` with a fresh staging name, retrying on the (unlikely)
/// collision of the random part.
fn create_sibling<T>(
    parent: &Path,
    name: &OsStr,
    tag: &str,
    create: impl Fn(&Path) -> io::Result<T>,
) -> Result<(PathBuf, T), OutputError> {
    let mut attempt = 0;
    loop {
        let p = parent.join(sibling_name(name, tag));
        match create(&p) {
            Ok(t) => return Ok((p, t)),
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists && attempt < 8 => attempt += 1,
            Err(e) => return Err(io_err(&p, "creating the staging area beside the output")(e)),
        }
    }
}

/// An output directory made ready for a run: the target checked and a staging directory
/// created beside it. [`OutputDir::commit`] swaps the staged set in; dropping an uncommitted
/// `OutputDir` removes the stage and leaves the target as it was.
#[derive(Debug)]
pub struct OutputDir {
    target: PathBuf,
    parent: PathBuf,
    stage: Option<PathBuf>,
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
    /// removes stale staging entries of dead runs there, and creates this run's stage, which
    /// also proves the parent writable. Call it before the computation.
    pub fn prepare(target: impl AsRef<Path>) -> Result<OutputDir, OutputError> {
        let target = target.as_ref().to_path_buf();
        let name = target.file_name().ok_or_else(|| OutputError::Unnamed { path: target.clone() })?.to_owned();
        let parent = parent_of(&target);
        check_not_inside_set(&target)?;
        fs::create_dir_all(&parent).map_err(io_err(&parent, "creating the parent directory of the output"))?;
        check_replaceable_dir(&target)?;
        clean_stale(&parent);
        let (stage, ()) = create_sibling(&parent, &name, STAGE_TAG, |p| fs::create_dir(p))?;
        Ok(OutputDir { target, parent, stage: Some(stage), streams: Vec::new() })
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
        let stage = self.stage.clone().expect("an OutputDir holds its stage until committed");
        let path = stage.join(&rel);
        if let Some(dir) = path.parent() {
            fs::create_dir_all(dir).map_err(io_err(dir, "creating a staged directory"))?;
        }
        let mut o = OpenOptions::new();
        o.write(true).create_new(true);
        #[cfg(unix)]
        {
            use std::os::unix::fs::OpenOptionsExt;
            o.mode(0o644);
        }
        let file = o.open(&path).map_err(io_err(&path, "creating a staged file"))?;
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

    /// Writes `artifacts` into the stage, writes the manifest last, syncs, and swaps the stage
    /// in for the target. On error the target is unchanged (the old set or nothing) and the
    /// stage is removed. Returns the paths of the written files under the target.
    pub fn commit(mut self, artifacts: &Artifacts) -> Result<Vec<PathBuf>, OutputError> {
        let stage = self.stage.clone().expect("an OutputDir holds its stage until committed");
        let files = artifacts.checked()?;
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
        let mut dirs = vec![stage.clone()];
        let mut entries = Vec::with_capacity(files.len());
        for (rel, bytes) in &files {
            let p = stage.join(rel);
            let dir = p.parent().unwrap_or(&stage);
            if !dir.exists() {
                fs::create_dir_all(dir).map_err(io_err(dir, "creating a staged directory"))?;
                for d in dir.ancestors().take_while(|d| *d != stage) {
                    dirs.push(d.to_path_buf());
                }
            }
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
        // Everything staged must be on disk before the swap is, or a power cut could leave
        // the new name pointing at incomplete files.
        #[cfg(target_os = "linux")]
        {
            // One syncfs costs one journal commit; an fsync per file costs one each (about
            // 2 s instead of a few ms for 300 files on ext4).
            let f = File::open(&stage).map_err(io_err(&stage, "opening the stage to sync it"))?;
            rustix::fs::syncfs(&f).map_err(|e| io_err(&stage, "syncing the stage")(e.into()))?;
        }
        #[cfg(not(target_os = "linux"))]
        {
            dirs.sort();
            dirs.dedup();
            for d in dirs.iter().rev() {
                sync_dir(d).map_err(io_err(d, "syncing a staged directory"))?;
            }
        }
        // The target may have changed during the computation; check it again.
        check_replaceable_dir(&self.target)?;
        swap_in(&self.parent, &stage, &self.target)?;
        // The stage path now holds the old set, or nothing.
        self.stage = None;
        remove_entry(&stage);
        sync_dir(&self.parent).map_err(io_err(&self.parent, "syncing the output's parent directory"))?;
        Ok(files
            .iter()
            .map(|(rel, _)| rel)
            .chain(streamed.iter().map(|e| &e.path))
            .map(|rel| self.target.join(rel))
            .collect())
    }
}

impl Drop for OutputDir {
    fn drop(&mut self) {
        if let Some(stage) = self.stage.take() {
            remove_entry(&stage);
        }
    }
}

/// Whether staged files are synced one by one; on Linux the whole stage is synced at once.
const PER_FILE_SYNC: bool = cfg!(not(target_os = "linux"));

/// Creates `path` (mode 0644 less the umask) with `bytes`, and syncs it if `sync`.
fn write_staged(path: &Path, bytes: &[u8], sync: bool) -> Result<(), OutputError> {
    let mut o = OpenOptions::new();
    o.write(true).create_new(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        o.mode(0o644);
    }
    let mut f = o.open(path).map_err(io_err(path, "creating a staged file"))?;
    f.write_all(bytes).map_err(io_err(path, "writing a staged file"))?;
    if sync {
        f.sync_all().map_err(io_err(path, "syncing a staged file"))?;
    }
    Ok(())
}

/// Puts the complete stage at `target`: a rename if there is no target, else an atomic
/// exchange, falling back to [`swap_aside`] where the exchange is not available.
fn swap_in(parent: &Path, stage: &Path, target: &Path) -> Result<(), OutputError> {
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
        swap_aside(parent, stage, target)
    } else {
        fs::rename(stage, target).map_err(io_err(target, "moving the new output in"))
    }
}

/// The swap without an atomic exchange: move the old set aside under a name that marks it
/// as ours, move the stage in, delete the old set. A crash between the two renames leaves no
/// target; the next run's [`clean_stale`] then restores the old set from the aside name.
fn swap_aside(parent: &Path, stage: &Path, target: &Path) -> Result<(), OutputError> {
    let name = target.file_name().ok_or_else(|| OutputError::Unnamed { path: target.to_path_buf() })?;
    let (aside, ()) = create_sibling(parent, name, OLD_TAG, |p| fs::rename(target, p))?;
    if let Err(e) = fs::rename(stage, target) {
        // Put the old set back so that a failure leaves the earlier output in place.
        let _ = fs::rename(&aside, target);
        return Err(io_err(target, "moving the new output in")(e));
    }
    let _ = sync_dir(parent);
    remove_entry(&aside);
    Ok(())
}

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
    tmp: Option<(PathBuf, File)>,
}

impl OutputFile {
    /// Checks `target` (`-` means standard output), creates its parent directories, removes
    /// stale temporaries of dead runs there, and creates this run's temporary file, which also
    /// proves the directory writable. Call it before the computation.
    pub fn prepare(target: impl AsRef<Path>) -> Result<OutputFile, OutputError> {
        let target = target.as_ref();
        if target == Path::new("-") {
            return Ok(OutputFile { target: None, parent: PathBuf::new(), tmp: None });
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
        let (tmp, file) = create_sibling(&parent, &name, TMP_TAG, |p| {
            let mut o = OpenOptions::new();
            o.write(true).create_new(true);
            #[cfg(unix)]
            {
                use std::os::unix::fs::OpenOptionsExt;
                o.mode(0o644);
            }
            o.open(p)
        })?;
        Ok(OutputFile { target: Some(target.to_path_buf()), parent, tmp: Some((tmp, file)) })
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
            check_replaceable_file(&target)?;
            fs::rename(&tmp, &target).map_err(io_err(&target, "moving the output file in"))?;
            sync_dir(&self.parent).map_err(io_err(&self.parent, "syncing the output's directory"))
        })();
        if result.is_err() {
            remove_entry(&tmp);
        }
        result.map(|()| Some(target))
    }
}

impl Drop for OutputFile {
    fn drop(&mut self) {
        if let Some((tmp, _)) = self.tmp.take() {
            remove_entry(&tmp);
        }
    }
}

/// SHA-256 of `bytes` as lowercase hex (FIPS 180-4), for the manifest.
pub fn sha256_hex(bytes: &[u8]) -> String {
    let mut h = Sha256::new();
    h.update(bytes);
    h.hex()
}

/// SHA-256 (FIPS 180-4, the `sha2` crate) fed in pieces, for files streamed to disk that are
/// never whole in memory.
#[derive(Debug, Clone, Default)]
pub struct Sha256(sha2::Sha256);

impl Sha256 {
    /// The hash of nothing yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// Feeds `bytes`.
    pub fn update(&mut self, bytes: &[u8]) {
        sha2::Digest::update(&mut self.0, bytes);
    }

    /// The digest as lowercase hex.
    pub fn hex(self) -> String {
        sha2::Digest::finalize(self.0).iter().map(|b| format!("{b:02x}")).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
        assert_eq!(
            sha256_hex(&vec![b'a'; 1_000_000]),
            "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0"
        );
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
}
