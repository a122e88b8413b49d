//! What the workspace's property tests share: how many cases each runs.
//!
//! Nothing outside tests calls this module, and it must not grow test
//! fixtures: scenes and files belong to `liftplan-fixtures`.

/// Environment variable that sets every property test's case count.
pub const CASES_VAR: &str = "PROPTEST_CASES";

/// How many cases a property test runs: `default` (sized for CI), or the
/// value of `PROPTEST_CASES` when it is set, for a soak such as
/// `PROPTEST_CASES=5000 cargo test --release -p liftplan-depthmap`.
///
/// Proptest reads that variable only for tests left at its default count.
/// Ours set their own count, which silently overrides it, so without this a
/// soak would run the CI count and look as if it had run the asked-for one.
///
/// # Panics
/// When the variable is set but is not a whole number above zero: a soak that
/// asked for cases must not pass having run other than it asked.
pub fn proptest_cases(default: u32) -> u32 {
    match std::env::var(CASES_VAR) {
        Err(std::env::VarError::NotPresent) => default,
        Ok(v) => match v.trim().parse::<u32>() {
            Ok(n) if n > 0 => n,
            _ => panic!("{CASES_VAR}={v:?}: expected a whole number of cases above zero"),
        },
        Err(std::env::VarError::NotUnicode(v)) => {
            panic!("{CASES_VAR}={v:?}: expected a whole number of cases above zero")
        }
    }
}
