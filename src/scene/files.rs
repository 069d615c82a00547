//! Reading an input file safely: checked to be a regular file of a bounded size before it is
//! opened, then read no further than that bound; the files a model names kept inside its own
//! folder ([`ModelFolder`]); and naming the kinds of file it is not.

use std::path::{Path, PathBuf};

/// Checks that `path` is a regular file of at most `limit` bytes before anything opens it (a
/// FIFO would block the open, `/dev/zero` would never end, a sparse file of gigabytes would fill
/// memory), then reads at most that much. The error is the problem alone, for the caller to name
/// the file.
pub fn check_file(path: &Path, limit: u64) -> std::result::Result<(), String> {
    let meta = std::fs::metadata(path).map_err(|e| format!("cannot read: {e}"))?;
    if meta.is_dir() {
        return Err("is a folder, not a file".into());
    }
    if !meta.is_file() {
        return Err("is not a regular file (a device, a FIFO or a socket)".into());
    }
    if meta.len() > limit {
        return Err(format!("is {} MiB; files over {} MiB are refused", meta.len() >> 20, limit >> 20));
    }
    Ok(())
}

pub fn read_bounded(path: &Path, limit: u64) -> std::result::Result<Vec<u8>, String> {
    use std::io::Read;
    check_file(path, limit)?;
    let mut bytes = Vec::new();
    let file = std::fs::File::open(path).map_err(|e| format!("cannot read: {e}"))?;
    file.take(limit + 1).read_to_end(&mut bytes).map_err(|e| format!("cannot read: {e}"))?;
    if bytes.len() as u64 > limit {
        return Err(format!("grew past {} MiB while being read", limit >> 20));
    }
    Ok(bytes)
}

/// The folder of a model file, from which alone the files it names (an OBJ's MTL and maps, a
/// glTF's buffers and images) are read. A name is resolved by its own words first: `/` and `\`
/// both separate folders, `.` and `..` are taken lexically, and a name that climbs above the
/// folder, or is absolute (`/etc/passwd`, `C:\maps\a.png`), is refused. Then the file found is
/// followed through its links: what it really is must lie inside the folder (so a link to
/// `/proc`, a device or a file elsewhere is refused too) and be a regular file, read no further
/// than the caller's bound.
#[derive(Clone, Debug)]
pub struct ModelFolder {
    /// The folder as the user named it, for messages and paths.
    shown: PathBuf,
    /// The folder with every link resolved; `None` when it cannot be read.
    real: Option<PathBuf>,
}

