//! Workbooks (xlsx, xlsm, xlsb, xls, ods) read into sparse sheets of numbers and
//! text, through `calamine`.
//!
//! xlsx and xlsb sheets are streamed cell by cell and capped at
//! [`MAX_CELLS`] in a sheet and in all sheets together, so a sheet that
//! declares a huge used range cannot drive an allocation; xls and ods are
//! read through calamine's dense ranges, only after [`crate::container`] has
//! counted the cells they will make (an ods file's repeat attributes, an xls
//! file's cell records).

use crate::error::{ChartError, Result};
use calamine::{Data, DataRef, Reader};
use liftplan_core::Location;
use liftplan_core::units::LengthUnit;
use std::collections::BTreeMap;
use std::path::Path;

pub const MAX_CELLS: usize = 2_000_000;

#[derive(Debug, Clone, PartialEq)]
pub enum Val {
    Num(f64),
    Text(String),
}

impl Val {
    /// The cell's number: a number cell's value, or a text cell holding a
    /// plain number ([`crate::decimals::plain_number`]), as charts pasted
    /// from a PDF or typed in another locale hold their radii and boom
    /// lengths ("12.5", "12,5"; Excel's "number stored as text"), with or
    /// without a length unit after it ([`length_and_unit`]: "3,0 m") and a
    /// footnote mark after that ("40*", "40 m¹").
    pub fn number(&self) -> Option<f64> {
        match self {
            Val::Num(v) => Some(*v),
            Val::Text(t) => {
                let (unmarked, _) = crate::detect::FootnoteMark::split_off(t);
                crate::decimals::plain_number(length_and_unit(unmarked).0).map(|(v, _)| v)
            }
        }
    }
}

/// Whether a cell's text is a spreadsheet's error value ("#REF!", "#N/A"),
/// as a broken formula shows.
pub fn shows_an_error(text: &str) -> bool {
    ["#DIV/0!", "#N/A", "#NAME?", "#NULL!", "#NUM!", "#REF!", "#VALUE!", "#DATA!"].contains(&text.trim())
}

/// A radius or boom length written as text with its unit after it, as
/// charts pasted from a PDF hold them ("3,0 m", "12.5m", "40 ft", "40'"):
/// the number's text and the unit. Text with no length unit after a number
/// comes back whole (trimmed), with none: what the number is, is the
/// caller's to read.
pub fn length_and_unit(text: &str) -> (&str, Option<LengthUnit>) {
    let t = text.trim_matches(|c: char| c.is_whitespace() || c == '\u{a0}');
    let number_end =
        t.find(|c: char| !(c.is_ascii_digit() || matches!(c, '.' | ',' | ' ' | '\u{a0}'))).unwrap_or(t.len());
    let (number, unit) = t.split_at(number_end);
    let number = number.trim_end_matches([' ', '\u{a0}']);
    // Words ("Radius") are passed by before anything is made of them: the
    // grid search asks this of every text cell of a sheet.
    if number.is_empty() || unit.len() > "metres".len() {
        return (t, None);
    }
    match unit.to_lowercase().as_str() {
        "m" | "meter" | "meters" | "metre" | "metres" => (number, Some(LengthUnit::M)),
        "ft" | "ft." | "feet" | "foot" | "'" | "\u{2032}" => (number, Some(LengthUnit::Ft)),
        _ => (t, None),
    }
}

#[derive(Debug, Clone, Default)]
pub struct Sheet {
    pub name: String,
    /// (row, column), 0-based.
    pub cells: BTreeMap<(u32, u32), Val>,
}

impl Sheet {
    pub fn get(&self, r: u32, c: u32) -> Option<&Val> {
        self.cells.get(&(r, c))
    }

    /// The cell's number ([`Val::number`]: a text cell holding a plain
    /// number counts).
    pub fn num(&self, r: u32, c: u32) -> Option<f64> {
        self.get(r, c).and_then(Val::number)
    }

    pub fn text(&self, r: u32, c: u32) -> Option<&str> {
        match self.get(r, c) {
            Some(Val::Text(t)) => Some(t.as_str()),
            _ => None,
        }
    }

