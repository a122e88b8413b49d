//! Artifact files: liftplan's own binary files between stages, and atomic writes.
//!
//! An artifact file is
//!
//! ```text
//! offset  size  field
//! 0       8     magic  b"LIFTPLAN"
//! 8       8     kind   e.g. b"MDM\0\0\0\0\0"
//! 16      4     format version (u32, little endian)
//! 20      4     reserved, zero
//! 24      8     payload length in bytes (u64 LE)
//! 32      n     payload
//! 32+n    32    blake3 of bytes [0, 32+n)
//! ```
//!
//! A reader checks every field and the checksum before it trusts a byte, so a
//! half-written or corrupted file is refused with its offset, never half-used.
//! [`ByteReader`] refuses any count that the remaining bytes cannot hold, so a
//! hostile length never drives an allocation.
//!
//! Every file liftplan writes goes through [`write_atomic`]: a temporary file in
//! the same folder, synced, then renamed over the target. A killed run leaves the
//! last good file (or none), never a torn one.

use crate::location::Location;
use std::fs;
use std::io::Write;
use std::path::Path;

pub const MAGIC: &[u8; 8] = b"LIFTPLAN";
const HEADER_LEN: usize = 32;
const CHECKSUM_LEN: usize = 32;

#[derive(Debug, thiserror::Error)]
pub enum ArtifactError {
    #[error("{0}: cannot read: {1}")]
    Io(Location, std::io::Error),
    #[error("{0}: {1}")]
    Format(Location, String),
}

/// A four-to-eight letter tag naming what an artifact holds.
pub fn kind_tag(kind: &str) -> [u8; 8] {
    let mut t = [0u8; 8];
    for (d, s) in t.iter_mut().zip(kind.bytes()) {
        *d = s;
    }
    t
}

/// Frames `payload` as an artifact of `kind` and `version`.
pub fn encode(kind: &str, version: u32, payload: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity(HEADER_LEN + payload.len() + CHECKSUM_LEN);
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&kind_tag(kind));
    out.extend_from_slice(&version.to_le_bytes());
    out.extend_from_slice(&0u32.to_le_bytes());
    out.extend_from_slice(&(payload.len() as u64).to_le_bytes());
    out.extend_from_slice(payload);
    let h = blake3::hash(&out);
    out.extend_from_slice(h.as_bytes());
    out
}

/// Checks the frame of an artifact and returns its payload.
pub fn decode<'a>(path: &Path, bytes: &'a [u8], kind: &str, version: u32) -> Result<&'a [u8], ArtifactError> {
    let bad = |off: u64, msg: String| ArtifactError::Format(Location::byte(path, off), msg);
    if bytes.len() < HEADER_LEN + CHECKSUM_LEN {
        return Err(bad(
            0,
            format!(
                "file is {} bytes, too short for a liftplan artifact (expected at least {})",
                bytes.len(),
                HEADER_LEN + CHECKSUM_LEN
            ),
        ));
    }
    if &bytes[0..8] != MAGIC {
        return Err(bad(0, "not a liftplan artifact (magic LIFTPLAN missing)".into()));
    }
    if bytes[8..16] != kind_tag(kind) {
        let found = String::from_utf8_lossy(&bytes[8..16]).trim_end_matches('\0').to_string();
        return Err(bad(8, format!("artifact kind is '{found}', expected '{kind}'")));
    }
    let v = u32::from_le_bytes(bytes[16..20].try_into().unwrap_or([0; 4]));
    if v != version {
        return Err(bad(16, format!("format version {v}, this liftplan reads version {version}")));
    }
    let len = u64::from_le_bytes(bytes[24..32].try_into().unwrap_or([0; 8]));
    let expected = (bytes.len() - HEADER_LEN - CHECKSUM_LEN) as u64;
    if len != expected {
        return Err(bad(24, format!("payload length field says {len} bytes, file holds {expected}")));
    }
    let end = HEADER_LEN + len as usize;
    let h = blake3::hash(&bytes[..end]);
    if h.as_bytes() != &bytes[end..] {
        return Err(bad(end as u64, "checksum mismatch: the file is damaged or was not completely written".into()));
    }
    Ok(&bytes[HEADER_LEN..end])
}

/// Writes `bytes` to `path` atomically (temporary file + fsync + rename).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let dir = path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    fs::create_dir_all(dir)?;
    let mut tmp = tempfile_in(dir, path)?;
    tmp.1.write_all(bytes)?;
    tmp.1.sync_all()?;
    drop(tmp.1);
    fs::rename(&tmp.0, path).inspect_err(|_| {
        let _ = fs::remove_file(&tmp.0);
    })
}

