//! The progress bar of the commands that render: on a terminal only, and not with `-q`.

use indicatif::{ProgressBar, ProgressStyle};
use raylab::render::PassObserver;
use std::io::IsTerminal;

/// A bar counting `rows` image rows for `what` ("rendering"), shown on standard error
/// when it is a terminal and `quiet` is off; hidden otherwise.
pub fn progress_bar(quiet: bool, rows: u64, what: &str) -> ProgressBar {
    if quiet || !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::new(rows);
    bar.set_style(
        ProgressStyle::with_template(&format!(
            // The bar takes what the terminal's width leaves, so the line never wraps.
            "{{spinner}} {what} [{{wide_bar}}] {{percent}}%, {{elapsed}}, ~{{eta}} left"
        ))
        .unwrap_or_else(|_| ProgressStyle::default_bar())
        .progress_chars("=> "),
    );
    bar
}

/// Counts finished rows on a progress bar.
pub struct Progress(pub ProgressBar);

impl PassObserver for Progress {
    fn band_done(&self, rows: u32) {
        self.0.inc(rows as u64);
    }
}
