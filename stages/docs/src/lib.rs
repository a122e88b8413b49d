//! # liftplan-docs: stage 6, pictures and the lift plan PDF

pub mod render;

use serde::{Deserialize, Serialize};

pub const NAME: &str = "docs";
pub const VERSION: u32 = 1;

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum Paper {
    #[default]
    A4,
    Letter,
}

/// `[docs]` in `liftplan.toml`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Settings {
    pub paper: Paper,
    /// One page per step with its picture.
    pub step_pictures: bool,
}

impl Default for Settings {
    fn default() -> Self {
        Settings { paper: Paper::A4, step_pictures: true }
    }
}
