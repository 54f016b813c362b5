//! Teaching instruments: windows that explain what the image shows.

use crate::optics::{brewster_angle, critical_angle, fresnel_table};
use egui_plot::{Legend, Line, Plot, PlotPoints, VLine};

/// The Fresnel plots for `ior`, both ways across the interface: from air into the
/// material, and from the material out into air (where total internal reflection sets in).
/// `marker` is an inspected ray's angle of incidence (degrees) and whether it was going
/// into the denser medium: it is marked on that plot.
pub fn fresnel_plot_ui(ui: &mut egui::Ui, ior: f32, marker: Option<(f32, bool)>) {
    for (title, n1, n2, into) in [
        ("Air into material", 1.0, ior, true),
        ("Material out to air", ior, 1.0, false),
    ] {
        ui.strong(title);
        let mark = marker.filter(|&(_, m)| m == into).map(|(a, _)| a);
        fresnel_curves_ui(ui, n1, n2, mark);
    }
}

/// R_s, R_p, exact R, Schlick and naive Schlick against the angle of incidence from `n1`
/// into `n2`, with Brewster's and the critical angle marked and the error of Schlick.
fn fresnel_curves_ui(ui: &mut egui::Ui, n1: f32, n2: f32, marker: Option<f32>) {
    let rows = fresnel_table(n1, n2, 0.25);
    let series = |f: &dyn Fn(&crate::optics::FresnelRow) -> f32| -> PlotPoints<'static> {
        rows.iter()
            .map(|r| [r.theta_i as f64, f(r) as f64])
            .collect::<Vec<[f64; 2]>>()
            .into()
    };
    let brewster = brewster_angle(n1, n2).to_degrees();
    let critical = critical_angle(n1, n2).map(f32::to_degrees);
    ui.label(format!(
        "n1 = {n1:.3} -> n2 = {n2:.3}. R0 = {:.4}. Brewster {brewster:.2}°{}",
        rows[0].r_exact,
        critical.map_or(String::new(), |c| format!(", critical {c:.2}°"))
    ));
    Plot::new(("fresnel-plot", n1 > n2))
        .legend(Legend::default())
        .height(230.0)
        .include_x(0.0)
        .include_x(90.0)
        .include_y(-0.1)
        .include_y(1.0)
        .x_axis_label("angle of incidence θi (degrees)")
        .y_axis_label("reflectance")
        .allow_drag(false)
        .allow_scroll(false)
        .x_grid_spacer(egui_plot::uniform_grid_spacer(|_| [5.0, 10.0, 30.0]))
        .y_grid_spacer(egui_plot::uniform_grid_spacer(|_| [0.05, 0.1, 0.5]))
        .y_axis_formatter(|mark, _| format!("{:.1}", mark.value))
        .show(ui, |p| {
            p.line(Line::new("Rs = Fs²", series(&|r| r.f_s * r.f_s)));
            p.line(Line::new("Rp = Fp²", series(&|r| r.f_p * r.f_p)));
            p.line(Line::new("R exact", series(&|r| r.r_exact)).width(2.5));
            p.line(Line::new("Schlick", series(&|r| r.r_schlick)));
            p.line(Line::new("naive Schlick", series(&|r| r.r_schlick_naive)));
            p.line(Line::new(
                "Schlick − exact",
                series(&|r| r.r_schlick - r.r_exact),
            ));
            p.vline(VLine::new(format!("Brewster {brewster:.1}°"), brewster));
            if let Some(c) = critical {
                p.vline(VLine::new(format!("critical {c:.1}°"), c));
            }
            if let Some(m) = marker {
                p.vline(VLine::new(format!("inspected ray {m:.1}°"), m).width(2.0));
            }
        });
}

/// The ray tree of one pixel, as the inspector shows it.
pub struct Inspection {
    /// The pixel.
    pub pixel: (u32, u32),
    /// The image size it belongs to.
    pub size: (u32, u32),
    /// The parameters it was traced with.
    pub params: crate::params::Params,
    /// The camera it was traced through.
    pub camera: crate::camera::Camera,
    /// Its tree for sample 0.
    pub tree: crate::tracer::RayTree,
    /// The radiance the sample returned.
    pub radiance: crate::math::Color,
}

