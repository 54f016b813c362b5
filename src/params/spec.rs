//! What a parameter's entry in the table says (its kind, choices, slider and words), and
//! how its values are checked against it.

/// What values a parameter takes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Kind {
    /// A whole number from `min` to `max`.
    Count {
        /// Smallest value.
        min: u64,
        /// Largest value.
        max: u64,
    },
    /// A real number from `min` to `max` (above `min`, if `open_min`).
    Number {
        /// Smallest value.
        min: f64,
        /// Largest value.
        max: f64,
        /// The value must exceed `min`.
        open_min: bool,
    },
    /// One of these choices.
    Choice(&'static [Choice]),
    /// A word meaning "off", or a real number from `min` to `max`.
    WordOrNumber {
        /// The word.
        word: &'static str,
        /// Smallest value.
        min: f64,
        /// Largest value.
        max: f64,
    },
}

/// One value of a choice parameter: its word, its label in the window and what it does.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Choice {
    /// The word in `--set`, scene files and sidecars.
    pub word: &'static str,
    /// Its label in the window's menu.
    pub label: &'static str,
    /// What it does, for the menu entry's tooltip and the documentation.
    pub explain: &'static str,
}

pub(super) const fn choice(
    word: &'static str,
    label: &'static str,
    explain: &'static str,
) -> Choice {
    Choice {
        word,
        label,
        explain,
    }
}

/// The range a slider offers, within the valid range.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SliderRange {
    /// Left end.
    pub min: f64,
    /// Right end.
    pub max: f64,
    /// Logarithmic spacing.
    pub log: bool,
}

/// One parameter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spec {
    /// Its name in `--set`, scene files' `[params]` and sidecars.
    pub name: &'static str,
    /// Its label in the window.
    pub label: &'static str,
    /// Its values.
    pub kind: Kind,
    /// Its unit, if it has one.
    pub unit: &'static str,
    /// What it does, in one line.
    pub doc: &'static str,
    /// The lecture's explanation, for the window's tooltip.
    pub explain: &'static str,
    /// The window's slider, if it has one.
    pub slider: Option<SliderRange>,
    /// It changes only how the image is shown, not the render.
    pub display_only: bool,
}

pub(super) const fn slider(min: f64, max: f64) -> Option<SliderRange> {
    Some(SliderRange {
        min,
        max,
        log: false,
    })
}

pub(super) const fn log_slider(min: f64, max: f64) -> Option<SliderRange> {
    Some(SliderRange {
        min,
        max,
        log: true,
    })
}

pub(super) const fn number(min: f64, max: f64) -> Kind {
    Kind::Number {
        min,
        max,
        open_min: false,
    }
}

/// The words of `choices`, comma separated.
fn words(choices: &[Choice]) -> String {
    choices
        .iter()
        .map(|c| c.word)
        .collect::<Vec<_>>()
        .join(", ")
}

impl Spec {
    /// The valid values, as words: "1 to 1048576", "0 to 1 frame time", "> 0 scene units",
    /// "split, stochastic".
    pub fn range_text(&self) -> String {
        let unit = if self.unit.is_empty() {
            String::new()
        } else {
            format!(" {}", self.unit)
        };
        match self.kind {
            Kind::Count { min, max } if max == u64::MAX => format!("{min} or more{unit}"),
            Kind::Count { min, max } => format!("{min} to {max}{unit}"),
            Kind::Number {
                min,
                open_min: true,
                max,
                ..
            } if max.is_infinite() => format!("> {min}{unit}"),
            Kind::Number {
                min,
                open_min: true,
                max,
            } => format!("> {min}, ≤ {max}{unit}"),
            Kind::Number { min, max, .. } => format!("{min} to {max}{unit}"),
            Kind::Choice(choices) => words(choices),
            Kind::WordOrNumber { word, min, max } => format!("{word}, or {min} to {max}{unit}"),
        }
    }

    /// The window's tooltip: the explanation, then the valid values.
    pub fn tooltip(&self) -> String {
        format!(
            "{}\n\nParameter {}: {}.",
            self.explain,
            self.name,
            self.range_text()
        )
    }

    /// Checks `value` (a JSON number or string; null is an override left to the scene).
    pub(super) fn check(&self, value: &serde_json::Value) -> Result<(), String> {
        let out_of_range = || format!("must be {}, got {value}", self.range_words());
        match (self.kind, value) {
            (_, serde_json::Value::Null) => Ok(()),
            (Kind::Count { min, max }, v) => match v.as_u64() {
                Some(n) if (min..=max).contains(&n) => Ok(()),
                _ => Err(out_of_range()),
            },
            (Kind::Number { min, max, open_min }, v) => match v.as_f64() {
                Some(x) if x.is_finite() && x <= max && (x > min || (!open_min && x == min)) => {
                    Ok(())
                }
                _ => Err(out_of_range()),
            },
            (Kind::Choice(choices), v) => match v.as_str() {
                Some(w) if choices.iter().any(|c| c.word == w) => Ok(()),
                _ => Err(format!("must be one of {}, got {value}", words(choices))),
            },
            (Kind::WordOrNumber { word, min, max }, v) => match (v.as_str(), v.as_f64()) {
                (Some(w), _) if w == word => Ok(()),
                (_, Some(x)) if x.is_finite() && (min..=max).contains(&x) => Ok(()),
                _ => Err(format!(
                    "must be {word} or a number from {min} to {max}, got {value}"
                )),
            },
        }
    }

    fn range_words(&self) -> String {
        let unit = if self.unit.is_empty() {
            String::new()
        } else {
            format!(" ({})", self.unit)
        };
        match self.kind {
            Kind::Number {
                min,
                max,
                open_min: true,
            } if max.is_infinite() => format!("greater than {min}{unit}"),
            Kind::Number {
                min,
                max,
                open_min: true,
            } => format!("greater than {min} and at most {max}{unit}"),
            Kind::Count { max, min } if max == u64::MAX => {
                format!("a whole number from {min} to {max}")
            }
            Kind::Count { min, max } => format!("between {min} and {max}{unit}"),
            Kind::Number { min, max, .. } => format!("between {min} and {max}{unit}"),
            Kind::Choice(choices) => words(choices),
            Kind::WordOrNumber { word, min, max } => {
                format!("{word} or between {min} and {max}{unit}")
            }
        }
    }
}
