//! The layers of `crate/src` (the table in `lib.rs`): every top-level module uses only the
//! modules of the layers below its own, so there is no cycle among them and a reader can take
//! the crate top-down. The test reads the source: every `crate::name` path in code (comments,
//! strings and doc tests left out; `crate::{a, b}` groups included) is an edge from the module
//! whose file or folder it is in to `name`.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The layers, lowest first. Modules of one layer do not use each other.
const LAYERS: &[&[&str]] = &[
    &["field", "progress", "parallel", "raster", "rounding"],
    &["surface"],
    &["job"],
    &["path"],
    &["tool"],
    &["nc"],
    &["dynamics", "analysis"],
    &["report", "display"],
    &["plan"],
];

fn src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// The text with comments, string and character literals blanked (newlines kept).
fn code_only(text: &str) -> String {
    let b: Vec<char> = text.chars().collect();
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    let blank = |out: &mut String, c: char| out.push(if c == '\n' { '\n' } else { ' ' });
    while i < b.len() {
        let c = b[i];
        let next = b.get(i + 1).copied();
        if c == '/' && next == Some('/') {
            while i < b.len() && b[i] != '\n' {
                i += 1;
            }
        } else if c == '/' && next == Some('*') {
            let mut depth = 0;
            while i < b.len() {
                if b[i] == '/' && b.get(i + 1) == Some(&'*') {
                    depth += 1;
                    i += 2;
                } else if b[i] == '*' && b.get(i + 1) == Some(&'/') {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    blank(&mut out, b[i]);
                    i += 1;
                }
            }
        } else if c == 'r' && (next == Some('"') || next == Some('#')) && raw_string_at(&b, i) {
            let mut j = i + 1;
            let mut hashes = 0;
            while b[j] == '#' {
                hashes += 1;
                j += 1;
            }
            j += 1;
            let close: String = std::iter::once('"')
                .chain("#".repeat(hashes).chars())
                .collect();
            let close: Vec<char> = close.chars().collect();
            while j < b.len() && b[j..].iter().take(close.len()).ne(close.iter()) {
                blank(&mut out, b[j]);
                j += 1;
            }
            i = j + close.len();
        } else if c == '"' {
            i += 1;
            while i < b.len() && b[i] != '"' {
                if b[i] == '\\' {
                    i += 1;
                }
                if i < b.len() {
                    blank(&mut out, b[i]);
                }
                i += 1;
            }
            i += 1;
        } else if c == '\'' && char_literal_len(&b, i) > 0 {
            i += char_literal_len(&b, i);
        } else {
            out.push(c);
            i += 1;
        }
    }
    out
}

/// Whether `r` at `i` opens a raw string `r"…"` or `r#"…"#` (not the end of an identifier).
fn raw_string_at(b: &[char], i: usize) -> bool {
    let ident_before = i > 0 && (b[i - 1].is_alphanumeric() || b[i - 1] == '_');
    let mut j = i + 1;
    while j < b.len() && b[j] == '#' {
        j += 1;
    }
    !ident_before && b.get(j) == Some(&'"')
}

/// The length of a character literal at `i` (`'x'`, `'\n'`, `'\u{1F}'`), 0 for a lifetime.
fn char_literal_len(b: &[char], i: usize) -> usize {
    if b.get(i + 1) == Some(&'\\') {
        (i + 2..b.len().min(i + 12))
            .find(|&j| b[j] == '\'')
            .map_or(0, |j| j - i + 1)
    } else if b.get(i + 2) == Some(&'\'') {
        3
    } else {
        0
    }
}

/// The top-level modules named by every `crate::` path in `code`, with their line numbers.
fn crate_uses(code: &str) -> Vec<(String, usize)> {
    let mut found = Vec::new();
    for (k, _) in code.match_indices("crate::") {
        let before = code[..k].chars().next_back();
        if before.is_some_and(|c| c.is_alphanumeric() || c == '_') {
            continue;
        }
        let line = code[..k].matches('\n').count() + 1;
        let rest = &code[k + "crate::".len()..];
        if let Some(group) = rest.strip_prefix('{') {
            let mut depth = 0;
            let mut item = String::new();
            for c in group.chars() {
                match c {
                    '{' => depth += 1,
                    '}' if depth == 0 => break,
                    '}' => depth -= 1,
                    ',' if depth == 0 => {
                        push_ident(&mut found, &item, line);
                        item.clear();
                    }
                    _ if depth == 0 => item.push(c),
                    _ => {}
                }
            }
            push_ident(&mut found, &item, line);
        } else {
            push_ident(&mut found, rest, line);
        }
    }
    found
}

fn push_ident(found: &mut Vec<(String, usize)>, text: &str, line: usize) {
    let name: String = text
        .trim_start()
        .chars()
        .take_while(|c| c.is_alphanumeric() || *c == '_')
        .collect();
    if !name.is_empty() && name != "self" {
        found.push((name, line));
    }
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let p = entry.unwrap().path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|e| e == "rs") {
            out.push(p);
        }
    }
}

