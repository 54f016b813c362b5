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