fn kind_color(kind: crate::tracer::RayKind) -> egui::Color32 {
    use crate::tracer::RayKind::*;
    match kind {
        Camera => egui::Color32::WHITE,
        Reflect => egui::Color32::from_rgb(90, 200, 255),
        Refract => egui::Color32::from_rgb(255, 170, 60),
        Shadow => egui::Color32::from_rgb(240, 230, 90),
    }
}

fn end_text(end: crate::tracer::End) -> &'static str {
    use crate::tracer::End::*;
    match end {
        Miss => "left the scene (background)",
        LightHit => "reached a light",
        Absorbed => "diffuse surface: shaded by shadow rays, absorbed",
        Split => "split into child rays",
        DepthLimit => "pruned: depth limit",
        WeightLimit => "pruned: weight below the minimum",
        TotalInternalReflection => "no refracted ray: total internal reflection",
        Lit => "reached its light",
        Occluded => "blocked: in shadow",
    }
}

/// Draws the recorded rays over the image: each segment projected through the camera.
pub fn draw_tree_overlay(
    painter: &egui::Painter,
    image: egui::Rect,
    frame: &crate::camera::CameraFrame,
    tree: &crate::tracer::RayTree,
) {
    let to_screen = |p: crate::math::Vec3| {
        frame
            .project(p)
            .map(|f| image.min + egui::vec2(f.x * image.width(), f.y * image.height()))
    };
    for n in &tree.nodes {
        // A segment behind the camera cannot be drawn; pruned branches have no length.
        let (Some(a), Some(b)) = (to_screen(n.ray.origin), to_screen(n.end_point)) else {
            continue;
        };
        let width = if n.kind == crate::tracer::RayKind::Shadow {
            1.0
        } else {
            2.0
        };
        painter.line_segment([a, b], egui::Stroke::new(width, kind_color(n.kind)));
        if n.hit.is_some() {
            painter.circle_filled(b, 3.0, kind_color(n.kind));
        }
    }
}

/// The inspector: the tree as nested sections, each ray with the lecture's quantities.
pub fn inspector_ui(
    ui: &mut egui::Ui,
    inspection: &Inspection,
    names: &[String],
    materials: &[String],
) {
    let c = inspection.radiance;
    ui.label(format!(
        "Pixel ({}, {}), sample 0: radiance ({:.3}, {:.3}, {:.3}), {} rays",
        inspection.pixel.0,
        inspection.pixel.1,
        c.x,
        c.y,
        c.z,
        inspection.tree.nodes.len()
    ));
    ui.label("White: camera ray. Blue: reflected. Orange: refracted. Yellow: shadow rays.");
    egui::ScrollArea::vertical()
        .max_height(460.0)
        .show(ui, |ui| {
            node_ui(ui, inspection, 0, names, materials);
        });
}

