//! The temporary files of an atomic write: their names (whose run left them), the folder's lock,
//! and the journal of a batch's renames that lets a killed run's set be completed.

use std::path::{Path, PathBuf};

use crate::{Error, Result};

/// The prefix of every temporary file this program writes: `.ssdo-tmp.<pid>.<random>.<name>`.
/// Only names of that form are ever swept, so no user's file can be taken for one.
pub(super) const TEMPORARY_PREFIX: &str = ".ssdo-tmp.";

/// A fresh temporary file beside `path`, created exclusively (never over an existing file), and
/// its name. The random part comes from the standard library's per-process random hash keys
/// and a counter, so two runs, or two threads of one, never pick the same name.
pub(super) fn create_temporary(path: &Path) -> std::io::Result<(PathBuf, std::fs::File)> {
    use std::hash::{BuildHasher, Hasher};
    use std::sync::atomic::{AtomicU64, Ordering};
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    loop {
        let mut hasher = std::collections::hash_map::RandomState::new().build_hasher();
        hasher.write_u64(COUNTER.fetch_add(1, Ordering::Relaxed));
        let tmp =
            path.with_file_name(format!("{TEMPORARY_PREFIX}{}.{:016x}.{name}", std::process::id(), hasher.finish()));
        match std::fs::OpenOptions::new().write(true).create_new(true).open(&tmp) {
            Ok(file) => return Ok((tmp, file)),
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => continue,
            Err(e) => return Err(e),
        }
    }
}

/// The process id in a temporary file's name, if the name is one of this program's.
pub(super) fn temporary_owner(name: &str) -> Option<u32> {
    let rest = name.strip_prefix(TEMPORARY_PREFIX)?;
    let (pid, rest) = rest.split_once('.')?;
    let (random, target) = rest.split_once('.')?;
    let well_formed = random.len() == 16 && random.bytes().all(|b| b.is_ascii_hexdigit()) && !target.is_empty();
    well_formed.then(|| pid.parse().ok()).flatten()
}

/// Whether the process `pid` is alive (Linux's /proc; elsewhere every process counts as alive).
pub(super) fn process_alive(pid: u32) -> bool {
    !Path::new("/proc/self").exists() || Path::new(&format!("/proc/{pid}")).exists()
}

/// Whether the process `pid` is a run of this program: alive, and (where /proc says) running the
/// same executable. A pid the system has given to another program since (pid 1, a shell) owns
/// no lock of ours.
fn is_this_program(pid: u32) -> bool {
    if !process_alive(pid) {
        return false;
    }
    // The executable where the system lets us read it, else the command's name.
    let exe = |p: &str| std::fs::read_link(format!("/proc/{p}/exe")).ok();
    let name = |p: &str| std::fs::read_to_string(format!("/proc/{p}/comm")).ok();
    let pid = pid.to_string();
    match (exe(&pid), exe("self"), name(&pid), name("self")) {
        (Some(theirs), Some(ours), _, _) => theirs == ours,
        (_, _, Some(theirs), Some(ours)) => theirs == ours,
        // Nothing to tell by (no /proc): it may be ours, so it counts as a run.
        _ => true,
    }
}

/// Holds a folder's commit lock (`.ssdo-tmp.lock`, holding the owner's pid) while a batch renames
/// its files into place, so batches of concurrent runs land one after the other, each whole.
pub(super) struct FolderLock {
    path: PathBuf,
}

/// How long an empty or garbled lock may be another run's, between its creation and the pid
/// written into it, before it is taken for a leftover.
const UNWRITTEN_LOCK: std::time::Duration = std::time::Duration::from_secs(1);

impl FolderLock {
    pub(super) fn acquire(dir: &Path) -> Result<Self> {
        use std::io::Write;
        let path = dir.join(format!("{TEMPORARY_PREFIX}lock"));
        let started = std::time::Instant::now();
        let mut said_waiting = false;
        loop {
            match std::fs::OpenOptions::new().write(true).create_new(true).open(&path) {
                Ok(mut file) => {
                    let _ = write!(file, "{}", std::process::id());
                    return Ok(Self { path });
                }
                Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {
                    let text = std::fs::read_to_string(&path).unwrap_or_default();
                    let owner = text.trim().parse::<u32>().ok();
                    let age = std::fs::metadata(&path).and_then(|m| m.modified()).ok().and_then(|t| t.elapsed().ok());
                    // A lock whose owner died (killed mid-commit), whose pid now belongs to another
                    // program, or that never got its pid, is a leftover: taken over at once.
                    let stale = match owner {
                        Some(pid) => pid != std::process::id() && !is_this_program(pid),
                        None => age.is_some_and(|a| a > UNWRITTEN_LOCK),
                    };
                    if stale {
                        let whose = owner
                            .map_or("an empty or garbled lock".into(), |pid| format!("pid {pid} is no run of ssdo"));
                        log::warn!("{}: took over a stale lock ({whose})", path.display());
                        let _ = std::fs::remove_file(&path);
                        continue;
                    }
                    if !said_waiting && started.elapsed() > std::time::Duration::from_secs(1) {
                        said_waiting = true;
                        log::warn!(
                            "{}: waiting for another run ({}) to finish writing here",
                            path.display(),
                            text.trim()
                        );
                    }
                    if started.elapsed() > std::time::Duration::from_secs(60) {
                        return Err(Error::output(
                            &path,
                            format!("another run ({}) has held this folder's lock for a minute", text.trim()),
                        ));
                    }
                    std::thread::sleep(std::time::Duration::from_millis(5));
                }
                Err(e) => return Err(Error::output(&path, format!("cannot lock the folder: {e}"))),
            }
        }
    }
}

