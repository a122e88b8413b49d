//! Errors of the scans stage. Every one names the file and, where it can, the
//! place in it (byte offset, line, scan name) and what was expected.

use liftplan_core::Location;

#[derive(Debug, thiserror::Error)]
pub enum ScanError {
    /// The file is malformed or not what its extension says.
    #[error("{0}: {1}")]
    Format(Location, String),
    /// The operating system refused to read or write the file.
    #[error("{0}: {1}")]
    Io(Location, std::io::Error),
    /// A scan could not be placed in the site frame.
    #[error("registration: {0}")]
    Registration(String),
    /// A setting is out of range.
    #[error("[scans] {0}")]
    Settings(String),
}

impl ScanError {
    pub fn format(loc: Location, msg: impl Into<String>) -> Self {
        ScanError::Format(loc, msg.into())
    }
}

pub type Result<T> = std::result::Result<T, ScanError>;
