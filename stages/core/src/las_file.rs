//! LAS and LAZ files' structure, checked before a third-party reader trusts
//! it.
//!
//! The `las` and `laz` crates size buffers from header fields, and assert on
//! them, instead of refusing a file whose fields its bytes cannot hold.
//! [`precheck`] reads the public header block, the VLR and EVLR headers and
//! the LAZ chunk table directly and refuses any count or offset the file
//! cannot hold, before those readers see it. Real files have odd headers
//! (padding after the header, extra bytes per point, user VLRs, legacy and
//! 64-bit point counts that disagree); those are accepted.
//!
//! Used by the scans stage's reader for the scans a survey hands over, and
//! by the stages that read the scans stage's `site.laz` back (depth map,
//! plan, docs), which is a file on disk like any other. This module reads no
//! points; the readers do, through [`crate::guard`].

use crate::Location;
use crate::frame::Aabb;
use std::io::{Read, Seek, SeekFrom};
use std::path::Path;

/// Why a LAS/LAZ file is refused, with the place in it.
#[derive(Debug, thiserror::Error)]
pub enum LasFileError {
    /// A field the file's bytes cannot hold, or a part the decoder cannot read.
    #[error("{0}: {1}")]
    Format(Location, String),
    /// The operating system refused to read the file.
    #[error("{0}: {1}")]
    Io(Location, std::io::Error),
}

impl LasFileError {
    pub fn format(loc: Location, msg: impl Into<String>) -> Self {
        LasFileError::Format(loc, msg.into())
    }
}

type Result<T> = std::result::Result<T, LasFileError>;

/// Runs the LAZ crate's decoder through the guard: a panic inside it is an
/// error at `place`.
fn guard_decoder<T>(place: impl FnOnce() -> Location, what: &str, f: impl FnOnce() -> Result<T>) -> Result<T> {
    crate::guard::run_reader(what, f).unwrap_or_else(|why| Err(LasFileError::format(place(), why)))
}

/// What the pre-check learned from the raw header.
#[derive(Debug, Clone)]
pub struct RawLasHeader {
    pub version: (u8, u8),
    pub header_size: u16,
    pub offset_to_points: u32,
    pub vlr_count: u32,
    pub point_format: u8,
    pub compressed: bool,
    pub record_length: u16,
    pub points: u64,
    pub scale: [f64; 3],
    pub offset: [f64; 3],
    pub bbox: Aabb,
    pub file_len: u64,
}

const MIN_RECORD: [u16; 11] = [20, 28, 26, 34, 57, 63, 30, 36, 38, 59, 67];

fn le_u16(b: &[u8], o: usize) -> u16 {
    u16::from_le_bytes([b[o], b[o + 1]])
}
fn le_u32(b: &[u8], o: usize) -> u32 {
    u32::from_le_bytes([b[o], b[o + 1], b[o + 2], b[o + 3]])
}
fn le_u64(b: &[u8], o: usize) -> u64 {
    let mut a = [0u8; 8];
    a.copy_from_slice(&b[o..o + 8]);
    u64::from_le_bytes(a)
}
fn le_f64(b: &[u8], o: usize) -> f64 {
    f64::from_bits(le_u64(b, o))
}

/// Reads `buf.len()` bytes of `f` at byte `at`; an I/O error names that byte.
fn read_at(path: &Path, f: &mut std::fs::File, at: u64, buf: &mut [u8]) -> Result<()> {
    f.seek(SeekFrom::Start(at))
        .and_then(|_| f.read_exact(buf))
        .map_err(|e| LasFileError::Io(Location::byte(path, at), e))
}

/// Where a LAS file's points lie and what the header says of them.
struct PointLayout {
    offset_to_points: u64,
    record_length: u16,
    points: u64,
    file_len: u64,
}

/// The most bytes one decompressed LAZ chunk may take (the chunk's points
/// times the record length). The decompressor holds a whole chunk at once, so
/// a header field must not make it ask for more: real files use chunks of
/// 50,000 points (a few MB); this allows about 30 M points of 34 bytes.
const MAX_LAZ_CHUNK_BYTES: u64 = 1 << 30;