    /// All text in the rectangle, a cell a line (for unit and label search:
    /// where one cell's words end is kept).
    pub fn text_in(&self, r0: u32, r1: u32, c0: u32, c1: u32) -> String {
        let mut out = String::new();
        for ((_, c), v) in self.cells.range((r0, 0)..=(r1, u32::MAX)) {
            if *c >= c0
                && *c <= c1
                && let Val::Text(t) = v
            {
                out.push_str(t);
                out.push('\n');
            }
        }
        out
    }
}

fn from_data(d: &Data) -> Option<Val> {
    match d {
        Data::Int(i) => Some(Val::Num(*i as f64)),
        Data::Float(f) => Some(Val::Num(*f)),
        Data::String(s) if !s.trim().is_empty() => Some(Val::Text(s.clone())),
        // What the cell shows ("#REF!"): in a chart's grid it is refused as
        // no number; read as an empty cell it was a capacity not permitted,
        // or a boom length's configuration lost, without a word.
        Data::Error(e) => Some(Val::Text(e.to_string())),
        Data::Bool(_)
        | Data::DateTime(_)
        | Data::DateTimeIso(_)
        | Data::DurationIso(_)
        | Data::String(_)
        | Data::Empty => None,
    }
}

fn from_ref(d: &DataRef) -> Option<Val> {
    match d {
        DataRef::Int(i) => Some(Val::Num(*i as f64)),
        DataRef::Float(f) => Some(Val::Num(*f)),
        DataRef::String(s) if !s.trim().is_empty() => Some(Val::Text(s.clone())),
        DataRef::SharedString(s) if !s.trim().is_empty() => Some(Val::Text(s.to_string())),
        DataRef::Error(e) => Some(Val::Text(e.to_string())),
        _ => None,
    }
}

/// The formula cells of a sheet whose values are not known: the first, and
/// how many.
#[derive(Default)]
struct Uncomputed {
    /// The first: its cell, its formula's text where known, whether the
    /// file stores no value for it (else the workbook asks to be
    /// calculated when opened).
    first: Option<((u32, u32), Option<String>, bool)>,
    cells: usize,
}

impl Uncomputed {
    fn note(&mut self, at: (u32, u32), formula: impl FnOnce() -> Option<String>, none_stored: bool) {
        self.cells += 1;
        self.first.get_or_insert_with(|| (at, formula(), none_stored));
    }

    /// The sheet's refusal at its first such cell, where it has one.
    fn refuse(&self, path: &Path, sheet: &str) -> Result<()> {
        let Some(((row, col), formula, none_stored)) = &self.first else { return Ok(()) };
        let cell = liftplan_core::location::cell_ref(*row, *col);
        let formula = formula.as_ref().map(|f| format!(" ('={f}')")).unwrap_or_default();
        let others = match self.cells {
            1 => String::new(),
            2 => " (as does one more cell on the sheet)".to_string(),
            n => format!(" (as do {} more cells on the sheet)", n - 1),
        };
        let why = match none_stored {
            false => format!(
                "the cell holds a formula{formula}{others}, and the workbook asks for its formulas to be calculated \
                 when it is opened, as programs that write workbooks without calculating them do: the value it \
                 stores (they store 0, or none) may not be what the cell shows in Excel"
            ),
            true => format!(
                "the cell holds a formula{formula} whose value the workbook does not store{others}: it was written \
                 by a program that calculates no formulas, and what the cell shows in Excel cannot be read from the \
                 file"
            ),
        };
        Err(ChartError::Format(
            Location::cell(path, &sheet_name_kept(sheet), &cell),
            format!("{why}. Open the workbook in Excel or LibreOffice and save it, so that its values are stored"),
        ))
    }
}

/// A formula's text as a cell's refusal quotes it (one line, kept short),
/// where the file gives it on the cell (a cell sharing another's formula
/// gives only the share).
fn formula_text(formula: &calamine::XlsxFormulaMetadata) -> Option<String> {
    match formula {
        calamine::XlsxFormulaMetadata::Normal { formula } | calamine::XlsxFormulaMetadata::Shared { formula, .. } => {
            Some(liftplan_core::names::kept(formula, 60).into_owned())
        }
        _ => None,
    }
}

