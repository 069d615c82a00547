//! Text that reaches a person or a table: numbers written as people write them, and strings read
//! from files (names in presets, materials, nodes) bounded and kept to one line before they are
//! shown, logged or put in a table cell.

/// The most characters of a name read from a file that are kept: a preset refuses a longer one,
/// a model's material or node name is cut to it.
pub const MAX_NAME_CHARS: usize = 256;

/// A number as people write it: 0.25, 1e6, 3.0e-5 (not 30 digits of a huge or tiny float).
pub fn num(v: f32) -> String {
    if v != 0.0 && v.is_finite() && !(1e-4..1e6).contains(&v.abs()) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

/// `text` with control characters (a newline in a file name, say) written as escapes, so an error
/// stays one line.
pub fn one_line(text: &str) -> String {
    text.chars().flat_map(|c| if c.is_control() { c.escape_default().collect::<Vec<_>>() } else { vec![c] }).collect()
}

/// A name read from a file as it may be shown: one line, at most [`MAX_NAME_CHARS`] characters
/// (a longer one is cut and ends in "…").
pub fn bounded_name(name: &str) -> String {
    let mut chars = name.chars();
    let kept: String = chars.by_ref().take(MAX_NAME_CHARS).collect();
    let line = one_line(&kept);
    if chars.next().is_some() {
        format!("{line}…")
    } else {
        line
    }
}

/// Why `text` cannot be a name kept in a file this program writes and reads (a preset's): over
/// [`MAX_NAME_CHARS`] characters, or holding a control character such as a line break.
pub fn name_problem(text: &str) -> Option<String> {
    let chars = text.chars().count();
    if chars > MAX_NAME_CHARS {
        return Some(format!("{chars} characters; at most {MAX_NAME_CHARS} are accepted"));
    }
    text.chars()
        .find(|c| c.is_control())
        .map(|c| format!("holds the control character {}; a name is one line of text", c.escape_default()))
}

/// `text` as a Markdown table cell: one line, its pipes escaped so they do not split the row.
pub fn markdown_cell(text: &str) -> String {
    bounded_name(text).replace('|', "\\|")
}

/// Now, in UTC to the minute ("2026-12-06 05:40 UTC"), as reports and presets date themselves.
pub fn utc_minute() -> String {
    jiff::Timestamp::now().to_zoned(jiff::tz::TimeZone::UTC).strftime("%Y-%m-%d %H:%M UTC").to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_bounded_and_one_line() {
        assert_eq!(bounded_name("a\nb"), "a\\nb");
        let long = "x".repeat(MAX_NAME_CHARS + 5);
        assert_eq!(bounded_name(&long).chars().count(), MAX_NAME_CHARS + 1);
        assert!(name_problem(&long).unwrap().contains("261 characters"));
        assert!(name_problem("a\r\n=cmd|x").unwrap().contains("\\r"));
        assert_eq!(name_problem("ultra, 8 ms"), None);
        assert_eq!(markdown_cell("a|b"), "a\\|b");
        assert_eq!(num(1e-45), "1e-45");
        assert_eq!(num(0.25), "0.25");
    }
}
