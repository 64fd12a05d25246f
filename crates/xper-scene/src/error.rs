//! Errors reported while reading a scene: each one names the file, the 1-based line and
//! column of the offending value, the field path and the reason.

use std::fmt;
use std::path::PathBuf;

/// One problem found in a scene file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SceneError {
    /// The scene file the error refers to.
    pub file: PathBuf,
    /// 1-based line of the offending value (or of the table when a key is missing);
    /// 0 when the file could not be read at all.
    pub line: usize,
    /// 1-based column (in characters) of the offending value; 0 for I/O errors.
    pub column: usize,
    /// Path of the offending field, e.g. `bodies[3].radius` (empty for syntax and I/O errors).
    pub field: String,
    /// Why the value is wrong, quoting the bad value.
    pub message: String,
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{}:{}:{}: {}: {}",
            self.file.display(),
            self.line,
            self.column,
            self.field,
            self.message
        )
    }
}

impl std::error::Error for SceneError {}

/// All the problems found in a scene file (never empty when returned by the parser),
/// sorted by line then column.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SceneErrors(pub Vec<SceneError>);

impl fmt::Display for SceneErrors {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, e) in self.0.iter().enumerate() {
            if i > 0 {
                writeln!(f)?;
            }
            write!(f, "{e}")?;
        }
        Ok(())
    }
}

impl std::error::Error for SceneErrors {}

impl SceneErrors {
    /// Whether some error concerns exactly the field `field`.
    pub fn has_field(&self, field: &str) -> bool {
        self.0.iter().any(|e| e.field == field)
    }

    /// The first error about exactly the field `field`, if any.
    pub fn find(&self, field: &str) -> Option<&SceneError> {
        self.0.iter().find(|e| e.field == field)
    }
}
