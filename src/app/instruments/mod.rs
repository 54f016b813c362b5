//! Teaching instruments: windows and overlays that explain what the image shows. The
//! Instruments menu switches them on.

mod fresnel;
mod heat;
mod inspector;
mod patterns;
mod section;
mod trace;

pub(crate) use heat::{cost_range, draw_colour_bar, heat_map_rgba};
pub(crate) use inspector::draw_tree_overlay;

use super::RaylabApp;
use crate::tracer::RayTree;
use inspector::Inspection;
pub(crate) use section::{SectionMode, SectionState};

/// Which instruments are on, and the inspected tree.
pub(crate) struct Instruments {
    pub(crate) show_fresnel: bool,
    /// The measured metal (an index into `METALS`) the Fresnel plot compares, if any.
    pub(crate) fresnel_metal: Option<usize>,
    /// A click on the image inspects a pixel.
    pub(crate) inspect_mode: bool,
    pub(crate) inspection: Option<Inspection>,
    /// A tree being traced aside (`trace.rs`).
    tracing: Option<trace::Tracing>,
    pub(crate) show_patterns: bool,
    pub(crate) show_cost: bool,
    /// The heat map's top, in rays per sample (black at 0): one fixed scale, so the same
    /// cost has the same colour whatever the rest of the image; `None` fits each image.
    pub(crate) cost_top: Option<f32>,
    /// The next click on the image sets the focus distance.
    pub(crate) click_to_focus: bool,
    /// The section view (a pixel's tree in its plane, or the interface workbench) is open.
    pub(crate) show_section: bool,
    pub(crate) section: SectionState,
    /// The ray of the inspected tree the pointer is over (in the section view, the list or
    /// the image's overlay): all three highlight it.
    pub(crate) hover: Option<usize>,
    /// In a hall, the one instrument the dock shows of those open (`None`: the first).
    pub(crate) hall_tab: Option<Tab>,
    // Whether anything reported a hovered ray this frame.
    hover_seen: bool,
}

/// An instrument of the dock. In a hall its text is too large for two at once: the dock
/// shows one, with a tab for each open.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Tab {
    Fresnel,
    Section,
    Inspector,
    Patterns,
    Sheet,
}

impl Tab {
    fn title(self) -> &'static str {
        match self {
            Tab::Fresnel => "Fresnel plot",
            Tab::Section => "Section view",
            Tab::Inspector => "Ray-tree inspector",
            Tab::Patterns => "Sample patterns",
            Tab::Sheet => "Contact sheet",
        }
    }
}

/// The heat map's scales offered: its top in rays per sample.
pub(crate) const COST_TOPS: [f32; 6] = [4.0, 8.0, 16.0, 32.0, 64.0, 256.0];

impl Default for Instruments {
    fn default() -> Self {
        Instruments {
            show_fresnel: false,
            fresnel_metal: None,
            inspect_mode: false,
            inspection: None,
            tracing: None,
            show_patterns: false,
            show_cost: false,
            cost_top: Some(32.0),
            click_to_focus: false,
            show_section: false,
            section: SectionState::default(),
            hover: None,
            hall_tab: None,
            hover_seen: false,
        }
    }
}

impl Instruments {
    /// The inspected ray tree, if any.
    pub(crate) fn tree(&self) -> Option<&RayTree> {
        self.inspection.as_ref().map(|i| &i.tree)
    }

    /// Whether the workbench's outline is laid over the image: while the section view is
    /// open on the workbench, with its outline on.
    pub(crate) fn outline_shown(&self) -> bool {
        self.show_section && self.section.outline && self.section.mode == SectionMode::Workbench
    }

    /// No pixel inspected, and none being traced.
    pub(crate) fn forget_inspection(&mut self) {
        self.inspection = None;
        self.tracing = None;
    }

    /// Ray `node` is under the pointer (`None`: this instrument's part has none).
    pub(crate) fn hovered(&mut self, node: Option<usize>) {
        if let Some(n) = node {
            self.hover = Some(n);
            self.hover_seen = true;
        }
    }

    /// At the end of a frame: nothing hovered it, so no ray is highlighted; a change is
    /// drawn at once (the instruments drawn before the one hovered see it next frame).
    pub(crate) fn end_frame(&mut self, ctx: &egui::Context) {
        let before = self.hover;
        if !self.hover_seen {
            self.hover = None;
        }
        self.hover_seen = false;
        if self.hover != before {
            ctx.request_repaint();
        }
    }
}

