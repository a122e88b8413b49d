//! End-to-end tests of the `liftplan` binary: each test gets a fresh project in a
//! temporary folder and runs the real executable.

mod backbone;
mod damaged_files;
mod demo;
mod util;
mod watch;
