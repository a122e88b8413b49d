//! The lift plan PDF: a small page-layout layer over printpdf's operations.
//!
//! Text uses the embedded DejaVu Sans (regular and bold, subset on save), so
//! degree and plus-minus signs print as such. Tables are vector lines; pictures
//! are embedded losslessly (Flate). Coordinates here are millimetres from the
//! top-left corner of the page; printpdf's origin is bottom-left.

use liftplan_core::image::Image;
use printpdf::{
    Color, FontId, ImageCompression, ImageOptimizationOptions, Line, LinePoint, Mm, Op, ParsedFont, PdfDocument,
    PdfFontHandle, PdfPage, PdfSaveOptions, Point, Pt, RawImage, RawImageData, RawImageFormat, Rect, Rgb, TextItem,
    XObjectTransform,
};
use std::sync::OnceLock;

const REGULAR: &[u8] = include_bytes!("../fonts/DejaVuSans.ttf");
const BOLD: &[u8] = include_bytes!("../fonts/DejaVuSans-Bold.ttf");

/// Page size in mm.
#[derive(Debug, Clone, Copy)]
pub struct PageSize {
    pub w: f32,
    pub h: f32,
}

pub const A4: PageSize = PageSize { w: 210.0, h: 297.0 };
pub const LETTER: PageSize = PageSize { w: 215.9, h: 279.4 };

/// The footer's baseline, from the foot of the page (mm).
pub const FOOTER_FROM_FOOT_MM: f32 = 10.0;

pub struct Doc {
    doc: PdfDocument,
    regular: FontId,
    bold: FontId,
    pub size: PageSize,
    pages: Vec<Vec<Op>>,
    /// The page drawing goes to.
    cur: usize,
    /// Text of every page, for tests and the search index.
    pub text: Vec<String>,
    /// The lowest text baseline or image foot of every page (mm from the
    /// top), for tests.
    pub lowest_mm: Vec<f32>,
}

fn col(c: [u8; 3]) -> Color {
    Color::Rgb(Rgb::new(c[0] as f32 / 255.0, c[1] as f32 / 255.0, c[2] as f32 / 255.0, None))
}

/// The advance widths of one of the embedded fonts, in ems, for every
/// character of the Basic Multilingual Plane (those the font lacks: its
/// missing glyph's, which is what is drawn for them).
struct Advances(Vec<f32>);

impl Advances {
    fn of(font: &[u8]) -> Option<Advances> {
        let parsed = ParsedFont::from_bytes(font, 0, &mut Vec::new())?;
        let em = f32::from(parsed.units_per_em.max(1));
        let width = |gid: u16| f32::from(parsed.get_glyph_width(gid).unwrap_or(0)) / em;
        let missing = width(0);
        let widths = (0..=u32::from(u16::MAX)).map(|c| parsed.lookup_glyph_index(c).map_or(missing, width)).collect();
        Some(Advances(widths))
    }

    fn em(&self, c: char) -> f32 {
        self.0.get(c as usize).copied().unwrap_or(self.0[0])
    }
}

/// The regular or the bold font's [`Advances`], read once; none where the
/// font does not parse (then [`Doc::new`] fails too).
fn advances(bold: bool) -> Option<&'static Advances> {
    static REGULAR_ADVANCES: OnceLock<Option<Advances>> = OnceLock::new();
    static BOLD_ADVANCES: OnceLock<Option<Advances>> = OnceLock::new();
    let (cell, bytes) = if bold { (&BOLD_ADVANCES, BOLD) } else { (&REGULAR_ADVANCES, REGULAR) };
    cell.get_or_init(|| Advances::of(bytes)).as_ref()
}

/// How wide `s` is drawn in the regular font at `size_pt` (mm), from the
/// embedded font's own advance widths: a line wrapped to a width is that
/// wide on the page (an estimate by character class measured lines about
/// 2 % short, and the cover's rows ran past its frame).
pub fn text_width_mm(s: &str, size_pt: f32) -> f32 {
    drawn_width_mm(s, size_pt, false)
}

/// [`text_width_mm`] in the bold font.
pub fn bold_text_width_mm(s: &str, size_pt: f32) -> f32 {
    drawn_width_mm(s, size_pt, true)
}

