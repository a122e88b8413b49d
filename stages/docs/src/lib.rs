//! # liftplan-docs

pub mod render;
