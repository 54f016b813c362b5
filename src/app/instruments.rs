//! Teaching instruments: windows that explain what the image shows.

use crate::optics::{brewster_angle, critical_angle, fresnel_table};
use egui_plot::{Legend, Line, Plot, PlotPoints, VLine};

/// Which way the light crosses the interface in the Fresnel plot.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Direction {
    /// From air into the material (n1 = 1, n2 = IOR).
    #[default]
    OutsideIn,
    /// From the material out into air (n1 = IOR, n2 = 1): total internal reflection.
    InsideOut,
}

/// The Fresnel plot: R_s, R_p, exact R, Schlick and naive Schlick against the angle of
/// incidence for `ior`, with Brewster's and the critical angle marked, the error of
/// Schlick's approximation, and `marker` (an inspected ray's angle, degrees) if any.
pub fn fresnel_plot_ui(
    ui: &mut egui::Ui,
    ior: f32,
    direction: &mut Direction,
    marker: Option<f32>,
) {
    ui.horizontal(|ui| {
        ui.radio_value(direction, Direction::OutsideIn, "Air into material")
            .on_hover_text("n1 = 1, n2 = IOR: R rises from R0 to 1 at grazing incidence.");
        ui.radio_value(direction, Direction::InsideOut, "Material out to air")
            .on_hover_text("n1 = IOR, n2 = 1: beyond the critical angle all light is reflected.");
    });
    let (n1, n2) = match direction {
        Direction::OutsideIn => (1.0, ior),
        Direction::InsideOut => (ior, 1.0),
    };
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
        "n1 = {n1:.3} → n2 = {n2:.3}. R0 = {:.4}. Brewster {brewster:.2}°{}",
        rows[0].r_exact,
        critical.map_or(String::new(), |c| format!(", critical {c:.2}°"))
    ));
    Plot::new("fresnel-plot")
        .legend(Legend::default())
        .height(300.0)
        .include_x(0.0)
        .include_x(90.0)
        .include_y(-0.1)
        .include_y(1.0)
        .x_axis_label("angle of incidence θi (degrees)")
        .y_axis_label("reflectance")
        .allow_drag(false)
        .allow_scroll(false)
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
