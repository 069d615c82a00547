//! What a glTF's URIs and views hold, read within bounds and within the model's folder: its
//! buffers (the `.glb`'s binary chunk, base64 data URIs, files beside it) and its images, each
//! file read once however many references name it, and sized against the memory budget before
//! it is read; the references the `gltf` crate would follow without checking (and panic on),
//! checked first; and its accessors checked against its buffers before the crate's reader
//! trusts them.

use std::collections::HashMap;
use std::path::PathBuf;
use std::rc::Rc;

use super::files::ModelFolder;
use crate::budget::{self, Share};

/// The largest glTF, `.glb` or buffer file read.
pub const MAX_GLTF_BYTES: u64 = 1 << 30;

/// The file name a non-data URI stands for: percent-decoded, with `/` for `\\` and no `file:`
/// scheme (`file:///x` is the absolute path `/x`, which the model's folder then refuses); an
/// URI of another scheme (`https://`) is no local file.
fn uri_file(uri: &str) -> std::result::Result<String, String> {
    if uri.contains("://") && !uri.starts_with("file://") {
        return Err(format!("'{uri}' is not a local file"));
    }
    let decoded = percent_encoding::percent_decode_str(uri).decode_utf8_lossy().replace('\\', "/");
    let name = match decoded.strip_prefix("file://") {
        Some(rest) => rest.to_string(),
        None => decoded.strip_prefix("file:").unwrap_or(&decoded).to_string(),
    };
    Ok(name)
}

/// The bytes of a base64 `data:` URI.
fn data_uri(uri: &str) -> Option<std::result::Result<Vec<u8>, String>> {
    use base64::Engine;
    let rest = uri.strip_prefix("data:")?;
    let Some((_, data)) = rest.split_once(";base64,") else { return Some(Err("a data URI that is not base64".into())) };
    Some(
        base64::engine::general_purpose::STANDARD
            .decode(data)
            .map_err(|e| format!("a data URI that is not valid base64: {e}")),
    )
}

/// Checks what the `gltf` crate indexes without checking when it validates a document or
/// reads an image: each primitive's accessors exist, and each image has a source (a `uri`, or a
/// `bufferView` with its `mimeType`).
pub(super) fn check_references(root: &::gltf::json::Root) -> std::result::Result<(), String> {
    let accessors = root.accessors.len();
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, primitive) in mesh.primitives.iter().enumerate() {
            let named = primitive.attributes.values().chain(&primitive.indices);
            if let Some(missing) = named.map(|a| a.value()).find(|&a| a >= accessors) {
                return Err(format!(
                    "mesh {m}, primitive {p} names accessor {missing}, but the file has {accessors} accessor(s)"
                ));
            }
        }
    }
    Ok(())
}

/// Why image `index` has no source the crate can name, if it has none.
pub(super) fn image_problem(root: &::gltf::json::Root, index: usize) -> Option<String> {
    let image = root.images.get(index)?;
    match (&image.uri, &image.buffer_view, &image.mime_type) {
        (None, None, _) => Some(format!("image {index} has neither a uri nor a bufferView")),
        (_, Some(_), None) => Some(format!("image {index} lies in a bufferView but has no mimeType")),
        _ => None,
    }
}

/// Where each buffer's bytes come from, sized before anything is read.
pub(super) struct BufferPlan {
    sources: Vec<Source>,
    /// Each file read, by its real path: the path found and the bytes to read from it.
    files: Vec<(PathBuf, u64)>,
    /// The bytes the buffers take in memory together (each file once).
    pub bytes: u64,
}

enum Source {
    /// The `.glb`'s binary chunk.
    Blob,
    /// A base64 data URI, decoded.
    Data(Vec<u8>),
    /// One of [`BufferPlan::files`].
    File(usize),
}

