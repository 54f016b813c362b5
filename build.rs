//! Names the commit raylab is built from, so that every image and sidecar can say which
//! build made it: `RAYLAB_COMMIT` (12 hex digits, or empty where it cannot be known) and
//! `RAYLAB_VERSION_LINE` ("0.2.0 (commit 1a2b3c4d5e6f)", or the version alone).
//!
//! The commit is git's `HEAD` in a clone, else the one `cargo package` records in
//! `.cargo_vcs_info.json` (a crate downloaded from a registry), else unknown (a source
//! archive, or no git installed). Local changes not yet committed are not marked.

use std::path::Path;
use std::process::Command;

fn main() {
    let commit = from_git().or_else(from_vcs_info).unwrap_or_default();
    let version = std::env::var("CARGO_PKG_VERSION").unwrap_or_default();
    let line = if commit.is_empty() {
        version
    } else {
        format!("{version} (commit {commit})")
    };
    println!("cargo:rustc-env=RAYLAB_COMMIT={commit}");
    println!("cargo:rustc-env=RAYLAB_VERSION_LINE={line}");
    // Run again only when what it read changes (a path that does not exist would make
    // cargo run it at every build).
    println!("cargo:rerun-if-changed=build.rs");
    if Path::new(".cargo_vcs_info.json").exists() {
        println!("cargo:rerun-if-changed=.cargo_vcs_info.json");
    }
}

/// `HEAD`'s commit, where this is a git checkout and git runs; and asks cargo to build
/// again when `HEAD` or the branch it names moves.
fn from_git() -> Option<String> {
    let git = |args: &[&str]| -> Option<String> {
        let out = Command::new("git").args(args).output().ok()?;
        let text = String::from_utf8(out.stdout).ok()?;
        out.status.success().then(|| text.trim().to_string())
    };
    let commit = git(&["rev-parse", "--short=12", "HEAD"])?;
    for path in [
        git(&["rev-parse", "--git-path", "HEAD"]),
        git(&["symbolic-ref", "-q", "HEAD"]).and_then(|r| git(&["rev-parse", "--git-path", &r])),
        git(&["rev-parse", "--git-path", "packed-refs"]),
    ]
    .into_iter()
    .flatten()
    {
        // (A branch's file before its first commit, or packed-refs before the first
        // pack, does not exist.)
        if Path::new(&path).exists() {
            println!("cargo:rerun-if-changed={path}");
        }
    }
    Some(commit)
}

/// The commit `cargo package` recorded, in a crate unpacked from a registry.
fn from_vcs_info() -> Option<String> {
    let text = std::fs::read_to_string(".cargo_vcs_info.json").ok()?;
    // {"git": {"sha1": "<40 hex digits>"}, ...}: read without a JSON parser, as a build
    // script has no dependencies.
    let after = &text[text.find("\"sha1\"")? + "\"sha1\"".len()..];
    let start = after.find('"')? + 1;
    let sha: String = after[start..]
        .chars()
        .take_while(|c| c.is_ascii_hexdigit())
        .collect();
    (sha.len() >= 12).then(|| sha[..12].to_string())
}
