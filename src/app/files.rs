//! raylab's own file dialog, drawn with egui (Open…, Save as…), and snapshot file names.
//!
//! The system's dialog is used where there is one (system_dialog.rs); this one is for
//! where there is none (minimal desktops, Xvfb) and for the tests, which must not open a
//! window of the system's. Written here rather than taken from a crate: egui_file 0.29
//! (the one for egui 0.37) has neither shortcuts to the home folder nor a question before
//! replacing a file, the two things this one adds.

use crate::render::output::{safe_file_stem, unused_png};
use egui::{Key, RichText};
use std::path::{Path, PathBuf};
use std::time::{SystemTime, UNIX_EPOCH};

/// What the dialog is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Purpose {
    /// Open a scene (.toml) or a model (.obj, .gltf, .glb).
    Open,
    /// Save the image as PNG or EXR.
    SaveAs,
}

/// What the user chose.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) enum Choice {
    /// Still choosing.
    Pending,
    /// Closed without a choice.
    Cancelled,
    /// This file.
    File(PathBuf),
}

/// The state of an open file dialog.
pub(crate) struct FileDialog {
    /// What it is for.
    pub purpose: Purpose,
    dir: PathBuf,
    /// The file name typed or picked.
    pub name: String,
    entries: Vec<(String, bool)>,
    error: Option<String>,
    /// A file chosen for saving that exists: replaced only once the user says so.
    confirm: Option<PathBuf>,
    /// The shortcuts to other folders, looked up once when the dialog opens.
    places: Vec<(String, PathBuf)>,
}

impl FileDialog {
    /// A dialog showing `dir`, with `name` proposed (for saving).
    pub fn new(purpose: Purpose, dir: PathBuf, name: String) -> Self {
        let mut d = FileDialog {
            purpose,
            dir,
            name,
            entries: Vec::new(),
            error: None,
            confirm: None,
            places: places(),
        };
        d.list();
        d
    }

    fn wanted(&self, name: &str) -> bool {
        let lower = name.to_ascii_lowercase();
        match self.purpose {
            Purpose::Open => crate::scene::opens(Path::new(&lower)),
            Purpose::SaveAs => lower.ends_with(".png") || lower.ends_with(".exr"),
        }
    }

    /// Reads the folder: sub-folders first, then the files of the wanted kinds.
    fn list(&mut self) {
        self.entries.clear();
        match std::fs::read_dir(&self.dir) {
            Ok(read) => {
                self.error = None;
                for entry in read.flatten() {
                    let name = entry.file_name().to_string_lossy().into_owned();
                    if name.starts_with('.') {
                        continue;
                    }
                    let is_dir = entry.file_type().is_ok_and(|t| t.is_dir());
                    if is_dir || self.wanted(&name) {
                        self.entries.push((name, is_dir));
                    }
                }
                self.entries.sort_by(|a, b| {
                    b.1.cmp(&a.1)
                        .then_with(|| a.0.to_lowercase().cmp(&b.0.to_lowercase()))
                });
            }
            Err(e) => self.error = Some(format!("{}: {e}", self.dir.display())),
        }
    }

    fn enter(&mut self, dir: PathBuf) {
        self.dir = dir;
        self.list();
    }

    /// Draws the dialog; returns the choice.
    pub fn ui(&mut self, ctx: &egui::Context) -> Choice {
        let mut choice = Choice::Pending;
        let title = match self.purpose {
            Purpose::Open => "Open a scene or model",
            Purpose::SaveAs => "Save the image as…",
        };
        let modal = egui::Modal::new(egui::Id::unique("raylab-file-dialog")).show(ctx, |ui| {
            ui.set_width(520.0);
            ui.heading(title);
            ui.horizontal(|ui| {
                if ui.button("Up").on_hover_text("The parent folder").clicked()
                    && let Some(parent) = self.dir.parent()
                {
                    self.enter(parent.to_path_buf());
                }
                ui.label(RichText::new(self.dir.display().to_string()).monospace());
            });
            ui.horizontal_wrapped(|ui| {
                let mut go = None;
                for (label, place) in &self.places {
                    let tip = place.display().to_string();
                    if ui.small_button(label).on_hover_text(tip).clicked() {
                        go = Some(place.clone());
                    }
                }
                if let Some(place) = go {
                    self.enter(place);
                }
            });
            if let Some(e) = &self.error {
                ui.colored_label(ui.visuals().error_fg_color, e);
            }
            egui::ScrollArea::vertical()
                .max_height(300.0)
                .show(ui, |ui| {
                    let mut go = None;
                    for (name, is_dir) in &self.entries {
                        let label = if *is_dir {
                            format!("{name}/")
                        } else {
                            name.clone()
                        };
                        let selected = !*is_dir && *name == self.name;
                        let r = ui.selectable_label(selected, label);
                        if r.clicked() {
                            if *is_dir {
                                go = Some(self.dir.join(name));
                            } else {
                                self.name = name.clone();
                            }
                        }
                        if r.double_clicked() && !*is_dir {
                            choice = Choice::File(self.dir.join(name));
                        }
                    }
                    if let Some(dir) = go {
                        self.enter(dir);
                    }
                });
            ui.horizontal(|ui| {
                ui.label("File name:");
                let edit = ui.add(egui::TextEdit::singleline(&mut self.name).desired_width(300.0));
                if edit.lost_focus()
                    && ui.input(|i| i.key_pressed(Key::Enter))
                    && !self.name.is_empty()
                {
                    choice = Choice::File(self.dir.join(&self.name));
                }
            });
            if self.purpose == Purpose::SaveAs {
                ui.horizontal(|ui| {
                    ui.label("Format:");
                    for (ext, tip) in [
                        ("png", "8-bit sRGB with the display exposure"),
                        ("exr", "linear radiance, 32-bit float"),
                    ] {
                        let on = self.name.to_ascii_lowercase().ends_with(&format!(".{ext}"));
                        if ui
                            .selectable_label(on, ext.to_uppercase())
                            .on_hover_text(tip)
                            .clicked()
                        {
                            let stem = Path::new(&self.name)
                                .file_stem()
                                .map_or("image".into(), |s| s.to_string_lossy().into_owned());
                            self.name = format!("{stem}.{ext}");
                        }
                    }
                });
            }
            if let Some(path) = self.confirm.clone() {
                let name = path
                    .file_name()
                    .map_or(String::new(), |n| n.to_string_lossy().into_owned());
                ui.colored_label(
                    ui.visuals().warn_fg_color,
                    format!("{name} exists. Replace it (and its sidecar)?"),
                );
                ui.horizontal(|ui| {
                    if ui.button("Replace").clicked() {
                        choice = Choice::File(path);
                    }
                    if ui.button("Keep it").clicked() {
                        self.confirm = None;
                    }
                });
                return;
            }
            ui.horizontal(|ui| {
                let verb = if self.purpose == Purpose::Open {
                    "Open"
                } else {
                    "Save"
                };
                if ui
                    .add_enabled(!self.name.is_empty(), egui::Button::new(verb))
                    .clicked()
                {
                    choice = Choice::File(self.dir.join(&self.name));
                }
                if ui.button("Cancel").clicked() {
                    choice = Choice::Cancelled;
                }
            });
        });
        if modal.should_close() && choice == Choice::Pending {
            choice = Choice::Cancelled;
        }
        // A typed path may name a folder: enter it instead of choosing it.
        if let Choice::File(path) = &choice
            && path.is_dir()
        {
            let dir = path.clone();
            self.name.clear();
            self.enter(dir);
            return Choice::Pending;
        }
        // Saving over a file asks first (the answer comes back as the chosen path).
        if let Choice::File(path) = &choice
            && self.purpose == Purpose::SaveAs
            && self.confirm.as_ref() != Some(path)
            && path.symlink_metadata().is_ok()
        {
            self.confirm = Some(path.clone());
            return Choice::Pending;
        }
        choice
    }
}

