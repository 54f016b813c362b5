//! The system's own file dialogs, through rfd: the Windows and macOS panels, and on Linux
//! and the BSDs the desktop portal's (GNOME, KDE, ...) or else zenity's. Each runs on a
//! thread of its own (the window keeps drawing) and its answer comes back on a channel.
//! Where there is none, or one fails to appear, raylab's own dialog (files.rs) is used.

use super::files::{Choice, FileDialog, Purpose};
use crossbeam_channel::{Receiver, TryRecvError};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// An answer sooner than this after the dialog was asked for is not a person's "Cancel":
/// the dialog failed to appear (no portal, no zenity), and raylab's own is used instead.
const TOO_SOON: Duration = Duration::from_millis(300);

/// Whether the system has a file dialog for raylab to use: always on Windows and macOS;
/// on Linux and the BSDs, in a desktop session (`XDG_CURRENT_DESKTOP`, whose portal
/// answers) or with zenity on the `PATH`. `RAYLAB_FILE_DIALOG=raylab` says no everywhere.
pub(crate) fn available() -> bool {
    let env = |name: &str| std::env::var_os(name).map(|v| v.to_string_lossy().into_owned());
    decide(
        env("RAYLAB_FILE_DIALOG").as_deref(),
        env("XDG_CURRENT_DESKTOP").as_deref(),
        || on_path("zenity"),
    )
}

/// [`available`] from what it reads: the `RAYLAB_FILE_DIALOG` and `XDG_CURRENT_DESKTOP`
/// variables, and whether zenity is found.
fn decide(choice: Option<&str>, desktop: Option<&str>, zenity: impl Fn() -> bool) -> bool {
    if choice == Some("raylab") {
        return false;
    }
    if cfg!(any(target_os = "windows", target_os = "macos")) {
        return true;
    }
    desktop.is_some_and(|d| !d.is_empty()) || zenity()
}

/// Whether an executable named `name` is in one of the `PATH`'s folders.
fn on_path(name: &str) -> bool {
    std::env::var_os("PATH")
        .is_some_and(|paths| std::env::split_paths(&paths).any(|dir| dir.join(name).is_file()))
}

/// Whether rfd will fall back to zenity: on Linux and the BSDs, where there is no session
/// bus to reach a desktop portal on (no `DBUS_SESSION_BUS_ADDRESS`, no
/// `$XDG_RUNTIME_DIR/bus`).
fn zenity_likely() -> bool {
    let runtime_bus =
        std::env::var_os("XDG_RUNTIME_DIR").is_some_and(|dir| Path::new(&dir).join("bus").exists());
    cfg!(not(any(target_os = "windows", target_os = "macos")))
        && std::env::var_os("DBUS_SESSION_BUS_ADDRESS").is_none()
        && !runtime_bus
}

/// A system file dialog that is open: its answer, once the user gives it.
pub(crate) struct SystemDialog {
    purpose: Purpose,
    // Where it opened and the name it proposed: raylab's own dialog takes them over.
    dir: PathBuf,
    name: String,
    // The file chosen (or none), and how long the dialog took to give it.
    answer: Receiver<(Option<PathBuf>, Duration)>,
}

impl SystemDialog {
    /// Opens the system's dialog for `purpose` in `dir`, proposing `name` (for saving);
    /// the window (`ctx`) is woken to say where to look, and again by the answer.
    pub(crate) fn open(
        ctx: &egui::Context,
        purpose: Purpose,
        dir: &Path,
        name: &str,
    ) -> SystemDialog {
        let (send, answer) = crossbeam_channel::bounded(1);
        let (dir, name) = (dir.to_path_buf(), name.to_string());
        let shown = SystemDialog {
            purpose,
            dir: dir.clone(),
            name: name.clone(),
            answer,
        };
        let wake = ctx.clone();
        let run = move || {
            let asked = Instant::now();
            let dialog = rfd::AsyncFileDialog::new().set_directory(&dir);
            let file = match purpose {
                Purpose::Open => {
                    let mut open = dialog
                        .set_title("Open a scene or model")
                        .add_filter("Scenes and models", &["toml", "obj", "gltf", "glb"]);
                    // zenity (rfd's fallback on Linux) starts where its file name points
                    // and ignores the folder; the portal, Windows and macOS take the folder
                    // (and Windows would show a file name given for opening).
                    if cfg!(not(any(target_os = "windows", target_os = "macos"))) {
                        open = open.set_file_name(format!("{}/", dir.display()));
                    }
                    pollster::block_on(open.pick_file())
                }
                Purpose::SaveAs => {
                    // zenity again: the folder goes in the name, where no portal answers.
                    let name = if zenity_likely() {
                        dir.join(&name).display().to_string()
                    } else {
                        name
                    };
                    pollster::block_on(
                        dialog
                            .set_title("Save the image as…")
                            .set_file_name(name)
                            .add_filter("PNG", &["png"])
                            .add_filter("OpenEXR (linear radiance)", &["exr"])
                            .save_file(),
                    )
                }
            };
            // The window may have closed meanwhile: then no one is asking.
            let _ = send.send((file.map(|f| f.path().to_path_buf()), asked.elapsed()));
            wake.request_repaint();
        };
        if let Err(e) = std::thread::Builder::new()
            .name("file dialog".into())
            .spawn(run)
        {
            log::warn!("no thread for the system's file dialog: {e}");
        }
        ctx.request_repaint();
        shown
    }

