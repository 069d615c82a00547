//! Writing result files without ever leaving a half-written one: data goes to a temporary name
//! in the same folder and is renamed over the target only once it is complete.

use std::path::{Path, PathBuf};

use crate::{Error, Result};

/// Writes `bytes` to `path` atomically (temporary file, then rename), creating parent folders.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    if let Some(parent) = path.parent().filter(|p| !p.as_os_str().is_empty()) {
        std::fs::create_dir_all(parent).map_err(|e| Error::output(parent, format!("cannot create folder: {e}")))?;
    }
    let tmp = temporary_name(path);
    let result = std::fs::write(&tmp, bytes).and_then(|()| std::fs::rename(&tmp, path));
    if let Err(e) = result {
        let _ = std::fs::remove_file(&tmp);
        return Err(Error::output(path, format!("cannot write: {e}")));
    }
    Ok(())
}

fn temporary_name(path: &Path) -> PathBuf {
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    path.with_file_name(format!(".{name}.{}.tmp", std::process::id()))
}

/// Encodes an RGBA8 image as PNG and writes it atomically.
pub fn save_png(path: &Path, image: &image::RgbaImage) -> Result<()> {
    let mut bytes = Vec::new();
    image
        .write_to(&mut std::io::Cursor::new(&mut bytes), image::ImageFormat::Png)
        .map_err(|e| Error::output(path, format!("PNG encoding failed: {e}")))?;
    write_atomic(path, &bytes)
}

/// Encodes a linear float image as OpenEXR and writes it atomically.
pub fn save_exr(path: &Path, image: &image::Rgba32FImage) -> Result<()> {
    let mut bytes = Vec::new();
    image::DynamicImage::ImageRgba32F(image.clone())
        .write_to(&mut std::io::Cursor::new(&mut bytes), image::ImageFormat::OpenExr)
        .map_err(|e| Error::output(path, format!("EXR encoding failed: {e}")))?;
    write_atomic(path, &bytes)
}
