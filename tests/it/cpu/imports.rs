//! The house has no circles: no two files of `src/` import each other, even through others.
//! Every path a file names (`use` statements with their groups, and paths in code that start at
//! `crate`, `super`, `self` or a child module) is followed to the file that defines what it
//! names, through `pub use` re-exports, and the graph of files must have no cycle
//! (ARCHITECTURE.md: "Imports run one way").

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The module path of a file under `src/` (`render/passes/gbuffer.rs` → render, passes, gbuffer).
fn module_of(file: &str) -> Vec<String> {
    let path = file.trim_end_matches(".rs");
    let mut parts: Vec<String> = path.split('/').map(str::to_owned).collect();
    if matches!(parts.last().map(String::as_str), Some("mod" | "lib" | "main")) {
        parts.pop();
    }
    parts
}

/// The files of a tree: path under `src/` → text without comments.
struct Tree {
    files: BTreeMap<String, String>,
}

impl Tree {
    fn read(root: &Path) -> Self {
        let mut files = BTreeMap::new();
        let mut stack = vec![root.to_path_buf()];
        while let Some(dir) = stack.pop() {
            for entry in std::fs::read_dir(&dir).unwrap().flatten() {
                let path = entry.path();
                if path.is_dir() {
                    stack.push(path);
                } else if path.extension().is_some_and(|e| e == "rs") {
                    let name = path.strip_prefix(root).unwrap().to_string_lossy().replace('\\', "/");
                    // A file's unit tests (its `mod tests`, at its end) import it by `super`.
                    let text = std::fs::read_to_string(&path).unwrap();
                    let code = text.split("#[cfg(test)]\nmod tests").next().unwrap_or_default();
                    files.insert(name, strip_comments(code));
                }
            }
        }
        Self { files }
    }

    /// The file of module `path` (the longest prefix that is a file) and what remains of it.
    fn file_of<'a>(&self, path: &'a [String]) -> Option<(String, &'a [String])> {
        for k in (0..=path.len()).rev() {
            let stem = path[..k].join("/");
            let candidates =
                if k == 0 { vec!["lib.rs".to_string()] } else { vec![format!("{stem}.rs"), format!("{stem}/mod.rs")] };
            if let Some(file) = candidates.into_iter().find(|c| self.files.contains_key(c)) {
                return Some((file, &path[k..]));
            }
        }
        None
    }

    /// The file that defines what `path` (from the crate's root) names, through re-exports.
    fn defining(&self, path: &[String], depth: usize) -> Option<String> {
        let (file, rest) = self.file_of(path)?;
        let Some(name) = rest.first() else { return Some(file) };
        if depth < 8 {
            for (target, exported) in uses(&self.files[&file], true) {
                if exported == *name {
                    let absolute = absolute(&module_of(&file), &target, self, &file)?;
                    return self.defining(&absolute, depth + 1);
                }
            }
        }
        Some(file)
    }

    /// The files `file` imports from.
    fn imports(&self, file: &str) -> BTreeSet<String> {
        let text = &self.files[file];
        let module = module_of(file);
        let mut paths: Vec<Vec<String>> = uses(text, false).into_iter().map(|(p, _)| p).collect();
        let code = without_uses(text);
        let text = &code;
        paths.extend(inline_paths(text, &["crate", "super", "self"]));
        // In a mod.rs (or lib.rs), a path may start at a child module: `view_state::TruthState`.
        if file.ends_with("mod.rs") || file == "lib.rs" {
            let dir = if file == "lib.rs" { String::new() } else { format!("{}/", module.join("/")) };
            let children: Vec<String> = self
                .files
                .keys()
                .filter_map(|f| f.strip_prefix(&dir))
                .filter_map(|rest| rest.strip_suffix(".rs").or(rest.strip_suffix("/mod.rs")))
                .filter(|c| !c.contains('/') && !matches!(*c, "mod" | "lib" | "main"))
                .map(str::to_owned)
                .collect();
            let starts: Vec<&str> = children.iter().map(String::as_str).collect();
            paths.extend(inline_paths(text, &starts));
        }
        paths
            .iter()
            .filter_map(|p| absolute(&module, p, self, file))
            .filter_map(|p| self.defining(&p, 0))
            .filter(|f| f != file)
            .collect()
    }
}