/// Shortcuts to where files usually are: the home folder and its Desktop and Documents,
/// the drives on Windows, the volumes on macOS, the root elsewhere; only those that exist.
fn places() -> Vec<(String, PathBuf)> {
    let mut places = Vec::new();
    let home = std::env::var_os("HOME")
        .or_else(|| std::env::var_os("USERPROFILE"))
        .map(PathBuf::from)
        .filter(|h| h.is_dir());
    if let Some(home) = home {
        for sub in ["Desktop", "Documents", "Pictures"] {
            if home.join(sub).is_dir() {
                places.push((sub.to_string(), home.join(sub)));
            }
        }
        places.insert(0, ("Home".to_string(), home));
    }
    if cfg!(windows) {
        for letter in 'A'..='Z' {
            let drive = PathBuf::from(format!("{letter}:\\"));
            if drive.is_dir() {
                places.push((format!("{letter}:"), drive));
            }
        }
    } else if cfg!(target_os = "macos") {
        places.push(("Volumes".to_string(), PathBuf::from("/Volumes")));
    } else {
        places.push(("/".to_string(), PathBuf::from("/")));
    }
    places
}

/// `YYYYMMDD-HHMMSS` in UTC for a time since the epoch.
pub(crate) fn timestamp(t: SystemTime) -> String {
    let secs = t.duration_since(UNIX_EPOCH).map_or(0, |d| d.as_secs()) as i64;
    let (days, rem) = (secs.div_euclid(86_400), secs.rem_euclid(86_400));
    // Civil date from days since 1970-01-01 (Howard Hinnant's algorithm).
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!(
        "{year:04}{month:02}{day:02}-{:02}{:02}{:02}",
        rem / 3600,
        rem % 3600 / 60,
        rem % 60
    )
}

/// `dir/<scene>-<timestamp>.png`, with `-2`, `-3`, ... if that file exists already.
pub(crate) fn snapshot_path(dir: &Path, scene: &str, t: SystemTime) -> PathBuf {
    let stem = format!("{}-{}", safe_file_stem(scene), timestamp(t));
    unused_png(dir, &stem)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

    #[test]
    fn timestamps_are_utc_calendar_dates() {
        assert_eq!(timestamp(UNIX_EPOCH), "19700101-000000");
        // 2026-11-19 04:39:05 UTC (checked with Python's datetime).
        let t = UNIX_EPOCH + Duration::from_secs(1_795_063_145);
        assert_eq!(timestamp(t), "20261119-043905");
        // A leap day.
        assert_eq!(
            timestamp(UNIX_EPOCH + Duration::from_secs(951_782_400)),
            "20000229-000000"
        );
    }

    #[test]
    fn snapshot_names_never_overwrite() {
        let dir = tempfile::tempdir().unwrap();
        let t = UNIX_EPOCH + Duration::from_secs(86_400);
        let first = snapshot_path(dir.path(), "ray tree", t);
        assert_eq!(first.file_name().unwrap(), "ray_tree-19700102-000000.png");
        std::fs::write(&first, b"x").unwrap();
        let second = snapshot_path(dir.path(), "ray tree", t);
        assert_eq!(
            second.file_name().unwrap(),
            "ray_tree-19700102-000000-2.png"
        );
    }
}
