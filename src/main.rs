//! The `raylab` command: the previewer window, and headless rendering, scene listing, the
//! Fresnel table and the engine benchmark.

use anyhow::Result;
use clap::{CommandFactory, Parser, Subcommand};
use raylab::scene::BUILTIN_SCENES;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Writes a line to stdout. When the reader has gone (`raylab params | head`), the program
/// ends quietly; when the write fails otherwise (a full disk), with status 1 and a message.
macro_rules! say {
    ($($arg:tt)*) => {
        $crate::cli::streams::out(format_args!("{}\n", format_args!($($arg)*)))
    };
}

/// Like `say!`, without the newline.
macro_rules! say_raw {
    ($($arg:tt)*) => {
        $crate::cli::streams::out(format_args!($($arg)*))
    };
}

/// One line to stderr (a message, a warning, a summary), never panicking.
macro_rules! tell {
    ($($arg:tt)*) => {
        $crate::cli::streams::tell(format_args!($($arg)*))
    };
}

mod cli;

use cli::bench::{BenchArgs, bench_command};
use cli::inspect::{InspectArgs, inspect_command};
use cli::render::{RenderArgs, render_command};
use cli::section::{SectionArgs, section_command};
use cli::sweep::{SweepArgs, sweep_command};

/// A failure while working (a file that cannot be written, threads that cannot start), as
/// against bad input: the program exits with status 1, not 2.
#[derive(Debug)]
struct Runtime(anyhow::Error);

impl std::fmt::Display for Runtime {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{:#}", self.0)
    }
}

impl std::error::Error for Runtime {}

/// Marks an error as a runtime failure (exit status 1).
fn runtime(e: impl Into<anyhow::Error>) -> anyhow::Error {
    anyhow::Error::new(Runtime(e.into()))
}

#[derive(Parser)]
#[command(
    name = "raylab",
    version = raylab::VERSION_LINE,
    about = "An interactive lab for dielectrics and distribution ray tracing",
    after_help = "Without a subcommand, opens the previewer window on SCENE (or the last scene).\n\
                  Scenes are TOML files (see docs/scenes.md), models (OBJ, glTF 2.0) or built-in names; `raylab scenes` lists them.\n\
                  RAYLAB_CLOSE_AFTER=SECONDS closes the window after that long (for scripted runs).\n\
                  RAYLAB_FILE_DIALOG=raylab makes Open and Save as use raylab's own file dialog, not the system's.\n\
                  RUST_LOG=info (or debug, trace, raylab=debug, ...) logs what raylab does to stderr.",
    args_conflicts_with_subcommands = true
)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    /// The scene to open in the window: a scene file (.toml), a model (.obj, .gltf, .glb) or a built-in name.
    scene: Option<std::ffi::OsString>,
    /// Worker threads for the window, below its own priority [default: every core].
    #[arg(long, value_name = "T", value_parser = clap::value_parser!(u32).range(1..=1024))]
    threads: Option<u32>,
    /// Stream the window's image into a running tev from the start (127.0.0.1:14158, or
    /// --tev=HOST:PORT; View > Stream to tev turns it on and off).
    #[arg(long, value_name = "HOST:PORT", num_args = 0..=1, require_equals = true,
          default_missing_value = raylab::render::tev::TEV_ADDRESS)]
    tev: Option<String>,
}

