//! `raylab inspect`: one sample's ray tree, as the window's inspector shows it, printed
//! (like pbrt's `--pixel`), as text or JSON.

use crate::parse_size;
use anyhow::{Context, Result, bail};
use raylab::scene::Scene;
use raylab::tracer::{RayTree, Tracer};

#[derive(clap::Args)]
pub struct InspectArgs {
    /// A scene file (.toml), a model (.obj, .gltf, .glb) or a built-in name.
    #[arg(default_value = "default")]
    scene: String,
    /// The pixel: X,Y from the top left of the image.
    #[arg(long, value_name = "X,Y", value_parser = parse_pixel)]
    pixel: (u32, u32),
    /// Which of the pixel's samples (0 is the first, the one the window inspects).
    #[arg(long, value_name = "N", default_value_t = 0)]
    sample: u32,
    /// Image size in pixels [default: the scene's].
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    size: Option<(u32, u32)>,
    /// Set any parameter by name (repeatable), as for `render`.
    #[arg(long = "set", value_name = "NAME=VALUE")]
    set: Vec<String>,
    /// Print the tree as JSON: every ray with its parent, kind, ray, hit and the lecture's
    /// quantities there, end, weights and radiance.
    #[arg(long)]
    json: bool,
}

fn parse_pixel(s: &str) -> Result<(u32, u32), String> {
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

pub fn inspect_command(args: &InspectArgs) -> Result<()> {
    let scene = Scene::load(&args.scene)?;
    let mut params = scene.params.clone();
    params.set_all(&args.set).context("--set")?;
    let (width, height) = args.size.unwrap_or((scene.width, scene.height));
    let (x, y) = args.pixel;
    if x >= width || y >= height {
        bail!("--pixel {x},{y} is outside the {width}x{height} image");
    }
    let mut tracer = Tracer::new(&scene, &params, width, height);
    // The sample as its pass traces it (with its photons, where there are some).
    tracer.prepare_photons(args.sample);
    let (tree, radiance) = tracer.inspect(x, y, args.sample);
    if args.json {
        let report = serde_json::json!({
            "scene": scene.name,
            "width": width,
            "height": height,
            "pixel": [x, y],
            "sample": args.sample,
            "radiance": [radiance.x, radiance.y, radiance.z],
            "rays": tree.nodes,
        });
        say!("{}", serde_json::to_string_pretty(&report)?);
        return Ok(());
    }
    say!(
        "{} {width}x{height}, pixel ({x}, {y}), sample {}: radiance ({:.3}, {:.3}, {:.3}), {} rays",
        scene.name,
        args.sample,
        radiance.x,
        radiance.y,
        radiance.z,
        tree.nodes.len()
    );
    if !tree.nodes.is_empty() {
        print_node(&tree, 0, 0, &scene);
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