/// Writes through a closure into a temporary file, then renames it into place.
pub fn write_atomic_with<F>(path: &Path, f: F) -> std::io::Result<()>
where
    F: FnOnce(&mut std::io::BufWriter<fs::File>) -> std::io::Result<()>,
{
    let dir = path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    fs::create_dir_all(dir)?;
    let (tmp_path, file) = tempfile_in(dir, path)?;
    let mut w = std::io::BufWriter::new(file);
    let res = f(&mut w).and_then(|_| w.flush());
    match res {
        Ok(()) => {
            let file = w.into_inner().map_err(|e| e.into_error())?;
            file.sync_all()?;
            fs::rename(&tmp_path, path).inspect_err(|_| {
                let _ = fs::remove_file(&tmp_path);
            })
        }
        Err(e) => {
            drop(w);
            let _ = fs::remove_file(&tmp_path);
            Err(e)
        }
    }
}

fn tempfile_in(dir: &Path, target: &Path) -> std::io::Result<(std::path::PathBuf, fs::File)> {
    use std::sync::atomic::{AtomicU64, Ordering};
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let name = target.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    loop {
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let p = dir.join(format!(".{name}.tmp-{}-{n}", std::process::id()));
        match fs::OpenOptions::new().write(true).create_new(true).open(&p) {
            Ok(f) => return Ok((p, f)),
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => continue,
            Err(e) => return Err(e),
        }
    }
}

/// Writes an artifact file atomically.
pub fn write_artifact(path: &Path, kind: &str, version: u32, payload: &[u8]) -> Result<(), ArtifactError> {
    write_atomic(path, &encode(kind, version, payload)).map_err(|e| ArtifactError::Io(Location::file(path), e))
}

/// Reads an artifact file and returns its checked payload.
pub fn read_artifact(path: &Path, kind: &str, version: u32) -> Result<Vec<u8>, ArtifactError> {
    let bytes = fs::read(path).map_err(|e| ArtifactError::Io(Location::file(path), e))?;
    decode(path, &bytes, kind, version).map(|p| p.to_vec())
}

/// Appends little-endian values to a payload.
#[derive(Default)]
pub struct ByteWriter {
    pub buf: Vec<u8>,
}

impl ByteWriter {
    pub fn new() -> Self {
        Self::default()
    }
    pub fn u8(&mut self, v: u8) {
        self.buf.push(v);
    }
    pub fn u32(&mut self, v: u32) {
        self.buf.extend_from_slice(&v.to_le_bytes());
    }
    pub fn u64(&mut self, v: u64) {
        self.buf.extend_from_slice(&v.to_le_bytes());
    }
    pub fn f32(&mut self, v: f32) {
        self.buf.extend_from_slice(&v.to_le_bytes());
    }
    pub fn f64(&mut self, v: f64) {
        self.buf.extend_from_slice(&v.to_le_bytes());
    }
    pub fn str(&mut self, s: &str) {
        self.u32(s.len() as u32);
        self.buf.extend_from_slice(s.as_bytes());
    }
    pub fn f32s(&mut self, v: &[f32]) {
        self.u64(v.len() as u64);
        for x in v {
            self.f32(*x);
        }
    }
    pub fn u32s(&mut self, v: &[u32]) {
        self.u64(v.len() as u64);
        for x in v {
            self.u32(*x);
        }
    }
    pub fn f64s(&mut self, v: &[f64]) {
        self.u64(v.len() as u64);
        for x in v {
            self.f64(*x);
        }
    }
}

/// Reads little-endian values from a payload, with the offset of every failure.
pub struct ByteReader<'a> {
    bytes: &'a [u8],
    pos: usize,
    /// Offset of `bytes[0]` in the file, for error messages.
    base: u64,
    path: &'a Path,
}

impl<'a> ByteReader<'a> {
    pub fn new(path: &'a Path, bytes: &'a [u8], base: u64) -> Self {
        ByteReader { bytes, pos: 0, base, path }
    }

    pub fn offset(&self) -> u64 {
        self.base + self.pos as u64
    }

    pub fn remaining(&self) -> usize {
        self.bytes.len() - self.pos
    }

    pub fn error(&self, msg: impl Into<String>) -> ArtifactError {
        ArtifactError::Format(Location::byte(self.path, self.offset()), msg.into())
    }