impl RaylabApp {
    /// The Instruments menu.
    pub(super) fn instruments_menu_ui(&mut self, ui: &mut egui::Ui) {
        let i = &mut self.instruments;
        ui.checkbox(&mut i.show_fresnel, "Fresnel plot").on_hover_text(
            "R_s, R_p, exact R, Schlick and naive Schlick against the angle, for the current IOR.",
        );
        ui.checkbox(&mut i.inspect_mode, "Ray-tree inspector: click a pixel")
            .on_hover_text("Click a pixel to see the whole ray tree of its first sample, drawn over the image.");
        if ui
            .checkbox(&mut i.show_section, "Section view and interface workbench")
            .on_hover_text("The lecture's 2D diagram: the clicked pixel's ray tree in its own plane, with the angles and indices at each interface; or one interface and one ray, its angle dragged.")
            .changed()
            && i.show_section
        {
            // A section is of a clicked pixel.
            i.inspect_mode = true;
        }
        ui.checkbox(&mut i.show_cost, "Cost heat map")
            .on_hover_text("Rays traced per sample in each pixel, black (few) to yellow (many): where the ray tree is deep. Compare pruning by depth and by weight.");
        ui.horizontal(|ui| {
            ui.label("Heat map: 0 to");
            let text = i.cost_top.map_or("fit image".to_string(), |t| format!("{t:.0}"));
            egui::ComboBox::from_id_salt("cost-top")
                .selected_text(text)
                .show_ui(ui, |ui| {
                    for top in COST_TOPS {
                        ui.selectable_value(&mut i.cost_top, Some(top), format!("{top:.0} rays/sample"));
                    }
                    ui.selectable_value(&mut i.cost_top, None, "fit each image")
                        .on_hover_text("From the image's fewest to most rays per sample: every frame its own scale.");
                });
        })
        .response
        .on_hover_text("The heat map's scale, fixed so that the same cost has the same colour as you change the tree.");
        ui.menu_button("A/B compare", |ui| self.compare_menu_ui(ui));
        if ui
            .button("Contact sheet…")
            .on_hover_text(
                "One labelled image per value of a parameter, side by side, saved as a PNG.",
            )
            .clicked()
        {
            self.open_sheet_form();
            ui.close();
        }
        ui.checkbox(&mut self.instruments.show_patterns, "Sample patterns")
            .on_hover_text("Where one pixel's samples fall: in the pixel, on the lens, in the shutter interval.");
    }

    /// The instruments' dock: a panel right of the image holding each open instrument, so
    /// that none covers the image it explains or the controls it follows.
    pub(super) fn instruments_dock_ui(&mut self, ui: &mut egui::Ui) {
        let i = &self.instruments;
        let sheet = self.sheet.is_some();
        let open = i.show_fresnel || i.show_section || i.show_patterns || sheet;
        if !(open || i.inspect_mode || i.inspection.is_some()) {
            return;
        }
        // In a hall the image keeps two thirds of the width, whatever the text's size.
        let width = ui.ctx().content_rect().width();
        let (default, max) = if self.hall.presenting {
            (width / 3.0, width / 3.0)
        } else {
            (420.0, width * 0.6)
        };
        egui::Panel::right("instruments")
            .resizable(true)
            .default_size(default)
            .max_size(max)
            .show(ui, |ui| {
                // Rows wider than the dock scroll (a hall's text is large): the dock keeps
                // its width, and the image the rest.
                egui::ScrollArea::both().show(ui, |ui| self.instruments_ui(ui));
            });
    }

    /// The instruments open, in the dock's order. In a hall the section view shows the
    /// inspected tree: the inspector's list, too long for a hall, goes; and the Fresnel
    /// plot shares its tab with the section view (`together`).
    fn open_tabs(&self) -> Vec<Tab> {
        let i = &self.instruments;
        let listed = !(self.hall.presenting && i.show_section);
        [
            (i.show_fresnel, Tab::Fresnel),
            (i.show_section && !self.together(), Tab::Section),
            (
                listed && (i.inspect_mode || i.inspection.is_some()),
                Tab::Inspector,
            ),
            (i.show_patterns, Tab::Patterns),
            (self.sheet.is_some(), Tab::Sheet),
        ]
        .into_iter()
        .filter_map(|(open, tab)| open.then_some(tab))
        .collect()
    }

    /// Whether the Fresnel plot and the section view (the workbench, on the slides that
    /// open both and whose captions speak of both) are shown one above the other in a
    /// hall, where the dock otherwise shows one instrument.
    fn together(&self) -> bool {
        let i = &self.instruments;
        self.hall.presenting && i.show_fresnel && i.show_section
    }

