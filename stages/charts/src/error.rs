//! Errors of the charts stage: each names the file and the sheet!cell.

use liftplan_core::Location;

#[derive(Debug, thiserror::Error)]
pub enum ChartError {
    #[error("{0}: {1}")]
    Format(Location, String),
    #[error("{0}: {1}")]
    Io(Location, std::io::Error),
    #[error("[charts] {0}")]
    Settings(String),
    #[error("lift '{0}': {1}")]
    Lift(String, String),
}

pub type Result<T> = std::result::Result<T, ChartError>;
