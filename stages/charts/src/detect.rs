//! Finding load-chart grids in manufacturer-style sheets and reading them.
//!
//! A grid is a row of boom lengths across (strictly increasing numbers in
//! adjacent columns) over a column of radii down (strictly increasing numbers in
//! the column just left of them), with capacities in between: blank, '-' or text
//! cells where the lift is not permitted. Title rows, merged headers and notes
//! around it are allowed. A chart may be transposed (radii across); the labels
//! beside the numbers ("Radius", "Ausladung", "Boom length", ...) decide. One
//! sheet may hold several grids, one per configuration; a grid of a single
//! capacity column under a text header is a chart that does not depend on boom
//! length (tower crane jibs).
//!
//! Units come from the words around the grid (m/ft, t/kg/lb/kips, and kN/daN
//! where the chart rates its capacities as weights, read as the mass they
//! weigh; a force named beside a mass unit is another figure's, such as an
//! outrigger's load) or from the radii's and boom lengths' cells ("3,0 m");
//! where none is found, the project must say (`[charts] length_unit`, `capacity_unit`, or the
//! grid's `[[charts.table]]` mapping): a chart in pounds and feet read as
//! tonnes and metres would be thousands of times too strong. Values like
//! `12,5` are read with a warning; `12.5t` is read if `t` is the grid's unit and
//! refused otherwise; a grid whose capacity rises with radius is refused with the
//! cell that rises. A footnote mark after a capacity, a boom length or a radius
//! is taken off and said with the note it points at (for a boom length or a
//! radius, as a warning on its whole column or row); a cell just past the last
//! boom length or radius that begins like a number but is none is said, as
//! its column or row is no part of the chart.

use crate::decimals::{self, GridMark, Reading};
use crate::sheet::{Sheet, Val, length_and_unit, shows_an_error};
use liftplan_core::capacity::{ChartCell, ChartConfig};
use liftplan_core::location::cell_ref;
use liftplan_core::units::{LengthUnit, MassUnit};

/// Where a grid sits in its sheet.
#[derive(Debug, Clone, PartialEq)]
pub struct Grid {
    /// Row of the values across (booms, or radii when transposed).
    pub header_row: u32,
    pub value_cols: Vec<u32>,
    /// Column of the values down (radii, or booms when transposed).
    pub label_col: u32,
    pub rows: Vec<u32>,
    /// Radii run across and booms down.
    pub transposed: bool,
    /// A single capacity column that holds for any boom.
    pub boom_independent: bool,
    pub title: String,
}

impl Grid {
    pub fn range(&self) -> String {
        let last_col = *self.value_cols.last().unwrap_or(&self.label_col);
        let last_row = *self.rows.last().unwrap_or(&self.header_row);
        format!("{}:{}", cell_ref(self.header_row, self.label_col), cell_ref(last_row, last_col))
    }
}

fn strictly_increasing(v: &[f64]) -> bool {
    v.windows(2).all(|w| w[1] > w[0])
}

/// Whether a cell counts as a number in a block's density: charts pasted
/// from PDFs often hold numbers as text.
fn reads_as_number(v: &Val) -> bool {
    match v {
        Val::Num(_) => true,
        Val::Text(t) => t.trim().starts_with(|ch: char| ch.is_ascii_digit()),
    }
}

/// One column of a sheet, for the grid search: its cells in row order, with
/// what the search asks of every stretch of it counted beforehand, so that
/// each question is a binary search instead of a walk down the column (the
/// walks made the search cost the cube of a sheet's side: 41 s for 16,384
/// cells on a diagonal, 4.3 s for 8,000 rows of three columns).
struct Column<'a> {
    rows: Vec<u32>,
    vals: Vec<&'a Val>,
    /// `numbers[i]`: how many of the first `i` cells read as numbers
    /// ([`reads_as_number`]).
    numbers: Vec<u32>,
    /// `rising[i]`: how many cells from the `i`-th on are positive numbers
    /// rising strictly down consecutive rows (0 where it is no positive
    /// number).
    rising: Vec<u32>,
}

impl<'a> Column<'a> {
    fn new(rows: Vec<u32>, vals: Vec<&'a Val>) -> Self {
        let mut numbers = Vec::with_capacity(rows.len() + 1);
        numbers.push(0);
        for v in &vals {
            numbers.push(numbers.last().copied().unwrap_or(0) + reads_as_number(v) as u32);
        }
        let mut rising = vec![0u32; rows.len()];
        for i in (0..rows.len()).rev() {
            if let Some(v) = vals[i].number()
                && v > 0.0
            {
                let next_rises =
                    i + 1 < rows.len() && rows[i + 1] == rows[i] + 1 && vals[i + 1].number().is_some_and(|w| w > v);
                rising[i] = if next_rises { 1 + rising[i + 1] } else { 1 };
            }
        }
        Column { rows, vals, numbers, rising }
    }

    fn index(&self, row: u32) -> Option<usize> {
        self.rows.binary_search(&row).ok()
    }

    fn get(&self, row: u32) -> Option<&'a Val> {
        self.index(row).map(|i| self.vals[i])
    }

    /// How many cells of rows `rows` read as numbers.
    fn numbers_in(&self, rows: &std::ops::Range<u32>) -> u32 {
        let a = self.rows.partition_point(|&r| r < rows.start);
        let b = self.rows.partition_point(|&r| r < rows.end);
        self.numbers[b] - self.numbers[a]
    }

    /// Numbers down the column from `start`, strictly increasing and
    /// positive, allowing up to two text or empty rows right at the start
    /// (unit lines): the rows they are in, one after another.
    fn increasing_down(&self, start: u32) -> std::ops::Range<u32> {
        for r in (0..3).filter_map(|k| start.checked_add(k)) {
            match self.index(r) {
                Some(i) if self.vals[i].number().is_some() => return r..r + self.rising[i],
                _ => {}
            }
        }
        start..start
    }
}

/// A sheet's columns ([`Column`]), by column number.
fn columns(sheet: &Sheet) -> std::collections::BTreeMap<u32, Column<'_>> {
    let mut cells: std::collections::BTreeMap<u32, (Vec<u32>, Vec<&Val>)> = std::collections::BTreeMap::new();
    for (&(r, c), v) in &sheet.cells {
        let col = cells.entry(c).or_default();
        col.0.push(r);
        col.1.push(v);
    }
    cells.into_iter().map(|(c, (rows, vals))| (c, Column::new(rows, vals))).collect()
}

/// The words of `text`, lower case, an English contraction's ending left
/// out: "don't" is "don", not "don" and "t" (a tonne: a US chart's note
/// "don't exceed" made a chart in pounds one of two mass units).
fn words(text: &str) -> Vec<String> {
    let mut kept = String::with_capacity(text.len());
    let mut chars = text.chars().peekable();
    let mut after_letter = false;
    while let Some(c) = chars.next() {
        if matches!(c, '\'' | '\u{2019}') && after_letter && chars.peek().is_some_and(|n| n.is_alphabetic()) {
            while chars.peek().is_some_and(|n| n.is_alphabetic()) {
                chars.next();
            }
            after_letter = false;
            continue;
        }
        after_letter = c.is_alphabetic();
        kept.push(c);
    }
    kept.to_lowercase().split(|c: char| !c.is_alphanumeric()).filter(|w| !w.is_empty()).map(String::from).collect()
}

pub fn says_radius(text: &str) -> bool {
    let t = text.to_lowercase();
    ["radius", "radii", "reach", "ausladung", "portée", "portee", "radio", "raggio", "working radius"]
        .iter()
        .any(|k| t.contains(k))
}

pub fn says_boom(text: &str) -> bool {
    let t = text.to_lowercase();
    ["boom", "length", "ausleger", "jib", "flèche", "fleche", "pluma", "mast", "hauptausleger"]
        .iter()
        .any(|k| t.contains(k))
}

/// The most cells a sheet may have to be searched for grids. Manufacturers'
/// chart sheets hold hundreds to a few thousand cells. The search asks
/// questions of rows and columns through an index (`Column`), so its cost
/// grows with the number of cells, not with the sheet's side cubed as the
/// first search's did (35 s for 1.96 M cells made from an 813-byte ODS file;
/// 41 s for 16,384 words on a diagonal): 200,000 cells on a diagonal take
/// about 0.1 s. A larger sheet's grid can still be described with
/// `[[charts.table]]`.
pub const MAX_SEARCHED_CELLS: usize = 200_000;

/// The most grids one sheet may hold: manufacturers put a few to a few
/// dozen configurations on a sheet. Past it the sheet is refused rather than
/// searched on (choosing among that many candidates costs their number
/// squared); its grids can be described with `[[charts.table]]`.
pub const MAX_GRIDS: usize = 256;

/// A grid found by the search, before it is chosen: its rows are one run.
struct Candidate {
    header_row: u32,
    value_cols: std::ops::Range<u32>,
    label_col: u32,
    rows: std::ops::Range<u32>,
    boom_independent: bool,
}

impl Candidate {
    fn area(&self) -> usize {
        self.rows.len() * self.value_cols.len()
    }

    /// The rectangle it covers: first and last row, first and last column.
    fn rect(&self) -> (u32, u32, u32, u32) {
        (self.header_row, self.rows.end - 1, self.label_col, self.value_cols.end - 1)
    }
}

