//! Scene-file errors, each pointing at a file, line, column and field.

use std::ops::Range;

/// An error while loading a scene file. Displays as one line, e.g.
/// `scenes/room.toml:12:9: objects[2].material: unknown material "whte" (known: white, red)`.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum SceneError {
    /// The scene file itself could not be read.
    #[error("{path}: cannot read scene file: {reason}")]
    Unreadable {
        /// The scene file.
        path: String,
        /// What went wrong.
        reason: String,
    },
    /// A mesh file loaded as a scene on its own could not be read or holds no faces.
    #[error("{message}")]
    Mesh {
        /// What went wrong, naming the file (and the line, where the importer can).
        message: String,
    },
    /// The file is not valid TOML, does not follow the format, or describes an invalid scene
    /// (including mesh and texture files that cannot be read).
    #[error("{file}:{line}:{column}: {field}: {message}")]
    Invalid {
        /// The scene file as named by the caller.
        file: String,
        /// Line of the offending text, counted from 1.
        line: usize,
        /// Column (in characters) of the offending text, counted from 1.
        column: usize,
        /// Dotted path of the field, e.g. `objects[2].radius` (array indices count from 0).
        field: String,
        /// What is wrong.
        message: String,
    },
}

/// The scene text being loaded, used to turn byte spans into error positions.
#[derive(Clone, Copy, Debug)]
pub(super) struct Source<'a> {
    /// The TOML text.
    pub text: &'a str,
    /// The file name shown in errors.
    pub file: &'a str,
}

impl Source<'_> {
    /// An [`SceneError::Invalid`] at the start of `span`.
    pub fn error(&self, span: Range<usize>, field: &str, message: impl ToString) -> SceneError {
        let (line, column) = line_column(self.text, span.start);
        SceneError::Invalid {
            file: self.file.to_string(),
            line,
            column,
            field: field.to_string(),
            message: message.to_string(),
        }
    }
}

/// One-based line and character column of byte `offset` in `text` (clamped to the text).
pub(super) fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let before = &text[..offset];
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    let line = before.matches('\n').count() + 1;
    let column = before[line_start..].chars().count() + 1;
    (line, column)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn positions_count_lines_and_characters_from_one() {
        let text = "a = 1\nbé = 2\n";
        assert_eq!(line_column(text, 0), (1, 1));
        assert_eq!(line_column(text, 6), (2, 1));
        // 'é' is two bytes but one column.
        assert_eq!(line_column(text, 9), (2, 3));
        assert_eq!(line_column(text, 1000), (3, 1));
    }

    #[test]
    fn invalid_error_displays_on_one_line() {
        let src = Source {
            text: "x = 1\n  y = 2\n",
            file: "s.toml",
        };
        let e = src.error(8..9, "y", "bad value");
        assert_eq!(e.to_string(), "s.toml:2:3: y: bad value");
    }
}
