//! What a glTF's URIs and views hold, read within bounds: its buffers (the `.glb`'s binary
//! chunk, base64 data URIs, files beside it) and its images; and its accessors checked against
//! those buffers before the `gltf` crate's reader trusts them.

use std::path::{Path, PathBuf};

use super::files::read_bounded;
use super::texture::find_texture;

/// The largest glTF, `.glb` or buffer file read.
pub const MAX_GLTF_BYTES: u64 = 1 << 30;

/// The relative file name a non-data URI stands for: percent-decoded, with `/` for `\\` and
/// no `file:` scheme; an URI of another scheme (`https://`) is no local file.
fn uri_file(uri: &str) -> std::result::Result<String, String> {
    if uri.contains("://") && !uri.starts_with("file://") {
        return Err(format!("'{uri}' is not a local file"));
    }
    let decoded = percent_encoding::percent_decode_str(uri).decode_utf8_lossy().replace('\\', "/");
    Ok(decoded.trim_start_matches("file:").to_string())
}

/// The bytes an URI names: a base64 `data:` URI, or a file relative to the glTF's folder.
pub(super) fn read_uri(uri: &str, dir: &Path) -> std::result::Result<Vec<u8>, String> {
    use base64::Engine;
    if let Some(rest) = uri.strip_prefix("data:") {
        let (_, data) = rest.split_once(";base64,").ok_or("a data URI that is not base64")?;
        return base64::engine::general_purpose::STANDARD
            .decode(data)
            .map_err(|e| format!("a data URI that is not valid base64: {e}"));
    }
    let path: PathBuf = dir.join(uri_file(uri)?);
    read_bounded(&path, MAX_GLTF_BYTES).map_err(|problem| format!("{}: {problem}", path.display()))
}

/// Every buffer the document declares, from the `.glb`'s binary chunk, a data URI or a file.
pub(super) fn read_buffers(
    document: &::gltf::Document,
    dir: &Path,
    mut blob: Option<Vec<u8>>,
) -> std::result::Result<Vec<Vec<u8>>, String> {
    document
        .buffers()
        .map(|buffer| {
            let data = match buffer.source() {
                ::gltf::buffer::Source::Bin => blob
                    .take()
                    .ok_or_else(|| format!("buffer {} is the binary chunk, which is missing", buffer.index()))?,
                ::gltf::buffer::Source::Uri(uri) => {
                    read_uri(uri, dir).map_err(|problem| format!("buffer {}: {problem}", buffer.index()))?
                }
            };
            if data.len() < buffer.length() {
                return Err(format!(
                    "buffer {} holds {} bytes; the file says {}",
                    buffer.index(),
                    data.len(),
                    buffer.length()
                ));
            }
            Ok(data)
        })
        .collect()
}

/// An image's name for messages, and its encoded bytes or why they could not be read.
pub(super) type Picture = (PathBuf, std::result::Result<Vec<u8>, String>);

/// The encoded bytes of an image (a file, a data URI or a buffer view), and what to call it.
pub(super) fn image_bytes(image: &::gltf::Image, dir: &Path, buffers: &[Vec<u8>]) -> Picture {
    match image.source() {
        ::gltf::image::Source::Uri { uri, .. } if !uri.starts_with("data:") => {
            // Found as OBJ's maps are: as written, by file name alone, or ignoring letter case.
            let name = match uri_file(uri) {
                Ok(name) => name,
                Err(problem) => return (PathBuf::from(uri), Err(problem)),
            };
            let path = find_texture(dir, &name).unwrap_or_else(|| dir.join(&name));
            let bytes = read_bounded(&path, MAX_GLTF_BYTES).map_err(|problem| format!("{}: {problem}", path.display()));
            (path, bytes)
        }
        ::gltf::image::Source::Uri { uri, .. } => {
            (PathBuf::from(format!("image {}", image.index())), read_uri(uri, dir))
        }
        ::gltf::image::Source::View { view, .. } => {
            // The offsets are the file's own numbers: their sum may overflow.
            let bytes = (view.offset().checked_add(view.length()))
                .and_then(|end| buffers.get(view.buffer().index())?.get(view.offset()..end))
                .map(<[u8]>::to_vec)
                .ok_or_else(|| format!("image {}'s buffer view lies outside its buffer", image.index()));
            (PathBuf::from(format!("image {}", image.index())), bytes)
        }
    }
}

/// An accessor's element type: dimensions and component type.
pub(super) type Kind = (::gltf::accessor::Dimensions, ::gltf::accessor::DataType);

pub(super) const VEC3_KINDS: &[Kind] = &[(::gltf::accessor::Dimensions::Vec3, ::gltf::accessor::DataType::F32)];
pub(super) const UV_KINDS: &[Kind] = &[
    (::gltf::accessor::Dimensions::Vec2, ::gltf::accessor::DataType::F32),
    (::gltf::accessor::Dimensions::Vec2, ::gltf::accessor::DataType::U8),
    (::gltf::accessor::Dimensions::Vec2, ::gltf::accessor::DataType::U16),
];
pub(super) const INDEX_KINDS: &[Kind] = &[
    (::gltf::accessor::Dimensions::Scalar, ::gltf::accessor::DataType::U8),
    (::gltf::accessor::Dimensions::Scalar, ::gltf::accessor::DataType::U16),
    (::gltf::accessor::Dimensions::Scalar, ::gltf::accessor::DataType::U32),
];

/// Whether an accessor is of one of the `kinds` glTF allows for its use, dense (sparse ones are
/// not read), and lies with its stride inside its view and the view inside its buffer.
pub(super) fn accessor_fits(accessor: &::gltf::Accessor, kinds: &[Kind], buffers: &[Vec<u8>]) -> bool {
    let Some(view) = accessor.view() else { return false };
    if accessor.sparse().is_some() || !kinds.contains(&(accessor.dimensions(), accessor.data_type())) {
        return false;
    }
    let buffer_length = buffers.get(view.buffer().index()).map_or(0, Vec::len);
    if view.offset().checked_add(view.length()).is_none_or(|end| end > buffer_length) {
        return false;
    }
    // An empty accessor is left unread too (the reader computes `count - 1`).
    let (size, count) = (accessor.size(), accessor.count());
    let stride = view.stride().unwrap_or(size);
    if count == 0 {
        return false;
    }
    let end =
        stride.checked_mul(count - 1).and_then(|s| s.checked_add(accessor.offset())).and_then(|s| s.checked_add(size));
    stride >= size && end.is_some_and(|end| end <= view.length())
}
