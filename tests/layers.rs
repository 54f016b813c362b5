//! The library's layers as docs/internals.md draws them: each module of `src/` uses only
//! the modules of the layers below its own (by `crate::` paths in code, not in comments).
//! One import that goes up or sideways fails this test, which names the file and line.
#![allow(clippy::unwrap_used)]

use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// The layers from the bottom, read from the diagram in docs/internals.md: the fenced block
/// after "Each layer uses only those below it", layers separated by `<-`, modules by
/// commas (words in parentheses are notes).
fn layers() -> Vec<Vec<String>> {
    let doc = std::fs::read_to_string("docs/internals.md").unwrap();
    let after = doc
        .split("Each layer uses only those below it")
        .nth(1)
        .expect("docs/internals.md says which layer uses which");
    let block = after
        .split("```")
        .nth(1)
        .expect("the diagram's fenced block");
    let mut layers = Vec::new();
    for layer in block.split("<-") {
        let mut names = Vec::new();
        for name in layer.split(',') {
            let name = name.split('(').next().unwrap().trim();
            if !name.is_empty() {
                names.push(name.to_string());
            }
        }
        layers.push(names);
    }
    layers
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The top-level module a file of `src/` belongs to (`src/render/film.rs`: `render`).
fn module_of(path: &Path) -> String {
    let rel = path.strip_prefix("src").unwrap();
    let first = rel
        .components()
        .next()
        .unwrap()
        .as_os_str()
        .to_string_lossy();
    first.trim_end_matches(".rs").to_string()
}

/// The `crate::module` paths of a line of code (its comment cut off).
fn crate_paths(line: &str) -> Vec<&str> {
    let code = line.split("//").next().unwrap();
    code.match_indices("crate::")
        .filter(|(at, _)| {
            // `crate::` itself, not the end of a longer name.
            !code[..*at]
                .chars()
                .next_back()
                .is_some_and(|c| c.is_alphanumeric() || c == '_' || c == ':')
        })
        .map(|(at, _)| {
            let rest = &code[at + "crate::".len()..];
            let end = rest
                .find(|c: char| !(c.is_alphanumeric() || c == '_'))
                .unwrap_or(rest.len());
            &rest[..end]
        })
        .collect()
}

#[test]
fn every_import_goes_down_the_documented_layers() {
    let layers = layers();
    let rank: HashMap<&str, usize> = layers
        .iter()
        .enumerate()
        .flat_map(|(i, names)| names.iter().map(move |n| (n.as_str(), i)))
        .collect();
    let mut files = Vec::new();
    rust_files(Path::new("src"), &mut files);
    files.sort();
    let binary = ["main", "cli", "lib"];
    let mut wrong = Vec::new();
    let mut checked = 0;
    for file in &files {
        let module = module_of(file);
        if binary.contains(&module.as_str()) {
            continue;
        }
        let Some(&own) = rank.get(module.as_str()) else {
            wrong.push(format!(
                "{}: module `{module}` is in no layer of the diagram",
                file.display()
            ));
            continue;
        };
        let text = std::fs::read_to_string(file).unwrap();
        for (n, line) in text.lines().enumerate() {
            for used in crate_paths(line) {
                checked += 1;
                if used == module {
                    continue;
                }
                match rank.get(used) {
                    // Crate-root items (VERSION, COMMIT) are below everything.
                    None if used.chars().all(|c| c.is_ascii_uppercase() || c == '_') => {}
                    Some(&theirs) if theirs < own => {}
                    _ => wrong.push(format!(
                        "{}:{}: `{module}` uses `crate::{used}`, which is not below it",
                        file.display(),
                        n + 1
                    )),
                }
            }
        }
    }
    assert!(
        checked > 200,
        "only {checked} imports found: is the parser right?"
    );
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

#[test]
fn the_layer_reader_sees_imports_and_skips_comments() {
    assert_eq!(
        crate_paths("use crate::math::Color; // crate::render"),
        ["math"]
    );
    assert_eq!(
        crate_paths("    x = crate::render::text::draw(crate::math::y);"),
        ["render", "math"]
    );
    assert_eq!(
        crate_paths("/// see [`crate::tracer::Tracer`]"),
        Vec::<&str>::new()
    );
    assert_eq!(crate_paths("let a = mycrate::math::x;"), Vec::<&str>::new());
    let layers = layers();
    assert_eq!(layers.first().unwrap(), &["math", "guard"]);
    assert!(
        layers.last().unwrap().contains(&"app".to_string()),
        "{layers:?}"
    );
}

/// The module path of a file of `src/` (`src/tracer/wave/shade.rs`: tracer, wave, shade;
/// a `mod.rs` is its folder's module; `src/lib.rs` the crate's root, no names).
fn module_path(path: &Path) -> Vec<String> {
    let rel = path.strip_prefix("src").unwrap().with_extension("");
    let mut names: Vec<String> = rel
        .components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect();
    if names.last().is_some_and(|n| n == "mod" || n == "lib") {
        names.pop();
    }
    names
}

/// Every module path named in `code` (comments cut off) by `crate::` or `super::` paths,
/// as written from the file of module `own` (whose `super` is its parent, for a `mod.rs`
/// its folder's parent), grouped imports (`use super::{a::X, b::{Y, Z}}`) expanded.
fn named_paths(code: &str, own: &[String]) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    let mut at = 0;
    while at < code.len() {
        let rest = &code[at..];
        let starts_path = !code[..at]
            .chars()
            .next_back()
            .is_some_and(|c| c.is_alphanumeric() || c == '_' || c == ':');
        let (base, len) = if starts_path && rest.starts_with("crate::") {
            (Vec::new(), "crate::".len())
        } else if starts_path && rest.starts_with("super::") {
            let mut base = own.to_vec();
            let mut len = 0;
            while code[at + len..].starts_with("super::") {
                base.pop();
                len += "super::".len();
            }
            (base, len)
        } else {
            at += code[at..].chars().next().map_or(1, char::len_utf8);
            continue;
        };
        at += len;
        at = path_tree(code, at, base, &mut out);
    }
    out
}

/// Reads a path (`a::b::X` or `a::{b::X, c}`) at `at` below `base` into `out`; returns
/// where it ends.
fn path_tree(
    code: &str,
    mut at: usize,
    mut base: Vec<String>,
    out: &mut Vec<Vec<String>>,
) -> usize {
    let bytes = code.as_bytes();
    loop {
        let start = at;
        while at < bytes.len() && (bytes[at].is_ascii_alphanumeric() || bytes[at] == b'_') {
            at += 1;
        }
        if at > start {
            base.push(code[start..at].to_string());
        }
        let group = if code[at..].starts_with("::{") {
            Some(3)
        } else {
            (at == start && code[at..].starts_with('{')).then_some(1)
        };
        if let Some(skip) = group {
            at += skip;
            loop {
                while at < bytes.len() && bytes[at].is_ascii_whitespace() {
                    at += 1;
                }
                if at >= bytes.len() || bytes[at] == b'}' {
                    return at + 1;
                }
                at = path_tree(code, at, base.clone(), out);
                while at < bytes.len() && (bytes[at].is_ascii_whitespace() || bytes[at] == b',') {
                    at += 1;
                }
            }
        } else if code[at..].starts_with("::") {
            at += 2;
        } else {
            out.push(base);
            return at;
        }
    }
}

/// The files of `src/` that use each other in a circle: within a folder, a file using a
/// sibling (or a sibling's descendant) that uses it back, directly or round a longer
/// loop. A file and the folder module that holds it (its `mod.rs`) use each other by
/// nature and are not counted.
#[test]
fn no_two_files_use_each_other() {
    let mut files = Vec::new();
    rust_files(Path::new("src"), &mut files);
    files.sort();
    let modules: Vec<Vec<String>> = files.iter().map(|f| module_path(f)).collect();
    let index: HashMap<&[String], usize> = modules
        .iter()
        .enumerate()
        .map(|(i, m)| (m.as_slice(), i))
        .collect();
    // The file a path names: its longest prefix that is a file's module.
    let file_of = |path: &[String]| {
        (0..=path.len())
            .rev()
            .find_map(|k| index.get(&path[..k]).copied())
    };
    let mut uses = vec![std::collections::BTreeSet::new(); files.len()];
    let mut named = 0;
    for (i, file) in files.iter().enumerate() {
        let text = std::fs::read_to_string(file).unwrap();
        let code: String = text
            .lines()
            .map(|l| l.split("//").next().unwrap())
            .collect::<Vec<_>>()
            .join("\n");
        for path in named_paths(&code, &modules[i]) {
            named += 1;
            let Some(j) = file_of(&path) else { continue };
            let (a, b) = (&modules[i], &modules[j]);
            // A file and a module holding it use each other by nature.
            if j != i && !a.starts_with(b) && !b.starts_with(a) {
                uses[i].insert(j);
            }
        }
    }
    assert!(
        named > 500,
        "only {named} paths found: is the reader right?"
    );
    // A file is in a circle when it reaches itself.
    let mut circles = Vec::new();
    for start in 0..files.len() {
        let mut seen = vec![false; files.len()];
        let mut stack: Vec<(usize, Vec<usize>)> =
            uses[start].iter().map(|&j| (j, vec![start, j])).collect();
        while let Some((at, route)) = stack.pop() {
            if at == start {
                let names: Vec<String> = route
                    .iter()
                    .map(|&k| files[k].display().to_string())
                    .collect();
                circles.push(names.join(" -> "));
                break;
            }
            if std::mem::replace(&mut seen[at], true) {
                continue;
            }
            for &next in &uses[at] {
                let mut route = route.clone();
                route.push(next);
                stack.push((next, route));
            }
        }
    }
    assert!(
        circles.is_empty(),
        "files that use each other:\n{}",
        circles.join("\n")
    );
}

#[test]
fn the_cycle_reader_resolves_super_and_groups() {
    let own: Vec<String> = ["tracer", "wave", "shade"].map(String::from).to_vec();
    let paths = named_paths(
        "use super::types::{Child, Node};\nuse super::super::{Tracer, media::Arrival};\nuse crate::math::{lanes::Real, Color};",
        &own,
    );
    let strings: Vec<String> = paths.iter().map(|p| p.join("::")).collect();
    assert_eq!(
        strings,
        [
            "tracer::wave::types::Child",
            "tracer::wave::types::Node",
            "tracer::Tracer",
            "tracer::media::Arrival",
            "math::lanes::Real",
            "math::Color",
        ]
    );
}
