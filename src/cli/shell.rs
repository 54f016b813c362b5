//! `raylab completions SHELL` and `raylab man`: the shell's completion script and the
//! manual page, made from the command line's own definitions, so they cannot drift.

use anyhow::Result;

/// The completion script of `command` for `shell`, on stdout.
pub fn completions(shell: clap_complete::Shell, mut command: clap::Command) -> Result<()> {
    let mut script = Vec::new();
    clap_complete::generate(shell, &mut command, "raylab", &mut script);
    say_raw!("{}", String::from_utf8_lossy(&script));
    Ok(())
}

/// The manual page of `command` (roff, for `man`), on stdout.
pub fn man(command: clap::Command) -> Result<()> {
    let mut page = Vec::new();
    clap_mangen::Man::new(command).render(&mut page)?;
    say_raw!("{}", String::from_utf8_lossy(&page));
    Ok(())
}