/// Reads every sheet of a workbook.
pub fn read_workbook(path: &Path) -> Result<Vec<Sheet>> {
    let checked = crate::container::check(path)?;
    // calamine panics on some damaged files (a compound file cut short inside
    // a sector, found by the chart_workbook fuzz target); the guard turns
    // that into an error naming the file. What would hang it or exhaust
    // memory is refused by the container check above, as no guard can.
    liftplan_core::guard::run_reader("the workbook reader (calamine)", || read_sheets(path, MAX_CELLS, checked))
        .unwrap_or_else(|why| Err(ChartError::Format(Location::file(path), why)))
}

/// The most characters of a sheet's name kept: Excel allows 31, an ODS
/// file any number.
pub const MAX_SHEET_NAME_CHARS: usize = 100;

/// A sheet's name as liftplan keeps it ([`liftplan_core::names::kept`]):
/// it names the sheet's configuration in the run's lines and on the plan's
/// pages, and an ODS file's may hold a line break. A `[[charts.table]]`'s
/// sheet is matched kept the same way.
pub fn sheet_name_kept(name: &str) -> String {
    liftplan_core::names::kept(name, MAX_SHEET_NAME_CHARS).into_owned()
}

/// The sheets of the workbook at `path`, refused past `max_cells` cells in
/// a sheet or in all; each named as kept ([`sheet_name_kept`]). An xlsx
/// sheet holding a formula whose value is not known (none stored, or the
/// workbook asking to be calculated when opened: `checked`) is refused.
fn read_sheets(path: &Path, max_cells: usize, checked: crate::container::Checked) -> Result<Vec<Sheet>> {
    let bad = |msg: String| ChartError::Format(Location::file(path), msg);
    let mut wb = calamine::open_workbook_auto(path).map_err(|e| bad(format!("cannot open the workbook: {e}")))?;
    let names = wb.sheet_names().to_vec();
    let mut out = Vec::new();
    // Cells kept from the sheets before this one: the workbook's sheets are
    // all held at once, so they share the bound.
    let mut before = 0usize;
    for name in names {
        let mut cells = BTreeMap::new();
        let mut put = |pos: (u32, u32), v: Val| {
            cells.insert(pos, v);
            if cells.len() > max_cells {
                Err(bad(format!("sheet '{name}' has more than {max_cells} cells; a load chart never does")))
            } else if before + cells.len() > max_cells {
                Err(bad(format!(
                    "its sheets up to '{name}' have more than {max_cells} cells in all; a load chart workbook never does"
                )))
            } else {
                Ok(())
            }
        };
        // xlsx and xlsb stream cell by cell; the other formats come as a range.
        match &mut wb {
            calamine::Sheets::Xlsx(x) => {
                // With each cell's formula: a formula whose value the file
                // does not store reads as an empty cell, and a capacity or
                // a boom length so lost is a chart changed without a word;
                // the 0 a program that calculates nothing stores for one
                // reads as "not permitted", or breaks the boom lengths.
                let mut r = x.worksheet_cells_reader(&name).map_err(|e| bad(format!("sheet '{name}': {e}")))?;
                let mut uncomputed = Uncomputed::default();
                while let Some(cell) =
                    r.next_cell_with_formula_metadata().map_err(|e| bad(format!("sheet '{name}': {e}")))?
                {
                    let stored = from_ref(&cell.value);
                    let none_stored = matches!(cell.value, DataRef::Empty);
                    if let Some(formula) = cell.formula.as_ref()
                        && (checked.calculated_on_open || none_stored)
                    {
                        uncomputed.note(cell.pos, || formula_text(formula), none_stored);
                    } else if let Some(v) = stored {
                        put(cell.pos, v)?;
                    }
                }
                uncomputed.refuse(path, &name)?;
            }
            calamine::Sheets::Xlsb(x) => {
                let mut r = x.worksheet_cells_reader(&name).map_err(|e| bad(format!("sheet '{name}': {e}")))?;
                while let Some(cell) = r.next_cell().map_err(|e| bad(format!("sheet '{name}': {e}")))? {
                    if let Some(v) = from_ref(cell.get_value()) {
                        put(cell.get_position(), v)?;
                    }
                }
            }
            other => {
                let range = other.worksheet_range(&name).map_err(|e| bad(format!("sheet '{name}': {e}")))?;
                let (r0, c0) = range.start().unwrap_or((0, 0));
                for (r, row) in range.rows().enumerate() {
                    for (c, d) in row.iter().enumerate() {
                        if let Some(v) = from_data(d) {
                            put((r0 + r as u32, c0 + c as u32), v)?;
                        }
                    }
                }
                // An ods file written by a program that calculates nothing
                // (odfpy) holds formulas with no value: an empty cell, as
                // in xlsx above. (An xls file stores each formula's value.)
                if let calamine::Sheets::Ods(ods) = other {
                    let formulas = ods.worksheet_formula(&name).map_err(|e| bad(format!("sheet '{name}': {e}")))?;
                    let (f0, g0) = formulas.start().unwrap_or((0, 0));
                    let mut uncomputed = Uncomputed::default();
                    for (r, c, formula) in formulas.used_cells() {
                        let at = (f0 + r as u32, g0 + c as u32);
                        let none_stored = matches!(range.get_value(at), None | Some(Data::Empty));
                        if !formula.is_empty() && none_stored {
                            // OpenFormula's namespace and '=' are no part of
                            // the formula as LibreOffice shows it.
                            let shown = formula.trim_start_matches("of:").trim_start_matches('=');
                            uncomputed.note(at, || Some(liftplan_core::names::kept(shown, 60).into_owned()), true);
                        }
                    }
                    uncomputed.refuse(path, &name)?;
                }
            }
        }
        before += cells.len();
        let sheet = Sheet { name: sheet_name_kept(&name), cells };
        out.push(sheet);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A workbook as a program that computes no formulas writes it (as
    /// openpyxl does): formulas with no stored value. Read, the cells were
    /// empty, and a boom length so lost dropped its configuration from the
    /// chart without a word; refused at the first such cell. A formula with
    /// its value stored is read as the value.
    #[test]
    fn formulas_whose_values_are_not_stored_are_refused() {
        let write_calculated = |cells: &str, calculation: &str| {
            let d = tempfile::tempdir().unwrap();
            let path = d.path().join("chart.xlsx");
            let workbook = &format!(
                r#"<workbook xmlns="http://schemas.openxmlformats.org/spreadsheetml/2006/main" xmlns:r="http://schemas.openxmlformats.org/officeDocument/2006/relationships"><sheets><sheet name="Main" sheetId="1" r:id="rId1"/></sheets>{calculation}</workbook>"#
            );
            let package = r#"<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships"><Relationship Id="rId1" Type="http://schemas.openxmlformats.org/officeDocument/2006/relationships/officeDocument" Target="xl/workbook.xml"/></Relationships>"#;
            let rels = r#"<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships"><Relationship Id="rId1" Type="http://schemas.openxmlformats.org/officeDocument/2006/relationships/worksheet" Target="worksheets/sheet1.xml"/></Relationships>"#;
            let sheet = format!(
                r#"<worksheet xmlns="http://schemas.openxmlformats.org/spreadsheetml/2006/main"><sheetData><row r="1">{cells}</row></sheetData></worksheet>"#
            );
            crate::container::zip_file(
                &path,
                &[
                    ("[Content_Types].xml", "<Types/>"),
                    ("_rels/.rels", package),
                    ("xl/workbook.xml", workbook),
                    ("xl/_rels/workbook.xml.rels", rels),
                    ("xl/worksheets/sheet1.xml", &sheet),
                ],
            );
            (d, path)
        };
        let write = |cells: &str| write_calculated(cells, "");
        let (_d, path) = write(
            r#"<c r="A1"><v>20</v></c><c r="B1"><f>A1+10</f><v>30</v></c><c r="C1" t="e"><f>#REF!+10</f><v>#REF!</v></c>"#,
        );
        let sheets = read_workbook(&path).unwrap();
        assert_eq!((sheets[0].num(0, 0), sheets[0].num(0, 1)), (Some(20.0), Some(30.0)));
        // A broken formula's error is what the cell shows.
        assert_eq!(sheets[0].text(0, 2), Some("#REF!"));
        let (_d, path) = write(r#"<c r="A1"><v>20</v></c><c r="B1"><f>A1+10</f></c><c r="C1"><f>B1+10</f></c>"#);
        let e = read_workbook(&path).unwrap_err().to_string();
        assert!(
            e.contains("[Main!B1]: the cell holds a formula ('=A1+10') whose value the workbook does not store (as does one more cell on the sheet): it was written by a program that calculates no formulas"),
            "{e}"
        );
        // XlsxWriter's way: 0 stored for every formula, and the workbook
        // asking to be calculated when opened. Without formulas such a
        // workbook reads (the demo's chart is one).
        let asks = r#"<calcPr calcId="124519" fullCalcOnLoad="1"/>"#;
        let (_d, path) = write_calculated(r#"<c r="A1"><v>20</v></c><c r="B1"><f>A1+10</f><v>0</v></c>"#, asks);
        let e = read_workbook(&path).unwrap_err().to_string();
        assert!(
            e.contains("[Main!B1]: the cell holds a formula ('=A1+10'), and the workbook asks for its formulas to be calculated when it is opened"),
            "{e}"
        );
        let (_d, path) = write_calculated(r#"<c r="A1"><v>20</v></c><c r="B1"><v>30</v></c>"#, asks);
        assert_eq!(read_workbook(&path).unwrap()[0].num(0, 1), Some(30.0));
        // An ods file: LibreOffice stores each formula's value (read); odfpy
        // writes none (refused), also where the cell lies past every value.
        let ods = |cells: &str| {
            let d = tempfile::tempdir().unwrap();
            let path = d.path().join("chart.ods");
            crate::container::ods_of(
                &path,
                &format!(
                    r#"<?xml version="1.0" encoding="UTF-8"?><office:document-content xmlns:office="urn:oasis:names:tc:opendocument:xmlns:office:1.0" xmlns:table="urn:oasis:names:tc:opendocument:xmlns:table:1.0" xmlns:text="urn:oasis:names:tc:opendocument:xmlns:text:1.0" office:version="1.2"><office:body><office:spreadsheet><table:table table:name="Main"><table:table-row><table:table-cell office:value-type="float" office:value="20"/>{cells}</table:table-row></table:table></office:spreadsheet></office:body></office:document-content>"#
                ),
            );
            (d, path)
        };
        let (_d, path) =
            ods(r#"<table:table-cell table:formula="of:=[.A1]+10" office:value-type="float" office:value="30"/>"#);
        assert_eq!(read_workbook(&path).unwrap()[0].num(0, 1), Some(30.0));
        let (_d, path) = ods(r#"<table:table-cell table:formula="of:=[.A1]+10"/>"#);
        let e = read_workbook(&path).unwrap_err().to_string();
        assert!(
            e.contains("[Main!B1]: the cell holds a formula ('=[.A1]+10') whose value the workbook does not store"),
            "{e}"
        );
    }

    /// A workbook's sheets are held together, so they share the cell bound:
    /// two sheets of six cells pass a bound of ten one by one, not together.
    #[test]
    fn a_workbook_s_sheets_share_the_cell_bound() {
        let d = tempfile::tempdir().unwrap();
        let path = d.path().join("two.xlsx");
        let mut wb = rust_xlsxwriter::Workbook::new();
        for name in ["Boom A", "Boom B"] {
            let ws = wb.add_worksheet().set_name(name).unwrap();
            for k in 0..6 {
                ws.write_number(k, 0, k as f64).unwrap();
            }
        }
        wb.save(&path).unwrap();
        assert_eq!(read_sheets(&path, 12, Default::default()).unwrap().len(), 2);
        let e = read_sheets(&path, 10, Default::default()).unwrap_err().to_string();
        assert!(e.contains("two.xlsx: its sheets up to 'Boom B' have more than 10 cells in all"), "{e}");
        let e = read_sheets(&path, 5, Default::default()).unwrap_err().to_string();
        assert!(e.contains("two.xlsx: sheet 'Boom A' has more than 5 cells"), "{e}");
    }
}