/// Finds the grids in a sheet, largest first, without overlaps. More than
/// [`MAX_GRIDS`] is refused: the error is the cell range of the first one
/// past it, and what is wrong.
pub fn find_grids(sheet: &Sheet) -> Result<Vec<Grid>, (String, String)> {
    let columns = columns(sheet);
    let column = |c: u32| columns.get(&c);
    let mut cands: Vec<Candidate> = Vec::new();
    let mut r = 0;
    // Each row with cells, once.
    while let Some((&(row, _), _)) = sheet.cells.range((r, 0)..).next() {
        let nums: Vec<(u32, f64)> = sheet
            .cells
            .range((row, 0)..=(row, u32::MAX))
            .filter_map(|((_, c), v)| v.number().map(|x| (*c, x)))
            .collect();
        let mut i = 0;
        while i < nums.len() {
            let mut j = i + 1;
            while j < nums.len() && nums[j].0 == nums[j - 1].0 + 1 && nums[j].1 > nums[j - 1].1 {
                j += 1;
            }
            let run = &nums[i..j];
            i = j;
            if run.len() < 2 || run[0].1 <= 0.0 || run[0].0 == 0 {
                continue;
            }
            let label_col = run[0].0 - 1;
            let rows = match (column(label_col), row.checked_add(1)) {
                (Some(labels), Some(below)) => labels.increasing_down(below),
                _ => continue,
            };
            if rows.len() < 2 {
                continue;
            }
            let Some(end) = run[run.len() - 1].0.checked_add(1) else { continue };
            let value_cols = run[0].0..end;
            let numbers: u64 = value_cols.clone().filter_map(column).map(|c| c.numbers_in(&rows) as u64).sum();
            if (numbers as f64 / (rows.len() * value_cols.len()) as f64) < 0.25 {
                continue;
            }
            cands.push(Candidate { header_row: row, value_cols, label_col, rows, boom_independent: false });
        }
        match row.checked_add(1) {
            Some(next) => r = next,
            None => break,
        }
    }
    // Single-column charts: increasing radii with one capacity column to the
    // right under a text (or empty) header: a run of at least three rising
    // numbers whose first row comes right under a row with cells.
    for (&c, labels) in &columns {
        for (i, &first) in labels.rows.iter().enumerate() {
            let len = labels.rising[i];
            if len < 3
                || first == 0
                || (i > 0 && labels.rows[i - 1] == first - 1 && labels.vals[i - 1].number().is_some())
            {
                continue;
            }
            let header_row = first - 1;
            if sheet.cells.range((header_row, 0)..=(header_row, u32::MAX)).next().is_none() {
                continue;
            }
            let Some((vc, end)) = c.checked_add(1).zip(c.checked_add(2)) else { continue };
            let values = column(vc);
            if values.and_then(|v| v.get(header_row)).and_then(Val::number).is_some() {
                continue;
            }
            let rows = first..first + len;
            let numbers = values.map_or(0, |v| v.numbers_in(&rows));
            if (numbers as f64 / rows.len() as f64) < 0.5 {
                continue;
            }
            cands.push(Candidate { header_row, value_cols: vc..end, label_col: c, rows, boom_independent: true });
        }
    }
    cands.sort_by_key(|g| std::cmp::Reverse(g.area()));
    let mut chosen: Vec<Candidate> = Vec::new();
    for g in cands {
        let (a0, a1, b0, b1) = g.rect();
        if chosen.iter().any(|o| {
            let (c0, c1, d0, d1) = o.rect();
            a0 <= c1 && c0 <= a1 && b0 <= d1 && d0 <= b1
        }) {
            continue;
        }
        if chosen.len() == MAX_GRIDS {
            return Err((
                format!("{}:{}", cell_ref(a0, b0), cell_ref(a1, b1)),
                format!(
                    "the sheet holds more than {MAX_GRIDS} load-chart grids (this one would be the next); no load \
                     chart sheet does: describe its grids with [[charts.table]]"
                ),
            ));
        }
        chosen.push(g);
    }
    let mut out: Vec<Grid> = chosen
        .into_iter()
        .map(|g| Grid {
            header_row: g.header_row,
            value_cols: g.value_cols.collect(),
            label_col: g.label_col,
            rows: g.rows.collect(),
            transposed: false,
            boom_independent: g.boom_independent,
            title: String::new(),
        })
        .collect();
    for g in &mut out {
        let last = *g.value_cols.last().unwrap_or(&g.label_col);
        let row_label = format!(
            "{} {}",
            sheet.text_in(g.header_row, g.header_row, 0, g.label_col),
            sheet.text_in(g.header_row.saturating_sub(2), g.header_row.saturating_sub(1), g.value_cols[0], last)
        );
        let col_label = sheet.text_in(g.header_row.saturating_sub(3), g.header_row, g.label_col, g.label_col);
        g.transposed = !g.boom_independent
            && ((says_radius(&row_label) && !says_radius(&col_label))
                || (says_boom(&col_label) && !says_boom(&row_label)));
        g.title = title_above(sheet, g);
    }
    out.sort_by_key(|g| (g.header_row, g.label_col));
    Ok(out)
}

/// The words above a grid that title it, which name its configuration
/// ("sheet / title") where a sheet holds several: on one line (a cell's
/// line breaks, Alt+Enter in Excel, as spaces: a lift names the
/// configuration in one line of its project file, and the run prints it in
/// one) and kept to [`MAX_TITLE_CHARS`] ([`liftplan_core::names::kept`]; a
/// cell holds up to 32,767 characters).
fn title_above(sheet: &Sheet, g: &Grid) -> String {
    let last = *g.value_cols.last().unwrap_or(&g.label_col);
    let lo = g.label_col.saturating_sub(1);
    for r in (g.header_row.saturating_sub(6)..g.header_row).rev() {
        for (_, v) in sheet.cells.range((r, lo)..=(r, last)) {
            if let Val::Text(t) = v
                && v.number().is_none()
            {
                let t = t.split_whitespace().collect::<Vec<_>>().join(" ");
                if t.len() >= 4 && !(says_boom(&t) && t.len() < 30) && !(says_radius(&t) && t.len() < 30) {
                    return liftplan_core::names::kept(&t, MAX_TITLE_CHARS).into_owned();
                }
            }
        }
    }
    String::new()
}

/// The most characters of a grid's title kept in its configuration's name.
pub const MAX_TITLE_CHARS: usize = 100;

/// Units read from the words around a grid.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Units {
    pub radius: LengthUnit,
    pub boom: LengthUnit,
    pub capacity: MassUnit,
    /// What was found, and where units the labels do not name came from,
    /// for chart.json.
    pub found: Vec<String>,
    /// Whether the labels name the radius' unit; where they do not,
    /// `radius` and `boom` are metres until the project says otherwise.
    pub length_named: bool,
    /// Whether the labels name the capacity's unit; where they do not,
    /// `capacity` is tonnes until the project says otherwise.
    pub capacity_named: bool,
}

fn length_in(text: &str) -> Vec<LengthUnit> {
    let mut v = Vec::new();
    for w in words(text) {
        let u = match w.as_str() {
            "m" | "meter" | "meters" | "metre" | "metres" | "mètre" | "mètres" | "metros" | "metri" => LengthUnit::M,
            "ft" | "feet" | "foot" => LengthUnit::Ft,
            _ => continue,
        };
        if !v.contains(&u) {
            v.push(u);
        }
    }
    v
}

fn mass_in(text: &str) -> Vec<MassUnit> {
    let lower = text.to_lowercase();
    let mut v = Vec::new();
    if lower.contains("1000 lb") || lower.contains("1,000 lb") || lower.contains("1000lb") {
        v.push(MassUnit::Kips);
    }
    if says_to_as_tonne(text) {
        v.push(MassUnit::T);
    }
    for w in words(text) {
        let u = match w.as_str() {
            "t" | "tonne" | "tonnes" | "mt" | "tonnen" | "toneladas" | "tonnellate" => MassUnit::T,
            "kg" | "kilogram" | "kilograms" => MassUnit::Kg,
            "lb" | "lbs" | "pound" | "pounds" if v.contains(&MassUnit::Kips) => continue,
            "lb" | "lbs" | "pound" | "pounds" => MassUnit::Lb,
            "kip" | "kips" => MassUnit::Kips,
            "ton" | "tons" => MassUnit::ShortTon,
            "kn" | "kilonewton" | "kilonewtons" => MassUnit::KiloNewton,
            "dan" | "decanewton" | "decanewtons" => MassUnit::DecaNewton,
            _ => continue,
        };
        if !v.contains(&u) {
            v.push(u);
        }
    }
    v
}

/// The cells of a grid's axes: across its header row (none where the grid
/// is one column of capacities by radius) and down its label column.
fn axis_cells(g: &Grid) -> (Vec<(u32, u32)>, Vec<(u32, u32)>) {
    let across = match g.boom_independent {
        true => Vec::new(),
        false => g.value_cols.iter().map(|&c| (g.header_row, c)).collect(),
    };
    (across, g.rows.iter().map(|&r| (r, g.label_col)).collect())
}

/// The length unit the `cells` write after their numbers, where they write
/// one and all the same.
fn written_with(sheet: &Sheet, cells: &[(u32, u32)]) -> Option<LengthUnit> {
    let mut units = cells.iter().filter_map(|&(r, c)| length_and_unit(sheet.text(r, c)?).1);
    let first = units.next()?;
    units.all(|u| u == first).then_some(first)
}

/// Whether `text` writes "to", German charts' tonne, as a unit: in
/// brackets ("(to)", "[to]"), or closing its line or phrase after a number
/// or "in" ("25 to", "Tragkraft in to"). Elsewhere "to" is an English word
/// ("radius from the axis of rotation to the hook"), and read as a tonne it
/// made a chart in pounds one of two mass units.
fn says_to_as_tonne(text: &str) -> bool {
    let lower = text.to_lowercase();
    let closes = |after: &str| after.is_empty() || after.starts_with([')', ']', ',', ';', ':', '.', '\n']);
    lower.match_indices("to").any(|(at, _)| {
        let (before, after) = (&lower[..at], &lower[at + 2..]);
        let word_ends = |s: &str, last: bool| {
            let c = if last { s.chars().next_back() } else { s.chars().next() };
            !c.is_some_and(char::is_alphanumeric)
        };
        if !word_ends(before, true) || !word_ends(after, false) {
            return false;
        }
        let (before, after) =
            (before.trim_end_matches([' ', '\u{a0}', '\t']), after.trim_start_matches([' ', '\u{a0}', '\t']));
        let bracketed =
            (before.ends_with('(') && after.starts_with(')')) || (before.ends_with('[') && after.starts_with(']'));
        let after_number_or_in = before.ends_with(|c: char| c.is_ascii_digit())
            || (before.ends_with("in") && word_ends(&before[..before.len() - 2], true));
        bracketed || (after_number_or_in && closes(after))
    })
}

/// Reads the units around `g`. Errors (cell, message) on mixed mass units.
pub fn units(sheet: &Sheet, g: &Grid) -> Result<Units, (String, String)> {
    let last = *g.value_cols.last().unwrap_or(&g.label_col);
    let corner = cell_ref(g.header_row, g.label_col);
    let window = sheet.text_in(g.header_row.saturating_sub(6), g.header_row, g.label_col.saturating_sub(1), last);
    let row_label = format!(
        "{} {}",
        sheet.text_in(g.header_row, g.header_row, 0, g.label_col),
        sheet.text_in(g.header_row.saturating_sub(2), g.header_row.saturating_sub(1), g.value_cols[0], last)
    );
    let col_label = sheet.text_in(g.header_row.saturating_sub(3), g.header_row, g.label_col, g.label_col);
    let mut found = Vec::new();
    let masses = mass_in(&window);
    // "ton(s)" next to metric words is a metric tonne.
    let masses: Vec<MassUnit> = if masses.contains(&MassUnit::ShortTon) && !length_in(&window).contains(&LengthUnit::Ft)
    {
        masses.into_iter().map(|m| if m == MassUnit::ShortTon { MassUnit::T } else { m }).fold(
            Vec::new(),
            |mut a, m| {
                if !a.contains(&m) {
                    a.push(m)
                }
                a
            },
        )
    } else {
        masses
    };
    // A force named beside a mass is another figure's (an outrigger's
    // load, "Stützkraft 450 kN"); named alone, the chart rates its
    // capacities as weights.
    let masses: Vec<MassUnit> = match masses.iter().all(|m| m.is_force()) {
        true => masses,
        false => masses.into_iter().filter(|m| !m.is_force()).collect(),
    };
    if masses.len() > 1 {
        return Err((
            corner,
            format!(
                "the chart header mentions more than one mass unit ({}); say which with an explicit [[charts.table]] mapping",
                masses.iter().map(|m| m.name()).collect::<Vec<_>>().join(", ")
            ),
        ));
    }
    let all_len = length_in(&window);
    // An axis' unit: its label's, else the one its cells write after their
    // numbers ("3,0 m"), else the one the labels around the grid name.
    let pick_len = |label: &str, cells: &[(u32, u32)]| -> Option<LengthUnit> {
        let l = length_in(label);
        if l.len() == 1 {
            Some(l[0])
        } else if let Some(written) = written_with(sheet, cells) {
            Some(written)
        } else if all_len.len() == 1 {
            Some(all_len[0])
        } else {
            None
        }
    };
    let (across, down) = axis_cells(g);
    let (radius_label, boom_label) = if g.transposed { (&row_label, &col_label) } else { (&col_label, &row_label) };
    let (radius_cells, boom_cells) = if g.transposed { (&across, &down) } else { (&down, &across) };
    let radius = pick_len(radius_label, radius_cells);
    let boom = pick_len(boom_label, boom_cells);
    match masses.first() {
        Some(m) if m.is_force() => found.push(format!(
            "capacity in {} of weight, read as the mass it weighs (1 {} = {:.4} kg)",
            m.name(),
            m.name(),
            m.to_kg()
        )),
        Some(m) => found.push(format!("capacity in {}", m.name())),
        None => {}
    }
    if let Some(r) = radius {
        found.push(format!("radius in {}", r.name()));
    }
    Ok(Units {
        radius: radius.unwrap_or(LengthUnit::M),
        boom: boom.or(radius).unwrap_or(LengthUnit::M),
        capacity: masses.first().copied().unwrap_or(MassUnit::T),
        found,
        length_named: radius.is_some(),
        capacity_named: !masses.is_empty(),
    })
}