#[derive(Subcommand)]
enum Command {
    /// Render a scene to a PNG or EXR without a window, with a JSON sidecar beside it.
    Render(RenderArgs),
    /// List the built-in scenes and the scene files in ./scenes.
    Scenes,
    /// Print the parameter table: every name `--set` takes, its default, its valid values
    /// and what it does.
    Params {
        /// As a Markdown table (docs/parameters.md's).
        #[arg(long)]
        markdown: bool,
    },
    /// Print the Fresnel reflectance against the angle of incidence as CSV: exact (F_s,
    /// F_p, R) and Schlick's approximations. theta_t is empty under total internal
    /// reflection.
    Fresnel(FresnelArgs),
    /// Render one labelled image per value of a parameter: a contact sheet side by side
    /// (.png), or an animation for a slide deck (.gif).
    Sweep(SweepArgs),
    /// Measure the progressive engine: latency from a parameter change to the first frame
    /// of the new generation, the time of a full-resolution 1-spp pass, and rays per second.
    Bench(BenchArgs),
    /// List the lecture's slides: number, title, scene, and the two sides of those that
    /// compare (render one with `raylab render --slide N`).
    Lecture {
        /// Slide by slide in Markdown, with each caption (docs/lecture.md's).
        #[arg(long)]
        markdown: bool,
    },
    /// Print the ray tree of one sample of one pixel, as the window's inspector shows it:
    /// every reflected, refracted and shadow ray with the lecture's quantities where it
    /// meets a surface.
    Inspect(InspectArgs),
    /// Compare an image with a reference of the same size: MSE and relative MSE over
    /// linear RGB, the RMS error of the brightness as shown, and (with -o) where they
    /// differ in false colour.
    Compare(cli::compare::CompareArgs),
    /// Draw the lecture's 2D diagram of one pixel's ray tree (the scene cut by the plane of
    /// its camera ray and first normal, the angles and indices at each interface), or the
    /// interface workbench at one angle (--angle), as an SVG or a PNG.
    Section(SectionArgs),
    /// Print a lens prescription's paraxial description (from its ray-transfer matrices):
    /// effective, back and front focal lengths, entrance pupil, f-number and field of
    /// view on 35 mm film. Built-in designs by name, or prescription files.
    Lens(cli::lens::LensArgs),
    /// Print the completion script for a shell (bash, zsh, fish, powershell, elvish), e.g.
    /// `raylab completions bash > ~/.local/share/bash-completion/completions/raylab`.
    Completions {
        /// The shell.
        shell: clap_complete::Shell,
    },
    /// Print the manual page (roff): `raylab man > raylab.1`, then `man ./raylab.1`.
    Man,
}

#[derive(clap::Args)]
struct FresnelArgs {
    /// Index of refraction on the side the light comes from.
    #[arg(long, default_value_t = 1.0, value_parser = parse_ior)]
    n1: f32,
    /// Index of refraction on the other side.
    #[arg(long, default_value_t = 1.5, value_parser = parse_ior)]
    n2: f32,
    /// Angle step in degrees; rows run from 0 to 90 inclusive.
    #[arg(long, default_value_t = 1.0, value_parser = parse_step)]
    step: f64,
    /// A conductor instead of a dielectric: the real part η of its complex index per
    /// channel, R,G,B (with --k). Prints R, R_s and R_p per channel.
    #[arg(long, value_name = "R,G,B", value_parser = parse_rgb, requires = "k", conflicts_with = "n2")]
    eta: Option<[f32; 3]>,
    /// The conductor's extinction coefficient κ per channel, R,G,B (with --eta).
    #[arg(long, value_name = "R,G,B", value_parser = parse_rgb, requires = "eta")]
    k: Option<[f32; 3]>,
    /// A measured metal instead of --eta and --k: gold, silver, copper, aluminium,
    /// chromium, nickel or tungsten.
    #[arg(long, value_name = "NAME", value_parser = raylab::material::find_metal, conflicts_with_all = ["n2", "eta", "k"])]
    metal: Option<&'static raylab::material::Metal>,
}

/// Three comma-separated numbers from 0 to 100: a conductor's η or κ per channel.
fn parse_rgb(s: &str) -> Result<[f32; 3], String> {
    let values: Vec<f32> = s
        .split(',')
        .map(|v| {
            v.trim()
                .parse::<f32>()
                .map_err(|_| format!("`{v}` is not a number"))
        })
        .collect::<Result<_, _>>()?;
    match values[..] {
        [r, g, b] if values.iter().all(|v| (0.0..=100.0).contains(v)) => Ok([r, g, b]),
        [_, _, _] => Err(format!("`{s}`: each value must be between 0 and 100")),
        _ => Err(format!("`{s}` is not three numbers R,G,B")),
    }
}

/// An index of refraction, in the range scene files and `--set ior` take.
fn parse_ior(s: &str) -> Result<f32, String> {
    let (lo, hi) = raylab::params::IOR_RANGE;
    match s.trim().parse::<f32>() {
        Ok(n) if n.is_finite() && (lo..=hi).contains(&n) => Ok(n),
        Ok(n) => Err(format!(
            "{n} is out of range (an index of refraction from {lo} to {hi})"
        )),
        Err(_) => Err(format!("`{s}` is not a number")),
    }
}

