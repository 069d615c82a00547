//! The text of OBJ and MTL files made safe for `tobj`: decoded from UTF-8, UTF-16 or Latin-1,
//! colour statements padded or dropped where tobj would panic, and faces whose references do not
//! hold together dropped (`model.rs` does the rest of the loading).

/// Reads text that may be UTF-8, UTF-16 (with a byte-order mark) or Latin-1.
pub fn decode_text(bytes: &[u8]) -> String {
    let utf16 = |le: bool| {
        let units: Vec<u16> = bytes[2..]
            .chunks_exact(2)
            .map(|c| if le { u16::from_le_bytes([c[0], c[1]]) } else { u16::from_be_bytes([c[0], c[1]]) })
            .collect();
        String::from_utf16_lossy(&units)
    };
    match bytes {
        [0xFF, 0xFE, ..] => utf16(true),
        [0xFE, 0xFF, ..] => utf16(false),
        [0xEF, 0xBB, 0xBF, rest @ ..] => String::from_utf8_lossy(rest).into_owned(),
        _ => match std::str::from_utf8(bytes) {
            Ok(text) => text.to_owned(),
            Err(_) => bytes.iter().map(|&b| b as char).collect(),
        },
    }
}

/// Pads colour statements that give one value (`Kd 0.5`, allowed by the format) to three, which
/// is what they mean, and drops colour statements tobj 4.0.5 would panic on (no value, two
/// values, or words that are not numbers). Returns the text and the number of lines dropped.
pub(super) fn sanitize_mtl(text: &str) -> (String, usize) {
    let mut out = String::with_capacity(text.len() + 64);
    let mut dropped = 0;
    for line in text.lines() {
        let mut words = line.split_whitespace();
        let keyword = words.next().unwrap_or("");
        let values: Vec<&str> = words.collect();
        if matches!(keyword, "Ka" | "Kd" | "Ks" | "Ke" | "Tf") {
            let numeric = values.iter().take(3).all(|v| v.parse::<f32>().is_ok());
            match values.len() {
                1 if numeric => out.push_str(&format!("{keyword} {0} {0} {0}\n", values[0])),
                n if n >= 3 && numeric => {
                    out.push_str(line);
                    out.push('\n');
                }
                _ => dropped += 1,
            }
        } else {
            out.push_str(line);
            out.push('\n');
        }
    }
    (out, dropped)
}

/// Drops face statements tobj would mishandle: a vertex reference of 0, one beyond the elements
/// defined so far (negative references count back from the last one), or a face whose vertices
/// disagree on which attributes they carry (`1/1 2//1`). tobj 4.0.5 overflows on some of these
/// and silently misreads others. Returns the text to parse and how many faces were dropped.
pub(super) fn sanitize_obj(text: &str) -> (String, usize) {
    let mut counts = [0i64; 3];
    let mut dropped = 0;
    let mut out = String::with_capacity(text.len());
    for line in text.lines() {
        let mut words = line.split_whitespace();
        let keyword = words.next().unwrap_or("");
        match keyword {
            "v" => counts[0] += 1,
            "vt" => counts[1] += 1,
            "vn" => counts[2] += 1,
            "f" => {
                let mut shape = None;
                let valid = words.all(|vertex| {
                    let parts: Vec<&str> = vertex.split('/').collect();
                    let form: Vec<bool> = parts.iter().map(|p| !p.is_empty()).collect();
                    let consistent = *shape.get_or_insert_with(|| form.clone()) == form;
                    let in_range = parts.iter().zip(counts).all(|(p, count)| {
                        p.is_empty()
                            || p.parse::<i64>().is_ok_and(|i| i != 0 && (if i > 0 { i <= count } else { -i <= count }))
                    });
                    consistent && parts.len() <= 3 && !parts[0].is_empty() && in_range
                });
                if !valid {
                    dropped += 1;
                    continue;
                }
            }
            _ => {}
        }
        out.push_str(line);
        out.push('\n');
    }
    (out, dropped)
}

/// What a quick pass over an OBJ file's bytes finds, before anything is parsed or built.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ObjCounts {
    /// `f` records.
    pub faces: u64,
    /// Triangles once every face is fanned (a face of n corners makes n - 2).
    pub triangles: u64,
    /// Whether anything but white space and NUL bytes is there.
    pub has_content: bool,
    /// NUL bytes (skipped: UTF-16 text has one in every ASCII character).
    pub zero_bytes: u64,
}

/// Counts faces and triangles by streaming the file in small chunks: a gigabyte of zero bytes
/// or one polygon of millions of corners is sized in a second, in a few kilobytes, before the
/// parser builds anything. NUL bytes are skipped, so UTF-16 text counts the same.
pub fn count_obj(path: &std::path::Path) -> std::io::Result<ObjCounts> {
    use std::io::Read;
    #[derive(Clone, Copy, PartialEq)]
    enum State {
        LineStart,
        SawF,
        Face { in_token: bool },
        Skip,
    }
    let mut file = super::files::open_regular(path, u64::MAX).map_err(std::io::Error::other)?;
    let mut buffer = vec![0u8; 1 << 16];
    let (mut counts, mut state, mut corners) = (ObjCounts::default(), State::LineStart, 0u64);
    let end_line = |counts: &mut ObjCounts, state: State, corners: &mut u64| {
        if matches!(state, State::Face { .. }) || (state == State::Skip && *corners > 0) {
            counts.faces += 1;
            counts.triangles += corners.saturating_sub(2);
        }
        *corners = 0;
    };
    loop {
        let n = file.read(&mut buffer)?;
        if n == 0 {
            break;
        }
        for &b in &buffer[..n] {
            if b == 0 {
                counts.zero_bytes += 1;
                continue;
            }
            let blank = b == b' ' || b == b'\t';
            if b == b'\n' || b == b'\r' {
                end_line(&mut counts, state, &mut corners);
                state = State::LineStart;
                continue;
            }
            counts.has_content |= !b.is_ascii_whitespace();
            state = match state {
                State::LineStart if blank => State::LineStart,
                State::LineStart if b == b'f' => State::SawF,
                State::SawF if blank => State::Face { in_token: false },
                State::Face { .. } if b == b'#' => State::Skip,
                State::Face { .. } if blank => State::Face { in_token: false },
                State::Face { in_token: false } => {
                    corners += 1;
                    State::Face { in_token: true }
                }
                State::Face { in_token: true } => state,
                _ => State::Skip,
            };
        }
    }
    end_line(&mut counts, state, &mut corners);
    Ok(counts)
}
