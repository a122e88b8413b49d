//! What the workspace's property tests share: how many cases each runs, a
//! seeded stream of numbers for random scenes, and how the readers' tests
//! damage a file.
//!
//! Nothing outside tests and the fuzz targets calls this module, and it must
//! not grow test fixtures: scenes and files belong to `liftplan-fixtures`.

/// Numbers in [0, 1) from `seed` (xorshift): the same stream for the same
/// seed on every machine, for the random scenes of property tests.
pub fn unit_stream(seed: u64) -> impl FnMut() -> f64 {
    let mut s = seed | 1;
    move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64
    }
}

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

/// How many cases a property test of `cases` cases may reject
/// (`prop_assume!`) in all before proptest gives up on it: as many as it has
/// cases, and proptest's own 1,024 at the least. At proptest's fixed 1,024 a
/// soak's large [`proptest_cases`] aborted tests whose assumptions reject
/// one case in a hundred ("Too many global rejects" after 96,534 cases
/// passed), a failure that says nothing of the property.
pub fn proptest_rejects(cases: u32) -> u32 {
    cases.max(1024)
}

/// Copy `k` of a file's `bytes`, damaged in one of four ways by `k`: a few
/// bits flipped; a 32-bit field (a length, a count, a float) overwritten
/// with an extreme value; the file cut short; a run of it copied over
/// another place. Deterministic, so a failure names a copy that can be made
/// again. The readers' tests run a few hundred of these on every test run,
/// beside the fuzz targets, which need a nightly toolchain.
pub fn damaged(bytes: &[u8], k: u64) -> Vec<u8> {
    let mut rng = crate::rng::seeded(k, "damaged copy");
    let mut at = |n: usize| crate::rng::index(&mut rng, n.max(1));
    let mut out = bytes.to_vec();
    if out.len() < 8 {
        out.truncate(at(out.len() + 1));
        return out;
    }
    match k % 4 {
        0 => {
            for _ in 0..1 + at(8) {
                let i = at(out.len());
                out[i] ^= 1 << at(8);
            }
        }
        1 => {
            let i = at(out.len() - 4);
            let v: u32 = [0xFFFF_FFFF, 0x7FFF_FFFF, 0x8000_0000, 0x7F80_0000, 0x7FC0_0000, 0][at(6)];
            let v = if at(2) == 0 { v.to_le_bytes() } else { v.to_be_bytes() };
            out[i..i + 4].copy_from_slice(&v);
        }
        2 => out.truncate(at(out.len())),
        _ => {
            let len = 1 + at(64.min(out.len() / 2));
            let (from, to) = (at(out.len() - len), at(out.len() - len));
            let run = out[from..from + len].to_vec();
            out[to..to + len].copy_from_slice(&run);
        }
    }
    out
}

/// Keeps panics raised in source files whose path contains `path_part` (a
/// third-party decoder whose panics the reader catches and reports as
/// errors) out of a test's output; every other panic is reported as before.
/// For a test binary of its own: the hook is the process's.
pub fn hide_panics_from(path_part: &'static str) {
    let default_hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        if !info.location().is_some_and(|l| l.file().contains(path_part)) {
            default_hook(info);
        }
    }));
}

/// Writes the CRC-32C of each 1024-byte page of an E57 file into its last
/// four bytes, as the format asks: a damaged copy then reaches the parser
/// instead of failing its page check.
pub fn e57_page_checksums(body: &mut [u8]) {
    for page in body.chunks_exact_mut(1024) {
        let crc = crc32c(&page[..1020]);
        page[1020..].copy_from_slice(&crc.to_be_bytes());
    }
}

/// CRC-32C (Castagnoli), bit by bit: test files are small.
fn crc32c(data: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &b in data {
        crc ^= b as u32;
        for _ in 0..8 {
            crc = if crc & 1 == 1 { (crc >> 1) ^ 0x82F6_3B78 } else { crc >> 1 };
        }
    }
    !crc
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn damaged_copies_differ_and_repeat() {
        let file: Vec<u8> = (0..=255).collect();
        for k in 0..64 {
            assert_eq!(damaged(&file, k), damaged(&file, k), "copy {k} is made again the same");
        }
        // A run copied onto itself, or a bit flipped twice, leaves a copy whole.
        let whole = (0..64).filter(|&k| damaged(&file, k) == file).count();
        assert!(whole <= 4, "{whole} of 64 copies undamaged");
        assert!(damaged(&[1, 2, 3], 5).len() <= 3);
    }

    #[test]
    fn crc32c_of_the_standard_check_string() {
        assert_eq!(crc32c(b"123456789"), 0xE306_9283);
    }
}