    /// Each open instrument under its heading, with a button that closes it; in a hall,
    /// where there is room for one, the one its tab picks (the plot with the section view
    /// under it, `together`).
    fn instruments_ui(&mut self, ui: &mut egui::Ui) {
        let tabs = self.open_tabs();
        let hall = self.hall.presenting;
        let together = self.together();
        // Where the dock's view ends: the plot ends above it, or 60 % of the way down
        // when the section view is under it (the workbench's drawing is wider than tall).
        let view = ui.clip_rect();
        let plot_bottom = if together {
            view.top() + 0.6 * view.height()
        } else {
            view.bottom()
        };
        // The tab shown, where the dock shows one instrument.
        let mut current = (hall && tabs.len() > 1).then(|| {
            let chosen = self.instruments.hall_tab.filter(|t| tabs.contains(t));
            chosen.unwrap_or(tabs[0])
        });
        let mut close = None;
        if let Some(chosen) = &mut current {
            ui.horizontal_wrapped(|ui| {
                for t in &tabs {
                    ui.selectable_value(chosen, *t, t.title());
                }
                if ui.button("Close").clicked() {
                    close = Some(*chosen);
                }
            });
            self.instruments.hall_tab = Some(*chosen);
            ui.separator();
        }
        // Whether to draw `tab`, and under a heading (false once closed).
        let shows = |tab: Tab| {
            current
                .is_none_or(|c| c == tab || (together && c == Tab::Fresnel && tab == Tab::Section))
        };
        let head = |ui: &mut egui::Ui, tab: Tab| match current {
            Some(_) => close != Some(tab),
            None => heading(ui, tab.title()),
        };
        let params = &self.settings.params;
        // The IOR the `ior` parameter sets, or the scene's first that it would replace.
        let ior = params.ior.or_else(|| {
            self.scene
                .materials
                .iter()
                .find_map(|m| m.dielectric().filter(|d| !d.ior_fixed).map(|d| d.ior))
        });
        // The roughness the Roughness α slider shows: the parameter's, else the scene's.
        let roughness = params
            .roughness
            .or_else(|| {
                self.scene
                    .materials
                    .iter()
                    .find_map(crate::material::Material::roughness)
            })
            .unwrap_or(0.0);
        let i = &mut self.instruments;
        if i.show_fresnel && shows(Tab::Fresnel) {
            // The inspected ray's angle, where it meets a dielectric interface (a diffuse
            // floor has no reflectance curve to mark).
            let marker = i
                .tree()
                .and_then(|t| t.nodes.first())
                .and_then(|n| n.hit)
                .and_then(|h| h.n1_n2.map(|(n1, n2)| (h.theta_i, n1 <= n2)));
            if !head(ui, Tab::Fresnel) {
                i.show_fresnel = false;
            }
            let room = hall.then_some(plot_bottom);
            fresnel::fresnel_plot_ui(ui, ior.unwrap_or(1.5), marker, &mut i.fresnel_metal, room);
            ui.separator();
        }
        if i.show_section && shows(Tab::Section) {
            // Under the plot it shares the plot's heading.
            if !together && !head(ui, Tab::Section) {
                i.show_section = false;
            }
            let hovered = section::section_ui(
                ui,
                &mut i.section,
                i.inspection.as_ref(),
                (&self.scene, ior.unwrap_or(1.5), roughness),
                i.hover,
                (hall, together),
            );
            i.hovered(hovered);
            ui.separator();
        }
        if tabs.contains(&Tab::Inspector) && shows(Tab::Inspector) {
            if !head(ui, Tab::Inspector) {
                i.inspect_mode = false;
                i.forget_inspection();
            }
            ui.checkbox(&mut i.inspect_mode, "Clicking the image inspects a pixel");
            let hovered = match &i.inspection {
                Some(inspection) => inspector::inspector_ui(
                    ui,
                    inspection,
                    &self.scene.object_names,
                    &self.scene.material_names,
                    i.hover,
                ),
                None => {
                    ui.label("Click a pixel of the image.");
                    None
                }
            };
            i.hovered(hovered);
            ui.separator();
        }
        if i.show_patterns && shows(Tab::Patterns) {
            if !head(ui, Tab::Patterns) {
                i.show_patterns = false;
            }
            patterns::sample_pattern_ui(ui, params);
            ui.separator();
        }
        if self.sheet.is_some() && shows(Tab::Sheet) {
            let open = head(ui, Tab::Sheet);
            self.sheet_form_ui(ui, open);
        }
    }
}

/// An instrument's heading in the dock; false once its Close button is clicked.
fn heading(ui: &mut egui::Ui, title: &str) -> bool {
    let mut open = true;
    ui.horizontal(|ui| {
        ui.heading(title);
        ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
            if ui
                .button("Close")
                .on_hover_text(format!("Close the {title}."))
                .clicked()
            {
                open = false;
            }
        });
    });
    open
}
