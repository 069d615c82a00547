//! Writing result files without ever leaving a half-written one: data goes to a temporary name
//! in the same folder and is renamed over the target only once it is complete.

use std::path::{Path, PathBuf};

use crate::{Error, Result};

/// Writes `bytes` to `path` atomically (temporary file, then rename), creating parent folders:
/// a batch of one.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    let mut batch = Batch::default();
    batch.stage(path, bytes)?;
    batch.commit().map(|_| ())
}

/// The prefix of every temporary file this program writes: `.ssdo-tmp.<pid>.<random>.<name>`.
/// Only names of that form are ever swept, so no user's file can be taken for one.
const TEMPORARY_PREFIX: &str = ".ssdo-tmp.";

/// A fresh temporary file beside `path`, created exclusively (never over an existing file), and
/// its name. The random part comes from the standard library's per-process random hash keys
/// and a counter, so two runs, or two threads of one, never pick the same name.
fn create_temporary(path: &Path) -> std::io::Result<(PathBuf, std::fs::File)> {
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
fn temporary_owner(name: &str) -> Option<u32> {
    let rest = name.strip_prefix(TEMPORARY_PREFIX)?;
    let (pid, rest) = rest.split_once('.')?;
    let (random, target) = rest.split_once('.')?;
    let well_formed = random.len() == 16 && random.bytes().all(|b| b.is_ascii_hexdigit()) && !target.is_empty();
    well_formed.then(|| pid.parse().ok()).flatten()
}

/// Whether the process `pid` is alive (Linux's /proc; elsewhere every process counts as alive).
fn process_alive(pid: u32) -> bool {
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
struct FolderLock {
    path: PathBuf,
}

/// How long an empty or garbled lock may be another run's, between its creation and the pid
/// written into it, before it is taken for a leftover.
const UNWRITTEN_LOCK: std::time::Duration = std::time::Duration::from_secs(1);

impl FolderLock {
    fn acquire(dir: &Path) -> Result<Self> {
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

/// Checks, before any work, that `dir` is a folder this run can write into (made if missing):
/// a dangling link, a file of that name or a folder without write access is refused before
/// the rendering rather than after it.
pub fn check_folder(dir: &Path) -> Result<()> {
    if let Ok(meta) = std::fs::symlink_metadata(dir) {
        if meta.file_type().is_symlink() && !dir.exists() {
            let target = std::fs::read_link(dir).map(|t| t.display().to_string()).unwrap_or_default();
            return Err(Error::output(dir, format!("is a link to {target}, which does not exist")));
        }
    }
    std::fs::create_dir_all(dir).map_err(|e| Error::output(dir, format!("cannot create folder: {e}")))?;
    if !dir.is_dir() {
        return Err(Error::output(dir, "is not a folder"));
    }
    let (probe, file) =
        create_temporary(&dir.join("probe")).map_err(|e| Error::output(dir, format!("cannot write: {e}")))?;
    drop(file);
    let _ = std::fs::remove_file(probe);
    remove_stale_temporaries(dir);
    Ok(())
}

/// Files written together or not at all: each is staged under a temporary name, and only
/// [`Batch::commit`] renames them into place; a batch dropped uncommitted (an error on the way)
/// removes what it staged. `capture --mode all` writes its five images this way.
#[derive(Default)]
pub struct Batch {
    staged: Vec<(PathBuf, PathBuf)>,
}

impl Batch {
    /// Writes `bytes` under a temporary name beside `path`.
    pub fn stage(&mut self, path: &Path, bytes: &[u8]) -> Result<()> {
        if let Some(parent) = path.parent().filter(|p| !p.as_os_str().is_empty()) {
            std::fs::create_dir_all(parent).map_err(|e| Error::output(parent, format!("cannot create folder: {e}")))?;
        }
        use std::io::Write;
        let (tmp, mut file) = create_temporary(path).map_err(|e| Error::output(path, format!("cannot write: {e}")))?;
        if let Err(e) = file.write_all(bytes) {
            drop(file);
            let _ = std::fs::remove_file(&tmp);
            return Err(Error::output(path, format!("cannot write: {e}")));
        }
        self.staged.push((tmp, path.to_path_buf()));
        Ok(())
    }

    /// Renames every staged file into place, holding each folder's lock so that a concurrent run
    /// into the same folder lands its set before or after this one, never mixed with it. What
    /// would make a rename fail once written beside its target (a folder of that name) is checked
    /// for every file before the first rename. Each folder's renames are written to its journal
    /// first ([`Journal`]): a run killed between two renames leaves a journal that the next run
    /// into the folder completes before it starts, so the folder holds one run's set.
    pub fn commit(mut self) -> Result<Vec<PathBuf>> {
        let mut folders: Vec<PathBuf> =
            self.staged.iter().map(|(tmp, _)| tmp.parent().unwrap_or(Path::new(".")).to_path_buf()).collect();
        folders.sort();
        folders.dedup();
        let _locks = folders.iter().map(|dir| FolderLock::acquire(dir)).collect::<Result<Vec<_>>>()?;
        for dir in &folders {
            Journal::complete(dir);
        }
        if let Some((_, path)) = self.staged.iter().find(|(_, path)| path.is_dir()) {
            return Err(Error::output(path, "cannot write: a folder has this name"));
        }
        let staged = std::mem::take(&mut self.staged);
        let mut done = Vec::new();
        for dir in &folders {
            let here: Vec<&(PathBuf, PathBuf)> =
                staged.iter().filter(|(tmp, _)| tmp.parent().unwrap_or(Path::new(".")) == dir).collect();
            let journal = Journal::write(dir, &here);
            if let Err(e) = journal {
                for (t, _) in &staged {
                    let _ = std::fs::remove_file(t);
                }
                return Err(e);
            }
            for (i, (tmp, path)) in here.iter().enumerate() {
                if let Err(e) = std::fs::rename(tmp, path) {
                    // Nothing to complete: what was not renamed is removed, the journal with it.
                    for (t, _) in &here[i..] {
                        let _ = std::fs::remove_file(t);
                    }
                    let _ = std::fs::remove_file(Journal::path(dir));
                    return Err(Error::output(path, format!("cannot write: {e}")));
                }
                done.push(path.clone());
            }
            let _ = std::fs::remove_file(Journal::path(dir));
        }
        Ok(done)
    }
}

/// A folder's journal of renames (`.ssdo-tmp.journal`): the staged files of one batch and the
/// names they take, written whole (under a temporary name, then renamed) before the first rename
/// and removed after the last. Only a run killed between its renames leaves one; the next run
/// into the folder renames the rest of that set into place ([`Journal::complete`]), so what the
/// folder holds is that run's whole set, and then its own.
struct Journal;

impl Journal {
    fn path(dir: &Path) -> PathBuf {
        dir.join(format!("{TEMPORARY_PREFIX}journal"))
    }

    /// One line a file: the staged name and the target's, each a file name in `dir`, in hex
    /// (a name may hold any byte but `/`).
    fn write(dir: &Path, renames: &[&(PathBuf, PathBuf)]) -> Result<()> {
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
    fn complete(dir: &Path) {
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
fn name_bytes(name: &std::ffi::OsStr) -> Vec<u8> {
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

fn name_from_bytes(bytes: Vec<u8>) -> std::ffi::OsString {
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

impl Drop for Batch {
    fn drop(&mut self) {
        for (tmp, _) in &self.staged {
            let _ = std::fs::remove_file(tmp);
        }
    }
}

/// Tidies what a killed run of this program left in `dir`: first the set it was renaming into
/// place when it was killed is completed (its journal, under the folder's lock), then the
/// temporary files of runs that are gone are removed: only names of this program's form
/// (`.ssdo-tmp.<pid>.<random>.<name>`) whose process is gone, and only where a process can be
/// looked up (Linux's /proc); elsewhere nothing is removed.
pub fn remove_stale_temporaries(dir: &Path) {
    if Journal::path(dir).exists() {
        if let Ok(_lock) = FolderLock::acquire(dir) {
            Journal::complete(dir);
        }
    }
    if !Path::new("/proc/self").exists() {
        return;
    }
    let Ok(entries) = std::fs::read_dir(dir) else { return };
    for entry in entries.flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        let Some(pid) = temporary_owner(&name) else { continue };
        if pid != std::process::id() && !process_alive(pid) && entry.file_type().is_ok_and(|t| t.is_file()) {
            let _ = std::fs::remove_file(entry.path());
        }
    }
}

/// A CSV document: the header, then one record a row, each field quoted where it needs to be (a
/// comma, a quote or a line break in a name stays inside its field).
pub fn csv_text<R: IntoIterator<Item = String>>(header: &[&str], rows: impl IntoIterator<Item = R>) -> String {
    let mut writer = csv::Writer::from_writer(Vec::new());
    let written = writer.write_record(header).and_then(|()| {
        rows.into_iter().try_for_each(|row| {
            writer.write_record(row.into_iter().map(|field| {
                // A field a spreadsheet would run as a formula starts with a quote mark instead.
                if field.starts_with(['=', '+', '@']) || (field.starts_with('-') && field.parse::<f64>().is_err()) {
                    format!("'{field}")
                } else {
                    field
                }
            }))
        })
    });
    written.expect("CSV into memory");
    let bytes = writer.into_inner().expect("CSV into memory");
    String::from_utf8(bytes).expect("CSV of UTF-8 fields")
}

/// PNG bytes of an RGBA8 image.
pub fn png_bytes(path: &Path, image: &image::RgbaImage) -> Result<Vec<u8>> {
    let mut bytes = Vec::new();
    image
        .write_to(&mut std::io::Cursor::new(&mut bytes), image::ImageFormat::Png)
        .map_err(|e| Error::output(path, format!("PNG encoding failed: {e}")))?;
    Ok(bytes)
}

/// EXR bytes of a linear float image.
pub fn exr_bytes(path: &Path, image: &image::Rgba32FImage) -> Result<Vec<u8>> {
    let mut bytes = Vec::new();
    image::DynamicImage::ImageRgba32F(image.clone())
        .write_to(&mut std::io::Cursor::new(&mut bytes), image::ImageFormat::OpenExr)
        .map_err(|e| Error::output(path, format!("EXR encoding failed: {e}")))?;
    Ok(bytes)
}

/// Encodes an RGBA8 image as PNG and writes it atomically.
pub fn save_png(path: &Path, image: &image::RgbaImage) -> Result<()> {
    write_atomic(path, &png_bytes(path, image)?)
}

/// Writes `text` and a newline to standard output. A reader that closed the pipe ends the program
/// quietly ([`Error::StdoutClosed`]); any other failure (a full disk) is an output error naming
/// standard output. Never panics, unlike `println!`.
pub fn print_line(text: &str) -> Result<()> {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    let written = out.write_all(text.as_bytes()).and_then(|()| out.write_all(b"\n")).and_then(|()| out.flush());
    written.map_err(|e| match e.kind() {
        std::io::ErrorKind::BrokenPipe => Error::StdoutClosed,
        _ => Error::output("standard output", e.to_string()),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_this_programs_temporary_names_are_taken_for_temporaries() {
        let (tmp, _file) = create_temporary(&std::env::temp_dir().join("x.png")).unwrap();
        let name = tmp.file_name().unwrap().to_string_lossy().into_owned();
        assert_eq!(temporary_owner(&name), Some(std::process::id()), "{name}");
        let _ = std::fs::remove_file(&tmp);
        for user in [
            ".off.png.4000000.tmp",
            ".ssdo-tmp.12.notes.txt",
            ".ssdo-tmp.12.0123456789abcdeg.x",
            "notes.tmp",
            ".ssdo-tmp.lock",
        ] {
            assert_eq!(temporary_owner(user), None, "{user}");
        }
        assert_eq!(temporary_owner(".ssdo-tmp.4000000.0123456789abcdef.off.png"), Some(4_000_000));
    }

    /// A pid no process has: a child that has ended.
    fn dead_pid() -> u32 {
        let mut child = std::process::Command::new("true").spawn().unwrap();
        let pid = child.id();
        child.wait().unwrap();
        pid
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn a_set_killed_between_its_renames_is_completed_before_the_next_run_starts() {
        let dir = tempfile::tempdir().unwrap();
        let names = ["off.png", "ssao.png", "ssdo.png", "both.png", "compare.png"];
        for name in names {
            std::fs::write(dir.path().join(name), "old").unwrap();
        }
        // What a run killed after its second rename leaves: the journal, two files renamed,
        // three staged under a dead process's temporary names.
        let pid = dead_pid();
        let staged: Vec<(PathBuf, PathBuf)> = names
            .iter()
            .enumerate()
            .map(|(i, name)| {
                let tmp = dir.path().join(format!("{TEMPORARY_PREFIX}{pid}.{i:016x}.{name}"));
                std::fs::write(&tmp, "new").unwrap();
                (tmp, dir.path().join(name))
            })
            .collect();
        Journal::write(dir.path(), &staged.iter().collect::<Vec<_>>()).unwrap();
        for (tmp, target) in &staged[..2] {
            std::fs::rename(tmp, target).unwrap();
        }
        // The next run checks its folder before any work: the killed run's set is whole.
        check_folder(dir.path()).unwrap();
        for name in names {
            assert_eq!(std::fs::read_to_string(dir.path().join(name)).unwrap(), "new", "{name}");
        }
        let left: Vec<String> = std::fs::read_dir(dir.path())
            .unwrap()
            .flatten()
            .map(|e| e.file_name().to_string_lossy().into_owned())
            .filter(|n| n.starts_with(TEMPORARY_PREFIX))
            .collect();
        assert!(left.is_empty(), "{left:?}");
        // A batch commits its own set whole over it, and leaves no journal.
        let mut batch = Batch::default();
        for name in names {
            batch.stage(&dir.path().join(name), b"newer").unwrap();
        }
        batch.commit().unwrap();
        assert!(!Journal::path(dir.path()).exists());
        for name in names {
            assert_eq!(std::fs::read_to_string(dir.path().join(name)).unwrap(), "newer", "{name}");
        }
    }
}
