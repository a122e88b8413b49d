//! LAS 1.0–1.4 and LAZ through the `las` and `laz` crates, with a header
//! pre-check of our own.
//!
//! The pre-check reads the public header block, the VLR and EVLR headers and the
//! LAZ chunk-table header directly and refuses any count or offset the file cannot
//! hold, before the `las` crate sizes a buffer from them. Real files have odd
//! headers (padding after the header, extra bytes per point, user VLRs, legacy and
//! 64-bit point counts that disagree); those are accepted.

use super::{CHUNK_POINTS, Format, ScanInfo, check_finite, guard_decoder, stem};
use crate::error::{Result, ScanError};
use las::Reader;
use liftplan_core::Location;
use liftplan_core::cloud::PointCloud;
use liftplan_core::frame::Aabb;
use serde_json::json;
use std::io::{Read, Seek, SeekFrom};
use std::path::Path;

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
    f.seek(SeekFrom::Start(at)).and_then(|_| f.read_exact(buf)).map_err(|e| ScanError::Io(Location::byte(path, at), e))
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
    let bad = |off: u64, msg: String| ScanError::format(Location::byte(path, off), msg);
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
    f.seek(SeekFrom::Start(t)).map_err(|e| ScanError::Io(Location::byte(path, t), e))?;
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
                return Err(ScanError::format(
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
    let bad = |off: u64, msg: String| ScanError::format(Location::byte(path, off), msg);
    let mut f = std::fs::File::open(path).map_err(|e| ScanError::Io(Location::file(path), e))?;
    let file_len = f.metadata().map_err(|e| ScanError::Io(Location::file(path), e))?.len();
    let mut h = vec![0u8; 375.min(file_len as usize)];
    f.read_exact(&mut h).map_err(|e| ScanError::Io(Location::file(path), e))?;
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

fn open(path: &Path) -> Result<Reader> {
    let file = std::fs::File::open(path).map_err(|e| ScanError::Io(Location::file(path), e))?;
    let r = std::io::BufReader::with_capacity(1 << 20, file);
    guard_decoder(
        || Location::file(path),
        "the LAS/LAZ reader",
        || Reader::new(r).map_err(|e| ScanError::format(Location::file(path), format!("cannot read LAS header: {e}"))),
    )
}

pub(super) fn list(path: &Path, format: Format) -> Result<Vec<ScanInfo>> {
    let raw = precheck(path)?;
    let reader = open(path)?;
    let hdr = reader.header();
    let fmt = if raw.compressed { Format::Laz } else { Format::Las };
    if fmt != format {
        tracing::warn!("{}: extension says {} but the file is {}", path.display(), format.name(), fmt.name());
    }
    let mut details = serde_json::Map::new();
    details.insert("version".into(), json!(format!("{}.{}", raw.version.0, raw.version.1)));
    details.insert("point_format".into(), json!(raw.point_format));
    details.insert("compressed".into(), json!(raw.compressed));
    details.insert("record_length".into(), json!(raw.record_length));
    details.insert("scale".into(), json!(raw.scale));
    details.insert("offset".into(), json!(raw.offset));
    details.insert("vlrs".into(), json!(hdr.vlrs().len()));
    details.insert("evlrs".into(), json!(hdr.evlrs().len()));
    details.insert("crs".into(), json!(hdr.has_crs_vlrs()));
    let unit = crs_unit(path, hdr)?;
    let said = match &unit {
        super::CrsUnit::Stated(u) => u.what.clone(),
        super::CrsUnit::Unstated { crs, .. } => format!("NOT STATED by its CRS ({crs})"),
        super::CrsUnit::None => "none stated (no CRS)".into(),
    };
    details.insert("unit".into(), json!(said));
    details.insert("system_identifier".into(), json!(hdr.system_identifier()));
    details.insert("generating_software".into(), json!(hdr.generating_software()));
    Ok(vec![ScanInfo {
        path: path.to_path_buf(),
        format: fmt,
        index: 0,
        name: stem(path),
        declared_points: Some(raw.points),
        pose: None,
        bbox: Some(raw.bbox),
        details,
        unit,
        date: hdr.date().map(|date| super::ScanDate { date, acquired: false }),
        to_m: [1.0; 3],
        read_in: String::new(),
    }])
}

/// The unit the file's CRS (E)VLRs state: the WKT's where it has one (LAS
/// 1.4 makes it the CRS), else the GeoTIFF keys'.
fn crs_unit(path: &Path, hdr: &las::Header) -> Result<super::CrsUnit> {
    let projection =
        |id: u16| hdr.all_vlrs().find(|v| v.user_id.trim_end_matches('\0') == "LASF_Projection" && v.record_id == id);
    let (found, record) = if let Some(v) = projection(2112) {
        (super::units::from_wkt(&v.data), "WKT CRS (record 2112)")
    } else if let Some(v) = projection(34735) {
        (super::units::from_geokeys(&v.data), "GeoTIFF keys (record 34735)")
    } else {
        return Ok(super::CrsUnit::None);
    };
    match found.map_err(|why| ScanError::format(Location::item(path, record), why))? {
        super::CrsUnit::Unstated { crs, heights } => {
            Ok(super::CrsUnit::Unstated { crs: format!("{crs}, in its {record}"), heights })
        }
        unit => Ok(unit),
    }
}

pub(super) fn stream(info: &ScanInfo, f: &mut dyn FnMut(&PointCloud) -> Result<()>) -> Result<u64> {
    let raw = precheck(&info.path)?;
    let mut reader = open(&info.path)?;
    let declared = raw.points;
    let mut data = las::PointDataBuilder::new().for_header(reader.header()).build();
    let has_rgb = reader.header().point_format().has_color;
    let mut chunk = PointCloud::default();
    let mut seen = 0u64;
    loop {
        let place = || Location::item(&info.path, format!("point {seen}"));
        let n = guard_decoder(place, "the LAS/LAZ point reader", || {
            reader.fill_points(CHUNK_POINTS as u64, &mut data).map_err(|e| {
                ScanError::format(
                    place(),
                    format!(
                        "cannot decode points after {seen} of the {declared} the header declares: {e} (truncated or corrupt file)"
                    ),
                )
            })
        })?;
        if n == 0 {
            break;
        }
        chunk.xyz.clear();
        chunk.intensity.clear();
        chunk.rgb.clear();
        chunk.class.clear();
        chunk.scan.clear();
        chunk.xyz.extend(data.x().zip(data.y()).zip(data.z()).map(|((x, y), z)| [x, y, z]));
        chunk.intensity.extend(data.intensity());
        chunk.class.extend(data.classification());
        if has_rgb && let Some(rgb) = data.rgb() {
            chunk.rgb.extend(rgb.map(|(r, g, b)| [r, g, b]));
        }
        check_finite(info, &chunk, seen)?;
        seen += n;
        f(&chunk)?;
    }
    if seen < declared {
        return Err(ScanError::format(
            Location::file(&info.path),
            format!("header declares {declared} points but the data ends after {seen} (truncated file)"),
        ));
    }
    Ok(seen)
}

#[cfg(test)]
mod tests {
    use super::*;
    use liftplan_core::cloud::PointCloud;

    /// A 1000-point LAZ written by liftplan, and where its laszip VLR's
    /// payload starts.
    fn small_laz(dir: &Path) -> (std::path::PathBuf, Vec<u8>, usize) {
        let mut c = PointCloud::default();
        for k in 0..1000 {
            c.xyz.push([k as f64 * 0.01, (k % 37) as f64 * 0.1, (k % 11) as f64 * 0.2]);
            c.intensity.push(k as u16);
        }
        let path = dir.join("a.laz");
        crate::write::write_las(&path, &c).unwrap();
        let bytes = std::fs::read(&path).unwrap();
        let user = bytes.windows(14).position(|w| w == b"laszip encoded").expect("a laszip VLR");
        // The user id starts 2 bytes into the 54-byte VLR header.
        (path, bytes, user - 2 + 54)
    }

    /// A file in `fixtures/scans/`.
    fn fixture(name: &str) -> std::path::PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/scans").join(name)
    }

    fn damaged(path: &Path, bytes: &[u8], at: usize, value: &[u8]) -> String {
        let mut b = bytes.to_vec();
        b[at..at + value.len()].copy_from_slice(value);
        std::fs::write(path, &b).unwrap();
        let err = list(path, Format::Laz).and_then(|s| super::super::read_all(&s[0]));
        err.expect_err("a damaged file must be refused").to_string()
    }

    #[test]
    fn laz_fields_the_decompressor_trusts_are_checked() {
        let dir = tempfile::tempdir().unwrap();
        let (path, bytes, vlr) = small_laz(dir.path());
        let info = list(&path, Format::Laz).unwrap();
        assert_eq!(super::super::read_all(&info[0]).unwrap().len(), 1000, "the undamaged file reads whole");

        // Items that make a point other than the header's record length
        // (found by the scan_file fuzz target: the decompressor asserted).
        let record = le_u16(&bytes, 105);
        let e = damaged(&path, &bytes, 105, &(record + 1).to_le_bytes());
        assert!(e.contains("a.laz") && e.contains("record length"), "{e}");

        // An item whose size is not its type's.
        let e = damaged(&path, &bytes, vlr + 34 + 2, &(record + 1).to_le_bytes());
        assert!(e.contains("item 0 (type 10) is given as 31 bytes; that type is 30 bytes"), "{e}");

        // A POINT14 item (30 bytes) retyped as RGB14 (6 bytes): the
        // decompressor would read a 6-byte first point and take the next
        // bytes for layer sizes (found by the fuzz target: a 4 GB layer).
        let e = damaged(&path, &bytes, vlr + 34, &11u16.to_le_bytes());
        assert!(e.contains("item 0 (type 11) is given as 30 bytes; that type is 6 bytes"), "{e}");

        // Chunks too large to hold in memory at once.
        let e = damaged(&path, &bytes, vlr + 12, &0x7fff_fff0u32.to_le_bytes());
        assert!(e.contains("MiB") && e.contains(&format!("byte {}", vlr + 12)), "{e}");

        // Chunks too small for the points declared: the one chunk cannot hold them.
        let e = damaged(&path, &bytes, vlr + 12, &100u32.to_le_bytes());
        assert!(e.contains("fewer than the 1000 points"), "{e}");

        let e = damaged(&path, &bytes, vlr + 12, &0u32.to_le_bytes());
        assert!(e.contains("chunk size of 0"), "{e}");

        // A layer of the first chunk stated at 2 GiB (found by the fuzz
        // target: the decompressor allocated it before reading). The chunk
        // opens after the 8-byte table offset with its first point (30 bytes
        // in format 6) and its point count.
        let sizes = le_u32(&bytes, 96) as usize + 8 + 30 + 4;
        let e = damaged(&path, &bytes, sizes, &0x7fff_ffffu32.to_le_bytes());
        assert!(e.contains("chunk 0's layers") && e.contains(&format!("byte {sizes}")), "{e}");
    }
    /// The fixture's 250 points in variable-size chunks (100, 70, 80, then the
    /// empty one lazrs ends with), as COPC files are chunked.
    fn variable_chunks(dir: &Path) -> (std::path::PathBuf, Vec<u8>) {
        let fixture = fixture("variable-chunks.laz");
        let bytes = std::fs::read(fixture).unwrap();
        let path = dir.join("v.laz");
        std::fs::write(&path, &bytes).unwrap();
        (path, bytes)
    }

    #[test]
    fn variable_size_chunks_read_whole_and_their_counts_are_checked() {
        let dir = tempfile::tempdir().unwrap();
        let (path, bytes) = variable_chunks(dir.path());
        let info = list(&path, Format::Laz).unwrap();
        let c = super::super::read_all(&info[0]).unwrap();
        assert_eq!(c.len(), 250);
        let b = info[0].bbox.unwrap();
        assert!(
            c.xyz.iter().all(|p| (0..3).all(|k| p[k] >= b.min[k] && p[k] <= b.max[k])),
            "points inside the header's box"
        );

        // One point more in the header than in the chunks, in both counts.
        let mut more = bytes.clone();
        more[107..111].copy_from_slice(&251u32.to_le_bytes());
        more[247..255].copy_from_slice(&251u64.to_le_bytes());
        std::fs::write(&path, &more).unwrap();
        let e = list(&path, Format::Laz).unwrap_err().to_string();
        assert!(e.contains("v.laz") && e.contains("hold 250 points, but the header declares 251"), "{e}");

        // The legacy count apart from the LAS 1.4 one.
        let e = damaged(&path, &bytes, 107, &249u32.to_le_bytes());
        assert!(e.contains("byte 247") && e.contains("disagree"), "{e}");
    }
    /// Found by the scan_file fuzz target: a LAZ (LAS 1.4, format 7) whose
    /// compressed points make `laz`'s arithmetic decoder index past its table
    /// and panic. Its structure passes every check, so the panic is caught and
    /// becomes an error naming the file and the point.
    #[test]
    fn a_panic_in_the_decompressor_is_an_error() {
        let path = fixture("damaged-decoder-panic.laz");
        let info = list(&path, Format::Laz).unwrap();
        let e = super::super::read_all(&info[0]).unwrap_err().to_string();
        assert!(
            e.contains("damaged-decoder-panic.laz") && e.contains("point 0") && e.contains("failed on damaged data"),
            "{e}"
        );
    }
    /// Found by the scan_file fuzz target: a chunk table whose
    /// arithmetic-coded counts make the same decoder panic while `precheck`
    /// reads the table.
    #[test]
    fn a_panic_decoding_the_chunk_table_is_an_error() {
        let path = fixture("damaged-chunk-table.laz");
        let e = list(&path, Format::Laz).unwrap_err().to_string();
        assert!(e.contains("damaged-chunk-table.laz at byte") && e.contains("chunk table's decoder failed"), "{e}");
    }
    /// Found by the scan_file fuzz target: a LAZ (format 1) whose GPS times
    /// switch sequence without end. `laz` 0.13.0 recursed once per switch
    /// and overflowed the stack, aborting the process; the patched copy
    /// (third_party/laz) stops after four switches in one point.
    #[test]
    fn gps_times_that_switch_without_end_are_an_error() {
        let path = fixture("damaged-gps-recursion.laz");
        let info = list(&path, Format::Laz).unwrap();
        let e = super::super::read_all(&info[0]).unwrap_err().to_string();
        assert!(e.contains("damaged-gps-recursion.laz") && e.contains("switches sequence more than 4 times"), "{e}");
    }
    /// GPS times taking turns among three sequences (`make_gps_switches.py`):
    /// LASzip switches sequence at nearly every point, once per point, and
    /// the patched decoder reads every point, in formats 1 and 6.
    #[test]
    fn gps_times_that_switch_once_per_point_read_whole() {
        for name in ["gps-switches-1.laz", "gps-switches-6.laz"] {
            let info = list(&fixture(name), Format::Laz).unwrap();
            let c = super::super::read_all(&info[0]).unwrap();
            assert_eq!(c.len(), 600, "{name}");
            for (k, p) in c.xyz.iter().enumerate() {
                assert!((p[0] - k as f64 / 100.0).abs() < 1e-9 && p[1] == 2.0 && p[2] == 0.5, "{name} {k}: {p:?}");
            }
        }
    }

    /// A LAS file with `crs` as its projection record (`record_id`), points
    /// at (100, 200, 10), (110, 200, 12) in its own numbers.
    fn las_with_crs(dir: &Path, name: &str, crs: Option<(u16, Vec<u8>)>) -> std::path::PathBuf {
        let mut b = las::Builder::from((1, 4));
        b.point_format = las::point::Format::new(0).unwrap();
        if let Some((record_id, data)) = crs {
            b.vlrs.push(las::Vlr { user_id: "LASF_Projection".into(), record_id, description: String::new(), data });
        }
        let path = dir.join(name);
        let mut w = las::Writer::from_path(&path, b.into_header().unwrap()).unwrap();
        for (x, z) in [(100.0, 10.0), (110.0, 12.0)] {
            w.write_point(las::Point { x, y: 200.0, z, ..Default::default() }).unwrap();
        }
        w.close().unwrap();
        path
    }

    /// A survey in US survey feet (its GeoTIFF keys say so) is read in
    /// metres; one without a CRS in `[scans] unit`; one whose CRS is in
    /// degrees is refused, naming the file and the record; `inspect` shows
    /// the file's own numbers and the unit it states.
    #[test]
    fn coordinates_are_read_in_metres_whatever_unit_the_file_states() {
        let d = tempfile::tempdir().unwrap();
        let us_ft = 1200.0 / 3937.0;
        let feet = las_with_crs(
            d.path(),
            "ft.las",
            Some((34735, super::super::units::geokeys(&[(1024, 1), (3072, 2263), (3076, 9003)]))),
        );
        for unit in [None, Some(crate::ScanUnit::Metre), Some(crate::ScanUnit::Foot)] {
            let scans = crate::list_all(std::slice::from_ref(&feet), unit).unwrap();
            let c = super::super::read_all(&scans[0]).unwrap();
            assert!(
                (c.xyz[0][0] - 100.0 * us_ft).abs() < 1e-9 && (c.xyz[1][2] - 12.0 * us_ft).abs() < 1e-9,
                "{:?}",
                c.xyz
            );
            let b = scans[0].bbox.unwrap();
            assert!((b.max[0] - 110.0 * us_ft).abs() < 1e-6, "{b:?}");
            assert!(matches!(&scans[0].unit, super::super::CrsUnit::Stated(u) if u.what.contains("US survey foot")));
        }
        let bare = las_with_crs(d.path(), "bare.las", None);
        let c = super::super::read_all(&crate::list_all(std::slice::from_ref(&bare), None).unwrap()[0]).unwrap();
        assert_eq!(c.xyz[0], [100.0, 200.0, 10.0]);
        let c = super::super::read_all(
            &crate::list_all(std::slice::from_ref(&bare), Some(crate::ScanUnit::Foot)).unwrap()[0],
        )
        .unwrap();
        assert!((c.xyz[0][1] - 200.0 * 0.3048).abs() < 1e-9, "{:?}", c.xyz);
        let degrees = br#"GEOGCS["WGS 84",DATUM["WGS_1984",SPHEROID["WGS 84",6378137,298.257223563]],UNIT["degree",0.0174532925199433]]"#;
        let geo = las_with_crs(d.path(), "geo.las", Some((2112, degrees.to_vec())));
        let e = crate::list_all(&[geo], Some(crate::ScanUnit::Metre)).unwrap_err().to_string();
        assert!(e.contains("geo.las") && e.contains("record 2112") && e.contains("degrees"), "{e}");
        let shown = crate::inspect(&feet).unwrap().to_string();
        assert!(shown.contains("US survey foot") && shown.contains("110"), "{shown}");
    }

    /// A file whose CRS is only an EPSG code does not state its unit: it is
    /// refused unless `[scans] unit` says it (a State Plane survey in US
    /// feet read as metres puts every obstacle 3.28 times too far), and read
    /// in that unit when it does; a code of a family in metres by definition
    /// (UTM) reads in metres.
    #[test]
    fn a_crs_named_only_by_its_code_needs_the_project_to_say_its_unit() {
        let d = tempfile::tempdir().unwrap();
        let keys = |k: &[(u16, u16)]| Some((34735, super::super::units::geokeys(k)));
        let state_plane = las_with_crs(d.path(), "sp.las", keys(&[(1024, 1), (3072, 2263)]));
        let e = crate::list_all(std::slice::from_ref(&state_plane), None).unwrap_err().to_string();
        assert!(
            e.contains("sp.las") && e.contains("EPSG:2263") && e.contains("record 34735") && e.contains("[scans] unit"),
            "{e}"
        );
        let us_ft = 1200.0 / 3937.0;
        let scans = crate::list_all(std::slice::from_ref(&state_plane), Some(crate::ScanUnit::UsSurveyFoot)).unwrap();
        let c = super::super::read_all(&scans[0]).unwrap();
        assert!((c.xyz[1][0] - 110.0 * us_ft).abs() < 1e-9 && (c.xyz[1][2] - 12.0 * us_ft).abs() < 1e-9, "{:?}", c.xyz);
        let c = super::super::read_all(
            &crate::list_all(std::slice::from_ref(&state_plane), Some(crate::ScanUnit::Metre)).unwrap()[0],
        )
        .unwrap();
        assert_eq!(c.xyz[1], [110.0, 200.0, 12.0]);
        // Heights the file states stay its own.
        let with_heights = las_with_crs(d.path(), "sph.las", keys(&[(1024, 1), (3072, 2263), (4099, 9001)]));
        let c =
            super::super::read_all(&crate::list_all(&[with_heights], Some(crate::ScanUnit::UsSurveyFoot)).unwrap()[0])
                .unwrap();
        assert!((c.xyz[1][0] - 110.0 * us_ft).abs() < 1e-9 && c.xyz[1][2] == 12.0, "{:?}", c.xyz);
        let utm = las_with_crs(d.path(), "utm.las", keys(&[(1024, 1), (3072, 32632)]));
        let c = super::super::read_all(&crate::list_all(&[utm], None).unwrap()[0]).unwrap();
        assert_eq!(c.xyz[1], [110.0, 200.0, 12.0]);
        let shown = crate::inspect(&state_plane).unwrap().to_string();
        assert!(shown.contains("NOT STATED") && shown.contains("EPSG:2263"), "{shown}");
    }

    /// A LAS header's creation date is the scan's date as far as the file
    /// says, marked as the file's, not the survey's; a header without one
    /// (day and year 0, against the standard) has none.
    #[test]
    fn a_las_files_creation_date_is_read_as_such() {
        let d = tempfile::tempdir().unwrap();
        for (name, date) in [("dated.las", chrono::NaiveDate::from_ymd_opt(2026, 10, 2)), ("undated.las", None)] {
            let mut b = las::Builder::from((1, 4));
            b.date = date;
            let path = d.path().join(name);
            let mut w = las::Writer::from_path(&path, b.into_header().unwrap()).unwrap();
            w.write_point(las::Point::default()).unwrap();
            w.close().unwrap();
            let scans = super::super::list_scans(&path).unwrap();
            assert_eq!(scans[0].date, date.map(|date| super::super::ScanDate { date, acquired: false }), "{name}");
        }
        let shown = crate::inspect(&d.path().join("dated.las")).unwrap().to_string();
        assert!(shown.contains("2026-10-02 (file created)"), "{shown}");
    }
}
