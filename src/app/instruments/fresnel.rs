//! The Fresnel plot: R_s, R_p, exact R, Schlick and naive Schlick against the angle of
//! incidence, both ways across the interface; or a measured metal's R, R_s and R_p per
//! colour channel above the dielectric's, on the same axes.

use crate::material::METALS;
use crate::optics::{brewster_angle, conductor_table, critical_angle, fresnel_table};
use egui::{Color32, RichText};
use egui_plot::{Legend, Line, LineStyle, Plot, PlotPoints, VLine};

/// The Fresnel plots for `ior`, both ways across the interface: from air into the
/// material, and from the material out into air (where total internal reflection sets in).
/// With `metal` (an index into [`METALS`]) the first plot is that metal's instead, so a
/// conductor and a dielectric are seen on the same axes. `marker` is an inspected ray's
/// angle of incidence (degrees) and whether it was going into the denser medium: it is
/// marked on that plot. In a hall (presentation mode, every text large: `hall` is where
/// the plot must end, the rest of the dock being another instrument's) one plot is shown,
/// as tall as there is room for, the inspected ray's way across (else into the material),
/// its legend in rows of text under it rather than over the curves, without the notes.
pub(crate) fn fresnel_plot_ui(
    ui: &mut egui::Ui,
    ior: f32,
    marker: Option<(f32, bool)>,
    metal: &mut Option<usize>,
    hall: Option<f32>,
) {
    ui.horizontal(|ui| {
        ui.label(if hall.is_some() {
            "Metal:"
        } else {
            "Compare with a metal:"
        });
        let name = |m: Option<usize>| m.map_or("none", |i| METALS[i].name);
        egui::ComboBox::from_id_salt("fresnel-metal")
            .selected_text(name(*metal))
            .show_ui(ui, |ui| {
                for choice in std::iter::once(None).chain((0..METALS.len()).map(Some)) {
                    ui.selectable_value(metal, choice, name(choice));
                }
            });
    });
    if let Some(i) = *metal {
        metal_curves_ui(ui, i, ior, hall);
        if hall.is_none() {
            ui.strong("Air into material");
            fresnel_curves_ui(ui, 1.0, ior, marker.filter(|m| m.1).map(|m| m.0), hall);
        }
        return;
    }
    for (title, n1, n2, into) in [
        ("Air into material", 1.0, ior, true),
        ("Material out to air", ior, 1.0, false),
    ] {
        if hall.is_some() && marker.map_or(!into, |(_, m)| m != into) {
            continue;
        }
        ui.strong(title);
        let mark = marker.filter(|&(_, m)| m == into).map(|(a, _)| a);
        fresnel_curves_ui(ui, n1, n2, mark, hall);
    }
}

/// A plot's legend as rows of text under it: each curve's name in its colour, after a
/// stroke of its style.
fn legend_rows_ui(ui: &mut egui::Ui, entries: &[(String, Color32, &str)]) {
    ui.horizontal_wrapped(|ui| {
        for (name, colour, stroke) in entries {
            // An entry is never broken across rows.
            let text = RichText::new(format!("{stroke}\u{a0}{name}")).color(*colour);
            ui.add(egui::Label::new(text).wrap_mode(egui::TextWrapMode::Extend));
        }
    });
}

/// The height of `entries` laid out in rows as `legend_rows_ui` lays them.
fn legend_height(ui: &egui::Ui, entries: &[(String, Color32, &str)]) -> f32 {
    let font = egui::TextStyle::Body.resolve(ui.style());
    let spacing = ui.spacing().item_spacing;
    let width = ui.available_width();
    let (mut rows, mut x) = (1, 0.0);
    for (name, _, stroke) in entries {
        let w = ui
            .painter()
            .layout_no_wrap(
                format!("{stroke}\u{a0}{name}"),
                font.clone(),
                Color32::WHITE,
            )
            .size()
            .x;
        if x > 0.0 && x + w > width {
            rows += 1;
            x = 0.0;
        }
        x += w + spacing.x;
    }
    rows as f32 * (ui.fonts_mut(|f| f.row_height(&font)) + spacing.y)
}

/// The plot's height: 230 points at a desk; in a hall, what is left above `hall`'s
/// bottom after the legend (`entries`) under it, between 4 and 10 lines of text (its
/// numbers are large).
fn plot_height(ui: &egui::Ui, hall: Option<f32>, entries: &[(String, Color32, &str)]) -> f32 {
    let Some(bottom) = hall else {
        return 230.0;
    };
    let text = egui::TextStyle::Body.resolve(ui.style()).size;
    let room =
        bottom - ui.cursor().top() - legend_height(ui, entries) - ui.spacing().item_spacing.y;
    room.clamp(4.0 * text, 10.0 * text)
}