    pub fn take(&mut self, n: usize) -> Result<&'a [u8], ArtifactError> {
        if self.remaining() < n {
            return Err(self.error(format!("expected {n} more bytes, {} left", self.remaining())));
        }
        let s = &self.bytes[self.pos..self.pos + n];
        self.pos += n;
        Ok(s)
    }

    pub fn u8(&mut self) -> Result<u8, ArtifactError> {
        Ok(self.take(1)?[0])
    }
    pub fn u32(&mut self) -> Result<u32, ArtifactError> {
        Ok(u32::from_le_bytes(self.take(4)?.try_into().unwrap_or([0; 4])))
    }
    pub fn u64(&mut self) -> Result<u64, ArtifactError> {
        Ok(u64::from_le_bytes(self.take(8)?.try_into().unwrap_or([0; 8])))
    }
    pub fn f32(&mut self) -> Result<f32, ArtifactError> {
        Ok(f32::from_le_bytes(self.take(4)?.try_into().unwrap_or([0; 4])))
    }
    pub fn f64(&mut self) -> Result<f64, ArtifactError> {
        Ok(f64::from_le_bytes(self.take(8)?.try_into().unwrap_or([0; 8])))
    }
    pub fn str(&mut self) -> Result<String, ArtifactError> {
        let n = self.u32()? as usize;
        let at = self.offset();
        let b = self.take(n)?;
        String::from_utf8(b.to_vec())
            .map_err(|_| ArtifactError::Format(Location::byte(self.path, at), "string is not UTF-8".into()))
    }
    /// A count of `elem_size`-byte elements that must fit in what is left.
    pub fn count(&mut self, elem_size: usize) -> Result<usize, ArtifactError> {
        let n = self.u64()?;
        let need = n.checked_mul(elem_size as u64);
        match need {
            Some(b) if b <= self.remaining() as u64 => Ok(n as usize),
            _ => {
                Err(self
                    .error(format!("count {n} of {elem_size}-byte items exceeds the {} bytes left", self.remaining())))
            }
        }
    }
    pub fn f32s(&mut self) -> Result<Vec<f32>, ArtifactError> {
        let n = self.count(4)?;
        (0..n).map(|_| self.f32()).collect()
    }
    pub fn u32s(&mut self) -> Result<Vec<u32>, ArtifactError> {
        let n = self.count(4)?;
        (0..n).map(|_| self.u32()).collect()
    }
    pub fn f64s(&mut self) -> Result<Vec<f64>, ArtifactError> {
        let n = self.count(8)?;
        (0..n).map(|_| self.f64()).collect()
    }
    pub fn finish(&self) -> Result<(), ArtifactError> {
        if self.remaining() != 0 {
            return Err(self.error(format!("{} unexpected bytes after the data", self.remaining())));
        }
        Ok(())
    }
}

/// blake3 of a file's contents, streamed.
pub fn hash_file(path: &Path) -> std::io::Result<blake3::Hash> {
    let mut h = blake3::Hasher::new();
    h.update_reader(fs::File::open(path)?)?;
    Ok(h.finalize())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn roundtrip_and_damage() {
        let d = tempfile::tempdir().unwrap();
        let p = d.path().join("x.bin");
        write_artifact(&p, "TEST", 3, b"hello").unwrap();
        assert_eq!(read_artifact(&p, "TEST", 3).unwrap(), b"hello");
        assert!(read_artifact(&p, "OTHER", 3).is_err());
        assert!(read_artifact(&p, "TEST", 4).is_err());
        let mut b = fs::read(&p).unwrap();
        b[33] ^= 1;
        fs::write(&p, &b).unwrap();
        let e = read_artifact(&p, "TEST", 3).unwrap_err().to_string();
        assert!(e.contains("checksum"), "{e}");
        b.truncate(40);
        fs::write(&p, &b).unwrap();
        let e = read_artifact(&p, "TEST", 3).unwrap_err().to_string();
        assert!(e.contains("at byte"), "{e}");
    }

    #[test]
    fn hostile_count() {
        let mut w = ByteWriter::new();
        w.u64(u64::MAX / 2);
        let p = Path::new("x");
        let mut r = ByteReader::new(p, &w.buf, 32);
        assert!(r.f32s().is_err());
    }

    #[test]
    fn atomic_with_failure_leaves_old() {
        let d = tempfile::tempdir().unwrap();
        let p = d.path().join("out.txt");
        write_atomic(&p, b"good").unwrap();
        let r = write_atomic_with(&p, |w| {
            w.write_all(b"partial")?;
            Err(std::io::Error::other("boom"))
        });
        assert!(r.is_err());
        assert_eq!(fs::read(&p).unwrap(), b"good");
        assert_eq!(fs::read_dir(d.path()).unwrap().count(), 1);
    }
}
