//! The UTF-8 byte order mark (`EF BB BF`) that Windows tools (Notepad,
//! Excel's "CSV UTF-8") write at the start of a text file: passed over
//! before a text format is read, since the third-party readers take it
//! for the first line's first characters (an OBJ file lost its first
//! vertex, a PLY file was refused for not starting with `ply`).
//!
//! Only the readers' input is touched: line numbers and offsets in their
//! errors stay those of the file.

use std::io::BufRead;

/// The mark's bytes.
pub const BYTES: [u8; 3] = [0xef, 0xbb, 0xbf];

/// The mark as a character, where a reader has the file's text as UTF-8.
pub const CHAR: char = '\u{feff}';

/// `bytes` without a mark at their start.
pub fn strip(bytes: &[u8]) -> &[u8] {
    bytes.strip_prefix(&BYTES).unwrap_or(bytes)
}

/// Consumes a mark at the start of what the reader holds; whether there
/// was one. Nothing is consumed otherwise, so a binary file whose first
/// bytes are the mark's first one or two is read whole. (A reader over a
/// file holds its first bytes together; one handing them over a byte at a
/// time keeps its mark.)
pub fn skip<R: BufRead>(r: &mut R) -> std::io::Result<bool> {
    let marked = r.fill_buf()?.starts_with(&BYTES);
    if marked {
        r.consume(BYTES.len());
    }
    Ok(marked)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_mark_is_passed_over_and_nothing_else() {
        assert_eq!(strip(b"\xef\xbb\xbfply\n"), b"ply\n");
        assert_eq!(strip(b"ply\n"), b"ply\n");
        let mut r = std::io::Cursor::new(b"\xef\xbb\xbfv 0 0 0\n".to_vec());
        assert!(skip(&mut r).unwrap());
        assert_eq!(r.fill_buf().unwrap(), b"v 0 0 0\n");
        let mut r = std::io::Cursor::new(b"v 0 0 0\n".to_vec());
        assert!(!skip(&mut r).unwrap());
        assert_eq!(r.fill_buf().unwrap(), b"v 0 0 0\n");
        // A binary file whose first bytes are the mark's first two is left whole.
        let mut r = std::io::Cursor::new(b"\xef\xbb\x00\x01".to_vec());
        assert!(!skip(&mut r).unwrap());
        assert_eq!(r.fill_buf().unwrap(), b"\xef\xbb\x00\x01");
        assert!(!skip(&mut std::io::Cursor::new(Vec::new())).unwrap());
    }
}