/// The mark a chart puts after a capacity to point at a footnote: "8.4*",
/// "8.4**", "8.4¹", "8.4 (2)".
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum FootnoteMark {
    /// That many asterisks.
    Stars(usize),
    /// A note's number, written as a superscript or in brackets.
    Number(u32),
}

impl FootnoteMark {
    /// Splits a trailing mark off a cell's text: the text before it and the
    /// mark, or `None` where the text ends in none.
    /// `t` trimmed, with the mark after it taken off, and the mark.
    pub fn split_off(t: &str) -> (&str, Option<FootnoteMark>) {
        let t = t.trim();
        match FootnoteMark::split(t) {
            Some((before, mark)) => (before, Some(mark)),
            None => (t, None),
        }
    }

    pub fn split(t: &str) -> Option<(&str, FootnoteMark)> {
        if t.ends_with(')')
            && let Some(i) = t.rfind('(')
            && i > 0
            && (1..=3).contains(&(t.len() - i - 2))
            && t[i + 1..t.len() - 1].chars().all(|c| c.is_ascii_digit())
        {
            let n = t[i + 1..t.len() - 1].parse().ok()?;
            return Some((t[..i].trim_end(), FootnoteMark::Number(n)));
        }
        let before = t.trim_end_matches('*');
        if before.len() < t.len() {
            return Some((before.trim_end(), FootnoteMark::Stars(t.len() - before.len())));
        }
        let last = t.chars().last()?;
        let n = SUPERSCRIPT_DIGITS.iter().position(|&c| c == last)?;
        Some((t[..t.len() - last.len_utf8()].trim_end(), FootnoteMark::Number(n as u32)))
    }

    /// The mark a note (a cell's text) opens with and its text after it:
    /// "* ...", "** ...", "(2) ...", "2) ...", "2. ...", "2: ...", "² ...",
    /// "Note 2: ...", after a leading "Notes:" where the first note shares
    /// that cell. The text is empty where the cell holds only the mark.
    pub fn leading(note: &str) -> Option<(FootnoteMark, &str)> {
        let mut s = note.trim();
        for lead in ["notes:", "note:", "remarks:", "footnotes:", "note "] {
            if s.get(..lead.len()).is_some_and(|l| l.eq_ignore_ascii_case(lead)) {
                s = s[lead.len()..].trim_start();
                break;
            }
        }
        let digits_end = |x: &str| x.find(|c: char| !c.is_ascii_digit()).unwrap_or(x.len());
        let number = |d: &str| (1..=3).contains(&d.len()).then(|| d.parse().ok()).flatten();
        let (mark, rest) = if let Some(after) = s.strip_prefix('(') {
            let end = digits_end(after);
            (FootnoteMark::Number(number(&after[..end])?), after[end..].strip_prefix(')')?)
        } else if s.starts_with('*') {
            let after = s.trim_start_matches('*');
            (FootnoteMark::Stars(s.len() - after.len()), after)
        } else if s.starts_with(|c: char| SUPERSCRIPT_DIGITS.contains(&c)) {
            let end = s.find(|c: char| !SUPERSCRIPT_DIGITS.contains(&c)).unwrap_or(s.len());
            let d: String = s[..end]
                .chars()
                .filter_map(|c| SUPERSCRIPT_DIGITS.iter().position(|&x| x == c))
                .map(|i| char::from(b'0' + i as u8))
                .collect();
            (FootnoteMark::Number(number(&d)?), &s[end..])
        } else {
            let end = digits_end(s);
            let after = s[end..].strip_prefix([')', '.', ':'])?;
            // "2) ...", not "25 t ..." or "2.5 m ...".
            if !(after.is_empty() || after.starts_with(char::is_whitespace)) {
                return None;
            }
            (FootnoteMark::Number(number(&s[..end])?), after)
        };
        Some((mark, rest.trim_start_matches([':', '.', ')', '-', ' ', '\u{a0}']).trim()))
    }

    /// As written in a cell.
    pub fn said(&self) -> String {
        match *self {
            FootnoteMark::Stars(n) => "*".repeat(n),
            FootnoteMark::Number(n) => format!("({n})"),
        }
    }
}

const SUPERSCRIPT_DIGITS: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];

/// The longest footnote quoted in a warning, in characters.
const FOOTNOTE_QUOTED_CHARS: usize = 300;

/// Where a sheet's notes are: the text cells that open with a footnote
/// mark, by mark, in the sheet's order. Built in one pass over the sheet,
/// so a chart with many marks does not walk it once for each.
#[derive(Debug, Default)]
pub struct SheetNotes(std::collections::HashMap<FootnoteMark, Vec<(u32, u32)>>);

impl SheetNotes {
    pub fn of(sheet: &Sheet) -> SheetNotes {
        let mut notes = SheetNotes::default();
        for (&(r, c), v) in &sheet.cells {
            if let Val::Text(t) = v
                && let Some((mark, _)) = FootnoteMark::leading(t)
            {
                notes.0.entry(mark).or_default().push((r, c));
            }
        }
        notes
    }

    /// The note a mark in grid `g` points at: the first cell outside the
    /// grid that opens with the mark and says something (the nearest below
    /// the grid first, as notes are printed under their table), with the
    /// text cells after it on its row (a note typed across the row). On a
    /// sheet of notes (`g` is `None`), the first such cell. Returns the cell
    /// and the note's text.
    pub fn find(&self, sheet: &Sheet, g: Option<&Grid>, mark: FootnoteMark) -> Option<(String, String)> {
        // The grid's rows and columns (none on a sheet of notes).
        let span = g.map(|g| {
            let last_row = *g.rows.last().unwrap_or(&g.header_row);
            let first_col = g.label_col.min(*g.value_cols.first().unwrap_or(&g.label_col));
            let last_col = g.label_col.max(*g.value_cols.last().unwrap_or(&g.label_col));
            (g.header_row..=last_row, first_col..=last_col)
        });
        let in_grid = |r: u32, c: u32| span.as_ref().is_some_and(|(rows, cols)| rows.contains(&r) && cols.contains(&c));
        let text_of = |&(r, c): &(u32, u32)| {
            let (_, opened) = sheet.text(r, c).and_then(FootnoteMark::leading)?;
            let mut text = opened.to_string();
            for (_, v) in sheet.cells.range((r, c + 1)..=(r, u32::MAX)) {
                if text.chars().count() > FOOTNOTE_QUOTED_CHARS {
                    break;
                }
                if let Val::Text(t) = v
                    && !t.trim().is_empty()
                {
                    if !text.is_empty() {
                        text.push(' ');
                    }
                    text.push_str(t.trim());
                }
            }
            (!text.is_empty()).then_some((r, c, text))
        };
        let cells = self.0.get(&mark)?.iter().filter(|&&(r, c)| !in_grid(r, c));
        let below =
            span.as_ref().and_then(|(rows, _)| cells.clone().filter(|&&(r, _)| r > *rows.end()).find_map(text_of));
        let (r, c, text) = below.or_else(|| cells.clone().find_map(text_of))?;
        // One line, as it is quoted in a sentence (a cell may hold line breaks).
        let mut text = text
            .split(|c: char| c.is_whitespace() || c.is_control())
            .filter(|w| !w.is_empty())
            .collect::<Vec<_>>()
            .join(" ");
        if text.chars().count() > FOOTNOTE_QUOTED_CHARS {
            text = text.chars().take(FOOTNOTE_QUOTED_CHARS).collect::<String>() + "...";
        }
        Some((format!("{}!{}", sheet.name, cell_ref(r, c)), text))
    }
}

/// A sheet and its notes, indexed on the first mark looked for
/// ([`SheetNotes::of`]) and then kept: a sheet with several grids, or a
/// sheet of notes asked for each grid's marks, is indexed once.
#[derive(Debug)]
pub struct LazyNotes<'a> {
    sheet: &'a Sheet,
    notes: std::cell::OnceCell<SheetNotes>,
}

impl<'a> LazyNotes<'a> {
    pub fn new(sheet: &'a Sheet) -> LazyNotes<'a> {
        LazyNotes { sheet, notes: std::cell::OnceCell::new() }
    }

    /// [`SheetNotes::find`] on this sheet.
    pub fn find(&self, g: Option<&Grid>, mark: FootnoteMark) -> Option<(String, String)> {
        self.notes.get_or_init(|| SheetNotes::of(self.sheet)).find(self.sheet, g, mark)
    }
}

/// The workbook's sheets that hold no chart grid (a sheet of notes, a
/// cover): where a footnote is looked for when the grid's own sheet has
/// none, as a workbook may keep a chart's notes on a sheet of their own.
#[derive(Debug, Default)]
pub struct NoteSheets<'a>(Vec<LazyNotes<'a>>);

impl<'a> NoteSheets<'a> {
    pub fn new(sheets: impl IntoIterator<Item = &'a Sheet>) -> NoteSheets<'a> {
        NoteSheets(sheets.into_iter().map(LazyNotes::new).collect())
    }

    /// Each sheet's note marked `mark`, in the workbook's order: (cell, text).
    pub fn find(&self, mark: FootnoteMark) -> Vec<(String, String)> {
        self.0.iter().filter_map(|notes| notes.find(None, mark)).collect()
    }

    pub fn names(&self) -> Vec<&str> {
        self.0.iter().map(|notes| notes.sheet.name.as_str()).collect()
    }
}

/// The words a chart writes in a cell where no capacity is permitted.
const NOT_PERMITTED: [&str; 10] = ["", "-", "–", "—", "*", "n/a", "na", "x", "/", "--"];

/// A capacity written as text, taken apart: its number as written, blanks
/// taken out; the unit after it; the footnote mark after that.
struct CapacityText<'a> {
    number: String,
    unit: &'a str,
    mark: Option<FootnoteMark>,
}