fn parse_step(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(d) if (0.01..=90.0).contains(&d) => Ok(d),
        Ok(d) => Err(format!("{d} is out of range (0.01 to 90 degrees)")),
        Err(_) => Err(format!("`{s}` is not a number")),
    }
}

#[cfg(feature = "gui")]
fn window(cli: Cli) -> Result<()> {
    let Cli {
        scene,
        threads,
        tev,
        ..
    } = cli;
    use anyhow::Context;
    let close_after = match std::env::var("RAYLAB_CLOSE_AFTER") {
        Ok(v) => Some(
            v.trim()
                .parse::<f64>()
                .ok()
                .filter(|s| s.is_finite() && *s >= 0.0)
                .map(std::time::Duration::from_secs_f64)
                .with_context(|| format!("RAYLAB_CLOSE_AFTER={v}: not a number of seconds"))?,
        ),
        Err(_) => None,
    };
    // A scene that does not load still opens the window, which shows the error.
    let options = raylab::app::AppOptions {
        scene,
        threads: threads.map(|t| t as usize),
        close_after,
        tev,
        system_dialogs: true,
        ..Default::default()
    };
    raylab::app::run(options).map_err(|e| {
        let why = raylab::app::open_failure::explain(&e);
        runtime(anyhow::anyhow!("cannot open the window: {why}"))
    })
}

/// Built without the `gui` feature: there is no window to open.
#[cfg(not(feature = "gui"))]
fn window(_cli: Cli) -> Result<()> {
    Err(runtime(anyhow::anyhow!(
        "this raylab was built without its window (cargo's `gui` feature): \
         `raylab render` and the other commands work; `raylab --help` lists them"
    )))
}

fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("`{s}` is not of the form WxH, e.g. 960x540"))?;
    let side = |v: &str| -> Result<u32, String> {
        v.trim()
            .parse()
            .map_err(|_| format!("`{v}` is not a whole number of pixels"))
    };
    let (w, h) = (side(w)?, side(h)?);
    raylab::scene::check_size(w, h)?;
    Ok((w, h))
}

/// RUST_LOG turns on the log of what raylab does (`info`: the SIMD width, the engines and
/// the slides shown; `debug`: scenes loaded and images finished or taken from those
/// rendered ahead; `trace`: each pass rendered ahead), on stderr with the seconds since
/// start. Nothing without it, as the commands' own output is what they say.
fn start_log() {
    let start = std::time::Instant::now();
    let _ = env_logger::Builder::from_env(env_logger::Env::default().default_filter_or("off"))
        .format(move |out, record| {
            use std::io::Write;
            let t = start.elapsed().as_secs_f64();
            let (level, target) = (record.level(), record.target());
            writeln!(out, "{t:9.3} {level:5} {target}: {}", record.args())
        })
        .try_init();
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    start_log();
    // Ctrl-C (or a termination request) mid-write leaves no temporary file behind; one
    // left by a kill -9 is removed by the next write to its folder.
    let _ = ctrlc::set_handler(|| {
        raylab::render::output::remove_temporaries();
        std::process::exit(130);
    });
    // A panic (a bug) is reported once, as one line, by `caught` below; RUST_BACKTRACE
    // keeps the full report for debugging.
    if std::env::var_os("RUST_BACKTRACE").is_none() {
        std::panic::set_hook(Box::new(|_| {}));
    }
    let result = raylab::guard::caught(|| run(cli))
        .unwrap_or_else(|failure| Err(runtime(anyhow::anyhow!(failure))));
    exit_code(result)
}

