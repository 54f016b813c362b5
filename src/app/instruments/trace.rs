//! The inspected pixel traced: on the UI thread where that is a few microseconds, on a
//! thread of its own where its sample first needs a photon map (20,000 photons, several
//! milliseconds of work that a drag would otherwise pay in every frame).

use super::inspector::Inspection;
use crate::app::RaylabApp;
use crate::camera::Camera;
use crate::params::Params;
use crate::scene::Scene;
use crate::tracer::Tracer;
use crossbeam_channel::{Receiver, TryRecvError};
use std::sync::Arc;

/// What a pixel's tree is traced with.
#[derive(Clone)]
struct Asked {
    pixel: (u32, u32),
    size: (u32, u32),
    params: Params,
    camera: Camera,
}

/// A tree being traced on a thread of its own, and the pixel (and image size) last asked
/// for meanwhile: traced next, with the controls as they are then (one thread at a time,
/// and no tree the controls have already left behind).
pub(crate) struct Tracing {
    done: Receiver<Inspection>,
    next: Option<((u32, u32), (u32, u32))>,
}

/// Traces sample 0 of the pixel asked, as the first pass does (with its photons, where
/// there are some).
fn trace(tracer: &mut Tracer, asked: &Asked) -> Inspection {
    tracer.prepare_photons(0);
    let (tree, radiance) = tracer.inspect(asked.pixel.0, asked.pixel.1, 0);
    let (film, lens_point) = tracer.camera_point(asked.pixel.0, asked.pixel.1, 0);
    Inspection {
        film,
        lens_point,
        pixel: asked.pixel,
        size: asked.size,
        params: asked.params.clone(),
        camera: asked.camera.clone(),
        tree,
        radiance,
    }
}

/// Starts tracing `asked` on a thread of its own; `None` where no thread could start.
fn trace_aside(ctx: &egui::Context, scene: Arc<Scene>, asked: Asked) -> Option<Tracing> {
    let (tell, done) = crossbeam_channel::bounded(1);
    let ctx = ctx.clone();
    std::thread::Builder::new()
        .name("raylab-inspect".into())
        .spawn(move || {
            let (w, h) = asked.size;
            let mut tracer = Tracer::with_camera(&scene, &asked.camera, &asked.params, w, h);
            // The window may be gone: nobody to tell then.
            let _ = tell.send(trace(&mut tracer, &asked));
            ctx.request_repaint();
        })
        .ok()?;
    Some(Tracing { done, next: None })
}

impl RaylabApp {
    /// Traces the tree of `pixel`'s first sample with the current parameters and camera,
    /// for the inspector, the section view and the overlay.
    pub(crate) fn inspect(&mut self, ctx: &egui::Context, pixel: (u32, u32), size: (u32, u32)) {
        if let Some(tracing) = &mut self.instruments.tracing {
            tracing.next = Some((pixel, size));
            return;
        }
        let s = &self.settings;
        let asked = Asked {
            pixel,
            size,
            params: s.params.clone(),
            camera: s.camera.clone(),
        };
        let mut tracer = Tracer::with_camera(&self.scene, &s.camera, &s.params, size.0, size.1);
        let aside = tracer
            .gathers_photons()
            .then(|| trace_aside(ctx, self.scene.clone(), asked.clone()))
            .flatten();
        match aside {
            Some(tracing) => self.instruments.tracing = Some(tracing),
            None => self.instruments.inspection = Some(trace(&mut tracer, &asked)),
        }
    }

    /// The tree traced aside, once it is done; then the newest asked for meanwhile.
    pub(crate) fn receive_inspection(&mut self, ctx: &egui::Context) {
        let Some(tracing) = &mut self.instruments.tracing else {
            return;
        };
        let traced = match tracing.done.try_recv() {
            Err(TryRecvError::Empty) => return,
            Ok(traced) => Some(traced),
            Err(TryRecvError::Disconnected) => None,
        };
        let next = tracing.next.take();
        self.instruments.tracing = None;
        let traced_at = traced.as_ref().map(|i| (i.pixel, i.size));
        if traced.is_some() {
            self.instruments.inspection = traced;
        }
        // Another pixel asked for meanwhile; the same one with other controls is traced
        // again by `refresh_inspection`, which compares them.
        if let Some((pixel, size)) = next.filter(|&n| Some(n) != traced_at) {
            self.inspect(ctx, pixel, size);
        }
    }

    /// Traces the inspected pixel again when the controls changed what it shows.
    pub(crate) fn refresh_inspection(&mut self, ctx: &egui::Context) {
        let s = &self.settings;
        if let Some(i) = &self.instruments.inspection
            && (i.params != s.params || i.camera != s.camera)
            && s.params.validate().is_ok()
        {
            let (pixel, size) = (i.pixel, i.size);
            self.inspect(ctx, pixel, size);
        }
    }

    /// Whether an inspected tree is being traced on a thread of its own.
    pub fn tracing_inspection(&self) -> bool {
        self.instruments.tracing.is_some()
    }
}