/// `None` for the words of "not permitted".
fn capacity_text(t: &str) -> Option<CapacityText<'_>> {
    let t = t.trim();
    if NOT_PERMITTED.contains(&t.to_lowercase().as_str()) {
        return None;
    }
    let (s, mark) = match FootnoteMark::split(t) {
        Some((before, mark)) => (before, Some(mark)),
        None => (t, None),
    };
    let num_end = s
        .char_indices()
        .find(|(_, c)| !(c.is_ascii_digit() || *c == '.' || *c == ',' || *c == ' ' || *c == '\u{a0}'))
        .map(|(i, _)| i)
        .unwrap_or(s.len());
    let number = s[..num_end].chars().filter(|c| *c != ' ' && *c != '\u{a0}').collect();
    Some(CapacityText { number, unit: s[num_end..].trim(), mark })
}

/// Numbers a grid holds as text that were read in a way worth saying, with
/// their cells: said once for the grid (`TextNumbers::said`), not cell by
/// cell (a chart typed in another locale has hundreds).
#[derive(Default)]
pub struct TextNumbers {
    decimal_commas: Vec<TextNumber>,
    guessed: Vec<TextNumber>,
}

/// A number written as text: its cell ("sheet!B6"), its text, its value.
struct TextNumber(String, String, f64);

impl TextNumbers {
    fn note(&mut self, reading: Reading, cell: &str, text: &str, value: f64) {
        let list = match reading {
            Reading::Plain => return,
            Reading::DecimalComma => &mut self.decimal_commas,
            Reading::Guessed => &mut self.guessed,
        };
        list.push(TextNumber(cell.to_string(), text.trim().to_string(), value));
    }

    /// The warnings for a grid (`range`: where it is, on sheet `sheet`),
    /// each opening with the cell, or the range of cells, it is about (as
    /// the plan's pages find the cells a step reads in the warnings).
    fn said(&self, sheet: &str, range: &str) -> Vec<String> {
        // The rectangle the numbers' cells span, as "sheet!B6" or "sheet!B6:M44".
        let span = |numbers: &[TextNumber]| {
            let corners = numbers.iter().filter_map(|TextNumber(cell, _, _)| {
                liftplan_core::location::parse_cell_range(cell.rsplit_once('!')?.1).map(|(first, _)| first)
            });
            let (mut lo, mut hi) = ((u32::MAX, u32::MAX), (0, 0));
            for (r, c) in corners {
                (lo, hi) = ((lo.0.min(r), lo.1.min(c)), (hi.0.max(r), hi.1.max(c)));
            }
            if lo == hi {
                format!("{sheet}!{}", cell_ref(lo.0, lo.1))
            } else {
                format!("{sheet}!{}:{}", cell_ref(lo.0, lo.1), cell_ref(hi.0, hi.1))
            }
        };
        let mut out = Vec::new();
        if let [TextNumber(cell, text, v), rest @ ..] = &self.decimal_commas[..] {
            out.push(if rest.is_empty() {
                format!("{cell}: '{text}' written as text with a decimal comma, read as {v}")
            } else {
                format!(
                    "{}: {} numbers written as text with decimal commas, read as decimals ({cell} '{text}' as {v})",
                    span(&self.decimal_commas),
                    rest.len() + 1
                )
            });
        }
        if let [TextNumber(cell, text, v), rest @ ..] = &self.guessed[..] {
            let how = if text.contains(',') { "the comma separating thousands" } else { "the point marking decimals" };
            let unsure = format!(
                "as no number written as text in the grid {sheet}!{range} shows whether it writes decimals with a \
                 point or a comma"
            );
            out.push(if rest.is_empty() {
                format!("{cell}: '{text}' written as text read as {v}, {how}, {unsure}: CHECK it against the chart")
            } else {
                format!(
                    "{}: {} numbers written as text read the common way, {unsure} ({cell} '{text}' as {v}, {how}): \
                     CHECK them against the chart",
                    span(&self.guessed),
                    rest.len() + 1
                )
            });
        }
        out
    }
}

/// A capacity cell's value: `Ok(None)` for "not permitted". A number
/// written as text is read with the grid's decimal mark where it shows none
/// of its own ([`GridMark::for_number`]) and noted in `read` where worth
/// saying. A footnote mark after it is dropped with a warning that ends
/// with what `footnote` says of the note it points at.
pub fn parse_capacity(
    v: Option<&Val>,
    unit: MassUnit,
    decimals: &GridMark,
    read: &mut TextNumbers,
    warnings: &mut Vec<String>,
    at: &str,
    footnote: &mut dyn FnMut(FootnoteMark) -> String,
) -> Result<Option<f64>, String> {
    let t = match v {
        None => return Ok(None),
        Some(Val::Num(x)) => {
            return if x.is_finite() && *x > 0.0 {
                Ok(Some(*x))
            } else if *x == 0.0 {
                Ok(None)
            } else {
                Err(format!("capacity {x} is not a positive number"))
            };
        }
        Some(Val::Text(t)) => t.trim(),
    };
    if shows_an_error(t) {
        return Err(format!(
            "the cell shows an error ('{t}'), not a capacity: its formula in the workbook is broken; correct it there"
        ));
    }
    let Some(parts) = capacity_text(t) else { return Ok(None) };
    if let Some(mark) = parts.mark {
        warnings.push(format!("{at}: footnote mark dropped from '{t}'{}", footnote(mark)));
    }
    if !parts.unit.is_empty() {
        let units = mass_in(parts.unit);
        match units.first() {
            Some(u) if *u == unit => {}
            Some(u) => {
                return Err(format!("'{t}' is in {}, but the chart's capacities are in {}", u.name(), unit.name()));
            }
            None => return Err(format!("cannot read '{t}' as a capacity (expected a number in {})", unit.name())),
        }
    }
    // In kilograms, pounds or decanewtons no chart gives three decimal
    // places: there a separator before three digits ("12,500 lb", "12.500 kg") separates
    // thousands, whichever it is and however the grid writes decimals.
    let thousands = matches!(unit, MassUnit::Kg | MassUnit::Lb | MassUnit::DecaNewton)
        && decimals::shown_by(&parts.number).is_none()
        && parts.number.contains([',', '.']);
    let mark = match thousands {
        true if parts.number.contains(',') => Some(decimals::DecimalMark::Point),
        true => Some(decimals::DecimalMark::Comma),
        false => decimals.for_number(&parts.number)?,
    };
    let Some((value, reading)) = decimals::read(&parts.number, mark) else {
        return Err(format!("cannot read '{t}' as a capacity (expected a number in {})", unit.name()));
    };
    read.note(reading, at, &parts.number, value);
    if value > 0.0 { Ok(Some(value)) } else { Ok(None) }
}

/// A radius or boom length written with a footnote mark after it ("40*"):
/// its place among the axis' values, the mark, the cell's text.
struct MarkedAxisValue(usize, FootnoteMark, String);

/// The numbers of a grid's radii or boom lengths (`what`), in its `cells`,
/// in `unit`, and those written with a footnote mark after them: a cell
/// holding none is refused, naming it and what it holds, and so is one
/// written with another unit after its number. Numbers written as text are
/// read with the grid's decimal mark (`decimals`) and noted in `read` where
/// worth saying.
fn axis_values(
    sheet: &Sheet,
    cells: &[(u32, u32)],
    (what, unit): (&str, LengthUnit),
    decimals: &GridMark,
    read: &mut TextNumbers,
) -> Result<(Vec<f64>, Vec<MarkedAxisValue>), (String, String)> {
    let at = |(r, c): (u32, u32)| format!("{}!{}", sheet.name, cell_ref(r, c));
    let mut values = Vec::with_capacity(cells.len());
    let mut marked = Vec::new();
    for (k, &(r, c)) in cells.iter().enumerate() {
        let v = match sheet.get(r, c) {
            Some(Val::Num(v)) => *v,
            Some(Val::Text(t)) => {
                let (unmarked, mark) = FootnoteMark::split_off(t);
                if let Some(mark) = mark {
                    marked.push(MarkedAxisValue(k, mark, t.trim().to_string()));
                }
                let (number, written) = length_and_unit(unmarked);
                if let Some(written) = written.filter(|&w| w != unit) {
                    let t = liftplan_core::names::kept(t.trim(), 40);
                    let (what, w, unit) = (plural(what), written.name(), unit.name());
                    return Err((
                        at((r, c)),
                        format!(
                            "'{t}' is in {w}, but the grid's {what} are in {unit} (as its labels, its other cells or \
                             the project's [charts] say): a chart gives an axis in one unit; correct the cell"
                        ),
                    ));
                }
                match decimals::read(number, decimals.for_number(number).map_err(|why| (at((r, c)), why))?) {
                    Some((v, reading)) => {
                        read.note(reading, &at((r, c)), t, v);
                        v
                    }
                    None => {
                        let t = liftplan_core::names::kept(t.trim(), 40);
                        return Err((at((r, c)), format!("expected a {what} (a number), found '{t}'")));
                    }
                }
            }
            None => return Err((at((r, c)), format!("expected a {what} (a number), found an empty cell"))),
        };
        values.push(v);
    }
    Ok((values, marked))
}

/// A cell just past a grid's last boom length or radius that begins like a
/// number but is not read as one ("40 boom", "12 see note"), or shows a
/// broken formula's error ("#REF!"): its column or row is then no part of
/// the chart, a configuration or radius lost without a word. The warning
/// names it.
fn beside_the_grid(sheet: &Sheet, g: &Grid, (across_is, down_is): (&str, &str)) -> Vec<String> {
    let mut out = Vec::new();
    let mut look = |(r, c): (u32, u32), what: &str, line: &str| {
        if let Some(v @ Val::Text(t)) = sheet.get(r, c)
            && ((reads_as_number(v) && v.number().is_none()) || shows_an_error(t))
        {
            let t = liftplan_core::names::kept(t.trim(), 40);
            out.push(format!(
                "{}!{}: '{t}', next to the grid's {}, is not read as one, so its {line} is no part of the chart \
                 {}!{}: write it as a number (a unit and a footnote mark after it are read), or describe the grid \
                 with [[charts.table]]",
                sheet.name,
                cell_ref(r, c),
                plural(what),
                sheet.name,
                g.range()
            ));
        }
    };
    if !g.boom_independent
        && let Some(next) = g.value_cols.last().and_then(|c| c.checked_add(1))
    {
        look((g.header_row, next), across_is, "column");
    }
    if let Some(next) = g.rows.last().and_then(|r| r.checked_add(1)) {
        look((next, g.label_col), down_is, "row");
    }
    out.extend(going_on_past_a_break(sheet, g, (across_is, down_is)));
    out
}

/// The most rows or columns that may break a grid's radii or boom lengths
/// and still be said when the numbers go on past them.
const BREAK_LOOKED_PAST: u32 = 2;

