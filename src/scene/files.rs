//! Reading an input file safely: checked to be a regular file of a bounded size before it is
//! opened, then read no further than that bound; the files a model names kept inside its own
//! folder ([`ModelFolder`]); and naming the kinds of file it is not.

use std::path::{Path, PathBuf};

/// Checks that `path` is a regular file of at most `limit` bytes before anything opens it (a
/// FIFO would block the open, `/dev/zero` would never end, a sparse file of gigabytes would fill
/// memory). The error is the problem alone, for the caller to name the file. What is then read
/// is checked again once open ([`open_regular`]): this check only keeps a device from being
/// opened at all.
pub fn check_file(path: &Path, limit: u64) -> std::result::Result<(), String> {
    let meta = std::fs::metadata(path).map_err(|e| cannot_read(path, &e))?;
    check_kind(&meta, limit)
}

/// What `meta` says against reading it as a file of at most `limit` bytes.
fn check_kind(meta: &std::fs::Metadata, limit: u64) -> std::result::Result<(), String> {
    if meta.is_dir() {
        return Err("is a folder, not a file".into());
    }
    if !meta.is_file() {
        return Err(format!("is {}, not a regular file", special_kind(meta)));
    }
    if meta.len() > limit {
        // In the limit's unit: a preset's is kibibytes, a model's mebibytes.
        let size =
            |b: u64| if limit >= 1 << 20 { format!("{} MiB", b >> 20) } else { format!("{} KiB", b.div_ceil(1024)) };
        return Err(format!("is {}; files over {} are refused", size(meta.len()), size(limit)));
    }
    Ok(())
}

/// "a FIFO", "a device", "a socket": what a file that is neither a regular file nor a folder is.
fn special_kind(meta: &std::fs::Metadata) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        let kind = meta.file_type();
        if kind.is_fifo() {
            return "a FIFO (a named pipe)";
        }
        if kind.is_char_device() || kind.is_block_device() {
            return "a device";
        }
        if kind.is_socket() {
            return "a socket";
        }
    }
    let _ = meta;
    "a special file (a device, a FIFO or a socket)"
}

/// "cannot read: ..." for an error opening or reading `path`, saying in words what the system's
/// errors say in numbers where a person would not guess it (a loop of links).
fn cannot_read(path: &Path, e: &std::io::Error) -> String {
    #[cfg(unix)]
    if e.raw_os_error() == Some(libc::ELOOP) {
        return "is a link that leads back to itself (a loop of links)".into();
    }
    #[cfg(unix)]
    if e.raw_os_error() == Some(libc::ENXIO) {
        return "is a socket or a device with nothing behind it, not a regular file".into();
    }
    if e.kind() == std::io::ErrorKind::NotFound {
        if let Ok(target) = std::fs::read_link(path) {
            return format!("is a link to {}, which does not exist", target.display());
        }
    }
    format!("cannot read: {e}")
}

/// Opens `path` for reading and checks what was opened, not what the name led to a moment
/// before: a regular file of at most `limit` bytes. The open never waits (a FIFO swapped in
/// after a check is refused, not waited on), and the checks read the open file itself.
pub fn open_regular(path: &Path, limit: u64) -> std::result::Result<std::fs::File, String> {
    let file = open_nonblocking(path)?;
    let meta = file.metadata().map_err(|e| cannot_read(path, &e))?;
    check_kind(&meta, limit)?;
    Ok(file)
}

/// Opens `path` for reading without waiting for a writer (a FIFO opens at once).
fn open_nonblocking(path: &Path) -> std::result::Result<std::fs::File, String> {
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        options.custom_flags(libc::O_NONBLOCK);
    }
    options.open(path).map_err(|e| cannot_read(path, &e))
}

/// Reads at most `limit` bytes of `file`; more is an error (the file grew while it was read).
fn read_at_most(file: std::fs::File, limit: u64) -> std::result::Result<Vec<u8>, String> {
    use std::io::Read;
    let mut bytes = Vec::new();
    file.take(limit.saturating_add(1)).read_to_end(&mut bytes).map_err(|e| format!("cannot read: {e}"))?;
    if bytes.len() as u64 > limit {
        return Err(format!("grew past {} KiB while being read", limit.div_ceil(1024)));
    }
    Ok(bytes)
}

/// The bytes of the regular file `path`, at most `limit` of them.
pub fn read_bounded(path: &Path, limit: u64) -> std::result::Result<Vec<u8>, String> {
    check_file(path, limit)?;
    read_at_most(open_regular(path, limit)?, limit)
}

