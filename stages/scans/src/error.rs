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

impl From<liftplan_core::las_file::LasFileError> for ScanError {
    fn from(e: liftplan_core::las_file::LasFileError) -> Self {
        use liftplan_core::las_file::LasFileError;
        match e {
            LasFileError::Format(at, why) => ScanError::Format(at, why),
            LasFileError::Io(at, e) => ScanError::Io(at, e),
        }
    }
}

pub type Result<T> = std::result::Result<T, ScanError>;