fn node_ui(
    ui: &mut egui::Ui,
    inspection: &Inspection,
    id: usize,
    names: &[String],
    materials: &[String],
) {
    let tree = &inspection.tree;
    let Some(n) = tree.nodes.get(id) else { return };
    let target = n.hit.map_or("nothing".to_string(), |h| {
        format!(
            "{} ({})",
            names.get(h.object as usize).map_or("?", |s| s.as_str()),
            materials
                .get(h.material as usize)
                .map_or("?", |s| s.as_str())
        )
    });
    let title = format!(
        "{:?} ray, level {}: {} — {}",
        n.kind,
        n.depth,
        target,
        end_text(n.end)
    );
    egui::CollapsingHeader::new(egui::RichText::new(title).color(kind_color(n.kind)))
        .id_salt(("ray-node", id))
        .default_open(n.depth < 3)
        .show(ui, |ui| {
            egui::Grid::new(("ray-grid", id))
                .num_columns(2)
                .show(ui, |ui| {
                    let mut row = |k: &str, v: String| {
                        ui.label(k);
                        ui.label(v);
                        ui.end_row();
                    };
                    if let Some(h) = n.hit {
                        row("θi", format!("{:.2}°", h.theta_i));
                        if let Some((n1, n2)) = h.n1_n2 {
                            row("n1 -> n2", format!("{n1:.3} -> {n2:.3}"));
                            row(
                                "θt",
                                h.theta_t
                                    .map_or("none (total internal reflection)".into(), |t| {
                                        format!("{t:.2}°")
                                    }),
                            );
                        }
                        if let Some((f_s, f_p)) = h.f_s_f_p {
                            row("Fs, Fp", format!("{f_s:.4}, {f_p:.4}"));
                        }
                        if let Some((exact, schlick)) = h.r_exact_schlick {
                            row("R exact, Schlick", format!("{exact:.4}, {schlick:.4}"));
                        }
                        if let Some(r) = h.r {
                            row("R used", format!("{r:.4}"));
                        }
                    }
                    row("branch weight", format!("{:.4}", n.branch_weight));
                    row("path weight", format!("{:.4}", n.path_weight));
                    row(
                        "radiance",
                        format!(
                            "({:.3}, {:.3}, {:.3})",
                            n.radiance.x, n.radiance.y, n.radiance.z
                        ),
                    );
                });
            for (child, _) in tree.children(id) {
                node_ui(ui, inspection, child, names, materials);
            }
        });
}

/// Where the samples of one pixel fall, for the current pattern and count: the image
/// position inside the pixel, the point on the lens, and the time in the shutter.
pub fn sample_pattern_ui(ui: &mut egui::Ui, pattern: crate::math::Pattern, spp: u32, seed: u64) {
    use crate::math::SampleStream;
    use crate::math::sampling::concentric_disk;
    let n = spp.min(1024);
    let mut pixel = Vec::new();
    let mut lens = Vec::new();
    let mut time = Vec::new();
    for s in 0..n {
        // Drawn in the renderer's order: image position, lens, time.
        let mut st = SampleStream::with_pattern(pattern, spp, seed, 0, s);
        pixel.push(st.next_2d());
        lens.push(concentric_disk(st.next_2d()));
        time.push(st.next_1d());
    }
    ui.label(format!(
        "{n} samples of one pixel, pattern {}",
        pattern.name()
    ));
    ui.horizontal(|ui| {
        let side = 200.0;
        for (title, is_lens) in [
            ("Position in the pixel", false),
            ("Point on the lens", true),
        ] {
            ui.vertical(|ui| {
                ui.label(title);
                let (rect, _) =
                    ui.allocate_exact_size(egui::vec2(side, side), egui::Sense::hover());
                let p = ui.painter_at(rect);
                p.rect_filled(rect, 0.0, egui::Color32::from_gray(30));
                if is_lens {
                    p.circle_stroke(
                        rect.center(),
                        side / 2.0,
                        egui::Stroke::new(1.0, egui::Color32::GRAY),
                    );
                } else {
                    let (nx, ny) = crate::math::rng::grid(spp);
                    if matches!(
                        pattern,
                        crate::math::Pattern::Regular | crate::math::Pattern::Jittered
                    ) && nx * ny <= 64 * 64
                    {
                        for i in 1..nx {
                            let x = rect.min.x + side * i as f32 / nx as f32;
                            p.line_segment(
                                [egui::pos2(x, rect.min.y), egui::pos2(x, rect.max.y)],
                                egui::Stroke::new(0.5, egui::Color32::DARK_GRAY),
                            );
                        }
                        for j in 1..ny {
                            let y = rect.min.y + side * j as f32 / ny as f32;
                            p.line_segment(
                                [egui::pos2(rect.min.x, y), egui::pos2(rect.max.x, y)],
                                egui::Stroke::new(0.5, egui::Color32::DARK_GRAY),
                            );
                        }
                    }
                }
                let points = if is_lens { &lens } else { &pixel };
                for q in points {
                    let q = if is_lens {
                        (*q + glam::Vec2::ONE) / 2.0
                    } else {
                        *q
                    };
                    p.circle_filled(
                        rect.min + egui::vec2(q.x * side, q.y * side),
                        2.0,
                        egui::Color32::from_rgb(255, 200, 80),
                    );
                }
            });
        }
    });
    ui.label("Time in the shutter interval");
    let (rect, _) = ui.allocate_exact_size(egui::vec2(408.0, 24.0), egui::Sense::hover());
    let p = ui.painter_at(rect);
    p.rect_filled(rect, 0.0, egui::Color32::from_gray(30));
    for t in &time {
        let x = rect.min.x + t * rect.width();
        p.line_segment(
            [
                egui::pos2(x, rect.min.y + 3.0),
                egui::pos2(x, rect.max.y - 3.0),
            ],
            egui::Stroke::new(1.0, egui::Color32::from_rgb(255, 200, 80)),
        );
    }
}

