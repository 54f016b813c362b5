//! The `raylab` command's larger subcommands, one file each.

pub mod bench;
mod bench_slides;
pub mod compare;
mod crop;
pub mod inspect;
pub mod lens;
pub mod output;
pub mod progress;
mod reference;
pub mod render;
pub mod section;
pub mod shell;
pub mod streams;
pub mod sweep;
pub mod threads;
