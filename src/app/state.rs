//! What the window holds and shows, read without changing it: by its tests (through the
//! public accessors) and by its own modules (the sides of an A/B view, the progress).

use super::RaylabApp;
use super::instruments::SectionMode;
use super::side::Side;
use crate::params::Params;
use crate::render::Frame;
use crate::scene::Scene;
use crate::tracer::RayTree;

/// What is open beside and over the image ([`RaylabApp::open`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Open {
    /// The Fresnel plot.
    pub fresnel_plot: bool,
    /// The section view of a pixel's ray tree.
    pub section: bool,
    /// The section view on the interface workbench.
    pub workbench: bool,
    /// The section view on the lens bench.
    pub lens_bench: bool,
    /// The workbench's outline over the image.
    pub outline: bool,
    /// An inspected pixel (its tree drawn over the image).
    pub inspected: bool,
    /// The A/B view's sides after A (0: no A/B view).
    pub sides: usize,
}

impl RaylabApp {
    /// The scene shown.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The parameters the controls hold.
    pub fn params(&self) -> &Params {
        &self.settings.params
    }

    /// The main view's engine (for its parameters and generation).
    pub fn engine(&self) -> &crate::render::Engine {
        self.main.engine()
    }

    /// The last scene error shown, if any.
    pub fn error(&self) -> Option<&str> {
        self.error.as_deref()
    }

    /// The newest frame received.
    pub fn latest_frame(&self) -> Option<&Frame> {
        self.main.frame()
    }

    /// What the main view's picture on screen was rendered from: its scene and parameters
    /// (none before the first frame).
    pub fn picture(&self) -> Option<(&Scene, &Params)> {
        self.main.rendered()
    }

    /// The main view's image as it is shown: sRGB RGBA rows of the newest frame's picture
    /// as shown ([`Frame::shown`](crate::render::Frame::shown): calmed while the image is
    /// on its way), or the cost heat map's colours while it is on.
    pub fn shown_pixels(&self) -> &[u8] {
        self.main.pixels()
    }

    /// The messages shown at the bottom right.
    pub fn toasts(&self) -> Vec<String> {
        self.toasts.texts()
    }

    /// The inspected ray tree, if a pixel was clicked in inspect mode.
    pub fn inspected_tree(&self) -> Option<&RayTree> {
        self.instruments.tree()
    }

    /// The inspected pixel, if any.
    pub fn inspected_pixel(&self) -> Option<(u32, u32)> {
        self.instruments.inspection.as_ref().map(|i| i.pixel)
    }

    /// The ray of the inspected tree the pointer is over, in the section view, the tree
    /// list or the image's overlay (all three highlight it).
    pub fn hovered_ray(&self) -> Option<usize> {
        self.instruments.hover
    }

    /// How far the section view is zoomed in on the inspected pixel's first hit.
    pub fn section_zoom(&self) -> f32 {
        self.instruments.section.zoom()
    }

    /// The interface workbench's angle of incidence, degrees.
    pub fn workbench_angle(&self) -> f32 {
        self.instruments.section.angle
    }

    /// How many pixels of the image the workbench outlines at its angle, once their angles
    /// are computed.
    pub fn outlined_pixels(&self) -> Option<usize> {
        self.instruments.section.outlined()
    }

    /// What is open beside and over the image: what a slide opens, and must close.
    pub fn open(&self) -> Open {
        let i = &self.instruments;
        Open {
            fresnel_plot: i.show_fresnel,
            section: i.show_section && i.section.mode == SectionMode::Pixel,
            workbench: i.show_section && i.section.mode == SectionMode::Workbench,
            lens_bench: i.show_section && i.section.mode == SectionMode::LensBench,
            outline: i.outline_shown(),
            inspected: i.inspection.is_some(),
            sides: self.compare.as_ref().map_or(0, |c| c.sides.len()),
        }
    }

    /// Whether presentation mode is on.
    pub fn presenting(&self) -> bool {
        self.hall.presenting
    }

    /// The number (from 0, in the Lecture menu's order) of the slide shown, if any.
    pub fn slide(&self) -> Option<usize> {
        self.lecture.current()
    }

    /// Whether the help overlay is open.
    pub fn help_open(&self) -> bool {
        self.hall.help
    }

    /// The parameters and newest frame of each side after A (B, and C), while the A/B
    /// view is on; none while it is off.
    pub fn compare_sides(&self) -> Vec<(&Params, Option<&Frame>)> {
        self.compare_engines()
            .map(|s| (s.engine().params(), s.frame()))
            .collect()
    }

    /// What the picture of each side after A shows was rendered from (as
    /// [`RaylabApp::picture`]), while the A/B view is on.
    pub fn compare_pictures(&self) -> Vec<Option<(&Scene, &Params)>> {
        self.compare_engines().map(Side::rendered).collect()
    }

    /// Whether the A/B view is on and each side after A has its newest frame finished and
    /// of its engine's newest generation.
    pub fn compare_settled(&self) -> bool {
        self.compare.is_some() && self.compare_engines().all(Side::settled)
    }

    /// The sides after A, while the A/B view is on.
    pub(super) fn compare_engines(&self) -> impl Iterator<Item = &Side> {
        self.compare.iter().flat_map(|c| &c.sides)
    }

    /// Every side shown with its letter: the main view (A), then B and C of an A/B view.
    pub(super) fn all_sides(&self) -> impl Iterator<Item = (char, &Side)> {
        ['A', 'B', 'C']
            .into_iter()
            .zip(std::iter::once(&self.main).chain(self.compare_engines()))
    }

    /// How far the view has refined, 0 to 1: the least done of its sides (an A/B view is
    /// finished when every side is), 1 for a side without a target.
    pub fn progress_fraction(&self) -> f32 {
        self.all_sides()
            .map(|(_, side)| side.frame().map_or(0.0, |f| f.progress.fraction()))
            .fold(1.0, f32::min)
    }

    /// The caption of the lecture slide shown, if any, as it reads now.
    pub fn caption(&self) -> Option<String> {
        let inspected = self.instruments.inspection.as_ref().map(|i| {
            let root = i.tree.nodes.first();
            root.and_then(|n| n.hit.map(|h| h.object))
        });
        self.lecture.caption(&crate::lecture::Shown {
            params: &self.settings.params,
            scene: &self.scene,
            camera: &self.settings.camera,
            inspected,
        })
    }
}