fn drawn_width_mm(s: &str, size_pt: f32, bold: bool) -> f32 {
    let ems: f32 = match advances(bold) {
        Some(a) => s.chars().map(|c| a.em(c)).sum(),
        // Unreachable with the fonts built in; kept to never panic.
        None => s.chars().count() as f32 * 0.6,
    };
    ems * size_pt * 0.3528
}

/// The lines `s` is broken into `width_mm` wide, each word whole on a line
/// where it fits on one ([`break_word`] where it does not).
pub fn wrap(s: &str, width_mm: f32, size_pt: f32) -> Vec<String> {
    wrap_in(s, width_mm, size_pt, false)
}

/// [`wrap`] for text drawn in the bold font.
pub fn wrap_bold(s: &str, width_mm: f32, size_pt: f32) -> Vec<String> {
    wrap_in(s, width_mm, size_pt, true)
}

fn wrap_in(s: &str, width_mm: f32, size_pt: f32, bold: bool) -> Vec<String> {
    let mut lines = Vec::new();
    let mut line = String::new();
    for word in s.split_whitespace().flat_map(|w| break_word(w, width_mm, size_pt, bold)) {
        let trial = if line.is_empty() { word.to_string() } else { format!("{line} {word}") };
        if drawn_width_mm(&trial, size_pt, bold) > width_mm && !line.is_empty() {
            lines.push(std::mem::replace(&mut line, word.to_string()));
        } else {
            line = trial;
        }
    }
    if !line.is_empty() {
        lines.push(line);
    }
    lines
}

/// `s` as it fits on one line `width_mm` wide: whole where it fits, else cut
/// between characters and ended with "...".
pub fn shortened(s: &str, width_mm: f32, size_pt: f32) -> String {
    if text_width_mm(s, size_pt) <= width_mm {
        return s.to_string();
    }
    let mut cut = String::new();
    for c in s.chars() {
        let trial = format!("{cut}{c}...");
        if text_width_mm(&trial, size_pt) > width_mm {
            break;
        }
        cut.push(c);
    }
    format!("{}...", cut.trim_end())
}

/// A word wider than `width_mm` (a plant model's group path, say) in pieces
/// that fit, each broken after a '/', '-' or '_' where one falls in it, else
/// between characters; a word that fits, whole.
fn break_word(word: &str, width_mm: f32, size_pt: f32, bold: bool) -> Vec<&str> {
    let mut pieces = Vec::new();
    let mut rest = word;
    while drawn_width_mm(rest, size_pt, bold) > width_mm {
        let (mut fits, mut after_mark) = (0, 0);
        for (i, c) in rest.char_indices() {
            let end = i + c.len_utf8();
            if drawn_width_mm(&rest[..end], size_pt, bold) > width_mm {
                break;
            }
            fits = end;
            if matches!(c, '/' | '-' | '_') {
                after_mark = end;
            }
        }
        // At least one character, however narrow the column.
        let cut = if after_mark > 0 { after_mark } else { fits.max(rest.chars().next().map_or(1, char::len_utf8)) };
        pieces.push(&rest[..cut]);
        rest = &rest[cut..];
    }
    if !rest.is_empty() {
        pieces.push(rest);
    }
    pieces
}

/// A table row's cells as the lines each takes in its column (1.2 mm of
/// padding each side).
fn table_cells(widths: &[f32], row: &[String], size_pt: f32) -> Vec<Vec<String>> {
    // A line break in a cell is kept: a row split over pages
    // ([`split_table_row`]) gives each piece its lines as they were wrapped.
    row.iter()
        .zip(widths)
        .map(|(cell, w)| cell.split('\n').flat_map(|line| wrap(line, w - 2.4, size_pt)).collect())
        .collect()
}

/// A table row as pieces at most `max_height_mm` tall each (but one line
/// each, where not even that fits), its cells' lines in order: the first
/// piece holds each cell's first lines, the next the lines after them, a
/// cell that has run out is empty. A row taller than a page is split so,
/// over as many pages as it takes, rather than drawn past the page's foot.
pub fn split_table_row(widths: &[f32], row: &[String], size_pt: f32, max_height_mm: f32) -> Vec<Vec<String>> {
    let (rh, lh) = (table_row_mm(size_pt), line_height_mm(size_pt));
    let per_piece = (((max_height_mm - rh) / lh).floor().max(0.0) as usize).saturating_add(1);
    let cells = table_cells(widths, row, size_pt);
    let lines = cells.iter().map(Vec::len).max().unwrap_or(0).max(1);
    (0..lines.div_ceil(per_piece))
        .map(|piece| {
            let from = piece * per_piece;
            cells.iter().map(|c| c.iter().skip(from).take(per_piece).cloned().collect::<Vec<_>>().join("\n")).collect()
        })
        .collect()
}

