//! What registration worked out on earlier runs, kept so that a rerun does not
//! work it out again.
//!
//! Registration places the scans one round at a time: each round tries every
//! scan not yet placed against the model of those placed, and places the best
//! ([`crate::register`]). Such a trial is a function of the scan, the placed
//! scans and their poses, the settings and the code, and of nothing else, so
//! its answer can be kept under a hash of all of them: the bits of every point,
//! normal and pose, the settings and the build. When one scan of a survey is
//! added, changed or thinned differently for the site cloud, the rounds before
//! it is placed find their other trials here, and a setting that registration
//! does not read (the ground filter, the site cloud's voxel) finds all of them.
//!
//! An answer found here is the one the run would have computed, bit for bit:
//! a memo lost, damaged or written by another build costs only time. The file
//! keeps only what the last run asked for, so it grows with the survey, not
//! with the number of runs.
//!
//! What this module must not do: hold anything that is not a function of its
//! key, or trust a file that fails its checksum (it is then ignored whole).

use liftplan_core::artifact::{self, ByteReader, ByteWriter};
use std::collections::HashMap;
use std::path::Path;

/// The hash answers are kept under.
pub type Key = [u8; 32];

/// The memo file is a liftplan artifact of this kind ([`artifact`]: checked
/// frame and checksum); its payload is a count, then (key, length, answer).
const KIND: &str = "REGMEMO";
const FORMAT: u32 = 1;
/// A memo file past this size is not read (a survey of a few hundred scans
/// keeps well under a megabyte).
const MAX_FILE_BYTES: u64 = 256 << 20;

/// Answers by key, and which of them this run asked for or added.
#[derive(Debug, Default)]
pub struct Memo {
    /// Names the build: answers of another build's code are never used.
    build: String,
    stored: HashMap<Key, Vec<u8>>,
    /// Answers looked up (found) or added during this run: what `save` keeps.
    used: HashMap<Key, Vec<u8>>,
    pub hits: u64,
    pub misses: u64,
}

impl Memo {
    /// An empty memo for answers of the code named by `build`.
    pub fn new(build: &str) -> Memo {
        Memo { build: build.to_string(), ..Memo::default() }
    }

    /// The memo kept at `path`, or an empty one if there is none or it is not
    /// a whole memo file (the reason is logged).
    pub fn load(path: &Path, build: &str) -> Memo {
        let mut memo = Memo::new(build);
        match read_file(path) {
            Ok(stored) => memo.stored = stored,
            Err(why) => tracing::warn!("registration memo ignored ({why}); registration runs in full"),
        }
        memo
    }

    pub fn build(&self) -> &str {
        &self.build
    }

    /// The answer kept under `key`, if any.
    pub fn get(&mut self, key: &Key) -> Option<&[u8]> {
        if !self.used.contains_key(key) {
            let Some(v) = self.stored.remove(key) else {
                self.misses += 1;
                return None;
            };
            self.used.insert(*key, v);
        }
        self.hits += 1;
        self.used.get(key).map(|v| v.as_slice())
    }

    pub fn put(&mut self, key: Key, answer: Vec<u8>) {
        self.used.insert(key, answer);
    }

    /// Writes the answers this run used or added to `path`, atomically.
    pub fn save(&self, path: &Path) -> Result<(), artifact::ArtifactError> {
        artifact::write_artifact(path, KIND, FORMAT, &self.payload())
    }

    fn payload(&self) -> Vec<u8> {
        let mut keys: Vec<&Key> = self.used.keys().collect();
        keys.sort_unstable();
        let mut w = ByteWriter::new();
        w.u64(keys.len() as u64);
        for k in keys {
            let v = &self.used[k];
            w.buf.extend_from_slice(k);
            w.u64(v.len() as u64);
            w.buf.extend_from_slice(v);
        }
        w.buf
    }
}

