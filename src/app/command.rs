//! What the window can be asked to do, as values: a key, a toolbar button or a menu item
//! each queues a [`Command`], and [`RaylabApp::apply_commands`] carries them out in one
//! place, at the end of the frame they were asked in (the keys read before any widget
//! could take them), so that the whole of the next frame shows the state they left. The keys, the words on the buttons and menus,
//! their tooltips and the help overlay all come from one table, [`COMMANDS`].

use super::RaylabApp;
use egui::{Context, Event, Key, Modifiers};

/// Something the window does when asked by a key, a button or a menu.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Command {
    /// Enter or leave presentation mode.
    Present,
    /// Show or hide the list of shortcuts.
    Help,
    /// Close the list of shortcuts, else leave presentation mode.
    Leave,
    /// The next slide (presentation mode).
    NextSlide,
    /// The previous slide (presentation mode).
    PreviousSlide,
    /// Step the slide's first control up (presentation mode).
    ControlUp,
    /// Step the slide's first control down (presentation mode).
    ControlDown,
    /// Pause or resume refining.
    Pause,
    /// Refine again from the first sample.
    Restart,
    /// Fit the image to the window.
    Fit,
    /// One image pixel per screen pixel.
    OneToOne,
    /// Undo the last parameter change.
    Undo,
    /// Redo the change last undone.
    Redo,
    /// Every parameter and the camera back to the scene's.
    Reset,
    /// Save a snapshot (image and parameters).
    Save,
    /// Save the image where the user chooses.
    SaveAs,
    /// Open a scene file.
    Open,
    /// Show slide number `.0` (counted from 0), from the Lecture menu.
    GoToSlide(usize),
}

/// Which modifiers a key takes to mean a command.
#[derive(Clone, Copy, Debug)]
enum Mods {
    /// Any (or none).
    Any,
    /// None at all.
    None,
    /// Ctrl (⌘ on a Mac), no Shift.
    Command,
    /// Ctrl (⌘) and Shift.
    CommandShift,
}

impl Mods {
    fn hold(self, m: Modifiers) -> bool {
        match self {
            Mods::Any => true,
            Mods::None => m.is_none(),
            Mods::Command => m.command && !m.shift && !m.alt,
            Mods::CommandShift => m.command && m.shift && !m.alt,
        }
    }
}

/// When a command's keys are live.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum When {
    /// Always, even while a text field has the keyboard.
    Always,
    /// While no text field has the keyboard and no file dialog is open.
    Free,
    /// In presentation mode (where no text field is shown).
    Presenting,
    /// Out of presentation mode, while no text field has the keyboard and no dialog is
    /// open (a presentation clicker may send Space: it does not pause a lecture).
    FreeAtTheDesk,
    /// While the help or presentation mode is open (else the key is left to the widgets).
    Open,
}

/// One command's row of the table: its keys (and the text typed that means it), the keys
/// as the help lists them, the words on its button or menu item, what it does, and when
/// its keys are live.
pub(crate) struct Entry {
    pub(crate) command: Command,
    keys: &'static [(Mods, Key)],
    typed: Option<&'static str>,
    /// The keys, as the help overlay and docs/window.md list them (empty: no key).
    pub(crate) keys_text: &'static str,
    /// The words on its button or menu item.
    pub(crate) label: &'static str,
    /// What it does: the help overlay's second column, and the tooltip.
    pub(crate) what: &'static str,
    when: When,
}