/// Where a grid's radii go on rising below it past a row or two that
/// breaks them (a blank row, or a header repeated where a chart pasted from
/// a PDF turned its page), with capacities beside them, or its boom
/// lengths to the right past a column: what follows the break is no part of
/// the chart, radii or configurations lost without a word. The warnings
/// name where the numbers go on and what breaks them.
fn going_on_past_a_break(sheet: &Sheet, g: &Grid, (across_is, down_is): (&str, &str)) -> Vec<String> {
    let num = |r: u32, c: u32| sheet.num(r, c);
    let said = |(r, c): (u32, u32)| match sheet.get(r, c) {
        Some(Val::Text(t)) => format!("'{}'", liftplan_core::names::kept(t.trim(), 40)),
        Some(Val::Num(v)) => format!("{v}"),
        None => "empty".to_string(),
    };
    let mut out = Vec::new();
    let mut warn = |first: (u32, u32), broken_at: (u32, u32), what: &str, line: &str| {
        out.push(format!(
            "{}!{}: the grid's {} go on here, past the {line} at {} ({}) that breaks them, but what follows is no \
             part of the grid {}!{} (where it makes a grid of its own, that is another configuration): take the \
             break out (a page break of a chart pasted from a PDF?), or describe the grid with [[charts.table]]",
            sheet.name,
            cell_ref(first.0, first.1),
            plural(what),
            cell_ref(broken_at.0, broken_at.1),
            said(broken_at),
            sheet.name,
            g.range()
        ));
    };
    let (Some(&last_row), Some(&last_col)) = (g.rows.last(), g.value_cols.last()) else { return out };
    // Down: a rising radius past the break, with a capacity beside it.
    if let Some(last) = num(last_row, g.label_col) {
        for gap in 1..=BREAK_LOOKED_PAST {
            let Some(r) = last_row.checked_add(gap + 1) else { break };
            let breaks = (last_row + 1..r).all(|b| num(b, g.label_col).is_none());
            if breaks
                && num(r, g.label_col).is_some_and(|v| v > last)
                && g.value_cols.iter().any(|&c| num(r, c).is_some())
            {
                warn((r, g.label_col), (last_row + 1, g.label_col), down_is, "row");
                break;
            }
        }
    }
    // Across: a rising boom length past the break, with a capacity under it.
    if !g.boom_independent
        && let Some(last) = num(g.header_row, last_col)
    {
        for gap in 1..=BREAK_LOOKED_PAST {
            let Some(c) = last_col.checked_add(gap + 1) else { break };
            let breaks = (last_col + 1..c).all(|b| num(g.header_row, b).is_none());
            if breaks && num(g.header_row, c).is_some_and(|v| v > last) && g.rows.iter().any(|&r| num(r, c).is_some()) {
                warn((g.header_row, c), (g.header_row, last_col + 1), across_is, "column");
                break;
            }
        }
    }
    out
}

fn plural(what: &str) -> String {
    match what {
        "radius" => "radii".to_string(),
        _ => format!("{what}s"),
    }
}

/// What a capacity's warning says of the note its mark points at: the note
/// on the grid's own sheet, else on the workbook's sheets without a chart
/// (naming any other note there that opens with the same mark, as which
/// applies is then for the engineer to read), else that none was found.
fn footnote_said(sheet: &Sheet, g: &Grid, notes: &LazyNotes, note_sheets: &NoteSheets, mark: FootnoteMark) -> String {
    if let Some((cell, text)) = notes.find(Some(g), mark) {
        return format!("; its footnote, {cell}, reads: \"{text}\"");
    }
    let elsewhere = note_sheets.find(mark);
    let Some(((cell, text), more)) = elsewhere.split_first() else {
        let others = note_sheets.names();
        let also = if others.is_empty() {
            String::new()
        } else {
            format!(" nor on the workbook's sheets without a chart ({})", others.join(", "))
        };
        return format!(
            "; no footnote marked '{}' was found on sheet {}{also}: read the chart's notes for it",
            mark.said(),
            sheet.name
        );
    };
    let more = if more.is_empty() {
        String::new()
    } else {
        let cells: Vec<&str> = more.iter().map(|(c, _)| c.as_str()).collect();
        format!("; {} also open with '{}': check which note applies", cells.join(", "), mark.said())
    };
    format!(
        "; none is marked '{}' on sheet {}, and the footnote so marked on a sheet of notes, {cell}, reads: \"{text}\"{more}",
        mark.said(),
        sheet.name
    )
}