/// The height of a table's row of one line, its header's too (mm).
pub fn table_row_mm(size_pt: f32) -> f32 {
    size_pt * 0.3528 * 1.9
}

/// Distance between the baselines of a paragraph's lines (mm).
pub fn line_height_mm(size_pt: f32) -> f32 {
    size_pt * 0.3528 * 1.35
}

impl Doc {
    pub fn new(title: &str, size: PageSize) -> Result<Doc, String> {
        let mut doc = PdfDocument::new(title);
        let mut w = Vec::new();
        let r = ParsedFont::from_bytes(REGULAR, 0, &mut w).ok_or("embedded font DejaVuSans.ttf does not parse")?;
        let b = ParsedFont::from_bytes(BOLD, 0, &mut w).ok_or("embedded font DejaVuSans-Bold.ttf does not parse")?;
        let regular = doc.add_font(&r);
        let bold = doc.add_font(&b);
        Ok(Doc { doc, regular, bold, size, pages: vec![], cur: 0, text: vec![], lowest_mm: vec![] })
    }

    pub fn new_page(&mut self) {
        self.pages.push(vec![]);
        self.text.push(String::new());
        self.lowest_mm.push(0.0);
        self.cur = self.pages.len() - 1;
    }

    fn ops(&mut self) -> &mut Vec<Op> {
        if self.pages.is_empty() {
            self.new_page();
        }
        &mut self.pages[self.cur]
    }

    /// Notes that the current page is drawn down to `y` mm from its top:
    /// never below the footer's line, where it would be cut off or hidden.
    fn drawn_down_to(&mut self, y: f32) {
        debug_assert!(y <= self.size.h - FOOTER_FROM_FOOT_MM + 1e-3, "drawn at {y} mm, below the footer");
        if let Some(low) = self.lowest_mm.get_mut(self.cur) {
            *low = low.max(y);
        }
    }

    fn pt(&self, x: f32, y: f32) -> Point {
        Point::new(Mm(x), Mm(self.size.h - y))
    }

    /// Text with its baseline at (x, y) mm from the top-left. It must end
    /// within the sheet (by [`text_width_mm`]'s estimate, with 5 mm to
    /// spare): what runs off the edge is never read.
    pub fn text(&mut self, x: f32, y: f32, s: &str, size_pt: f32, bold: bool, color: [u8; 3]) {
        debug_assert!(
            x + drawn_width_mm(s, size_pt, bold) <= self.size.w - 5.0,
            "\"{s}\" drawn from {x} mm runs past the sheet's right edge"
        );
        let font = if bold { self.bold.clone() } else { self.regular.clone() };
        let pos = self.pt(x, y);
        let ops = self.ops();
        ops.push(Op::StartTextSection);
        ops.push(Op::SetFillColor { col: col(color) });
        ops.push(Op::SetFont { font: PdfFontHandle::External(font), size: Pt(size_pt) });
        ops.push(Op::SetTextCursor { pos });
        ops.push(Op::ShowText { items: vec![TextItem::Text(s.to_string())] });
        ops.push(Op::EndTextSection);
        if let Some(t) = self.text.get_mut(self.cur) {
            t.push_str(s);
            t.push('\n');
        }
        self.drawn_down_to(y);
    }

    /// Text wrapped to `width` mm ([`wrap`]); returns the y below the last line.
    pub fn paragraph(&mut self, x: f32, mut y: f32, width: f32, s: &str, size_pt: f32) -> f32 {
        for line in wrap(s, width, size_pt) {
            self.text(x, y, &line, size_pt, false, [30, 30, 30]);
            y += line_height_mm(size_pt);
        }
        y
    }