fn read_file(path: &Path) -> Result<HashMap<Key, Vec<u8>>, String> {
    match std::fs::metadata(path) {
        Ok(m) if m.len() > MAX_FILE_BYTES => {
            return Err(format!("{}: {} bytes, more than a memo may have ({MAX_FILE_BYTES})", path.display(), m.len()));
        }
        Ok(_) => {}
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(HashMap::new()),
        Err(e) => return Err(format!("{}: {e}", path.display())),
    }
    let bytes = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
    from_bytes(path, &bytes)
}

/// The answers of a memo file's bytes (`path` names it in errors).
pub fn from_bytes(path: &Path, bytes: &[u8]) -> Result<HashMap<Key, Vec<u8>>, String> {
    let payload = artifact::decode(path, bytes, KIND, FORMAT).map_err(|e| e.to_string())?;
    parse(path, payload).map_err(|e| e.to_string())
}

fn parse(path: &Path, payload: &[u8]) -> Result<HashMap<Key, Vec<u8>>, artifact::ArtifactError> {
    let mut r = ByteReader::new(path, payload, 32);
    let count = r.count(32 + 8)?;
    let mut stored = HashMap::with_capacity(count);
    for _ in 0..count {
        let mut key: Key = [0; 32];
        key.copy_from_slice(r.take(32)?);
        let len = r.count(1)?;
        stored.insert(key, r.take(len)?.to_vec());
    }
    r.finish()?;
    Ok(stored)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn key(b: u8) -> Key {
        [b; 32]
    }

    #[test]
    fn saved_answers_come_back_and_only_those_used() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("memo").join("registration.memo");
        let mut m = Memo::new("build-1");
        m.put(key(1), vec![1, 2, 3]);
        m.put(key(2), vec![]);
        m.save(&path).unwrap();

        let mut m = Memo::load(&path, "build-1");
        assert_eq!(m.get(&key(1)), Some([1u8, 2, 3].as_slice()));
        assert_eq!(m.get(&key(3)), None);
        assert_eq!((m.hits, m.misses), (1, 1));
        m.put(key(4), vec![4]);
        m.save(&path).unwrap();

        // key(2) was neither asked for nor added: not kept.
        let mut m = Memo::load(&path, "build-1");
        assert_eq!(m.get(&key(2)), None);
        assert_eq!(m.get(&key(1)), Some([1u8, 2, 3].as_slice()));
        assert_eq!(m.get(&key(4)), Some([4u8].as_slice()));
    }

    #[test]
    fn a_damaged_memo_is_ignored_whole() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("registration.memo");
        let mut m = Memo::new("b");
        m.put(key(7), vec![9; 40]);
        m.put(key(8), vec![1]);
        m.save(&path).unwrap();
        let good = std::fs::read(&path).unwrap();
        assert!(Memo::load(&path, "b").get(&key(7)).is_some());
        // Every cut and every flipped byte fails the frame or its checksum.
        for cut in 0..good.len() {
            std::fs::write(&path, &good[..cut]).unwrap();
            assert!(read_file(&path).is_err(), "cut at {cut}");
            assert_eq!(Memo::load(&path, "b").get(&key(7)), None);
        }
        for at in 0..good.len() {
            let mut bad = good.clone();
            bad[at] ^= 0x40;
            std::fs::write(&path, &bad).unwrap();
            assert!(read_file(&path).is_err(), "byte {at} flipped");
        }
        // A whole frame around a payload whose counts promise more than it holds.
        let payload = m.payload();
        for at in [0, 32 + 8] {
            let mut p = payload.clone();
            p[at..at + 8].copy_from_slice(&u64::MAX.to_le_bytes());
            assert!(parse(&path, &p).is_err());
            liftplan_core::artifact::write_artifact(&path, KIND, FORMAT, &p).unwrap();
            assert!(read_file(&path).unwrap_err().contains("count"), "{:?}", read_file(&path));
        }
        assert!(parse(&path, &payload[..payload.len() - 1]).is_err());
        let mut longer = payload.clone();
        longer.push(0);
        assert!(parse(&path, &longer).is_err());
    }
}