/// Every command with a row, in the order the help lists them.
pub(crate) const COMMANDS: &[Entry] = &[
    Entry {
        command: Command::Present,
        keys: &[(Mods::Any, Key::F5), (Mods::Any, Key::F11)],
        typed: None,
        keys_text: "F5 or F11",
        label: "Presentation mode",
        what: "presentation mode: the image fullscreen, panels hidden, caption large",
        when: When::Always,
    },
    Entry {
        command: Command::Leave,
        keys: &[(Mods::Any, Key::Escape)],
        typed: None,
        keys_text: "Esc",
        label: "Leave",
        what: "leave presentation mode (or close the shortcut list)",
        when: When::Open,
    },
    Entry {
        command: Command::NextSlide,
        keys: &[
            (Mods::None, Key::PageDown),
            (Mods::None, Key::ArrowRight),
            (Mods::None, Key::ArrowDown),
        ],
        typed: None,
        keys_text: "Page Down, Right or Down arrow",
        label: "Next slide",
        what: "next slide (presentation mode)",
        when: When::Presenting,
    },
    Entry {
        command: Command::PreviousSlide,
        keys: &[
            (Mods::None, Key::PageUp),
            (Mods::None, Key::ArrowLeft),
            (Mods::None, Key::ArrowUp),
        ],
        typed: None,
        keys_text: "Page Up, Left or Up arrow",
        label: "Previous slide",
        what: "previous slide (presentation mode)",
        when: When::Presenting,
    },
    Entry {
        command: Command::Pause,
        keys: &[(Mods::None, Key::Space)],
        typed: None,
        keys_text: "Space",
        label: "Pause",
        what: "pause or resume refining (not in presentation mode, where a clicker may send it)",
        when: When::FreeAtTheDesk,
    },
    Entry {
        command: Command::ControlUp,
        keys: &[(Mods::None, Key::CloseBracket)],
        typed: None,
        keys_text: "]",
        label: "Control up",
        what: "step the slide's first control up (presentation mode)",
        when: When::Presenting,
    },
    Entry {
        command: Command::ControlDown,
        keys: &[(Mods::None, Key::OpenBracket)],
        typed: None,
        keys_text: "[",
        label: "Control down",
        what: "step the slide's first control down (presentation mode)",
        when: When::Presenting,
    },
    Entry {
        command: Command::Restart,
        keys: &[(Mods::None, Key::R)],
        typed: None,
        keys_text: "R",
        label: "Restart",
        what: "restart refining from the first sample",
        when: When::Free,
    },
    Entry {
        command: Command::Fit,
        keys: &[(Mods::None, Key::F)],
        typed: None,
        keys_text: "F",
        label: "Fit",
        what: "fit the image to the window",
        when: When::Free,
    },
    Entry {
        command: Command::OneToOne,
        keys: &[(Mods::None, Key::Num1)],
        typed: None,
        keys_text: "1",
        label: "1:1",
        what: "one image pixel per screen pixel",
        when: When::Free,
    },
    Entry {
        command: Command::Undo,
        keys: &[(Mods::Command, Key::Z)],
        typed: None,
        keys_text: "Ctrl+Z",
        label: "Undo",
        what: "undo the last parameter change",
        when: When::Free,
    },
    Entry {
        command: Command::Redo,
        keys: &[(Mods::CommandShift, Key::Z), (Mods::Command, Key::Y)],
        typed: None,
        keys_text: "Ctrl+Shift+Z or Ctrl+Y",
        label: "Redo",
        what: "redo the change last undone",
        when: When::Free,
    },
    Entry {
        command: Command::Reset,
        keys: &[],
        typed: None,
        keys_text: "",
        label: "Reset",
        what: "every parameter and the camera back to the scene's defaults",
        when: When::Free,
    },
    Entry {
        command: Command::Save,
        keys: &[(Mods::Command, Key::S)],
        typed: None,
        keys_text: "Ctrl+S",
        label: "Save snapshot",
        what: "save a snapshot (image and parameters)",
        when: When::Always,
    },
    Entry {
        command: Command::SaveAs,
        keys: &[],
        typed: None,
        keys_text: "",
        label: "Save as…",
        what: "choose where to save the image, and PNG or EXR",
        when: When::Always,
    },
    Entry {
        command: Command::Open,
        keys: &[(Mods::Command, Key::O)],
        typed: None,
        keys_text: "Ctrl+O",
        label: "Open…",
        what: "open a scene file",
        when: When::Always,
    },
    Entry {
        command: Command::Help,
        keys: &[(Mods::Any, Key::F1)],
        typed: Some("?"),
        keys_text: "F1 or ?",
        label: "Keyboard shortcuts",
        what: "list these shortcuts",
        when: When::Always,
    },
];

/// Keys egui itself answers, listed in the help with the table's.
pub(crate) const EGUI_KEYS: &[(&str, &str)] = &[(
    "Ctrl+= / Ctrl+- / Ctrl+0",
    "UI scale up, down, back to 100 %",
)];

impl Command {
    /// Its row of [`COMMANDS`] (every command but [`Command::GoToSlide`] has one: a unit
    /// test says so).
    pub(crate) fn entry(self) -> Option<&'static Entry> {
        COMMANDS.iter().find(|e| e.command == self)
    }
}

impl Entry {
    /// Its tooltip: what it does, and its keys.
    fn hint(&self) -> String {
        let mut what = self.what.to_string();
        if let Some(first) = what.get(..1) {
            what.replace_range(..1, &first.to_uppercase());
        }
        match self.keys_text {
            "" => format!("{what}."),
            keys => format!("{what} ({keys})."),
        }
    }
}

/// What decides which keys are live in a frame.
#[derive(Clone, Copy, Debug)]
struct KeyState {
    presenting: bool,
    /// The list of shortcuts is shown.
    help: bool,
    /// A text field has the keyboard, or a file dialog is open.
    busy: bool,
}