impl ModelFolder {
    /// The folder of the model file `model`.
    pub fn of(model: &Path) -> Self {
        let shown = model.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new(".")).to_path_buf();
        let real = std::fs::canonicalize(&shown).ok();
        Self { shown, real }
    }

    pub fn path(&self) -> &Path {
        &self.shown
    }

    /// The rule, for messages.
    fn rule(&self) -> String {
        format!("only files in the model's folder ({}) and its subfolders are read", self.shown.display())
    }

    /// The path `name` stands for inside the folder, by its words alone (nothing is opened).
    pub fn inside(&self, name: &str) -> std::result::Result<PathBuf, String> {
        let name = name.replace('\\', "/");
        let drive = name.as_bytes().get(1) == Some(&b':') && name.as_bytes()[0].is_ascii_alphabetic();
        if name.starts_with('/') || drive {
            return Err(format!("'{name}' is an absolute path; {}", self.rule()));
        }
        let mut parts: Vec<&str> = Vec::new();
        for part in name.split('/') {
            match part {
                "" | "." => {}
                ".." => {
                    if parts.pop().is_none() {
                        return Err(format!("'{name}' leads outside the model's folder; {}", self.rule()));
                    }
                }
                part => parts.push(part),
            }
        }
        if parts.is_empty() {
            return Err(format!("'{name}' names no file"));
        }
        Ok(parts.iter().fold(self.shown.clone(), |path, part| path.join(part)))
    }

    /// `path` (which exists) with its links resolved, if that lies inside the folder and is no
    /// special file.
    fn admit(&self, path: &Path) -> std::result::Result<PathBuf, String> {
        let real = std::fs::canonicalize(path).map_err(|e| format!("{}: cannot read: {e}", path.display()))?;
        let root = self.real.as_ref().ok_or_else(|| format!("{}: the folder cannot be read", self.shown.display()))?;
        let special = ["/proc", "/sys", "/dev"].iter().any(|p| real.starts_with(p) && !root.starts_with(p));
        if special || !real.starts_with(root) {
            return Err(format!(
                "{}: a link to {}, outside the model's folder; {}",
                path.display(),
                real.display(),
                self.rule()
            ));
        }
        Ok(real)
    }

    /// The bytes of the file `name` names in the folder, at most `limit` of them.
    pub fn read(&self, name: &str, limit: u64) -> std::result::Result<(PathBuf, Vec<u8>), String> {
        let path = self.inside(name)?;
        self.read_found(&path, limit).map(|bytes| (path, bytes))
    }

    /// The bytes of `path`, a file this folder found (see [`ModelFolder::find`]), at most `limit`.
    pub fn read_found(&self, path: &Path, limit: u64) -> std::result::Result<Vec<u8>, String> {
        let real = self.admit(path)?;
        read_bounded(&real, limit).map_err(|problem| format!("{}: {problem}", path.display()))
    }

    /// The first `length` bytes of `path`, a file this folder found; fewer is an error.
    pub fn read_prefix(&self, path: &Path, length: u64) -> std::result::Result<Vec<u8>, String> {
        use std::io::Read;
        let real = self.admit(path)?;
        check_file(&real, u64::MAX).map_err(|problem| format!("{}: {problem}", path.display()))?;
        let mut bytes = Vec::new();
        let file = std::fs::File::open(&real).map_err(|e| format!("{}: cannot read: {e}", path.display()))?;
        file.take(length).read_to_end(&mut bytes).map_err(|e| format!("{}: cannot read: {e}", path.display()))?;
        if (bytes.len() as u64) < length {
            return Err(format!("{}: holds {} bytes where {length} are needed", path.display(), bytes.len()));
        }
        Ok(bytes)
    }

    /// The size in bytes of `path`, a file this folder found, if it may be read.
    pub fn size_of(&self, path: &Path) -> std::result::Result<u64, String> {
        let real = self.admit(path)?;
        let meta = std::fs::metadata(&real).map_err(|e| format!("{}: cannot read: {e}", path.display()))?;
        if !meta.is_file() {
            return Err(format!("{}: is not a regular file (a folder, a device, a FIFO or a socket)", path.display()));
        }
        Ok(meta.len())
    }

    /// Finds a map as exporters write its name: as written, then by its file name alone in the
    /// folder it names and in the model's folder, ignoring letter case (files made on Windows
    /// often disagree with their MTL about case). A name outside the folder is never followed;
    /// a file of the same name inside it is taken instead, and the note says so.
    pub fn find(&self, name: &str) -> std::result::Result<(PathBuf, Option<String>), String> {
        let written = self.inside(name);
        if let Ok(path) = &written {
            if path.is_file() {
                return Ok((path.clone(), None));
            }
        }
        let file_name = name.replace('\\', "/").rsplit('/').next().unwrap_or_default().to_lowercase();
        let named_folder = written.as_ref().ok().and_then(|p| p.parent()).map(Path::to_path_buf);
        for folder in named_folder.into_iter().chain([self.shown.clone()]) {
            let Ok(entries) = std::fs::read_dir(&folder) else { continue };
            for entry in entries.flatten() {
                if entry.file_name().to_string_lossy().to_lowercase() == file_name && entry.path().is_file() {
                    let note = written
                        .as_ref()
                        .err()
                        .map(|why| format!("{why}; using {} from the model's folder", entry.path().display()));
                    return Ok((entry.path(), note));
                }
            }
        }
        match written {
            Ok(path) => Err(format!("{}: not found", path.display())),
            Err(why) => Err(why),
        }
    }
}

/// The kind of a model file in another format than OBJ or glTF, by its extension (read as OBJ it would
/// say only that it holds no triangles).
pub fn other_model_kind(path: &Path) -> Option<&'static str> {
    let ext = path.extension()?.to_str()?.to_ascii_lowercase();
    Some(match ext.as_str() {
        "fbx" => "FBX",
        "stl" => "STL",
        "ply" => "PLY",
        "dae" => "COLLADA",
        "3ds" => "3DS",
        "blend" => "Blender",
        "usd" | "usda" | "usdc" | "usdz" => "USD",
        "abc" => "Alembic",
        "mtl" => "material (MTL)",
        _ => return None,
    })
}
