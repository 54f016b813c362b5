//! `raylab inspect`: one sample's ray tree, as the window's inspector shows it, printed
//! (like pbrt's `--pixel`), as text or JSON.

use crate::parse_size;
use anyhow::{Context, Result, bail};
use raylab::scene::Scene;
use raylab::tracer::{RayTree, Tracer};

/// Which sample of a pixel, in what image, with what parameters: what `inspect` traces and
/// `section` draws.
#[derive(clap::Args)]
pub struct SampleArgs {
    /// Which of the pixel's samples (0 is the first, the one the window inspects).
    #[arg(long, value_name = "N", default_value_t = 0)]
    pub sample: u32,
    /// Image size in pixels [default: the scene's].
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    pub size: Option<(u32, u32)>,
    /// Set any parameter by name (repeatable), as for `render`.
    #[arg(long = "set", value_name = "NAME=VALUE")]
    pub set: Vec<String>,
}

#[derive(clap::Args)]
pub struct InspectArgs {
    /// A scene file (.toml), a model (.obj, .gltf, .glb) or a built-in name.
    #[arg(default_value = "default")]
    scene: std::ffi::OsString,
    /// The pixel: X,Y from the top left of the image.
    #[arg(long, value_name = "X,Y", value_parser = parse_pixel)]
    pixel: (u32, u32),
    #[command(flatten)]
    sample: SampleArgs,
    /// Print the tree as JSON: every ray with its parent, kind, ray, hit and the lecture's
    /// quantities there, end, weights and radiance.
    #[arg(long)]
    json: bool,
}

pub fn parse_pixel(s: &str) -> Result<(u32, u32), String> {
    let (x, y) = s
        .split_once(',')
        .ok_or_else(|| format!("`{s}` is not of the form X,Y, e.g. 480,270"))?;
    let coordinate = |v: &str| {
        v.trim()
            .parse::<u32>()
            .map_err(|_| format!("`{v}` is not a whole number of pixels"))
    };
    Ok((coordinate(x)?, coordinate(y)?))
}

/// One sample's ray tree, traced as the inspector traces it.
pub struct Traced {
    /// The scene it was traced in.
    pub scene: Scene,
    /// The image size.
    pub size: (u32, u32),
    /// The tree.
    pub tree: RayTree,
    /// The radiance the sample returned.
    pub radiance: raylab::math::Color,
    /// The camera frame its camera ray came through.
    pub frame: raylab::camera::CameraFrame,
    /// Its image position (0 to 1 across and down) and point on the lens (unit square).
    pub camera_point: (glam::Vec2, glam::Vec2),
}

/// Traces the sample `args` names of `pixel` in `scene` (a file or built-in name): the
/// tree `inspect` prints and `section` draws.
pub fn trace_pixel(
    scene: &std::ffi::OsStr,
    args: &SampleArgs,
    (x, y): (u32, u32),
) -> Result<Traced> {
    let SampleArgs { sample, size, set } = args;
    let sample = *sample;
    let scene = Scene::load(scene)?;
    crate::cli::streams::warn(&scene);
    let mut params = scene.params.clone();
    params.set_all(set).context("--set")?;
    let (width, height) = size.unwrap_or((scene.width, scene.height));
    if x >= width || y >= height {
        bail!("--pixel {x},{y} is outside the {width}x{height} image");
    }
    let mut tracer = Tracer::new(&scene, &params, width, height);
    // The sample as its pass traces it (with its photons, where there are some).
    tracer.prepare_photons(sample);
    let (tree, radiance) = tracer.inspect(x, y, sample);
    let frame = tracer.frame().clone();
    let camera_point = tracer.camera_point(x, y, sample);
    drop(tracer);
    Ok(Traced {
        scene,
        size: (width, height),
        tree,
        radiance,
        frame,
        camera_point,
    })
}

pub fn inspect_command(args: &InspectArgs) -> Result<()> {
    let Traced {
        scene,
        size: (width, height),
        tree,
        radiance,
        frame,
        ..
    } = trace_pixel(&args.scene, &args.sample, args.pixel)?;
    let (x, y) = args.pixel;
    if args.json {
        let report = serde_json::json!({
            "scene": scene.name,
            "width": width,
            "height": height,
            "pixel": [x, y],
            "sample": args.sample.sample,
            "radiance": [radiance.x, radiance.y, radiance.z],
            "rays": tree.nodes,
        });
        say!("{}", serde_json::to_string_pretty(&report)?);
        return Ok(());
    }
    say!(
        "{} {width}x{height}, pixel ({x}, {y}), sample {}: radiance ({:.3}, {:.3}, {:.3}), {} rays",
        scene.name,
        args.sample.sample,
        radiance.x,
        radiance.y,
        radiance.z,
        tree.nodes.len()
    );
    for root in tree.roots() {
        print_node(&tree, root, 0, &scene);
    }
    if tree.nodes.is_empty() && frame.real_lens().is_some() {
        say!("The lens blocks this sample's ray: it brings back black.");
    }
    Ok(())
}

/// Ray `id` and its subtree, indented two spaces a level: its title, then its rows.
fn print_node(tree: &RayTree, id: usize, indent: usize, scene: &Scene) {
    let n = &tree.nodes[id];
    let pad = "  ".repeat(indent);
    say!(
        "{pad}{}",
        n.title(&scene.object_names, &scene.material_names)
    );
    let rows: Vec<String> = n
        .rows()
        .into_iter()
        .map(|(label, value)| format!("{label} {value}"))
        .collect();
    say!("{pad}  {}", rows.join("; "));
    for (child, _) in tree.children(id) {
        print_node(tree, child, indent + 1, scene);
    }
}