    /// What it is for.
    pub(crate) fn purpose(&self) -> Purpose {
        self.purpose
    }

    /// raylab's own dialog in its place: the same folder and proposed name.
    pub(crate) fn instead(self) -> FileDialog {
        FileDialog::new(self.purpose, self.dir, self.name)
    }

    /// The user's answer so far, while a dimmed window says where to look; `None` when the
    /// dialog failed to appear (it answered too soon, or its thread is gone), for
    /// raylab's own dialog to take over.
    pub(crate) fn ui(&mut self, ctx: &egui::Context) -> Option<Choice> {
        let choice = match self.answer.try_recv() {
            Ok((Some(path), _)) => Choice::File(path),
            Ok((None, took)) if took < TOO_SOON => return None,
            Ok((None, _)) => Choice::Cancelled,
            Err(TryRecvError::Disconnected) => return None,
            Err(TryRecvError::Empty) => Choice::Pending,
        };
        if choice == Choice::Pending {
            let mut own = false;
            egui::Modal::new(egui::Id::unique("raylab-system-dialog")).show(ctx, |ui| {
                ui.label("Choose the file in the system's file dialog.");
                own = ui.button("Use raylab's dialog instead").clicked();
            });
            if own {
                return None;
            }
            // No repaint is asked for meanwhile: the answer's thread wakes the window.
        }
        Some(choice)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_system_dialog_is_used_where_there_is_one_unless_told_not_to() {
        let native = cfg!(any(target_os = "windows", target_os = "macos"));
        // A desktop session, or zenity: yes (and always on Windows and macOS).
        assert!(decide(None, Some("GNOME"), || false));
        assert!(decide(None, None, || true));
        // Xvfb or a bare X server with neither: only where the platform has its own.
        assert_eq!(decide(None, None, || false), native);
        assert_eq!(decide(None, Some(""), || false), native);
        // Told to use raylab's: never.
        assert!(!decide(Some("raylab"), Some("KDE"), || true));
        assert!(decide(Some("system"), Some("KDE"), || false));
    }

    /// What a dialog that gave `answer` after `took` says in the window's next frame.
    fn after(answer: Option<&str>, took: Duration) -> Option<Choice> {
        let (send, receive) = crossbeam_channel::bounded(1);
        let mut dialog = SystemDialog {
            purpose: Purpose::Open,
            dir: PathBuf::from("scenes"),
            name: String::new(),
            answer: receive,
        };
        if let Some(answer) = answer {
            let path = (!answer.is_empty()).then(|| PathBuf::from(answer));
            send.send((path, took)).expect("a slot");
        }
        let ctx = egui::Context::default();
        let mut choice = None;
        let _ = ctx.run_ui(egui::RawInput::default(), |ui| choice = dialog.ui(ui.ctx()));
        choice
    }

    #[test]
    fn a_dialog_that_answers_at_once_failed_and_raylabs_takes_over() {
        let (soon, late) = (Duration::from_millis(20), Duration::from_secs(2));
        // A file chosen, whenever: that file.
        let file = after(Some("glass.toml"), soon);
        assert_eq!(file, Some(Choice::File(PathBuf::from("glass.toml"))));
        // No file after a person's while: cancelled. At once: it never showed.
        assert_eq!(after(Some(""), late), Some(Choice::Cancelled));
        assert_eq!(after(Some(""), soon), None);
        // No answer yet: still choosing.
        assert_eq!(after(None, late), Some(Choice::Pending));
    }
}
