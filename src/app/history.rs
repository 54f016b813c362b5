//! Undo and redo of parameter changes (Ctrl+Z, Ctrl+Shift+Z). A change enters the history
//! once it settles, when no mouse button is held: a whole slider drag is one step.

use crate::params::Params;

/// The most steps kept.
const MAX_STEPS: usize = 200;

/// The parameters before each settled change, and those undone.
#[derive(Debug, Default)]
pub(crate) struct History {
    undo: Vec<Params>,
    redo: Vec<Params>,
    // The parameters as last settled.
    settled: Option<Params>,
}

impl History {
    /// Looks at the parameters once a frame: a change from the settled ones, with no
    /// button held, becomes a step (and what was undone can no longer be redone).
    pub(crate) fn observe(&mut self, current: &Params, button_held: bool) {
        match &self.settled {
            None => self.settled = Some(current.clone()),
            Some(settled) if settled != current && !button_held => {
                self.undo.push(settled.clone());
                if self.undo.len() > MAX_STEPS {
                    self.undo.remove(0);
                }
                self.redo.clear();
                self.settled = Some(current.clone());
            }
            Some(_) => {}
        }
    }

    /// The parameters before the last step, if any; `current` can be redone.
    pub(crate) fn undo(&mut self, current: &Params) -> Option<Params> {
        let previous = self.undo.pop()?;
        self.redo.push(current.clone());
        self.settled = Some(previous.clone());
        Some(previous)
    }

    /// The parameters of the step last undone, if any.
    pub(crate) fn redo(&mut self, current: &Params) -> Option<Params> {
        let next = self.redo.pop()?;
        self.undo.push(current.clone());
        self.settled = Some(next.clone());
        Some(next)
    }

    /// Whether there is a step to undo, and one to redo.
    pub(crate) fn can(&self) -> (bool, bool) {
        (!self.undo.is_empty(), !self.redo.is_empty())
    }

    /// A new scene: its parameters start a history of their own.
    pub(crate) fn clear(&mut self) {
        *self = History::default();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn with_ior(ior: f32) -> Params {
        Params {
            ior: Some(ior),
            ..Params::default()
        }
    }

    #[test]
    fn a_drag_is_one_step_and_undo_redo_walk_it_both_ways() {
        let mut h = History::default();
        h.observe(&Params::default(), false);
        // Dragging through 1.6, 1.7, 1.8 with the button held, released at 1.8.
        for ior in [1.6, 1.7, 1.8] {
            h.observe(&with_ior(ior), true);
        }
        h.observe(&with_ior(1.8), false);
        h.observe(&with_ior(2.0), false);
        assert_eq!(h.undo(&with_ior(2.0)), Some(with_ior(1.8)));
        assert_eq!(h.undo(&with_ior(1.8)), Some(Params::default()));
        assert_eq!(h.undo(&Params::default()), None);
        assert_eq!(h.redo(&Params::default()), Some(with_ior(1.8)));
        // A new change forgets what was undone.
        h.observe(&with_ior(1.33), false);
        assert_eq!(h.redo(&with_ior(1.33)), None);
        assert_eq!(h.undo(&with_ior(1.33)), Some(with_ior(1.8)));
    }
}