impl BufferPlan {
    /// Every buffer's source: a file must lie in the model's folder and hold at least the
    /// length the document gives; a file named by several buffers is read once.
    pub(super) fn new(
        document: &::gltf::Document,
        folder: &ModelFolder,
        blob: Option<&Vec<u8>>,
    ) -> std::result::Result<Self, String> {
        let mut plan = Self { sources: Vec::new(), files: Vec::new(), bytes: blob.map_or(0, |b| b.len() as u64) };
        let mut by_real: HashMap<PathBuf, usize> = HashMap::new();
        for buffer in document.buffers() {
            let i = buffer.index();
            let length = buffer.length() as u64;
            let source = match buffer.source() {
                ::gltf::buffer::Source::Bin if blob.is_some() => Source::Blob,
                ::gltf::buffer::Source::Bin => return Err(format!("buffer {i} is the binary chunk, which is missing")),
                ::gltf::buffer::Source::Uri(uri) => match data_uri(uri) {
                    Some(data) => {
                        let data = data.map_err(|problem| format!("buffer {i}: {problem}"))?;
                        plan.bytes += data.len() as u64;
                        Source::Data(data)
                    }
                    None => {
                        let name = uri_file(uri).map_err(|problem| format!("buffer {i}: {problem}"))?;
                        let path = folder.inside(&name).map_err(|problem| format!("buffer {i}: {problem}"))?;
                        let size = folder.size_of(&path).map_err(|problem| format!("buffer {i}: {problem}"))?;
                        if size < length {
                            return Err(format!(
                                "buffer {i}: {} holds {size} bytes; the file says {length}",
                                path.display()
                            ));
                        }
                        let real = std::fs::canonicalize(&path).unwrap_or_else(|_| path.clone());
                        let file = *by_real.entry(real).or_insert_with(|| {
                            plan.files.push((path, 0));
                            plan.files.len() - 1
                        });
                        let wanted = &mut plan.files[file].1;
                        plan.bytes += length.saturating_sub(*wanted);
                        *wanted = (*wanted).max(length);
                        Source::File(file)
                    }
                },
            };
            plan.sources.push(source);
        }
        if plan.files.iter().any(|&(_, n)| n > MAX_GLTF_BYTES) {
            return Err(format!("a buffer over {} MiB", MAX_GLTF_BYTES >> 20));
        }
        Ok(plan)
    }

    /// Reads the planned bytes: each file once, no further than the document's length.
    pub(super) fn read(
        self,
        folder: &ModelFolder,
        blob: Option<Vec<u8>>,
        lengths: &[usize],
    ) -> std::result::Result<Vec<Rc<Vec<u8>>>, String> {
        let files: Vec<Rc<Vec<u8>>> = self
            .files
            .iter()
            .map(|(path, n)| folder.read_prefix(path, *n).map(Rc::new))
            .collect::<std::result::Result<_, _>>()?;
        let blob = blob.map(Rc::new);
        let mut out = Vec::with_capacity(self.sources.len());
        for (i, source) in self.sources.into_iter().enumerate() {
            let data = match source {
                Source::Blob => {
                    blob.clone().ok_or_else(|| format!("buffer {i} is the binary chunk, which is missing"))?
                }
                Source::Data(data) => Rc::new(data),
                Source::File(f) => files[f].clone(),
            };
            if data.len() < lengths[i] {
                return Err(format!("buffer {i} holds {} bytes; the file says {}", data.len(), lengths[i]));
            }
            out.push(data);
        }
        Ok(out)
    }
}

/// An image's name for messages, and its encoded bytes or why they could not be read.
pub(super) type Picture = (PathBuf, std::result::Result<Rc<Vec<u8>>, String>);

