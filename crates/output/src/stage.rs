//! Staging entries beside a target: their names (owner and a random part), the owner's liveness, and the removal of the entries of runs that died.

use super::*;

/// The identity of the running process as it appears in staging names: pid and start time
/// (so that a recycled pid is not mistaken for the owner).
pub(crate) fn owner_tag() -> String {
    let pid = std::process::id();
    format!("{pid}-{}", start_time(pid).unwrap_or(0))
}

/// The start time of process `pid` in clock ticks since boot (field 22 of /proc/pid/stat).
pub(crate) fn start_time(pid: u32) -> Option<u64> {
    let s = fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    // The command name (field 2) may contain spaces and parentheses; it ends at the last ')'.
    let rest = &s[s.rfind(')')? + 1..];
    rest.split_whitespace().nth(19)?.parse().ok()
}

/// Whether the owner of a staging entry may still be running. Without /proc there is no way
/// to tell, and the answer is yes: leaving a stale entry is harmless, removing a live one not.
pub(crate) fn owner_alive(pid: u32, start: u64) -> bool {
    if !Path::new("/proc/self").exists() {
        return true;
    }
    match start_time(pid) {
        Some(t) => start == 0 || t == start,
        None => Path::new(&format!("/proc/{pid}")).exists(),
    }
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

/// A sibling name `.<name><tag><owner>-<random>` for staging beside `name`.
pub(crate) fn sibling_name(name: &OsStr, tag: &str) -> OsString {
    let mut s = OsString::from(".");
    s.push(name);
    s.push(format!("{tag}{}-{}", owner_tag(), random_suffix()));
    s
}

/// Parses a staging entry's name into (tag, target name, pid, start time).
pub(crate) fn parse_sibling(name: &str) -> Option<(&'static str, &str, u32, u64)> {
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

/// Creates a new entry beside `target` with a fresh staging name, retrying on the (unlikely)
/// collision of the random part.
pub(crate) fn create_sibling<T>(
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