/// A measured metal's R (thick), R_s (dashed) and R_p (dotted) from air, one colour per
/// channel: high at every angle, dipping a little in p before rising to 1 at grazing; and
/// the dielectric's R (`ior`, white) on the same axes, low until grazing. Its legend is
/// under it: seven entries over curves that run high would hide them.
fn metal_curves_ui(ui: &mut egui::Ui, index: usize, ior: f32, hall: Option<f32>) {
    let m = &METALS[index];
    let rows = conductor_table(1.0, m.eta, m.k, 0.25);
    let glass = fresnel_table(1.0, ior, 0.25);
    let fmt = |v: [f32; 3]| format!("{:.2}, {:.2}, {:.2}", v[0], v[1], v[2]);
    // In a hall the menu and the legend name the curves.
    if hall.is_none() {
        ui.strong(format!(
            "Air onto {} ({}) and n = {ior:.2}",
            m.name, m.symbol
        ));
        ui.label(format!(
            "η = ({}), κ = ({}). R0 = ({}) for R, G, B",
            fmt(m.eta),
            fmt(m.k),
            fmt(rows[0].r)
        ));
    }
    let channels = [
        ("red", egui::Color32::from_rgb(230, 75, 60)),
        ("green", egui::Color32::from_rgb(70, 175, 80)),
        ("blue", egui::Color32::from_rgb(70, 120, 235)),
    ];
    let dielectric = format!("R n = {ior:.2}");
    let mut entries: Vec<(String, Color32, &str)> = channels
        .iter()
        .map(|(channel, colour)| (format!("R {channel}"), *colour, "—"))
        .collect();
    entries.push(("Rs".into(), Color32::LIGHT_GRAY, "- -"));
    entries.push(("Rp".into(), Color32::LIGHT_GRAY, "···"));
    entries.push((dielectric.clone(), Color32::WHITE, "—"));
    // The curves run high: the legend goes under the plot, not over them.
    let plot = reflectance_plot(("metal-plot", index), ui, hall, false, &entries);
    plot.show(ui, |p| {
        for (c, (channel, colour)) in channels.into_iter().enumerate() {
            let series = |f: &dyn Fn(&crate::optics::ConductorRow) -> f32| {
                curve(&rows, |r| (r.theta_i, f(r)))
            };
            p.line(
                Line::new(format!("R {channel}"), series(&|r| r.r[c]))
                    .color(colour)
                    .width(2.5),
            );
            p.line(
                Line::new("Rs (dashed)", series(&|r| r.r_s[c]))
                    .color(colour)
                    .style(LineStyle::dashed_dense()),
            );
            p.line(
                Line::new("Rp (dotted)", series(&|r| r.r_p[c]))
                    .color(colour)
                    .style(LineStyle::dotted_dense()),
            );
        }
        p.line(
            Line::new(dielectric, curve(&glass, |r| (r.theta_i, r.r_exact)))
                .color(Color32::WHITE)
                .width(2.5),
        );
    });
    legend_rows_ui(ui, &entries);
}

/// A plot line through `rows`, each giving (θi in degrees, value).
fn curve<R>(rows: &[R], point: impl Fn(&R) -> (f32, f32)) -> PlotPoints<'static> {
    rows.iter()
        .map(|r| {
            let (x, y) = point(r);
            [x as f64, y as f64]
        })
        .collect::<Vec<[f64; 2]>>()
        .into()
}

/// The plot both kinds of curve share: reflectance 0..1 against 0..90 degrees, as tall as
/// `plot_height` says in a `hall`, its legend over the curves if `legend_inside` (else the
/// caller draws `entries` under the plot).
fn reflectance_plot(
    id: impl std::hash::Hash + std::fmt::Debug,
    ui: &egui::Ui,
    hall: Option<f32>,
    legend_inside: bool,
    entries: &[(String, Color32, &str)],
) -> Plot<'static> {
    let under = if legend_inside { &[][..] } else { entries };
    let plot = Plot::new(id)
        .height(plot_height(ui, hall, under))
        .include_x(0.0)
        .include_x(90.0)
        .include_y(-0.1)
        .include_y(1.0)
        .x_axis_label("angle of incidence θi (°)")
        .allow_drag(false)
        .allow_scroll(false)
        .x_grid_spacer(egui_plot::uniform_grid_spacer(|_| [5.0, 10.0, 30.0]))
        .y_grid_spacer(egui_plot::uniform_grid_spacer(|_| [0.05, 0.1, 0.5]))
        .y_axis_formatter(|mark, _| format!("{:.1}", mark.value));
    // In a hall the legend under the plot says R: the axis's word would take a column.
    let plot = if hall.is_none() {
        plot.y_axis_label("reflectance")
    } else {
        plot
    };
    if legend_inside {
        // Top left, where a dielectric's curves are low (R under 0.1 below 30°): the
        // legend covers none of them, nor the rise towards grazing it is there to explain.
        plot.legend(Legend::default().position(egui_plot::Corner::LeftTop))
    } else {
        plot
    }
}

