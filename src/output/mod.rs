//! Writing result files without ever leaving a half-written one: data goes to a temporary name
//! in the same folder and is renamed over the target only once it is complete.

use std::path::{Path, PathBuf};

mod temporary;

use temporary::{create_temporary, process_alive, temporary_owner, FolderLock, Journal};

use crate::{Error, Result};

/// Writes `bytes` to `path` atomically (temporary file, then rename), creating parent folders:
/// a batch of one.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    let mut batch = Batch::default();
    batch.stage(path, bytes)?;
    batch.commit().map(|_| ())
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
    use super::temporary::TEMPORARY_PREFIX;
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
