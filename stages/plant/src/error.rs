//! Errors of the plant stage, each naming the file and the place (byte offset,
//! line, group) and what was expected.

use liftplan_core::Location;

#[derive(Debug, thiserror::Error)]
pub enum PlantError {
    #[error("{0}: {1}")]
    Format(Location, String),
    #[error("{0}: {1}")]
    Io(Location, std::io::Error),
    #[error("[plant] {0}")]
    Settings(String),
}

impl PlantError {
    pub fn at(loc: Location, msg: impl Into<String>) -> Self {
        PlantError::Format(loc, msg.into())
    }
}

pub type Result<T> = std::result::Result<T, PlantError>;
