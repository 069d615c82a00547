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

fn temporary_name(path: &Path) -> PathBuf {
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    path.with_file_name(format!(".{name}.{}.tmp", std::process::id()))
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
        let tmp = temporary_name(path);
        if let Err(e) = std::fs::write(&tmp, bytes) {
            let _ = std::fs::remove_file(&tmp);
            return Err(Error::output(path, format!("cannot write: {e}")));
        }
        self.staged.push((tmp, path.to_path_buf()));
        Ok(())
    }

    /// Renames every staged file into place. What would make a rename fail once written beside
    /// its target (a folder of that name) is checked for every file before the first rename.
    pub fn commit(mut self) -> Result<Vec<PathBuf>> {
        if let Some((_, path)) = self.staged.iter().find(|(_, path)| path.is_dir()) {
            return Err(Error::output(path, "cannot write: a folder has this name"));
        }
        let staged = std::mem::take(&mut self.staged);
        let mut done = Vec::new();
        for (i, (tmp, path)) in staged.iter().enumerate() {
            if let Err(e) = std::fs::rename(tmp, path) {
                for (t, _) in &staged[i..] {
                    let _ = std::fs::remove_file(t);
                }
                return Err(Error::output(path, format!("cannot write: {e}")));
            }
            done.push(path.clone());
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

/// Removes temporary files a killed run left in `dir` (`.<name>.<pid>.tmp` whose process is
/// gone). Only where a process can be looked up (Linux's /proc); elsewhere nothing is removed.
pub fn remove_stale_temporaries(dir: &Path) {
    if !Path::new("/proc/self").exists() {
        return;
    }
    let Ok(entries) = std::fs::read_dir(dir) else { return };
    for entry in entries.flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        let Some(stem) = name.strip_prefix('.').and_then(|n| n.strip_suffix(".tmp")) else { continue };
        let Some(pid) = stem.rsplit('.').next().and_then(|p| p.parse::<u32>().ok()) else { continue };
        if pid != std::process::id() && !Path::new(&format!("/proc/{pid}")).exists() {
            let _ = std::fs::remove_file(entry.path());
        }
    }
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

/// Encodes a linear float image as OpenEXR and writes it atomically.
pub fn save_exr(path: &Path, image: &image::Rgba32FImage) -> Result<()> {
    write_atomic(path, &exr_bytes(path, image)?)
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