    pub fn line(&mut self, x0: f32, y0: f32, x1: f32, y1: f32, width_pt: f32, color: [u8; 3]) {
        let (a, b) = (self.pt(x0, y0), self.pt(x1, y1));
        let ops = self.ops();
        ops.push(Op::SetOutlineColor { col: col(color) });
        ops.push(Op::SetOutlineThickness { pt: Pt(width_pt) });
        ops.push(Op::DrawLine {
            line: Line {
                points: vec![LinePoint { p: a, bezier: false }, LinePoint { p: b, bezier: false }],
                is_closed: false,
            },
        });
    }

    pub fn fill_rect(&mut self, x: f32, y: f32, w: f32, h: f32, color: [u8; 3]) {
        let bl = self.pt(x, y + h);
        let ops = self.ops();
        ops.push(Op::SetFillColor { col: col(color) });
        ops.push(Op::DrawRectangle {
            rectangle: Rect {
                mode: Some(printpdf::PaintMode::Fill),
                ..Rect::from_xywh(bl.x, bl.y, Mm(w).into(), Mm(h).into())
            },
        });
    }

    pub fn frame(&mut self, x: f32, y: f32, w: f32, h: f32, width_pt: f32, color: [u8; 3]) {
        self.line(x, y, x + w, y, width_pt, color);
        self.line(x + w, y, x + w, y + h, width_pt, color);
        self.line(x + w, y + h, x, y + h, width_pt, color);
        self.line(x, y + h, x, y, width_pt, color);
    }

    /// An image `w` mm wide with its top-left at (x, y); returns its height in mm.
    pub fn image(&mut self, img: &Image, x: f32, y: f32, w: f32) -> f32 {
        let raw = RawImage {
            pixels: RawImageData::U8(img.data.clone()),
            width: img.width as usize,
            height: img.height as usize,
            data_format: RawImageFormat::RGB8,
            tag: vec![],
        };
        let id = self.doc.add_image(&raw);
        let h = w * img.height as f32 / img.width as f32;
        self.drawn_down_to(y + h);
        let dpi = img.width as f32 / (w / 25.4);
        let bl = self.pt(x, y + h);
        self.ops().push(Op::UseXobject {
            id,
            transform: XObjectTransform {
                translate_x: Some(bl.x),
                translate_y: Some(bl.y),
                dpi: Some(dpi),
                ..Default::default()
            },
        });
        h
    }

    /// Height of each of `rows` in a [`Doc::table`] of these `widths` (mm):
    /// a cell too wide for its column wraps onto more lines.
    pub fn table_row_heights(widths: &[f32], rows: &[Vec<String>], size_pt: f32) -> Vec<f32> {
        let (rh, lh) = (table_row_mm(size_pt), line_height_mm(size_pt));
        rows.iter()
            .map(|row| {
                rh + lh * (table_cells(widths, row, size_pt).iter().map(Vec::len).max().unwrap_or(1).max(1) - 1) as f32
            })
            .collect()
    }

    /// A table with a header row; `widths` in mm, `right` marks right-aligned
    /// columns; a cell wider than its column wraps onto more lines. Returns
    /// the y below it.
    pub fn table(
        &mut self,
        x: f32,
        mut y: f32,
        widths: &[f32],
        right: &[bool],
        header: &[&str],
        rows: &[Vec<String>],
        size_pt: f32,
    ) -> f32 {
        let rh = table_row_mm(size_pt);
        let lh = line_height_mm(size_pt);
        let total: f32 = widths.iter().sum();
        self.fill_rect(x, y, total, rh, [225, 232, 242]);
        let mut cx = x;
        for (k, h) in header.iter().enumerate() {
            self.text(cx + 1.2, y + rh * 0.68, h, size_pt, true, [20, 20, 20]);
            cx += widths[k];
        }
        self.line(x, y, x + total, y, 0.8, [80, 80, 80]);
        y += rh;
        self.line(x, y, x + total, y, 0.6, [80, 80, 80]);
        for (ri, row) in rows.iter().enumerate() {
            let cells = table_cells(widths, row, size_pt);
            let h = rh + lh * (cells.iter().map(Vec::len).max().unwrap_or(1).max(1) - 1) as f32;
            if ri % 2 == 1 {
                self.fill_rect(x, y, total, h, [246, 247, 250]);
            }
            let mut cx = x;
            for (k, lines) in cells.iter().enumerate() {
                for (n, line) in lines.iter().enumerate() {
                    let tw = text_width_mm(line, size_pt);
                    let tx = if right.get(k).copied().unwrap_or(false) { cx + widths[k] - 1.2 - tw } else { cx + 1.2 };
                    self.text(tx, y + rh * 0.68 + lh * n as f32, line, size_pt, false, [20, 20, 20]);
                }
                cx += widths[k];
            }
            y += h;
        }
        self.line(x, y, x + total, y, 0.8, [80, 80, 80]);
        y
    }