/// Every top-level module of the library (`pub mod` in lib.rs), with the files it is made of.
fn modules() -> BTreeMap<String, Vec<PathBuf>> {
    let lib = std::fs::read_to_string(src().join("lib.rs")).unwrap();
    let mut out = BTreeMap::new();
    for line in code_only(&lib).lines() {
        let Some(name) = line
            .trim()
            .strip_prefix("pub mod ")
            .or_else(|| line.trim().strip_prefix("mod "))
        else {
            continue;
        };
        let name = name.trim_end_matches(';').trim().to_string();
        let mut files = Vec::new();
        let file = src().join(format!("{name}.rs"));
        if file.exists() {
            files.push(file);
        }
        let dir = src().join(&name);
        if dir.is_dir() {
            rust_files(&dir, &mut files);
        }
        assert!(!files.is_empty(), "module {name} has no source");
        out.insert(name, files);
    }
    out
}

/// Edges `module → used module` with one place each is used from.
fn edges() -> BTreeMap<(String, String), String> {
    let mut out = BTreeMap::new();
    for (module, files) in modules() {
        for file in files {
            let code = code_only(&std::fs::read_to_string(&file).unwrap());
            for (used, line) in crate_uses(&code) {
                if used != module {
                    let at = file.strip_prefix(src()).unwrap().display().to_string();
                    out.entry((module.clone(), used))
                        .or_insert(format!("{at}:{line}"));
                }
            }
        }
    }
    out
}

fn layer_of(module: &str) -> Option<usize> {
    LAYERS.iter().position(|l| l.contains(&module))
}

#[test]
fn every_module_has_a_layer() {
    let modules: BTreeSet<String> = modules().into_keys().collect();
    let listed: BTreeSet<String> = LAYERS
        .iter()
        .flat_map(|l| l.iter())
        .map(|s| s.to_string())
        .collect();
    assert_eq!(
        modules, listed,
        "lib.rs's modules and this test's LAYERS differ: place a new module in a layer (and in \
         lib.rs's table)"
    );
}

/// The edges that do not go to a lower layer, as messages.
fn layer_violations(edges: &BTreeMap<(String, String), String>) -> Vec<String> {
    let mut wrong = Vec::new();
    for ((from, to), at) in edges {
        let (Some(a), Some(b)) = (layer_of(from), layer_of(to)) else {
            wrong.push(format!(
                "{from} → {to} ({at}): {to} is not a module of the crate"
            ));
            continue;
        };
        if b >= a {
            wrong.push(format!(
                "{from} (layer {a}) uses {to} (layer {b}) at {at}: a module may use only the \
                 layers below its own"
            ));
        }
    }
    wrong
}

/// A circle of modules that use each other, if there is one (depth-first search with the path
/// kept, so the circle is given whole).
fn find_cycle(edges: &BTreeMap<(String, String), String>) -> Option<Vec<String>> {
    let mut graph: BTreeMap<&str, BTreeSet<&str>> = BTreeMap::new();
    for (from, to) in edges.keys() {
        graph.entry(from).or_default().insert(to);
    }
    fn visit<'a>(
        node: &'a str,
        graph: &BTreeMap<&'a str, BTreeSet<&'a str>>,
        stack: &mut Vec<&'a str>,
        done: &mut BTreeSet<&'a str>,
    ) -> Option<Vec<String>> {
        if let Some(k) = stack.iter().position(|n| *n == node) {
            let mut cycle: Vec<String> = stack[k..].iter().map(|s| s.to_string()).collect();
            cycle.push(node.to_string());
            return Some(cycle);
        }
        if !done.insert(node) {
            return None;
        }
        stack.push(node);
        for next in graph.get(node).into_iter().flatten() {
            if let Some(c) = visit(next, graph, stack, done) {
                return Some(c);
            }
        }
        stack.pop();
        None
    }
    let mut done = BTreeSet::new();
    graph
        .keys()
        .find_map(|node| visit(node, &graph, &mut Vec::new(), &mut done))
}

#[test]
fn every_module_uses_only_the_layers_below_it() {
    let wrong = layer_violations(&edges());
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

#[test]
fn there_is_no_cycle_among_the_top_level_modules() {
    if let Some(cycle) = find_cycle(&edges()) {
        panic!(
            "the modules use each other in a circle: {}",
            cycle.join(" → ")
        );
    }
}

#[test]
fn the_reader_sees_paths_in_code_only() {
    let code = code_only(
        "use crate::a::X; // crate::b\n/* crate::c */ let s = \"crate::d\"; let c = '\"';\n\
         use crate::{e::Y, f}; fn g<'a>(x: &'a str) { crate::h::i(x) } let r = r#\"crate::j\"#;",
    );
    let names: Vec<String> = crate_uses(&code).into_iter().map(|(n, _)| n).collect();
    assert_eq!(names, ["a", "e", "f", "h"]);
}

#[test]
fn the_checks_find_an_upward_use_and_a_cycle() {
    let edge = |from: &str, to: &str| ((from.to_string(), to.to_string()), "here".to_string());
    let downward: BTreeMap<_, _> = [edge("plan", "report"), edge("report", "tool")].into();
    assert!(layer_violations(&downward).is_empty());
    assert_eq!(find_cycle(&downward), None);
    let circle: BTreeMap<_, _> = [edge("plan", "report"), edge("report", "plan")].into();
    assert_eq!(layer_violations(&circle).len(), 1);
    assert_eq!(
        find_cycle(&circle),
        Some(vec!["plan".into(), "report".into(), "plan".into()])
    );
    let unknown: BTreeMap<_, _> = [edge("plan", "nowhere")].into();
    assert_eq!(layer_violations(&unknown).len(), 1);
}
