//! `--threads`, as the commands that render take it.

use crate::runtime;
use anyhow::{Context, Result};

/// How many workers render.
#[derive(clap::Args)]
pub struct Threads {
    /// Worker threads [default: all cores].
    #[arg(long, value_name = "T", value_parser = clap::value_parser!(u32).range(1..=1024))]
    threads: Option<u32>,
}

impl Threads {
    /// A pool of that many workers (all cores where not given).
    pub fn pool(&self) -> Result<rayon::ThreadPool> {
        rayon::ThreadPoolBuilder::new()
            .num_threads(self.threads.unwrap_or(0) as usize)
            .build()
            .context("cannot start the worker threads")
            .map_err(runtime)
    }

    /// Makes that many workers the process's own (all cores where not given), for a
    /// command whose rendering calls back into code that stays on this thread (a sweep's
    /// frames go to an encoder that cannot be sent to a worker). Once per process.
    pub fn install_global(&self) -> Result<()> {
        rayon::ThreadPoolBuilder::new()
            .num_threads(self.threads.unwrap_or(0) as usize)
            .build_global()
            .context("cannot start the worker threads")
            .map_err(runtime)
    }
}