/// Checks what the LAZ decompressor trusts: the laszip VLR (at byte `lz_at`,
/// `lz_len` bytes long) against the header's record length, and the chunk table against
/// the declared points, the compressed data's size and
/// [`MAX_LAZ_CHUNK_BYTES`]. The decompressor asserts, or allocates, on these
/// fields instead of refusing them.
fn check_laz(path: &Path, f: &mut std::fs::File, (lz_at, lz_len): (u64, u16), l: &PointLayout) -> Result<()> {
    let bad = |off: u64, msg: String| LasFileError::format(Location::byte(path, off), msg);
    let (points, record_length, file_len) = (l.points, l.record_length, l.file_len);
    if lz_len < 34 {
        return Err(bad(lz_at, format!("laszip VLR is {lz_len} bytes, shorter than its 34-byte header")));
    }
    let mut lz = vec![0u8; lz_len as usize];
    read_at(path, f, lz_at, &mut lz)?;
    let chunk_size = le_u32(&lz, 12);
    let variable_chunks = chunk_size == u32::MAX;
    let num_items = le_u16(&lz, 32) as u64;
    if 34 + num_items * 6 > lz_len as u64 {
        return Err(bad(lz_at + 32, format!("laszip VLR lists {num_items} items, more than its {lz_len} bytes hold")));
    }
    // Each item is (type, size, version); together they make one point. The
    // decompressor reads each item's fixed size whatever size the VLR gives,
    // so the two must agree.
    let items: Vec<[u16; 3]> = (0..num_items as usize)
        .map(|k| [le_u16(&lz, 34 + 6 * k), le_u16(&lz, 34 + 6 * k + 2), le_u16(&lz, 34 + 6 * k + 4)])
        .collect();
    for (k, &[kind, size, _]) in items.iter().enumerate() {
        if let Some(fixed) = laz_item_size(kind)
            && fixed != size
        {
            return Err(bad(
                lz_at + 34 + 6 * k as u64 + 2,
                format!("laszip item {k} (type {kind}) is given as {size} bytes; that type is {fixed} bytes"),
            ));
        }
    }
    let items_size: u64 = items.iter().map(|i| i[1] as u64).sum();
    if items_size != record_length as u64 {
        return Err(bad(
            lz_at + 34,
            format!(
                "laszip VLR's items make {items_size}-byte points, but the header's record length is {record_length} bytes"
            ),
        ));
    }
    if chunk_size == 0 {
        return Err(bad(lz_at + 12, "laszip VLR gives a chunk size of 0 points".into()));
    }
    if !variable_chunks && chunk_size as u64 * record_length as u64 > MAX_LAZ_CHUNK_BYTES {
        return Err(bad(
            lz_at + 12,
            format!(
                "laszip chunks of {chunk_size} points of {record_length} bytes exceed the {} MiB liftplan decompresses at once (re-compress with smaller chunks, e.g. 50,000 points)",
                MAX_LAZ_CHUNK_BYTES >> 20
            ),
        ));
    }
    // Chunk table: an i64 offset at the start of the point data, or at the end.
    let data_at = l.offset_to_points;
    if data_at + 8 > file_len {
        return Err(bad(data_at, "the file ends where the compressed point data should start".into()));
    }
    let mut b = [0u8; 8];
    read_at(path, f, data_at, &mut b)?;
    let mut table_at = i64::from_le_bytes(b);
    if table_at <= data_at as i64 && file_len >= 8 {
        read_at(path, f, file_len - 8, &mut b)?;
        table_at = i64::from_le_bytes(b);
    }
    if table_at <= data_at as i64 {
        // No chunk table: the decompressor refuses the file with its own error.
        return Ok(());
    }
    let t = table_at as u64;
    if t + 8 > file_len {
        return Err(bad(
            data_at,
            format!(
                "LAZ chunk table offset {t} lies beyond the end of the file ({file_len} bytes): the file is truncated"
            ),
        ));
    }
    let mut tb = [0u8; 8];
    read_at(path, f, t, &mut tb)?;
    let chunks = le_u32(&tb, 4) as u64;
    let by_size = file_len / 4;
    let by_points = if variable_chunks { u64::MAX } else { points / chunk_size as u64 + 2 };
    if chunks > by_size.min(by_points) {
        return Err(bad(
            t + 4,
            format!(
                "LAZ chunk table lists {chunks} chunks, more than {points} points in chunks of {chunk_size} or a {file_len}-byte file can hold"
            ),
        ));
    }
    f.seek(SeekFrom::Start(t)).map_err(|e| LasFileError::Io(Location::byte(path, t), e))?;
    // laz's arithmetic decoder panics on some damaged tables (found by the
    // scan_file fuzz target).
    let table = guard_decoder(
        || Location::byte(path, t),
        "the LAZ chunk table's decoder",
        || {
            laz::laszip::ChunkTable::read(f, variable_chunks)
                .map_err(|e| bad(t, format!("LAZ chunk table cannot be decoded: {e}")))
        },
    )?;
    let entries: &[laz::laszip::ChunkTableEntry] = table.as_ref();
    // The decoder gives each count as a 32-bit integer; read as u64, a
    // negative one is huge, which the sums below refuse.
    let bytes = entries.iter().fold(0u64, |s, e| s.saturating_add(e.byte_count));
    let span = t - data_at;
    if bytes > span {
        return Err(bad(
            t,
            format!(
                "LAZ chunk table's chunks add up to {bytes} bytes, but only {span} lie between the point data and the table"
            ),
        ));
    }
    if variable_chunks {
        // Writers may end the table with an empty chunk (lazrs does).
        for (k, e) in entries.iter().enumerate() {
            if e.point_count.saturating_mul(record_length as u64) > MAX_LAZ_CHUNK_BYTES {
                return Err(bad(
                    t,
                    format!(
                        "LAZ chunk {k} holds {} points; a chunk may hold up to {} points of {record_length} bytes",
                        e.point_count,
                        MAX_LAZ_CHUNK_BYTES / record_length as u64
                    ),
                ));
            }
        }
        let listed = entries.iter().fold(0u64, |s, e| s.saturating_add(e.point_count));
        if listed != points {
            return Err(bad(
                t,
                format!("LAZ chunk table's chunks hold {listed} points, but the header declares {points}"),
            ));
        }
    } else if chunks.saturating_mul(chunk_size as u64) < points {
        return Err(bad(
            t + 4,
            format!(
                "LAZ chunk table lists {chunks} chunks of {chunk_size} points, fewer than the {points} points the header declares"
            ),
        ));
    }
    // The decompressor takes the points as layered when the first item's
    // version is 3 or 4, whatever the VLR's compressor field says.
    if matches!(items.first(), Some([_, _, 3 | 4])) {
        check_layers(path, f, &items, entries, data_at + 8, record_length)?;
    }
    Ok(())
}