/// Reads a located grid into a chart configuration. Errors are (cell, message).
pub fn read_grid(
    sheet: &Sheet,
    g: &Grid,
    u: &Units,
    file_label: &str,
    name: &str,
    (notes, note_sheets): (&LazyNotes, &NoteSheets),
    warnings: &mut Vec<String>,
) -> Result<ChartConfig, (String, String)> {
    let at = |r: u32, c: u32| format!("{}!{}", sheet.name, cell_ref(r, c));
    // Values across the header and down the label column.
    let (across_is, down_is) = if g.transposed { ("radius", "boom length") } else { ("boom length", "radius") };
    let (across_unit, down_unit) = if g.transposed { (u.radius, u.boom) } else { (u.boom, u.radius) };
    let (across_cells, down_cells) = axis_cells(g);
    // The numbers the grid holds as text, with their cells: what they show
    // decides how those that show nothing are read.
    let axis_texts = across_cells.iter().chain(&down_cells).filter_map(|&(r, c)| {
        let (unmarked, _) = FootnoteMark::split_off(sheet.text(r, c)?);
        Some((at(r, c), length_and_unit(unmarked).0.to_string()))
    });
    let capacity_texts = g.rows.iter().flat_map(|&r| g.value_cols.iter().map(move |&c| (r, c)));
    let capacity_texts = capacity_texts.filter_map(|(r, c)| Some((at(r, c), capacity_text(sheet.text(r, c)?)?.number)));
    let decimals = GridMark::of(axis_texts.chain(capacity_texts));
    let mut read = TextNumbers::default();
    let (across, across_marked) = match g.boom_independent {
        true => (vec![0.0], Vec::new()),
        false => axis_values(sheet, &across_cells, (across_is, across_unit), &decimals, &mut read)?,
    };
    let (down, down_marked) = axis_values(sheet, &down_cells, (down_is, down_unit), &decimals, &mut read)?;
    if !g.boom_independent && !strictly_increasing(&across) {
        return Err((at(g.header_row, g.value_cols[0]), "header values must increase from left to right".into()));
    }
    if !strictly_increasing(&down) {
        return Err((at(g.rows[0], g.label_col), "values down the first column must increase".into()));
    }
    let (radii_raw, booms_raw) =
        if g.transposed { (across.clone(), down.clone()) } else { (down.clone(), across.clone()) };
    let radii_m: Vec<f64> = radii_raw.iter().map(|r| r * u.radius.to_m()).collect();
    let booms_m: Vec<f64> = booms_raw.iter().map(|b| b * u.boom.to_m()).collect();
    let mut cells = vec![None; radii_m.len() * booms_m.len()];
    // Each mark's note is looked for once (a column may carry the same mark
    // in every cell).
    let mut said: std::collections::HashMap<FootnoteMark, String> = Default::default();
    let mut footnote = |mark: FootnoteMark| {
        said.entry(mark).or_insert_with(|| footnote_said(sheet, g, notes, note_sheets, mark)).clone()
    };
    // A mark on a boom length or radius points at a note on its whole
    // column or row: the warning opens with that range, so that a step
    // reading a capacity there is matched to it.
    let last_row = *g.rows.last().unwrap_or(&g.header_row);
    let last_col = *g.value_cols.last().unwrap_or(&g.label_col);
    for MarkedAxisValue(k, mark, t) in &across_marked {
        let col = g.value_cols[*k];
        let range = format!("{}!{}:{}", sheet.name, cell_ref(g.header_row, col), cell_ref(last_row, col));
        warnings.push(format!(
            "{range}: footnote mark dropped from the {across_is} '{t}' heading the column{}",
            footnote(*mark)
        ));
    }
    for MarkedAxisValue(k, mark, t) in &down_marked {
        let row = g.rows[*k];
        let range = format!("{}!{}:{}", sheet.name, cell_ref(row, g.label_col), cell_ref(row, last_col));
        warnings.push(format!(
            "{range}: footnote mark dropped from the {down_is} '{t}' heading the row{}",
            footnote(*mark)
        ));
    }
    warnings.extend(beside_the_grid(sheet, g, (across_is, down_is)));
    let cell_of = |ri: usize, bi: usize| {
        if g.transposed {
            (g.rows[bi], g.value_cols[ri])
        } else {
            (g.rows[ri], g.value_cols[if g.boom_independent { 0 } else { bi }])
        }
    };
    for (ri, _) in radii_m.iter().enumerate() {
        for (bi, _) in booms_m.iter().enumerate() {
            let (row, col) = cell_of(ri, bi);
            let here = at(row, col);
            let v =
                parse_capacity(sheet.get(row, col), u.capacity, &decimals, &mut read, warnings, &here, &mut footnote)
                    .map_err(|m| (here.clone(), m))?;
            cells[ri * booms_m.len() + bi] =
                v.map(|x| ChartCell { capacity_kg: x * u.capacity.to_kg(), cell: format!("{file_label} [{here}]") });
        }
    }
    warnings.extend(read.said(&sheet.name, &g.range()));
    // Capacity must not rise with radius; a column broken by a cell with
    // none (a blank or '-' between two capacities) is read as not
    // permitted there, which is safe but rarely what the chart means.
    for bi in 0..booms_m.len() {
        let mut prev: Option<(f64, usize)> = None;
        for ri in 0..radii_m.len() {
            if let Some((_, pri)) = prev
                && ri > pri + 1
                && cells[ri * booms_m.len() + bi].is_some()
            {
                let (first, last) = (cell_of(pri + 1, bi), cell_of(ri - 1, bi));
                let span = if first == last {
                    at(first.0, first.1)
                } else {
                    format!("{}:{}", at(first.0, first.1), cell_ref(last.0, last.1))
                };
                warnings.push(format!(
                    "{span}: no capacity between {:.2} m and {:.2} m on the {:.2} m boom, between two capacities: read as not permitted there (no lift is planned at those radii); a load chart's column is unbroken, check the cells",
                    radii_m[pri],
                    radii_m[ri],
                    booms_m[bi]
                ));
            }
            if let Some(c) = &cells[ri * booms_m.len() + bi] {
                if let Some((p, pri)) = prev
                    && c.capacity_kg > p * (1.0 + 1e-9)
                {
                    let (row, col) = cell_of(ri, bi);
                    return Err((
                        at(row, col),
                        format!(
                            "capacity rises with radius: {:.3} t at {:.2} m is more than {:.3} t at {:.2} m (boom {:.2} m); a load chart never does, check the cell or the layout",
                            c.capacity_kg / 1000.0,
                            radii_m[ri],
                            p / 1000.0,
                            radii_m[pri],
                            booms_m[bi]
                        ),
                    ));
                }
                prev = Some((c.capacity_kg, ri));
            }
        }
    }
    Ok(ChartConfig { name: name.to_string(), boom_lengths_m: booms_m, radii_m, cells })
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use std::collections::BTreeMap;

    fn sheet(rows: &[&[&str]]) -> Sheet {
        let mut cells = BTreeMap::new();
        for (r, row) in rows.iter().enumerate() {
            for (c, v) in row.iter().enumerate() {
                if v.is_empty() {
                    continue;
                }
                let val = match v.parse::<f64>() {
                    Ok(x) => Val::Num(x),
                    Err(_) => Val::Text(v.to_string()),
                };
                cells.insert((r as u32, c as u32), val);
            }
        }
        Sheet { name: "Main".into(), cells }
    }

    /// The grid search as first written, walking the sheet for every
    /// question (cubic in a sheet's side): the reference the indexed search
    /// must agree with. The grids it chooses, before they are described:
    /// header row, value columns, label column, rows, boom-independent.
    fn walked_grids(sheet: &Sheet) -> Vec<(u32, Vec<u32>, u32, Vec<u32>, bool)> {
        let increasing_down = |col: u32, start: u32| {
            let (mut rows, mut r, mut skipped, mut last) = (Vec::new(), start, 0, f64::NEG_INFINITY);
            loop {
                match sheet.get(r, col).map(|v| (v, v.number())) {
                    Some((_, Some(v))) if v > 0.0 && v > last => {
                        rows.push(r);
                        last = v;
                    }
                    Some((_, None)) | None if rows.is_empty() && skipped < 2 => skipped += 1,
                    _ => break,
                }
                r += 1;
            }
            rows
        };
        let density = |rows: &[u32], cols: &[u32]| {
            let n = rows.iter().flat_map(|&r| cols.iter().map(move |&c| (r, c)));
            let n = n.filter(|&(r, c)| sheet.get(r, c).is_some_and(reads_as_number)).count();
            n as f64 / (rows.len() * cols.len()) as f64
        };
        let mut sheet_rows: Vec<u32> = sheet.cells.keys().map(|k| k.0).collect();
        sheet_rows.dedup();
        let mut cols: Vec<u32> = sheet.cells.keys().map(|k| k.1).collect();
        cols.sort_unstable();
        cols.dedup();
        let mut cands = Vec::new();
        for &r in &sheet_rows {
            let nums: Vec<(u32, f64)> = cols.iter().filter_map(|&c| sheet.num(r, c).map(|x| (c, x))).collect();
            let mut i = 0;
            while i < nums.len() {
                let mut j = i + 1;
                while j < nums.len() && nums[j].0 == nums[j - 1].0 + 1 && nums[j].1 > nums[j - 1].1 {
                    j += 1;
                }
                let run: Vec<u32> = nums[i..j].iter().map(|x| x.0).collect();
                let first = nums[i].1;
                i = j;
                if run.len() < 2 || first <= 0.0 || run[0] == 0 {
                    continue;
                }
                let rows = increasing_down(run[0] - 1, r + 1);
                if rows.len() >= 2 && density(&rows, &run) >= 0.25 {
                    cands.push((r, run.clone(), run[0] - 1, rows, false));
                }
            }
        }
        for &c in &cols {
            for &r in &sheet_rows {
                if sheet.num(r, c).is_some() || sheet.num(r, c + 1).is_some() {
                    continue;
                }
                let rows = increasing_down(c, r + 1);
                if rows.len() >= 3 && rows[0] == r + 1 && density(&rows, &[c + 1]) >= 0.5 {
                    cands.push((r, vec![c + 1], c, rows, true));
                }
            }
        }
        cands.sort_by_key(|g| std::cmp::Reverse(g.1.len() * g.3.len()));
        let rect = |g: &(u32, Vec<u32>, u32, Vec<u32>, bool)| (g.0, *g.3.last().unwrap(), g.2, *g.1.last().unwrap());
        let mut out: Vec<(u32, Vec<u32>, u32, Vec<u32>, bool)> = Vec::new();
        for g in cands {
            let (a0, a1, b0, b1) = rect(&g);
            if !out.iter().any(|o| {
                let (c0, c1, d0, d1) = rect(o);
                a0 <= c1 && c0 <= a1 && b0 <= d1 && d0 <= b1
            }) {
                out.push(g);
            }
        }
        out.sort_by_key(|g| (g.0, g.2));
        out
    }

    fn found_grids(sheet: &Sheet) -> Vec<(u32, Vec<u32>, u32, Vec<u32>, bool)> {
        let grids = find_grids(sheet).unwrap();
        grids.into_iter().map(|g| (g.header_row, g.value_cols, g.label_col, g.rows, g.boom_independent)).collect()
    }

    /// A random sheet of up to 14 rows and 9 columns, most of whose numbers
    /// follow a slope down and across (so that rising runs both ways, and
    /// grids, are common), with stray numbers (zero and negative ones too),
    /// numbers as text (plain ones, which count as numbers, and ones with
    /// a unit, which do not), words and empty cells among them.
    fn random_sheet() -> impl Strategy<Value = Sheet> {
        let cell = prop_oneof![
            3 => Just(None),
            6 => (-2i32..3).prop_map(|d| Some((true, d))),
            2 => (-1i32..12).prop_map(|v| Some((false, v))),
            1 => (0i32..9).prop_map(|v| Some((false, 100 + v))),
            1 => (0i32..12).prop_map(|v| Some((false, 300 + v))),
            1 => (0i32..12).prop_map(|v| Some((false, 400 + v))),
            1 => Just(Some((false, 200))),
        ];
        (1usize..15, 1usize..10, 0i32..3, 0i32..3).prop_flat_map(move |(rows, cols, down, across)| {
            proptest::collection::vec(cell.clone(), rows * cols).prop_map(move |cells| {
                let cells = cells
                    .into_iter()
                    .enumerate()
                    .filter_map(|(k, v)| {
                        let (r, c) = ((k / cols) as i32, (k % cols) as i32);
                        let v = match v? {
                            (true, d) => Val::Num((down * r + across * c + d) as f64),
                            (false, t @ 100..200) => Val::Text(format!("{} t", t - 100)),
                            (false, t @ 300..400) => Val::Text(format!("{},5", t - 300)),
                            (false, t @ 400..500) => Val::Text(format!(" {} ", t - 400)),
                            (false, 200) => Val::Text("Radius".into()),
                            (false, v) => Val::Num(v as f64),
                        };
                        Some(((r as u32, c as u32), v))
                    })
                    .collect();
                Sheet { name: "Random".into(), cells }
            })
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2000))]
        /// The indexed search finds exactly the grids the walking one does.
        #[test]
        fn the_indexed_search_finds_what_the_walking_search_finds(sheet in random_sheet()) {
            prop_assert_eq!(found_grids(&sheet), walked_grids(&sheet));
        }
    }

    /// Layouts that made the walking search slow, each compared with it at a
    /// size it still manages: a diagonal of words, and rows of three rising
    /// columns (every row a header over the rows under it).
    #[test]
    fn the_slow_layouts_are_searched_alike() {
        let diagonal: BTreeMap<(u32, u32), Val> = (0..400).map(|i| ((i, i), Val::Text("x".into()))).collect();
        let rising: BTreeMap<(u32, u32), Val> = (0..400u32)
            .flat_map(|i| (0..3).map(move |c| ((i, c), Val::Num(if c == 0 { (i + 10) as f64 } else { c as f64 }))))
            .collect();
        for cells in [diagonal, rising] {
            let sheet = Sheet { name: "Slow".into(), cells };
            assert_eq!(found_grids(&sheet), walked_grids(&sheet));
        }
    }

    /// A sheet of more grids than any chart holds is refused with the cell
    /// range of the first one past the limit.
    #[test]
    fn a_sheet_of_too_many_grids_is_refused() {
        // 2 x 2 grids three columns apart, one per block of four rows.
        let grids = |n: u32| {
            let mut cells = BTreeMap::new();
            for k in 0..n {
                let (r, c) = (4 * (k / 100), 3 * (k % 100));
                cells.insert((r, c + 1), Val::Num(20.0));
                cells.insert((r, c + 2), Val::Num(30.0));
                for (i, radius) in [3.0, 5.0].into_iter().enumerate() {
                    cells.insert((r + 1 + i as u32, c), Val::Num(radius));
                    cells.insert((r + 1 + i as u32, c + 1), Val::Num(9.0));
                    cells.insert((r + 1 + i as u32, c + 2), Val::Num(6.0));
                }
            }
            Sheet { name: "Many".into(), cells }
        };
        assert_eq!(find_grids(&grids(MAX_GRIDS as u32)).unwrap().len(), MAX_GRIDS);
        let (cell, msg) = find_grids(&grids(MAX_GRIDS as u32 + 1)).unwrap_err();
        assert_eq!(cell, "FM9:FO11");
        assert!(msg.contains("more than 256 load-chart grids"), "{msg}");
    }

    #[test]
    fn finds_a_manufacturer_grid() {
        let s = sheet(&[
            &["Lifting capacities in t", "", "", ""],
            &["Counterweight 26.5 t, 360 deg", "", "", ""],
            &["Radius (m)", "Boom length (m)", "", ""],
            &["", "12", "20", "28"],
            &["3", "50", "", ""],
            &["4", "40", "35", ""],
            &["6", "30", "28", "20"],
            &["Notes: 1) hook block weight must be deducted", "", "", ""],
        ]);
        let g = find_grids(&s).unwrap();
        assert_eq!(g.len(), 1, "{g:?}");
        let g = &g[0];
        assert!(!g.transposed);
        assert_eq!(g.rows, vec![4, 5, 6]);
        let u = units(&s, g).unwrap();
        assert_eq!((u.radius, u.capacity), (LengthUnit::M, MassUnit::T));
        let mut w = vec![];
        let c = read_grid(&s, g, &u, "c.xlsx", "main", (&LazyNotes::new(&s), &NoteSheets::default()), &mut w).unwrap();
        assert_eq!(c.boom_lengths_m, vec![12.0, 20.0, 28.0]);
        assert_eq!(c.lookup(20.0, 4.0).unwrap().capacity_kg, 35000.0);
        assert!(c.lookup(20.0, 3.0).is_err());
        assert!(c.lookup(20.0, 4.0).unwrap().cell.contains("Main!C6"));
    }

    /// A grid's title names its configuration in one line of words kept
    /// short: a cell's line breaks as spaces, a cell of thousands of
    /// characters kept to its first 100 and a tag.
    #[test]
    fn a_grids_title_is_one_line_kept_short() {
        let titled = |title: &str| {
            let s = sheet(&[
                &[title, "", ""],
                &["Radius m", "Boom m", ""],
                &["", "12", "20"],
                &["3", "50", "30"],
                &["4", "45", "28"],
            ]);
            find_grids(&s).unwrap()[0].title.clone()
        };
        assert_eq!(titled("Main boom,\r\n\tcounterweight 140 t "), "Main boom, counterweight 140 t");
        let long = "Counterweight 140 t ".repeat(500);
        let title = titled(&long);
        assert_eq!(title, liftplan_core::names::kept(long.trim(), MAX_TITLE_CHARS));
        assert_eq!(title.chars().count(), MAX_TITLE_CHARS + liftplan_core::names::TAG_CHARS);
    }

    #[test]
    fn refuses_rising_capacity_with_the_cell() {
        let s = sheet(&[&["Radius m", "Boom m", ""], &["", "12", "20"], &["3", "50", "30"], &["4", "55", "28"]]);
        let g = &find_grids(&s).unwrap()[0];
        let u = units(&s, g).unwrap();
        let e = read_grid(&s, g, &u, "c.xlsx", "x", (&LazyNotes::new(&s), &NoteSheets::default()), &mut vec![])
            .unwrap_err();
        assert_eq!(e.0, "Main!B4");
        assert!(e.1.contains("rises with radius"), "{}", e.1);
    }

    /// A capacity missing between two others in a boom's column (a cell
    /// deleted by mistake) is read as not permitted, and said with its
    /// cells; blanks at a column's ends (the boom cannot reach so close or
    /// so far) are not.
    #[test]
    fn a_column_broken_between_two_capacities_is_said() {
        let s = sheet(&[
            &["Radius m", "Boom m", "", ""],
            &["", "12", "20", "28"],
            &["3", "50", "", ""],
            &["4", "40", "35", ""],
            &["6", "30", "-", "20"],
            &["8", "", "", "18"],
            &["10", "", "22", "15"],
        ]);
        let g = &find_grids(&s).unwrap()[0];
        let u = units(&s, g).unwrap();
        let mut w = vec![];
        let c = read_grid(&s, g, &u, "c.xlsx", "x", (&LazyNotes::new(&s), &NoteSheets::default()), &mut w).unwrap();
        assert!(c.lookup(20.0, 7.0).is_err());
        assert_eq!(w.len(), 1, "{w:?}");
        assert!(
            w[0].starts_with(
                "Main!C5:C6: no capacity between 4.00 m and 10.00 m on the 20.00 m boom, between two capacities"
            ),
            "{w:?}"
        );
    }

    #[test]
    fn typos_read_or_refused_with_the_cell() {
        let mut w = vec![];
        let mut read = TextNumbers::default();
        let mut no_note = |_| String::new();
        let mut parse = |t: &str, unit: MassUnit, decimals: GridMark, at: &str| {
            parse_capacity(Some(&Val::Text(t.into())), unit, &decimals, &mut read, &mut w, at, &mut no_note)
        };
        assert_eq!(parse("12,5", MassUnit::T, GridMark::Neither, "S!C3").unwrap(), Some(12.5));
        assert_eq!(parse("12.5t", MassUnit::T, GridMark::Neither, "S!C4").unwrap(), Some(12.5));
        assert!(parse("12.5kg", MassUnit::T, GridMark::Neither, "S!C5").unwrap_err().contains("kg"));
        assert!(parse("heavy", MassUnit::T, GridMark::Neither, "S!C6").is_err());
        assert_eq!(parse("—", MassUnit::T, GridMark::Neither, "S!C7").unwrap(), None);
        assert_eq!(parse("8.4*", MassUnit::T, GridMark::Neither, "S!C8").unwrap(), Some(8.4));
        assert_eq!(parse("12,500", MassUnit::T, GridMark::Neither, "S!C9").unwrap(), Some(12500.0));
        // In kg or lb, thousands whichever the separator, without a word.
        assert_eq!(parse("12,500", MassUnit::Lb, GridMark::Neither, "S!D9").unwrap(), Some(12500.0));
        assert_eq!(
            parse("12.500", MassUnit::Kg, GridMark::One(crate::decimals::DecimalMark::Point), "S!E9").unwrap(),
            Some(12500.0)
        );
        assert_eq!(
            parse("12,500", MassUnit::T, GridMark::One(crate::decimals::DecimalMark::Comma), "S!C10").unwrap(),
            Some(12.5)
        );
        assert_eq!(parse("1 250,5 kg", MassUnit::Kg, GridMark::Neither, "S!C11").unwrap(), Some(1250.5));
        assert_eq!(parse("1.250,5", MassUnit::Kg, GridMark::Neither, "S!C12").unwrap(), Some(1250.5));
        let both = GridMark::Both { comma: ("S!C3".into(), "12,5".into()), point: ("S!C8".into(), "8.4".into()) };
        assert!(parse("12.500", MassUnit::T, both, "S!C13").unwrap_err().contains("may be 12500 or 12.5"));
        assert!(parse("1,25,000", MassUnit::Lb, GridMark::Neither, "S!C14").is_err());
        assert!(
            parse("#N/A", MassUnit::T, GridMark::Neither, "S!C15")
                .unwrap_err()
                .starts_with("the cell shows an error ('#N/A'), not a capacity")
        );
        assert_eq!(w.len(), 1, "{w:?}");
        let said = read.said("S", "B2:C14");
        assert_eq!(
            said[0],
            "S!C3:C12: 4 numbers written as text with decimal commas, read as decimals (S!C3 '12,5' as 12.5)"
        );
        assert!(
            said[1].starts_with("S!C9: '12,500' written as text read as 12500, the comma separating thousands, as no number written as text in the grid S!B2:C14 shows"),
            "{said:?}"
        );
    }

    /// A capacity with a footnote mark is read without it, and the warning
    /// quotes the note the mark points at (it may restrict the value: "over
    /// the rear only"), or says none was found; each way a chart writes a
    /// mark and numbers its notes.
    #[test]
    fn a_footnote_marks_capacity_is_read_with_its_note_quoted() {
        let read = |mark: &str, notes: &[&[&str]]| {
            let marked = ["6", "30", mark, "20"];
            let mut rows: Vec<&[&str]> = vec![
                &["Radius m", "Boom m", "", ""],
                &["", "12", "20", "28"],
                &["3", "50", "", ""],
                &["4", "40", "35", ""],
                &marked,
                &["", "", "", ""],
            ];
            rows.extend_from_slice(notes);
            let s = sheet(&rows);
            let g = &find_grids(&s).unwrap()[0];
            let u = units(&s, g).unwrap();
            let mut w = vec![];
            let c = read_grid(&s, g, &u, "c.xlsx", "x", (&LazyNotes::new(&s), &NoteSheets::default()), &mut w).unwrap();
            assert_eq!(c.lookup(20.0, 6.0).unwrap().capacity_kg, 28000.0, "{mark}");
            assert_eq!(w.len(), 1, "{w:?}");
            w.remove(0)
        };
        // A line break in the note's cell is a space in the sentence.
        let rear: &[&str] = &["* Over the rear only,\noutriggers fully extended.", "", "", ""];
        assert_eq!(
            read("28*", &[rear]),
            "Main!C5: footnote mark dropped from '28*'; its footnote, Main!A7, reads: \"Over the rear only, outriggers fully extended.\""
        );
        // Two stars point at the note with two, not the one with one.
        let two: &[&str] = &["** With the jib stowed", "", "", ""];
        assert!(read("28**", &[rear, two]).ends_with("its footnote, Main!A8, reads: \"With the jib stowed\""));
        // Numbered notes, the first sharing its cell with "Notes:", a note
        // typed across its row's cells.
        let numbered: [&[&str]; 3] = [
            &["Notes: 1) hook block weight must be deducted", "", "", ""],
            &["2)", "360 deg", "on outriggers", ""],
            &["(3) Not over the front", "", "", ""],
        ];
        assert!(read("28 (1)", &numbered).ends_with("Main!A7, reads: \"hook block weight must be deducted\""));
        assert!(read("28²", &numbered).ends_with("Main!A8, reads: \"360 deg on outriggers\""));
        assert!(read("28 (3)", &numbered).ends_with("Main!A9, reads: \"Not over the front\""));
        // A value is not a note: "2.5 m ..." does not open note 2.
        let value: &[&str] = &["2.5 m minimum radius", "", "", ""];
        assert_eq!(
            read("28 (2)", &[value]),
            "Main!C5: footnote mark dropped from '28 (2)'; no footnote marked '(2)' was found on sheet Main: read the chart's notes for it"
        );
        assert!(
            read("28*", &[two])
                .ends_with("no footnote marked '*' was found on sheet Main: read the chart's notes for it")
        );
        // A long note is cut.
        let long = format!("* {}", "x".repeat(400));
        let cut = read("28*", &[&[long.as_str(), "", "", ""]]);
        assert!(cut.ends_with("...\"") && cut.len() < 420, "{cut}");
    }

    #[test]
    fn transposed_and_mixed_units() {
        let s = sheet(&[
            &["Boom length (ft)", "Radius (ft)", "", ""],
            &["", "10", "15", "20"],
            &["40", "100", "80", "60"],
            &["60", "90", "70", "50"],
            &["Capacities in lb", "", "", ""],
        ]);
        let g = &find_grids(&s).unwrap()[0];
        assert!(g.transposed, "{g:?}");
        let s2 = sheet(&[
            &["Capacity t or kg", "", ""],
            &["Radius m", "", ""],
            &["", "12", "20"],
            &["3", "50", "30"],
            &["4", "45", "28"],
        ]);
        let g2 = &find_grids(&s2).unwrap()[0];
        assert!(units(&s2, g2).is_err());
    }

    /// "to" is a German chart's tonne where written as a unit, and an
    /// English word elsewhere: a chart in pounds whose note says "radius
    /// from the axis of rotation to the hook" is one of pounds.
    #[test]
    fn to_is_a_tonne_only_where_written_as_a_unit() {
        for t in [
            "Tragkraft in to",
            "Tragkräfte (to)",
            "Last [to]",
            "Tragkraft in to:",
            "max. 25 to",
            "25 TO",
            "in to\nRadius",
        ] {
            assert!(says_to_as_tonne(t), "{t}");
            assert_eq!(mass_in(t), vec![MassUnit::T], "{t}");
        }
        // The words of other languages' charts.
        for t in ["Tragkraft in Tonnen", "Portata in tonnellate", "Capacidad en toneladas"] {
            assert_eq!(mass_in(t), vec![MassUnit::T], "{t}");
        }
        for t in ["Ausladung in Meter", "Portée en mètres", "Radio en metros", "Raggio in metri"] {
            assert_eq!(length_in(t), vec![LengthUnit::M], "{t}");
        }
        for t in
            ["radius from the axis of rotation to the hook", "3 to 12 m", "in total", "into", "Tonto", "go to", "logo"]
        {
            assert!(!says_to_as_tonne(t), "{t}");
        }
        // Nor is the end of an English contraction a tonne or a metre;
        // a foot mark after a number is not a contraction.
        assert_eq!(mass_in("Capacities in lb. Don't exceed; it isn't rated, won’t be"), vec![MassUnit::Lb]);
        assert!(length_in("I'm sure").is_empty());
        assert_eq!(words("40' boom, 'to' here"), ["40", "boom", "to", "here"]);
        let s = sheet(&[
            &["Capacities in pounds", "", ""],
            &["Radius from the axis of rotation to the hook", "", ""],
            &["Radius ft", "Boom ft", ""],
            &["", "40", "60"],
            &["10", "49000", "39200"],
            &["15", "34800", "29400"],
        ]);
        let g = &find_grids(&s).unwrap()[0];
        assert_eq!(units(&s, g).unwrap().capacity, MassUnit::Lb);
    }

    /// A boom length or radius with a footnote mark is read, the warning
    /// opening with its whole column or row and quoting the note; one
    /// next to the grid that is no number is said, as its column or row is
    /// then no part of the chart. Before, either dropped its column or row
    /// (a configuration, a radius) without a word.
    #[test]
    fn marks_on_boom_lengths_and_radii() {
        let read = |boom: &str, radius: &str| {
            let s = sheet(&[
                &["Capacities in t", "", "", ""],
                &["Radius m", "Boom m", "", ""],
                &["", "20", "30", boom],
                &["3", "49", "39.2", ""],
                &["5", "34.8", "29.4", "24.5"],
                &[radius, "19.6", "18.1", "15.7"],
                &["* With the jib stowed", "", "", ""],
            ]);
            let g = &find_grids(&s).unwrap()[0];
            let u = units(&s, g).unwrap();
            let mut w = vec![];
            let c = read_grid(&s, g, &u, "c.xlsx", "x", (&LazyNotes::new(&s), &NoteSheets::default()), &mut w).unwrap();
            (c, w)
        };
        let (c, w) = read("40*", "8");
        assert_eq!((c.boom_lengths_m, c.radii_m), (vec![20.0, 30.0, 40.0], vec![3.0, 5.0, 8.0]));
        assert_eq!(
            w,
            [
                "Main!D3:D6: footnote mark dropped from the boom length '40*' heading the column; its footnote, Main!A7, reads: \"With the jib stowed\""
            ]
        );
        // The mark is no part of the number whose decimal comma the grid
        // shows.
        let (c, _) = read("40,5*", "8");
        assert_eq!(c.boom_lengths_m, vec![20.0, 30.0, 40.5]);
        let (c, w) = read("40", "8 (1)");
        assert_eq!(c.radii_m, vec![3.0, 5.0, 8.0]);
        assert!(
            w[0].starts_with(
                "Main!A6:D6: footnote mark dropped from the radius '8 (1)' heading the row; no footnote marked '(1)'"
            ),
            "{w:?}"
        );
        let (c, w) = read("#REF!", "8");
        assert_eq!(c.boom_lengths_m, vec![20.0, 30.0]);
        assert!(w[0].starts_with("Main!D3: '#REF!', next to the grid's boom lengths, is not read as one"), "{w:?}");
        let (c, w) = read("40 boom", "8");
        assert_eq!(c.boom_lengths_m, vec![20.0, 30.0]);
        assert_eq!(
            w,
            [
                "Main!D3: '40 boom', next to the grid's boom lengths, is not read as one, so its column is no part of the chart Main!A3:C6: write it as a number (a unit and a footnote mark after it are read), or describe the grid with [[charts.table]]"
            ]
        );
    }

    /// Radii that go on rising past a blank row or a repeated header (a
    /// chart pasted from a PDF across a page break), or boom lengths past a
    /// blank column, are said: what follows the break is no part of the
    /// grid. A second grid below, its radii starting again, is not.
    #[test]
    fn numbers_going_on_past_a_break_are_said() {
        let read = |rows: &[&[&str]]| {
            let s = sheet(rows);
            let g = &find_grids(&s).unwrap()[0];
            let u = units(&s, g).unwrap();
            let mut w = vec![];
            read_grid(&s, g, &u, "c.xlsx", "x", (&LazyNotes::new(&s), &NoteSheets::default()), &mut w).unwrap();
            w
        };
        let head: [&[&str]; 3] =
            [&["Capacities in t", "", "", "", ""], &["Radius m", "Boom m", "", "", ""], &["", "20", "30", "", ""]];
        let radii: [&[&str]; 3] = [&["3", "49", "39", "", ""], &["4", "40", "35", "", ""], &["5", "34", "29", "", ""]];
        let mut rows: Vec<&[&str]> = head.iter().chain(&radii).copied().collect();
        rows.extend_from_slice(&[&["", "", "", "", ""], &["6", "30", "25", "", ""], &["8", "22", "19", "", ""]]);
        assert_eq!(
            read(&rows),
            [
                "Main!A8: the grid's radii go on here, past the row at A7 (empty) that breaks them, but what follows is no part of the grid Main!A3:C6 (where it makes a grid of its own, that is another configuration): take the break out (a page break of a chart pasted from a PDF?), or describe the grid with [[charts.table]]"
            ]
        );
        rows[6] = &["Radius m", "20", "30", "", ""];
        assert!(read(&rows)[0].starts_with("Main!A8: the grid's radii go on here, past the row at A7 ('Radius m')"));
        // A second grid below: its radii start again.
        rows[7] = &["3", "30", "25", "", ""];
        assert!(read(&rows).is_empty());
        // Boom lengths past a blank column.
        let rows: Vec<&[&str]> = vec![
            &["Capacities in t", "", "", "", ""],
            &["Radius m", "Boom m", "", "", ""],
            &["", "20", "30", "", "40"],
            &["3", "49", "39", "", "30"],
            &["4", "40", "35", "", "28"],
        ];
        assert!(
            read(&rows)[0].starts_with("Main!E3: the grid's boom lengths go on here, past the column at D3 (empty)")
        );
    }

    /// A chart rating its capacities as weights (kN, daN) is read as the
    /// mass they weigh; a force named beside a mass unit is another
    /// figure's, and the mass unit is the chart's.
    #[test]
    fn capacities_given_as_weights() {
        let chart = |title: &str, capacity: &str| {
            sheet(&[
                &[title, "", ""],
                &["Radius m", "Boom m", ""],
                &["", "20", "30"],
                &["3", capacity, "392"],
                &["5", "348", "294"],
            ])
        };
        let read = |s: &Sheet| {
            let g = &find_grids(s).unwrap()[0];
            let u = units(s, g).map_err(|e| e.1)?;
            let notes = (&LazyNotes::new(s), &NoteSheets::default());
            let c = read_grid(s, g, &u, "c.xlsx", "x", notes, &mut vec![]).map_err(|e| e.1)?;
            Ok::<_, String>((u, c.cells[0].as_ref().unwrap().capacity_kg))
        };
        let (u, kg) = read(&chart("Rated capacities in kN", "490")).unwrap();
        assert_eq!(u.capacity, MassUnit::KiloNewton);
        assert!(u.capacity_named, "{u:?}");
        assert!((kg - 490_000.0 / 9.806_65).abs() < 1e-6, "{kg}");
        assert_eq!(u.found[0], "capacity in kN of weight, read as the mass it weighs (1 kN = 101.9716 kg)");
        let (u, kg) = read(&chart("Charges en daN", "49 000")).unwrap();
        assert_eq!(u.capacity, MassUnit::DecaNewton);
        assert!((kg - 490_000.0 / 9.806_65).abs() < 1e-6, "{kg}");
        // In daN, as in kg, no chart writes three decimals: '49.000 daN'
        // is forty-nine thousand.
        assert!((read(&chart("Charges en daN", "49.000 daN")).unwrap().1 - 490_000.0 / 9.806_65).abs() < 1e-6);
        let (u, kg) = read(&chart("Tragkräfte in t, Stützkraft max. 450 kN", "490")).unwrap();
        assert_eq!((u.capacity, kg), (MassUnit::T, 490_000.0));
        let e = read(&chart("Capacities in t", "490 kN")).unwrap_err();
        assert_eq!(e, "'490 kN' is in kN, but the chart's capacities are in t");
        assert!(
            read(&chart("Capacities in kN and daN", "490")).unwrap_err().contains("more than one mass unit (kN, daN)")
        );
    }

    /// Radii and boom lengths pasted from a PDF with their unit in the
    /// cell: the grid is found, the unit is the cells' where the labels
    /// name none, and a cell in another unit than its axis is refused.
    #[test]
    fn lengths_written_with_their_unit_in_the_cell() {
        let chart = |radius_label: &str, boom: [&str; 2], radii: [&str; 2]| {
            sheet(&[
                &["Capacities in t", "", ""],
                &[radius_label, "Main boom", ""],
                &["", boom[0], boom[1]],
                &[radii[0], "50", "30"],
                &[radii[1], "45,5", "28"],
            ])
        };
        let read = |s: &Sheet| {
            let g = &find_grids(s).map_err(|e| e.1)?[..];
            let [g] = g else { return Err(format!("{} grids", g.len())) };
            let u = units(s, g).map_err(|e| e.1)?;
            let mut w = vec![];
            let notes = (&LazyNotes::new(s), &NoteSheets::default());
            read_grid(s, g, &u, "c.xlsx", "x", notes, &mut w)
                .map(|c| (u, c, w))
                .map_err(|(cell, m)| format!("{cell}: {m}"))
        };
        let (u, c, w) = read(&chart("Radius", ["30,5 m", "40,0 m"], ["3,0 m", "4,0 m"])).unwrap();
        assert!(u.length_named && u.radius == LengthUnit::M && u.boom == LengthUnit::M, "{u:?}");
        assert_eq!((c.boom_lengths_m, c.radii_m), (vec![30.5, 40.0], vec![3.0, 4.0]));
        assert_eq!(c.cells[2].as_ref().unwrap().capacity_kg, 45500.0);
        assert_eq!(w.len(), 1, "{w:?}");
        assert!(w[0].starts_with("Main!A3:C5: 5 numbers written as text with decimal commas"), "{w:?}");
        // Feet in the cells, written every way; no blank before the unit.
        let (u, c, _) = read(&chart("Radius", ["100ft", "120 ft."], ["10'", "15 feet"])).unwrap();
        assert!(u.length_named && u.radius == LengthUnit::Ft && u.boom == LengthUnit::Ft, "{u:?}");
        assert!((c.radii_m[0] - 3.048).abs() < 1e-9, "{:?}", c.radii_m);
        // The label's unit rules the axis: a cell in another is refused.
        let e = read(&chart("Radius [m]", ["30 m", "40 m"], ["3 m", "13 ft"])).unwrap_err();
        assert_eq!(
            e,
            "Main!A5: '13 ft' is in ft, but the grid's radii are in m (as its labels, its other cells or the \
             project's [charts] say): a chart gives an axis in one unit; correct the cell"
        );
        // Cells of two units with no label naming one: the unit is not
        // taken from them, and the cell unlike the project's is refused.
        let s = chart("Radius", ["30 m", "40 m"], ["3 ft", "4 m"]);
        let g = &find_grids(&s).unwrap()[0];
        let u = units(&s, g).unwrap();
        assert!(!u.length_named || u.radius == LengthUnit::M, "{u:?}");
        assert!(read(&s).unwrap_err().starts_with("Main!A4: '3 ft' is in ft, but the grid's radii are in m"));
        // What is no length after a number stays text.
        for t in ["3 mm", "m", "3 m 4", "-3 m", "3 t"] {
            assert_eq!(length_and_unit(t), (t, None), "{t}");
        }
    }

    #[test]
    fn single_column_tower_chart() {
        let s = sheet(&[
            &["Jib 60 m", ""],
            &["Radius (m)", "Capacity (t)"],
            &["3", "12"],
            &["20", "12"],
            &["30", "8.1"],
            &["60", "3.2"],
        ]);
        let g = find_grids(&s).unwrap();
        assert_eq!(g.len(), 1, "{g:?}");
        assert!(g[0].boom_independent);
        let u = units(&s, &g[0]).unwrap();
        let c = read_grid(&s, &g[0], &u, "t.xlsx", "jib", (&LazyNotes::new(&s), &NoteSheets::default()), &mut vec![])
            .unwrap();
        assert!(c.boom_independent());
        assert_eq!(c.lookup(55.0, 25.0).unwrap().capacity_kg, 8100.0);
    }
}
