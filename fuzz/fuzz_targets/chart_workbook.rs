//! Load-chart workbooks (xlsx, xls, xlsb, ods) through reading and grid
//! detection. The first byte picks what the rest is:
//! - 0 to 3: a whole xlsx, xls, xlsb or ods file;
//! - 4: an ODS `content.xml`, 5: an xlsx worksheet, 6: an xlsx shared-strings
//!   part, 7: an xlsb worksheet (BIFF12 records), each zipped here into an
//!   otherwise valid workbook (for xlsb, `fixtures/charts/chart.xlsb`'s).
//!
//! Modes 4 to 7 exist because workbook parts are deflated: a mutation of a
//! whole file almost never survives unpacking, so the XML readers behind the
//! zip container (and `liftplan_charts::container`'s counting) would go
//! untested.
#![no_main]
use libfuzzer_sys::fuzz_target;
use std::io::Write;

const MANIFEST: &str = r#"<?xml version="1.0" encoding="UTF-8"?><manifest:manifest xmlns:manifest="urn:oasis:names:tc:opendocument:xmlns:manifest:1.0" manifest:version="1.2"><manifest:file-entry manifest:full-path="/" manifest:media-type="application/vnd.oasis.opendocument.spreadsheet"/><manifest:file-entry manifest:full-path="content.xml" manifest:media-type="text/xml"/></manifest:manifest>"#;
const CONTENT_TYPES: &str = r#"<?xml version="1.0" encoding="UTF-8"?><Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types"><Default Extension="rels" ContentType="application/vnd.openxmlformats-package.relationships+xml"/><Default Extension="xml" ContentType="application/xml"/><Override PartName="/xl/workbook.xml" ContentType="application/vnd.openxmlformats-officedocument.spreadsheetml.sheet.main+xml"/><Override PartName="/xl/worksheets/sheet1.xml" ContentType="application/vnd.openxmlformats-officedocument.spreadsheetml.worksheet+xml"/><Override PartName="/xl/sharedStrings.xml" ContentType="application/vnd.openxmlformats-officedocument.spreadsheetml.sharedStrings+xml"/></Types>"#;
const RELS: &str = r#"<?xml version="1.0" encoding="UTF-8"?><Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships"><Relationship Id="rId1" Type="http://schemas.openxmlformats.org/officeDocument/2006/relationships/officeDocument" Target="xl/workbook.xml"/></Relationships>"#;
const WORKBOOK: &str = r#"<?xml version="1.0" encoding="UTF-8"?><workbook xmlns="http://schemas.openxmlformats.org/spreadsheetml/2006/main" xmlns:r="http://schemas.openxmlformats.org/officeDocument/2006/relationships"><sheets><sheet name="Chart" sheetId="1" r:id="rId1"/></sheets></workbook>"#;
const WORKBOOK_RELS: &str = r#"<?xml version="1.0" encoding="UTF-8"?><Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships"><Relationship Id="rId1" Type="http://schemas.openxmlformats.org/officeDocument/2006/relationships/worksheet" Target="worksheets/sheet1.xml"/><Relationship Id="rId2" Type="http://schemas.openxmlformats.org/officeDocument/2006/relationships/sharedStrings" Target="sharedStrings.xml"/></Relationships>"#;
/// A worksheet of a small chart whose labels are shared strings 0 to 2.
const SHEET: &str = r#"<?xml version="1.0" encoding="UTF-8"?><worksheet xmlns="http://schemas.openxmlformats.org/spreadsheetml/2006/main"><sheetData><row r="1"><c r="A1" t="s"><v>0</v></c></row><row r="2"><c r="A2" t="s"><v>1</v></c><c r="B2" t="s"><v>2</v></c></row><row r="3"><c r="B3"><v>20</v></c><c r="C3"><v>30</v></c></row><row r="4"><c r="A4"><v>3</v></c><c r="B4"><v>50</v></c><c r="C4"><v>40</v></c></row><row r="5"><c r="A5"><v>5</v></c><c r="B5"><v>30</v></c><c r="C5"><v>25</v></c></row></sheetData></worksheet>"#;
const SHARED: &str = r#"<?xml version="1.0" encoding="UTF-8"?><sst xmlns="http://schemas.openxmlformats.org/spreadsheetml/2006/main" count="3" uniqueCount="3"><si><t>Main boom, capacities in t</t></si><si><t>Radius (m)</t></si><si><t>Boom length (m)</t></si></sst>"#;