/// `path` as written in `file` (of `module`), from the crate's root; `None` for other crates.
fn absolute(module: &[String], path: &[String], tree: &Tree, file: &str) -> Option<Vec<String>> {
    let first = path.first()?;
    let mut out: Vec<String> = match first.as_str() {
        "crate" => Vec::new(),
        "self" => module.to_vec(),
        "super" => {
            let mut m = module.to_vec();
            m.pop();
            m
        }
        child => {
            // A child module of this file's module (`use controls::X` in a mod.rs).
            let own_dir = if file.ends_with("mod.rs") || file == "lib.rs" { module.to_vec() } else { Vec::new() };
            let mut candidate = own_dir.clone();
            candidate.push(child.to_owned());
            if own_dir.is_empty() && file != "lib.rs"
                || tree.file_of(&candidate).is_none_or(|(_, rest)| !rest.is_empty())
            {
                return None;
            }
            own_dir
        }
    };
    let mut rest = &path[usize::from(matches!(first.as_str(), "crate" | "self" | "super"))..];
    while rest.first().is_some_and(|s| s == "super") {
        out.pop();
        rest = &rest[1..];
    }
    out.extend(rest.iter().cloned());
    Some(out)
}

/// The `use` statements of `text`: with `exported` its re-exports (`pub use`, which hand names
/// on and are followed through, not counted as the file's own imports), else its own `use`s;
/// each path they bring in and the name it is known by.
fn uses(text: &str, exported: bool) -> Vec<(Vec<String>, String)> {
    let mut out = Vec::new();
    for statement in text.split(';') {
        // The statement's last line that starts one (after attributes, items, a `{`).
        let s = statement.trim();
        let line = s.rfind('\n').map_or(s, |i| s[i..].trim());
        let line = if line.contains("use ") { line } else { s };
        let public = ["pub use ", "pub(crate) use ", "pub(super) use "].iter().find_map(|p| line.strip_prefix(p));
        let body = match (public, line.strip_prefix("use ")) {
            (Some(b), _) if exported => b,
            (None, Some(b)) if !exported => b,
            _ => continue,
        };
        expand(&body.split_whitespace().collect::<String>(), &mut Vec::new(), &mut out);
    }
    out
}

/// Expands one `use` tree (`a::{b::C, d}`) into its paths and names.
fn expand(tree: &str, prefix: &mut Vec<String>, out: &mut Vec<(Vec<String>, String)>) {
    if let Some(open) = tree.find('{') {
        let head: Vec<String> = tree[..open].split("::").filter(|s| !s.is_empty()).map(str::to_owned).collect();
        let inner = &tree[open + 1..tree.rfind('}').unwrap_or(tree.len())];
        let mut depth = 0;
        let mut start = 0;
        let mut parts = Vec::new();
        for (i, c) in inner.char_indices() {
            match c {
                '{' => depth += 1,
                '}' => depth -= 1,
                ',' if depth == 0 => {
                    parts.push(&inner[start..i]);
                    start = i + 1;
                }
                _ => {}
            }
        }
        parts.push(&inner[start..]);
        let len = prefix.len();
        prefix.extend(head);
        for part in parts.into_iter().filter(|p| !p.is_empty()) {
            expand(part, prefix, out);
        }
        prefix.truncate(len);
    } else {
        let (path, alias) = match tree.split_once(" as ").or(tree.split_once("as")) {
            Some((p, a)) if tree.contains("as") && !p.ends_with(':') && tree.contains(" as ") => (p, Some(a)),
            _ => (tree, None),
        };
        let mut full = prefix.clone();
        full.extend(path.split("::").filter(|s| !s.is_empty() && *s != "*").map(str::to_owned));
        if full.last().is_some_and(|s| s == "self") {
            full.pop();
        }
        let name = alias.map(str::to_owned).or(full.last().cloned()).unwrap_or_default();
        out.push((full, name));
    }
}

/// `text` without its `use` statements (read by `uses`; a re-export's path is no import).
fn without_uses(text: &str) -> String {
    let mut out = String::new();
    let mut skipping = false;
    for line in text.lines() {
        let t = line.trim_start();
        if !skipping && ["use ", "pub use ", "pub(crate) use ", "pub(super) use "].iter().any(|p| t.starts_with(p)) {
            skipping = true;
        }
        if !skipping {
            out.push_str(line);
        }
        out.push('\n');
        if skipping && line.contains(';') {
            skipping = false;
        }
    }
    out
}

