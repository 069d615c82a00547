//! Reading an input file safely: checked to be a regular file of a bounded size before it is
//! opened, then read no further than that bound; and naming the kinds of file it is not.

use std::path::Path;

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