static PANIC_HOOK: std::sync::Once = std::sync::Once::new();

fuzz_target!(|data: &[u8]| {
    // calamine is called through `liftplan_core::guard`, which turns its
    // panics into errors; put the default panic hook back so such a caught
    // panic is not reported as a crash (see scan_file.rs).
    PANIC_HOOK.call_once(|| drop(std::panic::take_hook()));
    let Some((&sel, body)) = data.split_first() else { return };
    let dir = tempfile::tempdir().unwrap();
    let (ext, bytes) = match sel % 8 {
        m @ 0..=3 => (["xlsx", "xls", "xlsb", "ods"][m as usize], body.to_vec()),
        4 => (
            "ods",
            zipped(&[
                ("mimetype", b"application/vnd.oasis.opendocument.spreadsheet"),
                ("META-INF/manifest.xml", MANIFEST.as_bytes()),
                ("content.xml", body),
            ]),
        ),
        7 => {
            let mut parts: Vec<(&str, &[u8])> = xlsb_parts()
                .iter()
                .map(|(n, d)| (n.as_str(), d.as_slice()))
                .filter(|(n, _)| *n != XLSB_SHEET)
                .collect();
            parts.push((XLSB_SHEET, body));
            ("xlsb", zipped(&parts))
        }
        m => {
            let (sheet, shared) = if m == 5 { (body, SHARED.as_bytes()) } else { (SHEET.as_bytes(), body) };
            (
                "xlsx",
                zipped(&[
                    ("[Content_Types].xml", CONTENT_TYPES.as_bytes()),
                    ("_rels/.rels", RELS.as_bytes()),
                    ("xl/workbook.xml", WORKBOOK.as_bytes()),
                    ("xl/_rels/workbook.xml.rels", WORKBOOK_RELS.as_bytes()),
                    ("xl/worksheets/sheet1.xml", sheet),
                    ("xl/sharedStrings.xml", shared),
                ]),
            )
        }
    };
    let path = dir.path().join(format!("chart.{ext}"));
    std::fs::write(&path, bytes).unwrap();
    let _ = liftplan_charts::inspect(&path);
});

const XLSB_SHEET: &str = "xl/worksheets/sheet1.bin";

/// The parts of `fixtures/charts/chart.xlsb` (name, unpacked bytes).
fn xlsb_parts() -> &'static [(String, Vec<u8>)] {
    static PARTS: std::sync::OnceLock<Vec<(String, Vec<u8>)>> = std::sync::OnceLock::new();
    PARTS.get_or_init(|| {
        use std::io::Read;
        let file = include_bytes!("../../fixtures/charts/chart.xlsb");
        let mut zip = zip::ZipArchive::new(std::io::Cursor::new(&file[..])).unwrap();
        (0..zip.len())
            .map(|i| {
                let mut part = zip.by_index(i).unwrap();
                let mut data = Vec::new();
                part.read_to_end(&mut data).unwrap();
                (part.name().unwrap().into_owned(), data)
            })
            .collect()
    })
}

/// A zip archive of `parts`, deflated (the mimetype stored, as ODS asks).
fn zipped(parts: &[(&str, &[u8])]) -> Vec<u8> {
    let mut w = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    for (name, data) in parts {
        let method =
            if *name == "mimetype" { zip::CompressionMethod::Stored } else { zip::CompressionMethod::Deflated };
        w.start_file(*name, zip::write::SimpleFileOptions::default().compression_method(method)).unwrap();
        w.write_all(data).unwrap();
    }
    w.finish().unwrap().into_inner()
}
