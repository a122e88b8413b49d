//! The part of the `liftplan` binary that other crates need: reading and
//! validating a project's `liftplan.toml` ([`project`]) and the plans kept
//! by revision ([`revisions`]), so that the fuzz targets can feed them
//! hostile files as the binary reads them. Everything else of the binary
//! (the stage graph, its cache, watch mode, progress) stays in `main.rs` and
//! its modules; this library must not grow into a second home for them.

pub mod project;
pub mod revisions;
