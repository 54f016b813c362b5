//! The Fresnel plot: R_s, R_p, exact R, Schlick and naive Schlick against the angle of
//! incidence, both ways across the interface; or a measured metal's R, R_s and R_p per
//! colour channel above the dielectric's, on the same axes.

use crate::material::METALS;
use crate::optics::{brewster_angle, conductor_table, critical_angle, fresnel_table};
use egui_plot::{Legend, Line, LineStyle, Plot, PlotPoints, VLine};

/// The Fresnel plots for `ior`, both ways across the interface: from air into the
/// material, and from the material out into air (where total internal reflection sets in).
/// With `metal` (an index into [`METALS`]) the first plot is that metal's instead, so a
/// conductor and a dielectric are seen on the same axes. `marker` is an inspected ray's
/// angle of incidence (degrees) and whether it was going into the denser medium: it is
/// marked on that plot.
pub(crate) fn fresnel_plot_ui(
    ui: &mut egui::Ui,
    ior: f32,
    marker: Option<(f32, bool)>,
    metal: &mut Option<usize>,
) {
    ui.horizontal(|ui| {
        ui.label("Compare with a metal:");
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
        metal_curves_ui(ui, i);
        ui.strong("Air into material");
        fresnel_curves_ui(ui, 1.0, ior, marker.filter(|m| m.1).map(|m| m.0));
        return;
    }
    for (title, n1, n2, into) in [
        ("Air into material", 1.0, ior, true),
        ("Material out to air", ior, 1.0, false),
    ] {
        ui.strong(title);
        let mark = marker.filter(|&(_, m)| m == into).map(|(a, _)| a);
        fresnel_curves_ui(ui, n1, n2, mark);
    }
}

/// A measured metal's R (thick), R_s (dashed) and R_p (dotted) from air, one colour per
/// channel: high at every angle, dipping a little in p before rising to 1 at grazing.
fn metal_curves_ui(ui: &mut egui::Ui, index: usize) {
    let m = &METALS[index];
    let rows = conductor_table(1.0, m.eta, m.k, 0.25);
    let fmt = |v: [f32; 3]| format!("{:.2}, {:.2}, {:.2}", v[0], v[1], v[2]);
    ui.strong(format!("Air onto {} ({})", m.name, m.symbol));
    ui.label(format!(
        "η = ({}), κ = ({}). R0 = ({}) for R, G, B",
        fmt(m.eta),
        fmt(m.k),
        fmt(rows[0].r)
    ));
    let channels = [
        ("red", egui::Color32::from_rgb(230, 75, 60)),
        ("green", egui::Color32::from_rgb(70, 175, 80)),
        ("blue", egui::Color32::from_rgb(70, 120, 235)),
    ];
    // The curves run high: the legend goes in room made below them.
    let legend = Legend::default().position(egui_plot::Corner::LeftBottom);
    reflectance_plot(("metal-plot", index))
        .legend(legend)
        .include_y(-0.55)
        .show(ui, |p| {
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
        });
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

/// The plot both kinds of curve share: reflectance 0..1 against 0..90 degrees.
fn reflectance_plot(id: impl std::hash::Hash + std::fmt::Debug) -> Plot<'static> {
    // Top left, where a dielectric's curves are low (R under 0.1 below 30°): the legend
    // covers none of them, nor the rise towards grazing it is there to explain.
    Plot::new(id)
        .legend(Legend::default().position(egui_plot::Corner::LeftTop))
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
}

/// R_s, R_p, exact R, Schlick and naive Schlick against the angle of incidence from `n1`
/// into `n2`, with Brewster's and the critical angle marked and the error of Schlick.
fn fresnel_curves_ui(ui: &mut egui::Ui, n1: f32, n2: f32, marker: Option<f32>) {
    let rows = fresnel_table(n1, n2, 0.25);
    let series =
        |f: &dyn Fn(&crate::optics::FresnelRow) -> f32| curve(&rows, |r| (r.theta_i, f(r)));
    let brewster = brewster_angle(n1, n2).to_degrees();
    let critical = critical_angle(n1, n2).map(f32::to_degrees);
    ui.label(format!(
        "n1 = {n1:.3} -> n2 = {n2:.3}. R0 = {:.4}. Brewster {brewster:.2}°{}",
        rows[0].r_exact,
        critical.map_or(String::new(), |c| format!(", critical {c:.2}°"))
    ));
    reflectance_plot(("fresnel-plot", n1 > n2)).show(ui, |p| {
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