/// One slide of the lecture: a scene, parameters, and what to look at.
pub struct Slide {
    /// Menu entry.
    pub title: &'static str,
    /// The built-in scene.
    pub scene: &'static str,
    /// Parameters set on top of the scene's, as `--set` would.
    pub params: &'static [(&'static str, &'static str)],
    /// The caption shown over the image.
    pub caption: &'static str,
}

/// The lecture, slide by slide.
pub const LECTURE: &[Slide] = &[
    Slide {
        title: "Fresnel reflection on the black glazed sphere",
        scene: "glazed",
        params: &[],
        caption: "Left: constant reflectance, 10% at every angle. Right: Fresnel, 4% head-on rising to 100% at grazing angles: the bright rim that makes it look glazed.",
    },
    Slide {
        title: "Snell's law",
        scene: "glass",
        params: &[],
        caption: "n1 sin θi = n2 sin θt: the refracted rays bend towards the normal going in and away coming out, so the sphere is a lens and shows the floor upside down. Drag the IOR.",
    },
    Slide {
        title: "Total internal reflection",
        scene: "tir",
        params: &[],
        caption: "Inside the prism light meets the back faces at 45°, beyond the critical angle asin(1/n) for n > 1.41: a perfect mirror. Set the IOR below 1.41 and the red wall appears.",
    },
    Slide {
        title: "Pruning the ray tree",
        scene: "ray-tree",
        params: &[("max_depth", "2")],
        caption: "Every hit on glass spawns a reflected and a refracted ray. Cut at depth 2, the far spheres go dark; raise Max depth, or prune by weight instead.",
    },
    Slide {
        title: "Antialiasing: 1 against 4 samples",
        scene: "antialiasing",
        params: &[("spp", "4"), ("pattern", "jittered")],
        caption: "Four jittered samples per pixel, averaged (a box filter). Set Samples per pixel to 1 and Pattern to regular to see the aliasing they remove.",
    },
    Slide {
        title: "Soft shadows",
        scene: "soft-shadows",
        params: &[],
        caption: "Each sample's shadow ray goes to a different point of the area light: the penumbra. Drag Light size; at 0 the light is a point and shadows are hard.",
    },
    Slide {
        title: "Glossy reflection",
        scene: "glossy",
        params: &[],
        caption: "Reflected rays jittered over a Phong lobe cos^n around the mirror direction: n = 10 to 10,000 from left to right.",
    },
    Slide {
        title: "Depth of field",
        scene: "depth-of-field",
        params: &[],
        caption: "Eye rays from random points on the lens meet on the plane of focus: the blue sphere is sharp, the others blur by their circle of confusion. Try Click to focus.",
    },
    Slide {
        title: "Motion blur",
        scene: "motion-blur",
        params: &[],
        caption: "Each sample has a time in the shutter interval; moving spheres smear over their travel. Set the shutter interval to 0 to freeze them.",
    },
];

