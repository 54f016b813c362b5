//! Standard output and error, written without ever panicking (`println!` and `eprintln!`
//! panic when a write fails, as on a full disk): a reader that has gone (`raylab fresnel |
//! head`) ends the program quietly; any other failure ends it with status 1, saying why on
//! stderr where it can.

use std::io::Write;
use std::sync::atomic::{AtomicBool, Ordering};

/// Set when a line for stderr could not be written: the run then ends with status 1.
static STDERR_LOST: AtomicBool = AtomicBool::new(false);

/// Writes `args` to stdout, flushed, or ends the program (see [`stdout_failed`]).
pub fn out(args: std::fmt::Arguments) {
    let mut stdout = std::io::stdout().lock();
    if let Err(e) = stdout.write_fmt(args).and_then(|()| stdout.flush()) {
        stdout_failed(e)
    }
}

/// Ends the program after stdout failed: quietly with status 0 when its reader has gone,
/// else with status 1 and one line on stderr.
pub fn stdout_failed(e: std::io::Error) -> ! {
    if e.kind() == std::io::ErrorKind::BrokenPipe {
        std::process::exit(0);
    }
    let _ = writeln!(
        std::io::stderr(),
        "error: cannot write to standard output: {e}"
    );
    std::process::exit(1)
}

/// Writes one line to stderr; a failure is remembered for the exit status.
pub fn tell(args: std::fmt::Arguments) {
    if writeln!(std::io::stderr(), "{args}").is_err() {
        STDERR_LOST.store(true, Ordering::Relaxed);
    }
}

/// Whether a line for stderr was lost.
pub fn stderr_lost() -> bool {
    STDERR_LOST.load(Ordering::Relaxed)
}

/// Says each of a scene's warnings (what was missing from its files but not fatal).
pub fn warn(scene: &raylab::scene::Scene) {
    for line in &scene.warnings {
        tell(format_args!("warning: {line}"));
    }
}