/// R_s, R_p, exact R, Schlick and naive Schlick against the angle of incidence from `n1`
/// into `n2`, with Brewster's and the critical angle marked and the error of Schlick.
fn fresnel_curves_ui(ui: &mut egui::Ui, n1: f32, n2: f32, marker: Option<f32>, hall: Option<f32>) {
    let rows = fresnel_table(n1, n2, 0.25);
    let series =
        |f: &dyn Fn(&crate::optics::FresnelRow) -> f32| curve(&rows, |r| (r.theta_i, f(r)));
    let brewster = brewster_angle(n1, n2).to_degrees();
    let critical = critical_angle(n1, n2).map(f32::to_degrees);
    if hall.is_none() {
        ui.label(format!(
            "n1 = {n1:.3} -> n2 = {n2:.3}. R0 = {:.4}. Brewster {brewster:.2}°{}",
            rows[0].r_exact,
            critical.map_or(String::new(), |c| format!(", critical {c:.2}°"))
        ));
    }
    type Of = fn(&crate::optics::FresnelRow) -> f32;
    // Each its own colour, far apart in hue (egui_plot's own drew two alike greens).
    let curves: [(&str, Color32, f32, Of); 6] = [
        ("Rs = Fs²", Color32::from_rgb(235, 90, 70), 1.5, |r| {
            r.f_s * r.f_s
        }),
        ("Rp = Fp²", Color32::from_rgb(80, 140, 240), 1.5, |r| {
            r.f_p * r.f_p
        }),
        ("R exact", Color32::from_rgb(245, 245, 245), 2.5, |r| {
            r.r_exact
        }),
        ("Schlick", Color32::from_rgb(90, 200, 90), 1.5, |r| {
            r.r_schlick
        }),
        (
            "naive Schlick",
            Color32::from_rgb(210, 110, 220),
            1.5,
            |r| r.r_schlick_naive,
        ),
        (
            "Schlick − exact",
            Color32::from_rgb(240, 190, 60),
            1.5,
            |r| r.r_schlick - r.r_exact,
        ),
    ];
    // A hall's plot is small and its legend large: naive Schlick (an aside: Schlick
    // with the wrong angle past the critical one) stays at the desk.
    let curves: Vec<_> = curves
        .into_iter()
        .filter(|c| hall.is_none() || c.0 != "naive Schlick")
        .collect();
    // In a hall the legend goes under the plot, in rows of text at the caption's size.
    let mut entries: Vec<(String, Color32, &str)> = curves
        .iter()
        .map(|(name, colour, _, _)| (name.to_string(), *colour, "—"))
        .collect();
    entries.push((format!("Brewster {brewster:.1}°"), Color32::GRAY, "|"));
    if let Some(c) = critical {
        entries.push((format!("critical {c:.1}°"), Color32::DARK_GRAY, "|"));
    }
    if let Some(m) = marker {
        entries.push((format!("inspected ray {m:.1}°"), Color32::YELLOW, "|"));
    }
    let inside = hall.is_none();
    let plot = reflectance_plot(("fresnel-plot", n1 > n2), ui, hall, inside, &entries);
    let vlines = |p: &mut egui_plot::PlotUi| {
        p.vline(VLine::new(format!("Brewster {brewster:.1}°"), brewster).color(Color32::GRAY));
        if let Some(c) = critical {
            p.vline(VLine::new(format!("critical {c:.1}°"), c).color(Color32::DARK_GRAY));
        }
        if let Some(m) = marker {
            p.vline(
                VLine::new(format!("inspected ray {m:.1}°"), m)
                    .width(2.0)
                    .color(Color32::YELLOW),
            );
        }
    };
    plot.show(ui, |p| {
        for &(name, colour, width, of) in &curves {
            p.line(Line::new(name, series(&of)).color(colour).width(width));
        }
        vlines(p);
    });
    if !inside {
        legend_rows_ui(ui, &entries);
    }
}