/// Paths in code that start at one of `starts` (`crate`, `super`, `self`, a child module).
fn inline_paths(text: &str, starts: &[&str]) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    let bytes = text.as_bytes();
    for start in starts.iter().map(|s| format!("{s}::")) {
        let start = start.as_str();
        let mut from = 0;
        while let Some(i) = text[from..].find(start).map(|i| from + i) {
            from = i + start.len();
            if i > 0 && (bytes[i - 1].is_ascii_alphanumeric() || bytes[i - 1] == b'_' || bytes[i - 1] == b':') {
                continue;
            }
            let end =
                text[i..].find(|c: char| !(c.is_alphanumeric() || c == '_' || c == ':')).map_or(text.len(), |e| i + e);
            // `super::{a, b}` is a use group, read whole by `uses`.
            if text[..end].ends_with("::") {
                continue;
            }
            out.push(text[i..end].split("::").filter(|s| !s.is_empty()).map(str::to_owned).collect());
        }
    }
    out
}

/// `text` without `//` comments and string literals' contents (a path in a doc is no import).
fn strip_comments(text: &str) -> String {
    let mut out = String::new();
    for line in text.lines() {
        let mut in_string = false;
        let mut kept = String::new();
        let mut chars = line.chars().peekable();
        while let Some(c) = chars.next() {
            if !in_string && c == '/' && chars.peek() == Some(&'/') {
                break;
            }
            if c == '"' {
                in_string = !in_string;
            }
            if !in_string || c == '"' {
                kept.push(c);
            }
        }
        out.push_str(&kept);
        out.push('\n');
    }
    out
}

/// A cycle of the import graph, if there is one.
fn cycle(graph: &BTreeMap<String, BTreeSet<String>>) -> Option<Vec<String>> {
    fn visit(
        node: &str,
        graph: &BTreeMap<String, BTreeSet<String>>,
        state: &mut BTreeMap<String, u8>,
        stack: &mut Vec<String>,
    ) -> Option<Vec<String>> {
        state.insert(node.to_owned(), 1);
        stack.push(node.to_owned());
        for next in graph.get(node).into_iter().flatten() {
            match state.get(next.as_str()) {
                Some(1) => {
                    let at = stack.iter().position(|n| n == next).unwrap_or(0);
                    return Some(stack[at..].iter().cloned().chain([next.clone()]).collect());
                }
                Some(_) => {}
                None => {
                    if let Some(c) = visit(next, graph, state, stack) {
                        return Some(c);
                    }
                }
            }
        }
        stack.pop();
        state.insert(node.to_owned(), 2);
        None
    }
    let mut state = BTreeMap::new();
    for node in graph.keys() {
        if !state.contains_key(node.as_str()) {
            if let Some(c) = visit(node, graph, &mut state, &mut Vec::new()) {
                return Some(c);
            }
        }
    }
    None
}

fn graph(tree: &Tree) -> BTreeMap<String, BTreeSet<String>> {
    tree.files.keys().filter(|f| *f != "main.rs").map(|f| (f.clone(), tree.imports(f))).collect()
}

#[test]
fn no_two_files_of_src_import_each_other_even_through_others() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("src");
    let tree = Tree::read(&root);
    let graph = graph(&tree);
    // The checker sees the imports it must: a use, a group, a re-export, a child of a mod.rs.
    let of = |f: &str| graph.get(f).unwrap_or_else(|| panic!("{f} read"));
    assert!(
        of("render/passes/gbuffer.rs").contains("render/resources/scene.rs"),
        "{:?}",
        of("render/passes/gbuffer.rs")
    );
    assert!(of("app/truth_view.rs").contains("app/mod.rs"), "super::Viewer: {:?}", of("app/truth_view.rs"));
    assert!(of("app/mod.rs").contains("app/view_state.rs"), "a child's type: {:?}", of("app/mod.rs"));
    assert!(
        of("scene/obj_model.rs").contains("scene/triangle.rs"),
        "model::Vertex, re-exported: {:?}",
        of("scene/obj_model.rs")
    );
    if let Some(c) = cycle(&graph) {
        panic!("an import circle: {}", c.join(" -> "));
    }
}

#[test]
fn the_checker_finds_a_circle_through_a_re_export() {
    let files = [
        ("lib.rs", "pub mod a;\npub mod b;\n"),
        ("a/mod.rs", "mod inner;\npub use inner::Thing;\n"),
        ("a/inner.rs", "use crate::b::Other;\npub struct Thing;\n"),
        ("b.rs", "pub struct Other(crate::a::Thing);\n"),
    ];
    let tree = Tree { files: files.iter().map(|(f, t)| (f.to_string(), strip_comments(t))).collect() };
    let c = cycle(&graph(&tree)).expect("a -> b -> a through the re-export");
    assert!(c.contains(&"a/inner.rs".to_string()) && c.contains(&"b.rs".to_string()), "{c:?}");
}