/// The size in bytes of a laszip item of a fixed-size type (`None` for the
/// extra-bytes types, whose size the VLR gives, and for unknown types, which
/// the decompressor refuses).
fn laz_item_size(kind: u16) -> Option<u16> {
    match kind {
        6 => Some(20),      // POINT10
        7 => Some(8),       // GPSTIME11
        8 | 11 => Some(6),  // RGB12, RGB14
        9 | 13 => Some(29), // WAVEPACKET13, WAVEPACKET14
        10 => Some(30),     // POINT14
        12 => Some(8),      // RGBNIR14
        _ => None,          // BYTE, BYTE14, unknown
    }
}

/// Checks that every chunk's layers fit in the chunk, for LAS 1.4's layered
/// compression. A chunk opens with its first point raw, its point count and
/// each layer's size in bytes, and the decompressor allocates each layer's
/// stated size before it reads the layer, so a damaged size would have it
/// ask for up to 4 GiB.
///
/// `items` are the laszip VLR's (type, size, version); the chunks lie one
/// after the other from `first_chunk_at`, each `byte_count` long.
fn check_layers(
    path: &Path,
    f: &mut std::fs::File,
    items: &[[u16; 3]],
    entries: &[laz::laszip::ChunkTableEntry],
    first_chunk_at: u64,
    record_length: u16,
) -> Result<()> {
    // Layers per item: POINT14 9 (xy and returns, z, classification, flags,
    // intensity, scan angle, user data, point source, GPS time), RGB14 1,
    // RGBNIR14 2, WAVEPACKET14 1, BYTE14 one per byte.
    let layers: usize = items
        .iter()
        .map(|&[kind, size, _]| match kind {
            10 => 9,
            11 | 13 => 1,
            12 => 2,
            14 => size as usize,
            _ => 0,
        })
        .sum();
    let head = record_length as u64 + 4 + 4 * layers as u64;
    let mut sizes = vec![0u8; 4 * layers];
    let mut at = first_chunk_at;
    for (k, e) in entries.iter().enumerate() {
        // A chunk too short to hold its sizes fails to decompress on its own,
        // reading past its end; only the sizes it holds can mislead.
        if e.byte_count >= head {
            let sizes_at = at + record_length as u64 + 4;
            read_at(path, f, sizes_at, &mut sizes)?;
            let stated: u64 = sizes.chunks_exact(4).map(|b| le_u32(b, 0) as u64).sum();
            let room = e.byte_count - head;
            if stated > room {
                return Err(LasFileError::format(
                    Location::byte(path, sizes_at),
                    format!(
                        "LAZ chunk {k}'s layers add up to {stated} bytes, but the chunk holds {room} after its first point and layer sizes"
                    ),
                ));
            }
        }
        at = at.saturating_add(e.byte_count);
    }
    Ok(())
}