/// An "inferno"-like ramp from black through purple, red and orange to pale yellow, for
/// t in [0, 1].
pub fn heat_color(t: f32) -> [u8; 3] {
    const STOPS: [[f32; 3]; 6] = [
        [0.0, 0.0, 0.02],
        [0.34, 0.06, 0.43],
        [0.73, 0.21, 0.33],
        [0.96, 0.48, 0.10],
        [0.98, 0.80, 0.25],
        [0.99, 1.0, 0.64],
    ];
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    } * (STOPS.len() - 1) as f32;
    let i = (t.floor() as usize).min(STOPS.len() - 2);
    let f = t - i as f32;
    let (a, b) = (STOPS[i], STOPS[i + 1]);
    [0, 1, 2].map(|k| ((a[k] + (b[k] - a[k]) * f) * 255.0 + 0.5) as u8)
}

/// The cost heat map as RGBA: rays per sample from `lo` (black) to `hi` (pale yellow).
pub fn heat_map_rgba(cost: &[f32], lo: f32, hi: f32) -> Vec<u8> {
    let span = (hi - lo).max(1e-6);
    cost.iter()
        .flat_map(|&c| {
            let [r, g, b] = heat_color((c - lo) / span);
            [r, g, b, 255]
        })
        .collect()
}

/// The smallest and largest values of `cost`.
pub fn cost_range(cost: &[f32]) -> (f32, f32) {
    cost.iter().fold((f32::INFINITY, 0.0f32), |(lo, hi), &c| {
        (lo.min(c), hi.max(c))
    })
}

/// What the two sides of the A/B view differ in.
#[derive(Clone, Debug, PartialEq)]
pub enum CompareKind {
    /// Schlick's approximation against the exact Fresnel equations.
    SchlickExact,
    /// Random against jittered samples, at the same samples per pixel.
    RandomJittered,
    /// Constant reflectance against Fresnel.
    ConstantFresnel,
    /// The split ray tree against the stochastic one.
    SplitStochastic,
    /// The parameters as they were when frozen (B) against the controls (A).
    Frozen(crate::params::Params),
}

impl CompareKind {
    /// The presets, for the menu.
    pub fn presets() -> [(&'static str, CompareKind); 4] {
        [
            ("Schlick | exact", CompareKind::SchlickExact),
            ("random | jittered", CompareKind::RandomJittered),
            ("constant | Fresnel", CompareKind::ConstantFresnel),
            ("split | stochastic tree", CompareKind::SplitStochastic),
        ]
    }

    /// The labels of side A and side B.
    pub fn labels(&self) -> (&'static str, &'static str) {
        match self {
            CompareKind::SchlickExact => ("A: Schlick", "B: exact Fresnel"),
            CompareKind::RandomJittered => ("A: random", "B: jittered"),
            CompareKind::ConstantFresnel => ("A: constant k", "B: exact Fresnel"),
            CompareKind::SplitStochastic => ("A: split tree", "B: stochastic tree"),
            CompareKind::Frozen(_) => ("A: the controls", "B: frozen"),
        }
    }

    /// Side A's parameters when the comparison starts.
    pub fn side_a(&self, p: &crate::params::Params) -> crate::params::Params {
        use crate::optics::FresnelMode;
        use crate::params::{Pattern, TreeMode};
        let mut p = p.clone();
        match self {
            CompareKind::SchlickExact => p.fresnel = Some(FresnelMode::Schlick),
            CompareKind::RandomJittered => p.pattern = Pattern::Random,
            CompareKind::ConstantFresnel => p.fresnel = Some(FresnelMode::Constant),
            CompareKind::SplitStochastic => p.tree = TreeMode::Split,
            CompareKind::Frozen(_) => {}
        }
        p
    }

    /// Side B's parameters, given side A's: A's with the compared setting changed.
    pub fn side_b(&self, a: &crate::params::Params) -> crate::params::Params {
        use crate::optics::FresnelMode;
        use crate::params::{Pattern, TreeMode};
        let mut p = a.clone();
        match self {
            CompareKind::SchlickExact | CompareKind::ConstantFresnel => {
                p.fresnel = Some(FresnelMode::Exact)
            }
            CompareKind::RandomJittered => p.pattern = Pattern::Jittered,
            CompareKind::SplitStochastic => p.tree = TreeMode::Stochastic,
            CompareKind::Frozen(b) => return b.clone(),
        }
        p
    }
}
