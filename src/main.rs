//! The `raylab` command: the previewer window, and headless rendering, scene listing, the
//! Fresnel table and the engine benchmark.

use anyhow::{Context, Result, bail};
use clap::{Parser, Subcommand};
use indicatif::{ProgressBar, ProgressStyle};
use raylab::render::{Film, PassObserver, Sidecar, render_pass, sidecar_path};
use raylab::scene::{BUILTIN_SCENES, Scene};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

/// Writes a line to stdout. When the reader has gone (`raylab params | head`), the program
/// ends quietly instead of panicking on the closed pipe.
macro_rules! say {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        if writeln!(std::io::stdout(), $($arg)*).is_err() {
            std::process::exit(0);
        }
    }};
}

/// Like `say!`, without the newline.
macro_rules! say_raw {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        if write!(std::io::stdout(), $($arg)*).is_err() {
            std::process::exit(0);
        }
    }};
}

mod cli;

use cli::bench::{BenchArgs, bench_command};
use cli::output::check_output;

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
    version,
    about = "An interactive lab for dielectrics and distribution ray tracing",
    after_help = "Without a subcommand, opens the previewer window on SCENE (or the last scene).\n\
                  Scenes are TOML files (see scenes/README.md), OBJ files or built-in names; `raylab scenes` lists them.\n\
                  RAYLAB_CLOSE_AFTER=SECONDS closes the window after that long (for scripted runs).",
    args_conflicts_with_subcommands = true
)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    /// The scene to open in the window: a scene file, an OBJ file or a built-in name.
    scene: Option<String>,
    /// Worker threads for the window [default: all cores but one].
    #[arg(long, value_name = "T", value_parser = clap::value_parser!(u32).range(1..=1024))]
    threads: Option<u32>,
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
        /// As a Markdown table (README's).
        #[arg(long)]
        markdown: bool,
    },
    /// Print the Fresnel reflectance against the angle of incidence as CSV: exact (F_s,
    /// F_p, R) and Schlick's approximations. theta_t is empty under total internal
    /// reflection.
    Fresnel(FresnelArgs),
    /// Render a contact sheet: one labelled image per value of a parameter, side by side.
    Sweep(SweepArgs),
    /// Measure the progressive engine: latency from a parameter change to the first frame
    /// of the new generation, the time of a full-resolution 1-spp pass, and rays per second.
    Bench(BenchArgs),
    /// List the lecture's slides: number, title, scene, and the two sides of those that
    /// compare (render one with `raylab render --slide N`).
    Lecture,
}