    /// Footer on every page ("page i of n"), then the PDF bytes.
    pub fn finish(mut self, footer: &str, date: &str) -> Vec<u8> {
        let n = self.pages.len();
        for i in 0..n {
            self.cur = i;
            let y = self.size.h - FOOTER_FROM_FOOT_MM;
            let w = self.size.w;
            self.line(15.0, y - 5.0, w - 15.0, y - 5.0, 0.5, [150, 150, 150]);
            let p = format!("page {} of {}", i + 1, n);
            // The footer leaves room for the page number, however long the
            // project's name in it.
            let room = w - 30.0 - text_width_mm(&p, 8.0) - 6.0;
            self.text(15.0, y, &shortened(footer, room, 8.0), 8.0, false, [90, 90, 90]);
            self.text(w - 15.0 - text_width_mm(&p, 8.0), y, &p, 8.0, false, [90, 90, 90]);
        }
        let pages: Vec<PdfPage> =
            self.pages.into_iter().map(|ops| PdfPage::new(Mm(self.size.w), Mm(self.size.h), ops)).collect();
        self.doc.metadata.info.producer = "liftplan".into();
        self.doc.metadata.info.creator = format!("liftplan {}", env!("CARGO_PKG_VERSION"));
        let ymd: Vec<i32> = date.split('-').filter_map(|v| v.parse().ok()).collect();
        if let [y, m, d] = ymd[..] {
            let dt = printpdf::DateTime {
                date: printpdf::Date { year: y, month: m as u8, day: d as u8 },
                time: printpdf::Time { hour: 0, minute: 0, second: 0, millisecond: 0 },
                offset: printpdf::Offset { hours: 0, minutes: 0, seconds: 0, milliseconds: 0 },
            };
            self.doc.metadata.info.creation_date = dt;
            self.doc.metadata.info.modification_date = dt;
            self.doc.metadata.info.metadata_date = dt;
        }
        let opts = PdfSaveOptions {
            image_optimization: Some(ImageOptimizationOptions {
                quality: None,
                max_image_size: None,
                dither_greyscale: None,
                convert_to_greyscale: Some(false),
                auto_optimize: Some(false),
                format: Some(ImageCompression::Flate),
            }),
            ..Default::default()
        };
        let mut warnings = Vec::new();
        self.doc.with_pages(pages).save(&opts, &mut warnings)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Widths come from the embedded fonts: a narrow letter is narrower than
    /// a wide one (an estimate by character class gave "iiii" and "mmmm"
    /// the same width), bold is wider than regular, DejaVu Sans' "M" is
    /// 1767/2048 em, and every wrapped line is as wide as asked or less.
    #[test]
    fn widths_are_the_embedded_fonts() {
        assert!(text_width_mm("iiii", 10.0) < text_width_mm("mmmm", 10.0) / 2.0);
        assert!(bold_text_width_mm("Lift plan V-101", 22.0) > text_width_mm("Lift plan V-101", 22.0));
        let m = text_width_mm("M", 10.0);
        assert!((m - 1767.0 / 2048.0 * 10.0 * 0.3528).abs() < 1e-4, "{m}");
        // A character the font lacks is as wide as its missing glyph.
        assert!(text_width_mm("\u{10FFFF}", 10.0) > 0.0);
        let text = "0.50 m in step 2 (load to scanned structure); required 1.00 m, 0.20 m over landing zones; the rope, hook and load measured swung sideways as far as a sudden gust at the permissible wind can swing them";
        for width in [40.0, 80.0, 138.0] {
            for line in wrap(text, width, 9.0) {
                assert!(text_width_mm(&line, 9.0) <= width, "{line} at {width} mm");
            }
        }
    }
}