/// The commands this frame's key events (and typed text) ask for, in order, every press
/// counted (three quick clicks of a presentation clicker can land in one frame); the
/// events taken are consumed, so that no widget also acts on them.
fn commands_of_keys(ctx: &Context, state: KeyState) -> Vec<Command> {
    let live = |when: When| match when {
        When::Always => true,
        When::Free => !state.busy,
        When::Presenting => state.presenting,
        When::FreeAtTheDesk => !state.busy && !state.presenting,
        When::Open => state.help || state.presenting,
    };
    let of_event = |e: &Event| -> Option<Command> {
        COMMANDS
            .iter()
            .filter(|c| live(c.when))
            .find(|c| match e {
                Event::Key {
                    key,
                    pressed: true,
                    modifiers,
                    ..
                } => c.keys.iter().any(|(m, k)| k == key && m.hold(*modifiers)),
                // Typed text means a command only while no text field takes it.
                Event::Text(t) => !state.busy && c.typed == Some(t.as_str()),
                _ => false,
            })
            .map(|c| c.command)
    };
    ctx.input_mut(|i| {
        let mut commands = Vec::new();
        i.events.retain(|e| match of_event(e) {
            Some(c) => {
                commands.push(c);
                false
            }
            None => true,
        });
        commands
    })
}

impl RaylabApp {
    /// Queues `command`, carried out at the end of this frame.
    pub(super) fn ask(&mut self, ctx: &Context, command: Command) {
        self.commands.push(command);
        ctx.request_repaint();
    }

    /// A button for `command` (its label, and its tooltip with its keys), enabled where
    /// `enabled`: a click queues it.
    pub(super) fn command_button(&mut self, ui: &mut egui::Ui, command: Command, enabled: bool) {
        let Some(entry) = command.entry() else {
            return;
        };
        let label = match command {
            Command::Pause if self.main.paused() => "Resume",
            _ => entry.label,
        };
        if ui
            .add_enabled(enabled, egui::Button::new(label))
            .on_hover_text(entry.hint())
            .clicked()
        {
            self.ask(ui.ctx(), command);
        }
    }

    /// A menu item for `command`: its label, its keys at the right, and its tooltip; a
    /// click queues it and closes the menu.
    pub(super) fn command_item(&mut self, ui: &mut egui::Ui, command: Command) {
        let Some(entry) = command.entry() else {
            return;
        };
        let item = egui::Button::new(entry.label).shortcut_text(entry.keys_text);
        if ui.add(item).on_hover_text(entry.hint()).clicked() {
            self.ask(ui.ctx(), command);
            ui.close();
        }
    }

    /// This frame's keys, read before any widget sees them (and consumed): queued with
    /// what the buttons and menus ask for while the panels are drawn.
    pub(super) fn read_keys(&mut self, ctx: &Context) {
        let state = KeyState {
            presenting: self.hall.presenting,
            help: self.hall.help,
            busy: ctx.egui_wants_keyboard_input() || self.dialog.is_some(),
        };
        let keys = commands_of_keys(ctx, state);
        self.commands.extend(keys);
    }

    /// Every command queued this frame carried out, in order, after the panels are drawn
    /// and before the engines are told: the one place the window acts on what it is asked.
    pub(super) fn apply_commands(&mut self, ctx: &Context) {
        // Slide steps in a row are taken as one: three clicks go three slides on, with one
        // slide loaded, not three.
        let mut slides = 0;
        for command in std::mem::take(&mut self.commands) {
            match command {
                Command::NextSlide => slides += 1,
                Command::PreviousSlide => slides -= 1,
                _ => {
                    self.step_slides(std::mem::take(&mut slides));
                    self.apply(ctx, command);
                }
            }
        }
        self.step_slides(slides);
    }

    fn step_slides(&mut self, by: i32) {
        if by != 0 {
            self.step_slide(by);
        }
    }