#[derive(clap::Args)]
struct SweepArgs {
    /// A scene file or built-in name.
    scene: String,
    /// The parameter and its values, e.g. spp=1,4,16 or fresnel=schlick,exact.
    #[arg(long, value_name = "NAME=V1,V2,...")]
    param: String,
    /// The sheet to write (.png).
    #[arg(short, long, value_name = "SHEET.png")]
    output: PathBuf,
    /// Size of each image [default: the scene's, halved].
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    size: Option<(u32, u32)>,
    /// Set other parameters for every image (repeatable).
    #[arg(long = "set", value_name = "NAME=VALUE")]
    set: Vec<String>,
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

fn parse_ior(s: &str) -> Result<f32, String> {
    match s.trim().parse::<f32>() {
        Ok(n) if n.is_finite() && (1.0..=3.0).contains(&n) => Ok(n),
        Ok(n) => Err(format!(
            "{n} is out of range (an index of refraction from 1 to 3)"
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

#[derive(clap::Args)]
struct RenderArgs {
    /// A scene file, or the name of a built-in scene [default: the default scene, or the
    /// scene of --params].
    scene: Option<String>,
    /// The image to write: .png (8-bit sRGB) or .exr (linear radiance).
    #[arg(short, long, value_name = "OUT.png|OUT.exr")]
    output: PathBuf,
    /// Samples per pixel (same as --set spp=N).
    #[arg(long, value_name = "N")]
    spp: Option<u32>,
    /// Image size in pixels.
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    size: Option<(u32, u32)>,
    /// Random seed (same as --set seed=S).
    #[arg(long, value_name = "S")]
    seed: Option<u64>,
    /// Worker threads [default: all cores].
    #[arg(long, value_name = "T", value_parser = clap::value_parser!(u32).range(1..=1024))]
    threads: Option<u32>,
    /// Set any parameter by name, e.g. --set max_depth=3 --set min_weight=0.01 (repeatable).
    #[arg(long = "set", value_name = "NAME=VALUE")]
    set: Vec<String>,
    /// Start from a snapshot's sidecar JSON: its scene, size and every parameter, to
    /// reproduce its image bit for bit. Other options override it.
    #[arg(long, value_name = "SIDECAR.json")]
    params: Option<PathBuf>,
    /// Render slide N of the lecture (`raylab lecture` lists them) as the window shows it:
    /// its scene and parameters; a slide that compares two things as its split image, side
    /// A left and B right (no sidecar: no one set of parameters makes it).
    #[arg(long, value_name = "N", conflicts_with_all = ["scene", "params"])]
    slide: Option<usize>,
    /// With --slide: the slide's caption under the image, in a strip of its own (PNG only).
    #[arg(long, requires = "slide")]
    caption: bool,
    /// No progress bar and no summary line.
    #[arg(short, long)]
    quiet: bool,
}

fn window(scene: Option<String>, threads: Option<u32>) -> Result<()> {
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
        ..Default::default()
    };
    raylab::app::run(options).map_err(|e| runtime(anyhow::anyhow!("cannot open the window: {e}")))
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

fn main() -> ExitCode {
    let cli = Cli::parse();
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
        Some(Command::Fresnel(args)) => fresnel_command(&args),
        Some(Command::Bench(args)) => bench_command(&args),
        Some(Command::Sweep(args)) => sweep_command(&args),
        Some(Command::Lecture) => {
            for (i, (title, scene, sides)) in raylab::app::lecture_slides().enumerate() {
                match sides {
                    Some((a, b)) => say!("{:2}. {title} (scene {scene}; {a} | {b})", i + 1),
                    None => say!("{:2}. {title} (scene {scene})", i + 1),
                }
            }
            Ok(())
        }
        None => window(cli.scene, cli.threads),
    }
}

fn exit_code(result: Result<()>) -> ExitCode {
    match result {
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
            eprintln!("error: {e:#}");
            ExitCode::from(if e.downcast_ref::<Runtime>().is_some() {
                1
            } else {
                2
            })
        }
    }
}

/// Counts finished rows on a progress bar.
struct Progress(ProgressBar);

impl PassObserver for Progress {
    fn band_done(&self, rows: u32) {
        self.0.inc(rows as u64);
    }
}

fn render_command(args: RenderArgs) -> Result<()> {
    let sidecar = args.params.as_deref().map(Sidecar::read).transpose()?;
    let (scene, mut params, side_b, caption) = match args.slide.map(raylab::app::slide_setup) {
        Some(slide) => {
            let s = slide?;
            (s.scene, s.params, s.side_b, Some(s.caption))
        }
        None => {
            let scene_ref = match (&args.scene, &sidecar) {
                (Some(s), _) => s.clone(),
                (None, Some(sc)) => sc.scene.clone(),
                (None, None) => BUILTIN_SCENES[0].name.to_string(),
            };
            let scene = Scene::load(&scene_ref)?;
            let params = match &sidecar {
                Some(sc) => sc.params.clone(),
                None => scene.params.clone(),
            };
            (scene, params, None, None)
        }
    };
    let (mut width, mut height) = match &sidecar {
        Some(sc) => (sc.width, sc.height),
        None => (scene.width, scene.height),
    };
    if let Some((w, h)) = args.size {
        (width, height) = (w, h);
    }
    // A snapshot from the window may have moved the camera.
    let camera = sidecar
        .as_ref()
        .and_then(|sc| sc.camera.clone())
        .unwrap_or_else(|| scene.camera.clone());
    // A snapshot of a render still refining holds fewer samples than its target.
    let mut samples = sidecar.as_ref().and_then(|sc| sc.samples);
    if let Some(spp) = args.spp {
        params.set("spp", &spp.to_string()).context("--spp")?;
        samples = None;
    }
    if let Some(seed) = args.seed {
        params.seed = seed;
    }
    params.set_all(&args.set).context("--set")?;
    let params_b = side_b.map(|b| b(&params));
    check_output(&args.output, args.caption)?;
    let json = sidecar_path(&args.output);
    if params_b.is_none() {
        Sidecar::check_target(&json, args.params.as_deref())?;
    }

    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.threads.unwrap_or(0) as usize)
        .build()
        .context("cannot start the worker threads")
        .map_err(runtime)?;
    let show_progress = !args.quiet && std::io::stderr().is_terminal();
    let bar = if show_progress {
        ProgressBar::new(height as u64 * (1 + params_b.is_some() as u64))
    } else {
        ProgressBar::hidden()
    };
    bar.set_style(
        ProgressStyle::with_template(
            "{spinner} rendering [{bar:40}] {percent}% rows, {elapsed} elapsed, ~{eta} left",
        )
        .unwrap_or_else(|_| ProgressStyle::default_bar())
        .progress_chars("=> "),
    );
    let start = Instant::now();
    let (film, stats) = pool
        .install(|| {
            let mut film = Film::new(width, height);
            let n = samples.unwrap_or(params.spp);
            let observer = Progress(bar.clone());
            let mut stats = render_pass(&scene, &camera, &params, &mut film, n, &observer)?;
            if let Some(b) = &params_b {
                // The A/B view's split, at the window's starting divider: the middle.
                let mut right = Film::new(width, height);
                stats += render_pass(&scene, &camera, b, &mut right, b.spp, &observer)?;
                film.split_with(&right, width / 2);
            }
            Ok::<_, raylab::render::Cancelled>((film, stats))
        })
        .map_err(runtime)?;
    let seconds = start.elapsed().as_secs_f64();
    bar.finish_and_clear();

    // Replacing the file named by -o is what was asked; the summary still says so.
    let replaced = if args.output.exists() {
        " (replacing the file there)"
    } else {
        ""
    };
    match caption.filter(|_| args.caption) {
        // The caption as it reads for the parameters rendered (after any --set).
        Some(caption) => {
            let image =
                raylab::render::with_caption(&film.to_srgb8(params.exposure), &caption(&params));
            raylab::render::output::save_image(&image, &args.output, image::ImageFormat::Png)
                .with_context(|| format!("cannot write {}", args.output.display()))
                .map_err(runtime)?;
        }
        None => film.save(&args.output, params.exposure).map_err(runtime)?,
    }
    if params_b.is_some() {
        if !args.quiet {
            eprintln!(
                "slide {}: A/B split written to {}{replaced} (no sidecar: no one set of parameters makes it)",
                args.slide.unwrap_or(0),
                args.output.display()
            );
        }
        return Ok(());
    }
    Sidecar {
        raylab_version: raylab::VERSION.to_string(),
        scene: Sidecar::scene_reference(&scene.source, &json),
        width,
        height,
        params: params.clone(),
        samples,
        camera: (camera != scene.camera).then(|| camera.clone()),
        image: args
            .output
            .file_name()
            .map(|n| n.to_string_lossy().into_owned()),
        seconds: Some(seconds),
        stats: Some(stats),
    }
    .write(&json)
    .map_err(runtime)?;

    if !args.quiet {
        let pixels = (width as u64 * height as u64) as f64;
        // The status bar's estimate, so a render's noise can be judged without a window.
        let noise = film
            .noise(params.exposure)
            .map_or(String::new(), |n| format!(" noise {:.2}%;", n * 100.0));
        let rays = stats.total_rays();
        eprintln!(
            "{} {}x{} at {} spp: {:.2} s, {:.2} M samples, {:.2} M rays ({:.2} M rays/s, {:.1} rays/pixel); {} total internal reflections; pruned {} by depth, {} by weight, {} by the ray budget; {} non-finite samples dropped;{noise} wrote {}{replaced} and {}",
            scene.name,
            width,
            height,
            samples.unwrap_or(params.spp),
            seconds,
            stats.samples as f64 / 1e6,
            rays as f64 / 1e6,
            rays as f64 / seconds.max(1e-9) / 1e6,
            rays as f64 / pixels,
            stats.tir_events,
            stats.pruned_by_depth,
            stats.pruned_by_weight,
            stats.pruned_by_budget,
            stats.non_finite,
            args.output.display(),
            json.display()
        );
    }
    Ok(())
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

fn sweep_command(args: &SweepArgs) -> Result<()> {
    let (name, values) = raylab::render::parse_sweep(&args.param).context("--param")?;
    let scene = Scene::load(&args.scene)?;
    let mut params = scene.params.clone();
    params.set_all(&args.set).context("--set")?;
    let ext = args
        .output
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    if ext.as_deref() != Some("png") {
        bail!("{}: a contact sheet is a .png", args.output.display());
    }
    let (w, h) = args
        .size
        .unwrap_or(((scene.width / 2).max(1), (scene.height / 2).max(1)));
    let start = Instant::now();
    let sheet =
        raylab::render::contact_sheet(&scene, &scene.camera, &params, w, h, &name, &values, &())?;
    raylab::render::output::save_image(&sheet, &args.output, image::ImageFormat::Png)
        .with_context(|| format!("{}: cannot write the sheet", args.output.display()))
        .map_err(runtime)?;
    eprintln!(
        "{}: {} images of {w}x{h} across {name} in {:.2} s; wrote {}",
        scene.name,
        values.len(),
        start.elapsed().as_secs_f64(),
        args.output.display()
    );
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