/// Runs the command, or opens the window.
fn run(cli: Cli) -> Result<()> {
    match cli.command {
        Some(Command::Render(args)) => render_command(args),
        Some(Command::Scenes) => scenes_command(),
        Some(Command::Params { markdown }) => {
            say_raw!(
                "{}",
                if markdown {
                    raylab::params::markdown_table()
                } else {
                    raylab::params::text_table()
                }
            );
            Ok(())
        }
        Some(Command::Fresnel(args)) => fresnel_command(&args).map_err(|e| match e.downcast() {
            Ok(io) => cli::streams::stdout_failed(io),
            Err(e) => e,
        }),
        Some(Command::Bench(args)) => bench_command(&args),
        Some(Command::Sweep(args)) => sweep_command(&args),
        Some(Command::Inspect(args)) => inspect_command(&args),
        Some(Command::Section(args)) => section_command(&args),
        Some(Command::Compare(args)) => cli::compare::compare_command(&args),
        Some(Command::Lens(args)) => cli::lens::lens_command(&args),
        Some(Command::Completions { shell }) => cli::shell::completions(shell, Cli::command()),
        Some(Command::Man) => cli::shell::man(Cli::command()),
        Some(Command::Lecture { markdown: true }) => {
            say_raw!("{}", raylab::lecture::markdown()?);
            Ok(())
        }
        Some(Command::Lecture { markdown: false }) => {
            for (i, s) in raylab::lecture::LECTURE.iter().enumerate() {
                let (title, scene) = (s.title, s.scene);
                match s.compare.map(|c| c.labels().join(" | ")) {
                    Some(sides) => say!("{:2}. {title} (scene {scene}; {sides})", i + 1),
                    None => say!("{:2}. {title} (scene {scene})", i + 1),
                }
            }
            Ok(())
        }
        None => window(cli),
    }
}

fn exit_code(result: Result<()>) -> ExitCode {
    match result {
        // The work is done, but what it had to say was lost.
        Ok(()) if cli::streams::stderr_lost() => ExitCode::FAILURE,
        Ok(()) => ExitCode::SUCCESS,
        // The reader of our output has gone (`raylab fresnel | head`): nothing went wrong.
        Err(e)
            if e.downcast_ref::<std::io::Error>()
                .is_some_and(|e| e.kind() == std::io::ErrorKind::BrokenPipe) =>
        {
            ExitCode::SUCCESS
        }
        // Bad input exits 2 (as clap does for bad options); a failure while working, 1.
        Err(e) => {
            tell!("error: {e:#}");
            ExitCode::from(if e.downcast_ref::<Runtime>().is_some() {
                1
            } else {
                2
            })
        }
    }
}

fn fresnel_command(args: &FresnelArgs) -> Result<()> {
    use std::io::Write;
    let mut out = std::io::BufWriter::new(std::io::stdout().lock());
    let conductor = match (args.metal, args.eta, args.k) {
        (Some(m), _, _) => Some((m.eta, m.k)),
        (None, Some(eta), Some(k)) => Some((eta, k)),
        _ => None,
    };
    if let Some((eta, k)) = conductor {
        writeln!(
            out,
            "theta_i_deg,r_exact_r,r_exact_g,r_exact_b,r_s_r,r_s_g,r_s_b,r_p_r,r_p_g,r_p_b"
        )?;
        for row in raylab::optics::conductor_table(args.n1, eta, k, args.step) {
            let cells: Vec<String> = [row.r, row.r_s, row.r_p]
                .iter()
                .flatten()
                .map(|v| format!("{v:.6}"))
                .collect();
            writeln!(out, "{},{}", row.theta_i, cells.join(","))?;
        }
        out.flush()?;
        return Ok(());
    }
    writeln!(
        out,
        "theta_i_deg,theta_t_deg,f_s,f_p,r_exact,r_schlick,r_schlick_naive"
    )?;
    for row in raylab::optics::fresnel_table(args.n1, args.n2, args.step) {
        let theta_t = row.theta_t.map(|t| format!("{t:.4}")).unwrap_or_default();
        writeln!(
            out,
            "{},{theta_t},{:.6},{:.6},{:.6},{:.6},{:.6}",
            row.theta_i, row.f_s, row.f_p, row.r_exact, row.r_schlick, row.r_schlick_naive
        )?;
    }
    out.flush()?;
    Ok(())
}

fn scenes_command() -> Result<()> {
    for b in BUILTIN_SCENES {
        say!("{:<28} {} (built in)", b.name, b.description());
    }
    let dir = Path::new("scenes");
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Ok(());
    };
    let mut files: Vec<PathBuf> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    for f in files {
        let description = match raylab::scene::input::read_text(&f) {
            Ok(text) => raylab::scene::describe(&text).unwrap_or_else(|| "(no description)".into()),
            Err(e) => format!("(unreadable: {e})"),
        };
        say!("{:<28} {description}", f.display());
    }
    Ok(())
}
