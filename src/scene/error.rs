//! Scene errors: one line, naming the file and line:column where there is one.

use std::fmt;

/// Where in the input something went wrong.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Location {
    /// The file (a path, or `builtin:NAME` for an embedded scene).
    pub file: String,
    /// 1-based line and column, when known.
    pub line_col: Option<(usize, Option<usize>)>,
}

impl Location {
    /// The whole file.
    pub fn file(file: impl Into<String>) -> Self {
        Location {
            file: file.into(),
            line_col: None,
        }
    }

    /// The position of byte `offset` in `text`.
    pub fn at_offset(file: impl Into<String>, text: &str, offset: usize) -> Self {
        let (line, col) = line_col(text, offset);
        Location {
            file: file.into(),
            line_col: Some((line, Some(col))),
        }
    }

    /// A line, without a column.
    pub fn at_line(file: impl Into<String>, line: usize) -> Self {
        Location {
            file: file.into(),
            line_col: Some((line, None)),
        }
    }
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.file)?;
        match self.line_col {
            Some((line, Some(col))) => write!(f, ":{line}:{col}"),
            Some((line, None)) => write!(f, ":{line}"),
            None => Ok(()),
        }
    }
}

/// 1-based line and column (in characters) of byte `offset` in `text`.
pub fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let offset = offset.min(text.len());
    let before = text.get(..offset).unwrap_or(text);
    let line = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    let col = before[line_start..].chars().count() + 1;
    (line, col)
}

/// A scene that cannot be loaded: `file:line:col: message`.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{location}: {message}")]
pub struct SceneError {
    /// Where.
    pub location: Location,
    /// What, in one line.
    pub message: String,
}

impl SceneError {
    /// An error at `location`.
    pub fn new(location: Location, message: impl Into<String>) -> Self {
        SceneError {
            location,
            message: one_line(&message.into()),
        }
    }
}

/// A message on one line, whatever its source said: runs of whitespace (newlines in a
/// quoted key among them) become one space, other control characters are escaped.
pub(crate) fn one_line(message: &str) -> String {
    message
        .split_whitespace()
        .map(|word| {
            word.chars()
                .map(|c| {
                    if c.is_control() {
                        c.escape_default().collect()
                    } else {
                        c.to_string()
                    }
                })
                .collect::<String>()
        })
        .collect::<Vec<_>>()
        .join(" ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn offsets_become_lines_and_columns() {
        let text = "a = 1\nbb = 2\n\nccc";
        assert_eq!(line_col(text, 0), (1, 1));
        assert_eq!(line_col(text, 6), (2, 1));
        assert_eq!(line_col(text, 11), (2, 6));
        assert_eq!(line_col(text, 14), (4, 1));
        let e = SceneError::new(Location::at_offset("s.toml", text, 8), "bad\n  value");
        assert_eq!(e.to_string(), "s.toml:2:3: bad value");
    }
}
