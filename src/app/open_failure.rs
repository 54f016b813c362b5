//! Why the window could not open, in one line a user can act on: eframe's and winit's
//! messages name a source file inside the build machine's cargo registry, and not what to
//! do.

/// The line for a window that could not open with `error`.
pub fn explain(error: &eframe::Error) -> String {
    explain_message(&error.to_string())
}

/// [`explain`] of the error's message: what to do, where the cause is known, then the
/// message without source paths.
fn explain_message(message: &str) -> String {
    let message = without_source_paths(message);
    let has = |words: &[&str]| words.iter().any(|w| message.contains(w));
    let hint = if has(&["DISPLAY", "WAYLAND"]) {
        "no display to open it on: run it in an X11 or Wayland session (`raylab render` and \
         the other commands need none)"
    } else if has(&[
        "wgpu", "Wgpu", "Vulkan", "OpenGL", "opengl", "glutin", "Glutin", "adapter",
    ]) {
        "no OpenGL 3.3 or Vulkan driver found: install the GPU's driver, or Mesa (its \
         llvmpipe draws without a GPU)"
    } else {
        return message;
    };
    format!("{hint} ({message})")
}

/// `message` without the ` at PATH.rs:LINE` its sources add (a path on the machine that
/// built raylab, of no use to the one running it).
fn without_source_paths(message: &str) -> String {
    let mut out = String::new();
    let mut rest = message;
    while let Some(i) = rest.find(" at ") {
        let after = &rest[i + 4..];
        // The path runs to ".rs:" and the line number (and a column, and ": ").
        let source = after.find(".rs:").filter(|&j| !after[..j].contains(' '));
        let Some(j) = source else {
            out.push_str(&rest[..i + 4]);
            rest = after;
            continue;
        };
        out.push_str(&rest[..i]);
        let tail = after[j + 4..].trim_start_matches(|c: char| c.is_ascii_digit() || c == ':');
        rest = tail.trim_start();
        if !rest.is_empty() {
            out.push_str(": ");
        }
    }
    out.push_str(rest);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_missing_display_says_what_to_do_without_the_registry_path() {
        let winit = "winit EventLoopError: os error at /root/.cargo/registry/src/index.crates.io-1949cf8c6b5b557f/winit-0.30.13/src/platform_impl/linux/mod.rs:765: neither WAYLAND_DISPLAY nor WAYLAND_SOCKET nor DISPLAY is set.";
        let line = explain_message(winit);
        assert!(!line.contains(".cargo") && !line.contains(".rs"), "{line}");
        assert!(line.starts_with("no display to open it on"), "{line}");
        assert!(
            line.contains(
                "os error: neither WAYLAND_DISPLAY nor WAYLAND_SOCKET nor DISPLAY is set."
            ),
            "{line}"
        );
    }

    #[test]
    fn a_missing_driver_is_named_and_other_errors_pass_through() {
        let line = explain_message(
            "wgpu error: Failed to create wgpu adapter, no suitable adapter found.",
        );
        assert!(
            line.starts_with("no OpenGL 3.3 or Vulkan driver found"),
            "{line}"
        );
        assert_eq!(
            explain_message("the app was closed at start"),
            "the app was closed at start"
        );
        assert_eq!(
            without_source_paths("a at C:\\src\\x.rs:12:5"),
            "a",
            "a path at the end, with a column"
        );
    }
}
