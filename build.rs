//! Hashes the code behind each stage into the binary (`LIFTPLAN_CODE_<STAGE>`),
//! so that a stage's cache key changes when the code that computes its outputs
//! does: the make-style rule treats the code as an input, like the files and
//! the settings. A stage's code is its crate and the liftplan crates it depends
//! on (read from their `[dependencies]`), whole but for their tests, examples,
//! benches, proptest seeds and READMEs (so fonts, shaders and the built-in
//! crane files count); the binary's glue (`src/stages.rs`); `Cargo.lock`
//! (third-party versions); and the patched crates in `third_party/`.
//!
//! It must not hash anything that varies between two checkouts of one commit
//! (times, absolute paths), or every clone would rerun every stage.

use std::path::{Path, PathBuf};

const STAGES: [&str; 6] = ["scans", "plant", "charts", "depthmap", "plan", "docs"];

/// What of a crate does not go into the binary's answers.
const NOT_CODE: [&str; 5] = ["tests", "examples", "benches", "proptest-regressions", "README.md"];

fn main() {
    let root = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR"));
    for name in ["Cargo.lock", "src/stages.rs", "third_party"] {
        println!("cargo:rerun-if-changed={name}");
    }
    println!("cargo:rerun-if-changed=stages");
    for stage in STAGES {
        let mut files = Vec::new();
        for krate in with_dependencies(&root, stage) {
            // The whole crate (sources, shaders, fonts, crane files) but what
            // only its tests, examples and benches use.
            let dir = root.join("stages").join(&krate);
            for e in std::fs::read_dir(&dir).unwrap_or_else(|e| panic!("reading {}: {e}", dir.display())).flatten() {
                let name = e.file_name();
                if !NOT_CODE.contains(&name.to_string_lossy().as_ref()) {
                    collect(&e.path(), &mut files);
                }
            }
        }
        // A checkout without a lock file (a package) hashes what it has.
        files.extend([root.join("Cargo.lock"), root.join("src/stages.rs")].into_iter().filter(|f| f.exists()));
        collect(&root.join("third_party"), &mut files);
        files.sort();
        files.dedup();
        let mut h = blake3::Hasher::new();
        for f in &files {
            let rel = f.strip_prefix(&root).unwrap_or(f).to_string_lossy().replace('\\', "/");
            let bytes = std::fs::read(f).unwrap_or_else(|e| panic!("reading {}: {e}", f.display()));
            h.update(&(rel.len() as u64).to_le_bytes());
            h.update(rel.as_bytes());
            h.update(&(bytes.len() as u64).to_le_bytes());
            h.update(&bytes);
        }
        println!("cargo:rustc-env=LIFTPLAN_CODE_{}={}", stage.to_uppercase(), &h.finalize().to_hex()[..16]);
    }
}

/// `stage` and the stage crates it depends on, directly or not.
fn with_dependencies(root: &Path, stage: &str) -> Vec<String> {
    let mut found = vec![stage.to_string()];
    let mut k = 0;
    while k < found.len() {
        let manifest = root.join("stages").join(&found[k]).join("Cargo.toml");
        let text = std::fs::read_to_string(&manifest).unwrap_or_else(|e| panic!("reading {}: {e}", manifest.display()));
        let mut in_dependencies = false;
        for line in text.lines().map(str::trim) {
            if line.starts_with('[') {
                in_dependencies = line == "[dependencies]";
            } else if in_dependencies && let Some(rest) = line.strip_prefix("liftplan-") {
                let name: String = rest.chars().take_while(|c| c.is_ascii_alphanumeric() || *c == '_').collect();
                if root.join("stages").join(&name).is_dir() && !found.contains(&name) {
                    found.push(name);
                }
            }
        }
        k += 1;
    }
    found
}

/// `path` if it is a file, else every file under it, recursively.
fn collect(path: &Path, out: &mut Vec<PathBuf>) {
    if path.is_file() {
        out.push(path.to_path_buf());
        return;
    }
    let Ok(entries) = std::fs::read_dir(path) else { return };
    for e in entries.flatten() {
        let p = e.path();
        if p.is_dir() {
            collect(&p, out);
        } else {
            out.push(p);
        }
    }
}