impl Drop for FolderLock {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.path);
    }
}

/// A folder's journal of renames (`.ssdo-tmp.journal`): the staged files of one batch and the
/// names they take, written whole (under a temporary name, then renamed) before the first rename
/// and removed after the last. Only a run killed between its renames leaves one; the next run
/// into the folder renames the rest of that set into place ([`Journal::complete`]), so what the
/// folder holds is that run's whole set, and then its own.
pub(super) struct Journal;

impl Journal {
    pub(super) fn path(dir: &Path) -> PathBuf {
        dir.join(format!("{TEMPORARY_PREFIX}journal"))
    }

    /// One line a file: the staged name and the target's, each a file name in `dir`, in hex
    /// (a name may hold any byte but `/`).
    pub(super) fn write(dir: &Path, renames: &[&(PathBuf, PathBuf)]) -> Result<()> {
        let hex = |p: &Path| {
            p.file_name().map(name_bytes).unwrap_or_default().iter().map(|b| format!("{b:02x}")).collect::<String>()
        };
        let text: String = renames.iter().map(|(tmp, target)| format!("{} {}\n", hex(tmp), hex(target))).collect();
        let journal = Self::path(dir);
        use std::io::Write;
        let (tmp, mut file) =
            create_temporary(&journal).map_err(|e| Error::output(&journal, format!("cannot write: {e}")))?;
        let written = file.write_all(text.as_bytes()).and_then(|()| file.sync_all());
        drop(file);
        if let Err(e) = written.and_then(|()| std::fs::rename(&tmp, &journal)) {
            let _ = std::fs::remove_file(&tmp);
            return Err(Error::output(&journal, format!("cannot write: {e}")));
        }
        Ok(())
    }

    /// Completes the set a killed run's journal in `dir` names: every staged file still there is
    /// renamed into place, then the journal is removed. The caller holds the folder's lock, so
    /// no live run is between its renames here.
    pub(super) fn complete(dir: &Path) {
        let journal = Self::path(dir);
        let Ok(text) = std::fs::read_to_string(&journal) else { return };
        let unhex = |word: &str| -> Option<Vec<u8>> {
            word.len()
                .is_multiple_of(2)
                .then(|| (0..word.len()).step_by(2).map(|i| u8::from_str_radix(word.get(i..i + 2)?, 16).ok()).collect())
                .flatten()
        };
        let mut completed = Vec::new();
        for line in text.lines() {
            let Some((tmp, target)) = line.split_once(' ').and_then(|(a, b)| Some((unhex(a)?, unhex(b)?))) else {
                continue;
            };
            let (tmp, target) = (dir.join(name_from_bytes(tmp)), dir.join(name_from_bytes(target)));
            // Only this program's temporaries, and only names inside the folder.
            let ours = tmp.file_name().and_then(|n| n.to_str()).and_then(temporary_owner).is_some();
            let plain = target.file_name().is_some() && target.parent() == Some(dir);
            if ours && plain && tmp.is_file() && std::fs::rename(&tmp, &target).is_ok() {
                completed.push(target.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default());
            }
        }
        let _ = std::fs::remove_file(&journal);
        if !completed.is_empty() {
            log::warn!(
                "{}: a run killed while writing its files left them half renamed; completed its set ({})",
                dir.display(),
                completed.join(", ")
            );
        }
    }
}

/// A file name's bytes (on Unix any byte but `/`; elsewhere its UTF-8).
pub(super) fn name_bytes(name: &std::ffi::OsStr) -> Vec<u8> {
    #[cfg(unix)]
    {
        use std::os::unix::ffi::OsStrExt;
        name.as_bytes().to_vec()
    }
    #[cfg(not(unix))]
    {
        name.to_string_lossy().as_bytes().to_vec()
    }
}

pub(super) fn name_from_bytes(bytes: Vec<u8>) -> std::ffi::OsString {
    #[cfg(unix)]
    {
        use std::os::unix::ffi::OsStringExt;
        std::ffi::OsString::from_vec(bytes)
    }
    #[cfg(not(unix))]
    {
        String::from_utf8_lossy(&bytes).into_owned().into()
    }
}