/// Validates the structure of a LAS/LAZ file without trusting any field.
pub fn precheck(path: &Path) -> Result<RawLasHeader> {
    let bad = |off: u64, msg: String| LasFileError::format(Location::byte(path, off), msg);
    let mut f = std::fs::File::open(path).map_err(|e| LasFileError::Io(Location::file(path), e))?;
    let file_len = f.metadata().map_err(|e| LasFileError::Io(Location::file(path), e))?.len();
    let mut h = vec![0u8; 375.min(file_len as usize)];
    f.read_exact(&mut h).map_err(|e| LasFileError::Io(Location::file(path), e))?;
    if h.len() < 227 {
        return Err(bad(0, format!("file is {file_len} bytes, shorter than a LAS header (227 bytes)")));
    }
    if &h[0..4] != b"LASF" {
        return Err(bad(0, "missing the 'LASF' signature: not a LAS/LAZ file".into()));
    }
    let version = (h[24], h[25]);
    if version.0 != 1 || version.1 > 4 {
        return Err(bad(24, format!("LAS version {}.{} is not 1.0 to 1.4", version.0, version.1)));
    }
    let min_header: u16 = match version.1 {
        0..=2 => 227,
        3 => 235,
        _ => 375,
    };
    let header_size = le_u16(&h, 94);
    if header_size < min_header || header_size as u64 > file_len {
        return Err(bad(
            94,
            format!(
                "header size {header_size} is invalid for LAS {}.{} (expected at least {min_header}, file is {file_len} bytes)",
                version.0, version.1
            ),
        ));
    }
    let offset_to_points = le_u32(&h, 96);
    if (offset_to_points as u64) < header_size as u64 || offset_to_points as u64 > file_len {
        return Err(bad(
            96,
            format!(
                "offset to point data {offset_to_points} lies outside the file (header {header_size} bytes, file {file_len} bytes)"
            ),
        ));
    }
    let vlr_count = le_u32(&h, 100);
    let vlr_space = (offset_to_points - header_size as u32) as u64;
    if vlr_count as u64 * 54 > vlr_space {
        return Err(bad(100, format!("{vlr_count} VLRs cannot fit in the {vlr_space} bytes before the point data")));
    }
    let format_byte = h[104];
    let compressed = format_byte & 0x80 != 0 || format_byte & 0x40 != 0;
    let point_format = format_byte & 0x3f;
    if point_format > 10 {
        return Err(bad(104, format!("point data format {point_format} is not 0 to 10")));
    }
    let record_length = le_u16(&h, 105);
    if record_length < MIN_RECORD[point_format as usize] {
        return Err(bad(
            105,
            format!(
                "record length {record_length} is shorter than point format {point_format} needs ({})",
                MIN_RECORD[point_format as usize]
            ),
        ));
    }
    let legacy_points = le_u32(&h, 107) as u64;
    let points = if version.1 >= 4 && h.len() >= 255 {
        let p64 = le_u64(&h, 247);
        // LAS 1.4 R15: a non-zero legacy count must equal the 64-bit one (a
        // reader that finds them apart should say so). The point reader goes
        // by the legacy one, so a file whose counts differ is refused rather
        // than read to a count its checks were not made for.
        if legacy_points != 0 && p64 != legacy_points {
            return Err(bad(
                247,
                format!(
                    "the header's point counts disagree: {p64} (LAS 1.4, byte 247) against {legacy_points} (legacy, byte 107)"
                ),
            ));
        }
        if p64 != 0 { p64 } else { legacy_points }
    } else {
        legacy_points
    };
    let scale = [le_f64(&h, 131), le_f64(&h, 139), le_f64(&h, 147)];
    let offset = [le_f64(&h, 155), le_f64(&h, 163), le_f64(&h, 171)];
    if scale.iter().any(|s| !s.is_finite() || *s == 0.0) {
        return Err(bad(131, format!("scale factors {scale:?} must be finite and non-zero")));
    }
    if offset.iter().any(|s| !s.is_finite()) {
        return Err(bad(155, format!("offsets {offset:?} must be finite")));
    }
    let (maxx, minx, maxy, miny, maxz, minz) =
        (le_f64(&h, 179), le_f64(&h, 187), le_f64(&h, 195), le_f64(&h, 203), le_f64(&h, 211), le_f64(&h, 219));
    let bbox = Aabb { min: [minx, miny, minz], max: [maxx, maxy, maxz] };

    // VLR headers: each must fit before the point data.
    let mut pos = header_size as u64;
    let mut laszip: Option<(u64, u16)> = None;
    for i in 0..vlr_count {
        if pos + 54 > offset_to_points as u64 {
            return Err(bad(pos, format!("VLR {i} header runs past the start of the point data")));
        }
        let mut vh = [0u8; 54];
        read_at(path, &mut f, pos, &mut vh)?;
        let len = le_u16(&vh, 20) as u64;
        if pos + 54 + len > offset_to_points as u64 {
            return Err(bad(
                pos + 20,
                format!("VLR {i} declares {len} bytes, more than the space before the point data"),
            ));
        }
        let user = String::from_utf8_lossy(&vh[2..18]).trim_end_matches('\0').to_string();
        if user == "laszip encoded" && le_u16(&vh, 18) == 22204 {
            laszip = Some((pos + 54, len as u16));
        }
        pos += 54 + len;
    }
    if compressed {
        let Some(laszip) = laszip else {
            return Err(bad(104, "point format is marked compressed but the laszip VLR is missing".into()));
        };
        let layout = PointLayout { offset_to_points: offset_to_points as u64, record_length, points, file_len };
        check_laz(path, &mut f, laszip, &layout)?;
    } else {
        let need = points.saturating_mul(record_length as u64);
        let have = file_len - offset_to_points as u64;
        if need > have {
            let fits = have / record_length as u64;
            return Err(bad(
                offset_to_points as u64,
                format!(
                    "header declares {points} points of {record_length} bytes but the file holds only {fits} (truncated file or wrong point count)"
                ),
            ));
        }
    }
    // LAS 1.4 EVLRs must lie inside the file.
    if version.1 >= 4 && h.len() >= 247 {
        let evlr_start = le_u64(&h, 235);
        let evlr_count = le_u32(&h, 243) as u64;
        if evlr_count > 0 {
            if evlr_start < offset_to_points as u64
                || evlr_start > file_len
                || evlr_count.saturating_mul(60) > file_len - evlr_start
            {
                return Err(bad(
                    235,
                    format!("{evlr_count} EVLRs at byte {evlr_start} do not fit in the {file_len}-byte file"),
                ));
            }
            let mut p = evlr_start;
            for i in 0..evlr_count {
                let mut eh = [0u8; 60];
                if p + 60 > file_len {
                    return Err(bad(p, format!("EVLR {i} header runs past the end of the file")));
                }
                read_at(path, &mut f, p, &mut eh)?;
                let len = le_u64(&eh, 20);
                if len > file_len - p - 60 {
                    return Err(bad(p + 20, format!("EVLR {i} declares {len} bytes, past the end of the file")));
                }
                p += 60 + len;
            }
        }
    }
    Ok(RawLasHeader {
        version,
        header_size,
        offset_to_points,
        vlr_count,
        point_format,
        compressed,
        record_length,
        points,
        scale,
        offset,
        bbox,
        file_len,
    })
}