/// The encoded bytes of the images in `wanted` (the others are `None`): files from the model's
/// folder, data URIs or buffer views. Each file is read once; all of them together are held
/// within the textures' transient room, and what would not fit is refused, in order, with the
/// budget named.
pub(super) fn read_images(
    document: &::gltf::Document,
    wanted: &std::collections::BTreeSet<usize>,
    folder: &ModelFolder,
    buffers: &[Rc<Vec<u8>>],
) -> Vec<Option<Picture>> {
    let mut held = 0u64;
    let mut by_real: HashMap<PathBuf, Rc<Vec<u8>>> = HashMap::new();
    let mut out = Vec::new();
    for image in document.images() {
        let index = image.index();
        if !wanted.contains(&index) {
            out.push(None);
            continue;
        }
        let name = PathBuf::from(format!("image {index}"));
        if let Some(problem) = image_problem(document.as_json(), index) {
            out.push(Some((name, Err(problem))));
            continue;
        }
        let mut within = |what: &PathBuf, bytes: u64| {
            budget::check_transient(Share::Textures, held.saturating_add(bytes), || {
                format!("{} with the images before it", what.display())
            })?;
            held += bytes;
            Ok::<(), String>(())
        };
        let picture = match image.source() {
            ::gltf::image::Source::Uri { uri, .. } => match data_uri(uri) {
                Some(data) => (name.clone(), data.and_then(|d| within(&name, d.len() as u64).map(|()| Rc::new(d)))),
                None => file_image(uri, folder, &mut by_real, &mut within),
            },
            ::gltf::image::Source::View { view, .. } => {
                // The offsets are the file's own numbers: their sum may overflow.
                let bytes = (view.offset().checked_add(view.length()))
                    .and_then(|end| buffers.get(view.buffer().index())?.get(view.offset()..end))
                    .ok_or_else(|| format!("image {index}'s buffer view lies outside its buffer"))
                    .and_then(|b| within(&name, b.len() as u64).map(|()| Rc::new(b.to_vec())));
                (name, bytes)
            }
        };
        out.push(Some(picture));
    }
    out
}

/// An image file from the model's folder, found as OBJ's maps are, read once however many
/// images name it.
fn file_image(
    uri: &str,
    folder: &ModelFolder,
    by_real: &mut HashMap<PathBuf, Rc<Vec<u8>>>,
    within: &mut impl FnMut(&PathBuf, u64) -> std::result::Result<(), String>,
) -> Picture {
    // Found ignoring letter case, as OBJ's maps are; a name outside the folder is refused.
    let found = uri_file(uri).and_then(|name| folder.inside(&name).and_then(|_| folder.find(&name)));
    let found = found.map(|(path, _)| path);
    let path = match found {
        Ok(path) => path,
        Err(problem) => return (PathBuf::from(uri), Err(problem)),
    };
    let real = std::fs::canonicalize(&path).unwrap_or_else(|_| path.clone());
    if let Some(bytes) = by_real.get(&real) {
        return (path, Ok(bytes.clone()));
    }
    let bytes = folder
        .size_of(&path)
        .and_then(|size| within(&path, size).map(|()| size))
        .and_then(|size| folder.read_prefix(&path, size))
        .map(Rc::new);
    if let Ok(bytes) = &bytes {
        by_real.insert(real, bytes.clone());
    }
    (path, bytes)
}

/// An accessor's element type: dimensions and component type.
pub(super) type Kind = (::gltf::accessor::Dimensions, ::gltf::accessor::DataType);

pub(super) const VEC3_KINDS: &[Kind] = &[(::gltf::accessor::Dimensions::Vec3, ::gltf::accessor::DataType::F32)];
pub(super) const VEC4_KINDS: &[Kind] = &[(::gltf::accessor::Dimensions::Vec4, ::gltf::accessor::DataType::F32)];
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
pub(super) fn accessor_fits(accessor: &::gltf::Accessor, kinds: &[Kind], buffers: &[Rc<Vec<u8>>]) -> bool {
    let Some(view) = accessor.view() else { return false };
    if accessor.sparse().is_some() || !kinds.contains(&(accessor.dimensions(), accessor.data_type())) {
        return false;
    }
    let buffer_length = buffers.get(view.buffer().index()).map_or(0, |b| b.len());
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