/// Where the open file `file` (opened as `path`) really is, as the system names it now: on
/// Linux what `/proc/self/fd` says of the open file itself, so that no swap of a folder for a
/// link between a check and the open can make the file read another than the file checked.
/// Elsewhere the path with its links resolved, taken only if it is the same file as the one
/// open (device and inode).
fn opened_path(file: &std::fs::File, path: &Path) -> std::result::Result<PathBuf, String> {
    #[cfg(target_os = "linux")]
    {
        use std::os::unix::io::AsRawFd;
        if let Ok(real) = std::fs::read_link(format!("/proc/self/fd/{}", file.as_raw_fd())) {
            if real.is_absolute() && !real.to_string_lossy().ends_with(" (deleted)") {
                return Ok(real);
            }
            return Err(format!("{}: was removed or replaced while it was opened", path.display()));
        }
    }
    let real = std::fs::canonicalize(path).map_err(|e| format!("{}: {}", path.display(), cannot_read(path, &e)))?;
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        let (open, named) = (file.metadata(), std::fs::metadata(&real));
        let same = matches!((open, named), (Ok(a), Ok(b)) if a.dev() == b.dev() && a.ino() == b.ino());
        if !same {
            return Err(format!("{}: was replaced while it was opened", path.display()));
        }
    }
    Ok(real)
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
    /// The folder of the model file `model`: the folder the path names, as every program that
    /// follows a file's relative names takes it. A model file that is a link is said to be one,
    /// with the folder used and the one not used, so a map beside the link's target that is not
    /// found is no mystery.
    pub fn of(model: &Path) -> Self {
        let shown = model.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new(".")).to_path_buf();
        let real = std::fs::canonicalize(&shown).ok();
        if std::fs::symlink_metadata(model).is_ok_and(|m| m.file_type().is_symlink()) {
            let target = std::fs::canonicalize(model).ok();
            let target_folder = target.as_deref().and_then(Path::parent).map(Path::to_path_buf);
            if target_folder.is_some() && target_folder != real {
                log::info!(
                    "{} is a link to {}: the files it names are read from the link's folder ({}), not from {}",
                    model.display(),
                    target.as_deref().unwrap_or(model).display(),
                    shown.display(),
                    target_folder.as_deref().unwrap_or(Path::new(".")).display()
                );
            }
        }
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
    /// special file: checked before anything is opened, so a device or a file outside the
    /// folder is never opened at all as things stand.
    fn admit(&self, path: &Path) -> std::result::Result<PathBuf, String> {
        let real = std::fs::canonicalize(path).map_err(|e| format!("{}: {}", path.display(), cannot_read(path, &e)))?;
        self.holds(path, &real)?;
        Ok(real)
    }

    /// Whether `real`, where `path` leads, lies inside the folder (and not in `/proc`, `/sys` or
    /// `/dev` unless the folder does).
    fn holds(&self, path: &Path, real: &Path) -> std::result::Result<(), String> {
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
        Ok(())
    }

    /// Opens `path`, a file this folder found, and checks the file that was opened: where it
    /// really is (inside the folder) and what it is (a regular file of at most `limit` bytes).
    /// The check and the read are one act: a folder swapped for a link to another between the
    /// first look and the open changes what is opened, and the check of the open file refuses it.
    fn open(&self, path: &Path, limit: u64) -> std::result::Result<std::fs::File, String> {
        self.admit(path)?;
        let named = |problem: String| format!("{}: {problem}", path.display());
        let file = open_nonblocking(path).map_err(named)?;
        self.holds(path, &opened_path(&file, path)?)?;
        let meta = file.metadata().map_err(|e| named(cannot_read(path, &e)))?;
        check_kind(&meta, limit).map_err(named)?;
        Ok(file)
    }

    /// The bytes of the file `name` names in the folder, at most `limit` of them.
    pub fn read(&self, name: &str, limit: u64) -> std::result::Result<(PathBuf, Vec<u8>), String> {
        let path = self.inside(name)?;
        self.read_found(&path, limit).map(|bytes| (path, bytes))
    }

    /// The bytes of `path`, a file this folder found (see [`ModelFolder::find`]), at most `limit`.
    pub fn read_found(&self, path: &Path, limit: u64) -> std::result::Result<Vec<u8>, String> {
        let file = self.open(path, limit)?;
        read_at_most(file, limit).map_err(|problem| format!("{}: {problem}", path.display()))
    }

    /// The first `length` bytes of `path`, a file this folder found; fewer is an error.
    pub fn read_prefix(&self, path: &Path, length: u64) -> std::result::Result<Vec<u8>, String> {
        use std::io::Read;
        let file = self.open(path, u64::MAX)?;
        let mut bytes = Vec::new();
        file.take(length).read_to_end(&mut bytes).map_err(|e| format!("{}: cannot read: {e}", path.display()))?;
        if (bytes.len() as u64) < length {
            return Err(format!("{}: holds {} bytes where {length} are needed", path.display(), bytes.len()));
        }
        Ok(bytes)
    }

    /// The size in bytes of `path`, a file this folder found, if it may be read.
    pub fn size_of(&self, path: &Path) -> std::result::Result<u64, String> {
        let file = self.open(path, u64::MAX)?;
        file.metadata().map(|m| m.len()).map_err(|e| format!("{}: cannot read: {e}", path.display()))
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
            // Something is there, but not a file to read: say what (a folder, a FIFO, a loop of
            // links, a link out of the folder), not "not found".
            Ok(path) if std::fs::symlink_metadata(&path).is_ok() => Err(self
                .size_of(&path)
                .err()
                .unwrap_or_else(|| format!("{}: is not a file that can be read", path.display()))),
            Ok(path) => Err(format!("{}: not found", path.display())),
            Err(why) => Err(why),
        }
    }
}

/// The model formats this program loads and their extensions: the one list every check and
/// message reads.
pub const MODEL_FORMATS: [(&str, &[&str]); 2] = [("OBJ", &["obj"]), ("glTF 2.0", &["gltf", "glb"])];

/// Whether `path`'s extension is one of `extensions`, in any letter case.
pub fn has_extension(path: &Path, extensions: &[&str]) -> bool {
    path.extension().is_some_and(|e| extensions.iter().any(|x| e.eq_ignore_ascii_case(x)))
}

/// "OBJ (.obj) and glTF 2.0 (.gltf, .glb)": the formats in words.
pub fn model_formats() -> String {
    let each = MODEL_FORMATS.map(|(name, exts)| format!("{name} ({})", dotted(exts)));
    each.join(" and ")
}

/// ".obj, .gltf, .glb": every model extension.
pub fn model_extensions() -> String {
    dotted(&MODEL_FORMATS.iter().flat_map(|(_, exts)| exts.iter().copied()).collect::<Vec<_>>())
}

fn dotted(extensions: &[&str]) -> String {
    extensions.iter().map(|e| format!(".{e}")).collect::<Vec<_>>().join(", ")
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
