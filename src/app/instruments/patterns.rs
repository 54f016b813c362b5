//! Where one pixel's samples fall: in the pixel, on the lens, in the shutter interval.

/// Where the samples of one pixel fall, for the parameters' pattern and count: the image
/// position inside the pixel, the point on the lens, and the time in the shutter. A
/// pinhole (aperture 0) uses no point on the lens and a shutter of 0 no time: their
/// panels say so, with no marks.
pub(crate) fn sample_pattern_ui(ui: &mut egui::Ui, params: &crate::params::Params) {
    let (pattern, spp, seed) = (params.pattern, params.spp, params.seed);
    let lens_used = params.aperture > 0.0;
    let time_used = params.shutter > 0.0;
    use crate::camera::CameraSample;
    use crate::math::SampleStream;
    use crate::math::sampling::concentric_disk;
    let n = spp.min(1024);
    let mut pixel = Vec::new();
    let mut lens = Vec::new();
    let mut time = Vec::new();
    for s in 0..n {
        let cs = CameraSample::draw(
            &mut SampleStream::with_pattern(pattern, spp, seed, 0, s),
            true,
            true,
        );
        pixel.push(cs.pixel);
        lens.push(concentric_disk(cs.lens));
        time.push(cs.time);
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
                let points: &[glam::Vec2] = match (is_lens, lens_used) {
                    (false, _) => &pixel,
                    (true, true) => &lens,
                    (true, false) => &[],
                };
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
                if is_lens && !lens_used {
                    ui.label(PINHOLE);
                }
            });
        }
    });
    ui.label(TIME_TITLE[usize::from(time_used)]);
    let (rect, _) = ui.allocate_exact_size(egui::vec2(408.0, 24.0), egui::Sense::hover());
    let p = ui.painter_at(rect);
    p.rect_filled(rect, 0.0, egui::Color32::from_gray(30));
    for t in time.iter().filter(|_| time_used) {
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

/// Under the lens panel of a pinhole, which takes no point on the lens (under the
/// panel, so that the two panels' titles stay one line and level).
const PINHOLE: &str = "None: a pinhole (aperture 0)";

/// The shutter panel's title: unused (shutter 0), used.
const TIME_TITLE: [&str; 2] = [
    "Time in the shutter interval: none, the shutter is 0 (every sample at its opening)",
    "Time in the shutter interval",
];
