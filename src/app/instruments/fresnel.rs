//! The Fresnel plot: R_s, R_p, exact R, Schlick and naive Schlick against the angle of
//! incidence, both ways across the interface.

use crate::optics::{brewster_angle, critical_angle, fresnel_table};
use egui_plot::{Legend, Line, Plot, PlotPoints, VLine};

/// The Fresnel plots for `ior`, both ways across the interface: from air into the
/// material, and from the material out into air (where total internal reflection sets in).
/// `marker` is an inspected ray's angle of incidence (degrees) and whether it was going
/// into the denser medium: it is marked on that plot.
pub(crate) fn fresnel_plot_ui(ui: &mut egui::Ui, ior: f32, marker: Option<(f32, bool)>) {
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