    /// Carries out one command.
    fn apply(&mut self, ctx: &Context, command: Command) {
        match command {
            Command::Present => self.set_presenting(ctx, !self.hall.presenting),
            Command::Help => self.hall.help = !self.hall.help,
            Command::Leave => {
                if self.hall.help {
                    self.hall.help = false;
                } else if self.hall.presenting {
                    self.set_presenting(ctx, false);
                }
            }
            Command::NextSlide => self.step_slides(1),
            Command::PreviousSlide => self.step_slides(-1),
            Command::ControlUp => self.step_first_control(true),
            Command::ControlDown => self.step_first_control(false),
            Command::Pause => self.main.toggle_pause(),
            Command::Restart => self.main.restart(),
            Command::Fit => self.view.fit(),
            Command::OneToOne => self.view.one_to_one(ctx.pixels_per_point()),
            Command::Undo => self.step_history(false),
            Command::Redo => self.step_history(true),
            Command::Reset => self.reset_to_defaults(),
            Command::Save => self.save_snapshot(ctx),
            Command::SaveAs => self.save_as_dialog(ctx),
            Command::Open => self.open_dialog(ctx),
            Command::GoToSlide(i) => self.go_to_slide(i),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_command_but_a_slide_number_has_one_row_and_no_key_means_two_commands() {
        use Command::*;
        let all = [
            Present,
            Help,
            Leave,
            NextSlide,
            PreviousSlide,
            ControlUp,
            ControlDown,
            Pause,
            Restart,
            Fit,
            OneToOne,
            Undo,
            Redo,
            Reset,
            Save,
            SaveAs,
            Open,
        ];
        for c in all {
            let rows = COMMANDS.iter().filter(|e| e.command == c).count();
            assert_eq!(rows, 1, "{c:?}");
        }
        assert_eq!(COMMANDS.len(), all.len());
        assert!(GoToSlide(0).entry().is_none());
        for e in COMMANDS {
            assert!(e.hint().ends_with('.'), "{:?}", e.command);
        }
        // A key with the same modifiers in two rows would be read as the first alone,
        // unless the rows are never live at once.
        for (i, a) in COMMANDS.iter().enumerate() {
            for b in &COMMANDS[i + 1..] {
                for (ma, ka) in a.keys {
                    for (mb, kb) in b.keys {
                        assert!(
                            ka != kb || format!("{ma:?}") != format!("{mb:?}"),
                            "{:?} and {:?} share {ka:?}",
                            a.command,
                            b.command
                        );
                    }
                }
            }
        }
    }

    /// The commands `events` mean in a frame with `state`, and the events left for the
    /// widgets.
    fn keys_in(state: KeyState, events: Vec<Event>) -> (Vec<Command>, usize) {
        let ctx = Context::default();
        let mut out = (Vec::new(), 0);
        let input = egui::RawInput {
            events,
            ..Default::default()
        };
        let _ = ctx.run_ui(input, |ui| {
            out.0 = commands_of_keys(ui.ctx(), state);
            out.1 = ui.input(|i| i.events.len());
        });
        out
    }

    fn press(key: Key, modifiers: Modifiers) -> Event {
        Event::Key {
            key,
            physical_key: None,
            pressed: true,
            repeat: false,
            modifiers,
        }
    }

    #[test]
    fn each_key_means_its_command_only_where_it_is_live_and_every_press_counts() {
        use Command::*;
        let desk = KeyState {
            presenting: false,
            help: false,
            busy: false,
        };
        let hall = KeyState {
            presenting: true,
            ..desk
        };
        let typing = KeyState { busy: true, ..desk };
        let none = Modifiers::NONE;
        let clicks = || {
            vec![
                press(Key::PageDown, none),
                press(Key::PageDown, none),
                press(Key::Space, none),
                press(Key::CloseBracket, none),
            ]
        };
        // A clicker's three presses in one frame: two slides on, Space left alone (it does
        // not pause a lecture), the control stepped; the Space goes to the widgets.
        assert_eq!(
            keys_in(hall, clicks()),
            (vec![NextSlide, NextSlide, ControlUp], 1)
        );
        // At the desk the slide keys are the widgets' (arrows move sliders), Space pauses.
        assert_eq!(keys_in(desk, clicks()), (vec![Pause], 3));
        // While a text field has the keyboard, plain keys and typed text are its own;
        // Ctrl+S still saves.
        let typed = vec![
            press(Key::R, none),
            Event::Text("?".into()),
            press(Key::S, Modifiers::COMMAND),
        ];
        assert_eq!(keys_in(typing, typed.clone()), (vec![Save], 2));
        assert_eq!(keys_in(desk, typed), (vec![Restart, Help, Save], 0));
        let undo = vec![
            press(Key::Z, Modifiers::COMMAND),
            press(Key::Z, Modifiers::COMMAND | Modifiers::SHIFT),
        ];
        assert_eq!(keys_in(desk, undo), (vec![Undo, Redo], 0));
        // Esc is the widgets' unless help or a presentation is open.
        let esc = || vec![press(Key::Escape, none)];
        assert_eq!(keys_in(desk, esc()), (vec![], 1));
        assert_eq!(keys_in(hall, esc()), (vec![Leave], 0));
    }

    #[test]
    fn modifiers_tell_undo_from_redo() {
        let ctrl = Modifiers::COMMAND;
        let ctrl_shift = Modifiers::COMMAND | Modifiers::SHIFT;
        assert!(Mods::Command.hold(ctrl) && !Mods::Command.hold(ctrl_shift));
        assert!(Mods::CommandShift.hold(ctrl_shift) && !Mods::CommandShift.hold(ctrl));
        assert!(Mods::None.hold(Modifiers::NONE) && !Mods::None.hold(Modifiers::SHIFT));
        assert!(Mods::Any.hold(Modifiers::ALT));
    }
}
