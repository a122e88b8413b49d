//! Load-chart capacity tables and the manufacturers' rule for reading them.
//!
//! A chart is one grid per crane configuration (counterweight, outrigger spread,
//! working sector): radii down, boom lengths across, capacity in each cell or
//! nothing where the lift is not permitted. Every value keeps the spreadsheet cell
//! it came from, so a plan can quote the chart row it relied on.
//!
//! **Rule** ([`ChartConfig::lookup`]), as charts state it: never interpolate. For
//! a radius between two listed radii use the row of the next larger radius; for a
//! boom between two listed lengths use the column of the next longer boom, or the
//! next shorter boom's where that is less (a chart may list more at a radius for a
//! longer boom, whose sections telescope differently; a boom in between is then
//! given the less of the two). A radius or boom outside the listed range, or a
//! blank cell, is not permitted. The charts stage refuses grids whose capacity
//! rises with radius, so the next larger radius is always the smaller (safe) value.

use serde::{Deserialize, Serialize};
use std::path::Path;

const TOL_M: f64 = 1e-6;

/// The most cells (booms x radii, blank cells included) a capacity table's
/// grids may hold in all. A real crane's charts hold a few thousand, and a
/// chart workbook no more than this (the charts stage's reader refuses more
/// cells); the bound keeps a damaged or hostile `capacity.csv`, each of whose
/// rows may bring a boom and a radius of its own, from asking for rows²
/// cells when its grids are rebuilt.
pub const MAX_GRID_CELLS: u64 = 2_000_000;

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ChartCell {
    pub capacity_kg: f64,
    /// Where the value was read, e.g. `chart.xlsx [Main boom 26.5t!D14]`.
    pub cell: String,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ChartConfig {
    /// Configuration name as the chart states it (counterweight, outriggers, sector).
    pub name: String,
    /// Ascending boom lengths (m), one per column.
    pub boom_lengths_m: Vec<f64>,
    /// Ascending radii (m), one per row.
    pub radii_m: Vec<f64>,
    /// Row-major `radii x booms`; `None` where the chart permits no lift.
    pub cells: Vec<Option<ChartCell>>,
}

/// A value a chart sheet states in words beside its grid (a wind speed in
/// m/s, a counterweight in kg), the cell it is in (`Sheet!A3`) and the
/// cell's text.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StatedOnChart {
    pub value: f64,
    pub cell: String,
    pub text: String,
}

/// A capacity read from the chart, with the row and column that gave it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Capacity {
    pub capacity_kg: f64,
    /// Chart column (boom length) used, m.
    pub boom_m: f64,
    /// Chart row (radius) used, m.
    pub radius_m: f64,
    pub cell: String,
}

#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CapacityError {
    #[error("chart has no configuration '{0}' (it has: {1})")]
    UnknownConfig(String, String),
    #[error("boom length {boom_m:.2} m is longer than the chart's longest boom {max_m:.2} m")]
    BoomBeyondChart { boom_m: f64, max_m: f64 },
    #[error("boom length {boom_m:.2} m is shorter than the chart's shortest boom {min_m:.2} m")]
    BoomBelowChart { boom_m: f64, min_m: f64 },
    #[error("radius {radius_m:.2} m is less than the chart's smallest radius {min_m:.2} m")]
    RadiusBelowChart { radius_m: f64, min_m: f64 },
    #[error("radius {radius_m:.2} m is beyond the chart's largest radius {max_m:.2} m")]
    RadiusBeyondChart { radius_m: f64, max_m: f64 },
    #[error("the chart permits no lift at radius {radius_m:.2} m with boom {boom_m:.2} m (blank cell {cell})")]
    NotPermitted { boom_m: f64, radius_m: f64, cell: String },
    #[error(
        "the chart lists capacities by boom length ({min_m:.2} to {max_m:.2} m), which a tower crane does not have: name a chart configuration of one capacity column, for its jib"
    )]
    ByBoomForTower { min_m: f64, max_m: f64 },
}

impl ChartConfig {
    pub fn cell(&self, row: usize, col: usize) -> Option<&ChartCell> {
        self.cells.get(row * self.boom_lengths_m.len() + col).and_then(|c| c.as_ref())
    }

    /// Whether the chart has one capacity column that holds for any boom (a tower
    /// crane's jib, or a chart that lists no boom lengths); stored as boom 0.
    pub fn boom_independent(&self) -> bool {
        self.boom_lengths_m == [0.0]
    }

    /// Capacity at `radius_m` for a boom of `boom_m`, by the rule in the module docs.
    pub fn lookup(&self, boom_m: f64, radius_m: f64) -> Result<Capacity, CapacityError> {
        let boom_m = if self.boom_independent() { 0.0 } else { boom_m };
        let (Some(&bmin), Some(&bmax)) = (self.boom_lengths_m.first(), self.boom_lengths_m.last()) else {
            return Err(CapacityError::BoomBeyondChart { boom_m, max_m: 0.0 });
        };
        let (Some(&rmin), Some(&rmax)) = (self.radii_m.first(), self.radii_m.last()) else {
            return Err(CapacityError::RadiusBeyondChart { radius_m, max_m: 0.0 });
        };
        if !(boom_m <= bmax + TOL_M) {
            return Err(CapacityError::BoomBeyondChart { boom_m, max_m: bmax });
        }
        if boom_m < bmin - TOL_M {
            return Err(CapacityError::BoomBelowChart { boom_m, min_m: bmin });
        }
        if !(radius_m <= rmax + TOL_M) {
            return Err(CapacityError::RadiusBeyondChart { radius_m, max_m: rmax });
        }
        if radius_m < rmin - TOL_M {
            return Err(CapacityError::RadiusBelowChart { radius_m, min_m: rmin });
        }
        let col =
            self.boom_lengths_m.iter().position(|&b| b >= boom_m - TOL_M).unwrap_or(self.boom_lengths_m.len() - 1);
        let row = self.radii_m.iter().position(|&r| r >= radius_m - TOL_M).unwrap_or(self.radii_m.len() - 1);
        // Between two listed booms, the shorter one's cell where it is less.
        let col = match (col.checked_sub(1), self.cell(row, col)) {
            (Some(shorter), Some(longer))
                if self.boom_lengths_m[col] > boom_m + TOL_M
                    && self.cell(row, shorter).is_some_and(|s| s.capacity_kg < longer.capacity_kg) =>
            {
                shorter
            }
            _ => col,
        };
        match self.cell(row, col) {
            Some(c) => Ok(Capacity {
                capacity_kg: c.capacity_kg,
                boom_m: self.boom_lengths_m[col],
                radius_m: self.radii_m[row],
                cell: c.cell.clone(),
            }),
            None => Err(CapacityError::NotPermitted {
                boom_m: self.boom_lengths_m[col],
                radius_m: self.radii_m[row],
                cell: format!("row {:.2} m, column {:.2} m", self.radii_m[row], self.boom_lengths_m[col]),
            }),
        }
    }
}

/// Every configuration of one crane's load chart.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct CapacityTable {
    pub configs: Vec<ChartConfig>,
}

/// One row of `capacity.csv`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CapacityRow {
    pub config: String,
    pub boom_m: f64,
    pub radius_m: f64,
    pub capacity_kg: f64,
    pub cell: String,
}

impl CapacityTable {
    pub fn config(&self, name: &str) -> Result<&ChartConfig, CapacityError> {
        self.configs.iter().find(|c| c.name == name).ok_or_else(|| {
            CapacityError::UnknownConfig(
                name.to_string(),
                self.configs.iter().map(|c| format!("'{}'", c.name)).collect::<Vec<_>>().join(", "),
            )
        })
    }

    /// The long table: one row per permitted cell, in chart order.
    pub fn rows(&self) -> Vec<CapacityRow> {
        let mut out = Vec::new();
        for c in &self.configs {
            for (ri, r) in c.radii_m.iter().enumerate() {
                for (bi, b) in c.boom_lengths_m.iter().enumerate() {
                    if let Some(cell) = c.cell(ri, bi) {
                        out.push(CapacityRow {
                            config: c.name.clone(),
                            boom_m: *b,
                            radius_m: *r,
                            capacity_kg: cell.capacity_kg,
                            cell: cell.cell.clone(),
                        });
                    }
                }
            }
        }
        out
    }

    /// Rebuilds the grids from long rows (as read back from `capacity.csv`).
    ///
    /// Rows are grouped by configuration in one pass, and each row finds its
    /// boom and radius by binary search: asking every row for each
    /// configuration, and searching the booms and radii row by row, cost
    /// configurations x rows (2,000 configurations of 100 cells took 3.2 s,
    /// in the plan and docs stages each). The tests keep that as the
    /// reference. Rows whose grids would hold more than [`MAX_GRID_CELLS`]
    /// cells in all are refused before any grid is made.
    pub fn from_rows(rows: &[CapacityRow]) -> Result<CapacityTable, String> {
        let mut t = CapacityTable::default();
        let mut index: std::collections::HashMap<&str, usize> = std::collections::HashMap::new();
        let mut by_config: Vec<Vec<&CapacityRow>> = Vec::new();
        for r in rows {
            let k = *index.entry(r.config.as_str()).or_insert_with(|| {
                t.configs.push(ChartConfig {
                    name: r.config.clone(),
                    boom_lengths_m: vec![],
                    radii_m: vec![],
                    cells: vec![],
                });
                by_config.push(Vec::new());
                by_config.len() - 1
            });
            by_config[k].push(r);
        }
        // The first value equal to `v` (as `==` has it, so -0 finds 0): a
        // binary search where the values are ordered, else a walk.
        fn index_of(values: &[f64], v: f64) -> usize {
            let i = values.partition_point(|&x| x < v);
            if values.get(i) == Some(&v) { i } else { values.iter().position(|&x| x == v).unwrap_or(0) }
        }
        for (c, mine) in t.configs.iter_mut().zip(&by_config) {
            (c.boom_lengths_m, c.radii_m) = axes_of(mine);
        }
        t.check_grid_cells()?;
        for (c, mine) in t.configs.iter_mut().zip(by_config) {
            c.cells = cells_of(&mine, &c.boom_lengths_m, &c.radii_m, index_of);
        }
        Ok(t)
    }

    pub fn write_csv(&self, path: &Path) -> std::io::Result<()> {
        let mut w = csv::Writer::from_writer(Vec::new());
        for r in self.rows() {
            w.serialize(&r).map_err(std::io::Error::other)?;
        }
        let bytes = w.into_inner().map_err(|e| std::io::Error::other(e.to_string()))?;
        crate::artifact::write_atomic(path, &bytes)
    }

    pub fn read_csv(path: &Path) -> Result<CapacityTable, String> {
        let bytes = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
        Self::from_csv_bytes(path, &bytes)
    }

    /// [`CapacityTable::read_csv`] of the bytes read from `path` (which
    /// names the file in errors): each row's numbers finite and not
    /// negative, and the grids they make within [`MAX_GRID_CELLS`].
    pub fn from_csv_bytes(path: &Path, bytes: &[u8]) -> Result<CapacityTable, String> {
        let mut r = csv::Reader::from_reader(bytes);
        let headers = r.headers().map_err(|e| format!("{}: {e}", path.display()))?.clone();
        let mut rows = Vec::new();
        for rec in r.records() {
            let rec = rec.map_err(|e| format!("{}: {e}", path.display()))?;
            let line = rec.position().map_or(0, |p| p.line());
            let row: CapacityRow =
                rec.deserialize(Some(&headers)).map_err(|e| format!("{}:{line}: {e}", path.display()))?;
            if ![row.capacity_kg, row.radius_m, row.boom_m].iter().all(|v| v.is_finite() && *v >= 0.0) {
                return Err(format!(
                    "{}:{line}: capacity, radius and boom must be finite and non-negative",
                    path.display()
                ));
            }
            rows.push(row);
        }
        CapacityTable::from_rows(&rows).map_err(|e| format!("{}: {e}", path.display()))
    }

    /// The cells of every configuration's grid, booms x radii, blank cells
    /// included (saturating).
    pub fn grid_cells(&self) -> u64 {
        self.configs.iter().fold(0u64, |sum, c| {
            sum.saturating_add((c.boom_lengths_m.len() as u64).saturating_mul(c.radii_m.len() as u64))
        })
    }

    /// Refuses a table whose grids hold more than [`MAX_GRID_CELLS`] cells
    /// in all, which could not be read back from its `capacity.csv`.
    pub fn check_grid_cells(&self) -> Result<(), String> {
        let cells = self.grid_cells();
        if cells > MAX_GRID_CELLS {
            return Err(format!(
                "its grids hold {cells} cells in all (booms x radii, blank cells included), more than the \
                 {MAX_GRID_CELLS} liftplan takes; a crane's load charts never hold so many"
            ));
        }
        Ok(())
    }
}

/// One configuration's booms and radii from its rows: sorted, each once.
fn axes_of(rows: &[&CapacityRow]) -> (Vec<f64>, Vec<f64>) {
    let mut booms: Vec<f64> = rows.iter().map(|r| r.boom_m).collect();
    let mut radii: Vec<f64> = rows.iter().map(|r| r.radius_m).collect();
    booms.sort_by(f64::total_cmp);
    booms.dedup();
    radii.sort_by(f64::total_cmp);
    radii.dedup();
    (booms, radii)
}

/// One configuration's cells, radius-major, from its rows over its
/// [`axes_of`]; `index_of` finds a value's place in the booms or radii. A
/// later row of the same cell replaces an earlier one.
fn cells_of(
    rows: &[&CapacityRow],
    booms: &[f64],
    radii: &[f64],
    index_of: impl Fn(&[f64], f64) -> usize,
) -> Vec<Option<ChartCell>> {
    let mut cells = vec![None; booms.len() * radii.len()];
    for r in rows {
        let (bi, ri) = (index_of(booms, r.boom_m), index_of(radii, r.radius_m));
        cells[ri * booms.len() + bi] = Some(ChartCell { capacity_kg: r.capacity_kg, cell: r.cell.clone() });
    }
    cells
}

#[cfg(test)]
mod tests {
    use super::*;

    /// How `from_rows` rebuilt the grids before it grouped the rows in one
    /// pass: every row asked for each configuration, booms and radii searched
    /// row by row.
    fn from_rows_by_search(rows: &[CapacityRow]) -> CapacityTable {
        let mut t = CapacityTable::default();
        for r in rows {
            if !t.configs.iter().any(|c| c.name == r.config) {
                t.configs.push(ChartConfig {
                    name: r.config.clone(),
                    boom_lengths_m: vec![],
                    radii_m: vec![],
                    cells: vec![],
                });
            }
        }
        for c in &mut t.configs {
            let mine: Vec<&CapacityRow> = rows.iter().filter(|r| r.config == c.name).collect();
            (c.boom_lengths_m, c.radii_m) = axes_of(&mine);
            c.cells = cells_of(&mine, &c.boom_lengths_m, &c.radii_m, |values, v| {
                values.iter().position(|&x| x == v).unwrap_or(0)
            });
        }
        t
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(500))]
        /// Random rows: configurations interleaved, repeated cells, both
        /// signed zeros, NaN and infinities (which `read_csv` refuses, but
        /// `from_rows` is public) give the reference's table.
        #[test]
        fn rows_rebuild_the_reference_s_table(
            rows in proptest::collection::vec((0u8..4, 0usize..7, 0usize..7, 0u32..5000), 0..60),
        ) {
            let values = [0.0, -0.0, 12.5, 3.0, f64::NAN, -f64::NAN, f64::INFINITY];
            let rows: Vec<CapacityRow> = rows
                .iter()
                .map(|&(c, b, r, kg)| CapacityRow {
                    config: format!("C{c}"),
                    boom_m: values[b],
                    radius_m: values[r],
                    capacity_kg: kg as f64,
                    cell: format!("S!B{kg}"),
                })
                .collect();
            let (got, want) = (CapacityTable::from_rows(&rows).unwrap(), from_rows_by_search(&rows));
            // NaN != NaN: compare the tables' text.
            proptest::prop_assert_eq!(format!("{got:?}"), format!("{want:?}"));
        }
    }

    fn chart() -> ChartConfig {
        // Radii 3, 4, 6 m; booms 12, 20 m. Blank at 3 m with the 20 m boom.
        let c = |v: f64, r: &str| Some(ChartCell { capacity_kg: v, cell: r.to_string() });
        ChartConfig {
            name: "CW 26.5t 360".into(),
            boom_lengths_m: vec![12.0, 20.0],
            radii_m: vec![3.0, 4.0, 6.0],
            cells: vec![c(50000.0, "B2"), None, c(40000.0, "B3"), c(35000.0, "C3"), c(30000.0, "B4"), c(28000.0, "C4")],
        }
    }

    #[test]
    fn exact_cells() {
        let k = chart().lookup(12.0, 4.0).unwrap();
        assert_eq!((k.capacity_kg, k.cell.as_str()), (40000.0, "B3"));
    }

    #[test]
    fn between_radii_takes_next_larger_radius() {
        let k = chart().lookup(12.0, 4.5).unwrap();
        assert_eq!(k.capacity_kg, 30000.0);
        assert_eq!(k.radius_m, 6.0);
    }

    #[test]
    fn between_booms_takes_next_longer_boom() {
        let k = chart().lookup(15.0, 4.0).unwrap();
        assert_eq!(k.capacity_kg, 35000.0);
        assert_eq!(k.boom_m, 20.0);
    }

    /// Where a chart lists more at a radius for the longer boom, a boom in
    /// between gets the shorter boom's (less) value; a listed boom its own.
    #[test]
    fn between_booms_never_more_than_the_shorter_boom() {
        let mut ch = chart();
        ch.cells[3] = Some(ChartCell { capacity_kg: 45000.0, cell: "C3".into() });
        let k = ch.lookup(15.0, 4.0).unwrap();
        assert_eq!((k.capacity_kg, k.boom_m, k.cell.as_str()), (40000.0, 12.0, "B3"));
        assert_eq!(ch.lookup(20.0, 4.0).unwrap().capacity_kg, 45000.0);
        // A blank for the shorter boom (out of its reach) leaves the longer's.
        assert_eq!(ch.lookup(15.0, 3.0).err().map(|_| ()), Some(()));
        ch.cells[0] = None;
        ch.cells[1] = Some(ChartCell { capacity_kg: 20000.0, cell: "C2".into() });
        assert_eq!(ch.lookup(15.0, 3.0).unwrap().capacity_kg, 20000.0);
    }

    #[test]
    fn at_and_beyond_last_row() {
        assert_eq!(chart().lookup(20.0, 6.0).unwrap().capacity_kg, 28000.0);
        assert!(matches!(chart().lookup(20.0, 6.01), Err(CapacityError::RadiusBeyondChart { .. })));
        assert!(matches!(chart().lookup(20.5, 5.0), Err(CapacityError::BoomBeyondChart { .. })));
        assert!(matches!(chart().lookup(12.0, 2.5), Err(CapacityError::RadiusBelowChart { .. })));
        assert!(matches!(chart().lookup(11.0, 4.0), Err(CapacityError::BoomBelowChart { .. })));
    }

    #[test]
    fn blank_cell_not_permitted() {
        assert!(matches!(chart().lookup(14.0, 3.0), Err(CapacityError::NotPermitted { .. })));
        assert!(chart().lookup(f64::NAN, 3.0).is_err());
    }

    #[test]
    fn csv_roundtrip() {
        let t = CapacityTable { configs: vec![chart()] };
        let d = tempfile::tempdir().unwrap();
        let p = d.path().join("capacity.csv");
        t.write_csv(&p).unwrap();
        let back = CapacityTable::read_csv(&p).unwrap();
        assert_eq!(back, t);
    }

    fn csv_of(rows: impl Iterator<Item = (f64, f64)>) -> Vec<u8> {
        let mut text = String::from("config,boom_m,radius_m,capacity_kg,cell\n");
        for (boom, radius) in rows {
            text.push_str(&format!("C,{boom},{radius},1000,S!B2\n"));
        }
        text.into_bytes()
    }

    /// Rows that each bring a boom or a radius of their own make grids of
    /// rows² cells; past [`MAX_GRID_CELLS`] the file is refused before any
    /// grid is made.
    #[test]
    fn a_capacity_csv_whose_grids_would_be_too_large_is_refused() {
        let p = Path::new("out/capacity.csv");
        // 1,000 booms x 2,000 radii: the bound, taken.
        let at_bound = csv_of((0..2000).map(|i| ((i % 1000) as f64, i as f64)));
        let t = CapacityTable::from_csv_bytes(p, &at_bound).unwrap();
        assert_eq!(t.grid_cells(), MAX_GRID_CELLS);
        assert!(t.check_grid_cells().is_ok());
        // One radius more: 2,001,000 cells.
        let over = csv_of((0..2001).map(|i| ((i % 1000) as f64, i as f64)));
        let e = CapacityTable::from_csv_bytes(p, &over).unwrap_err();
        assert!(e.starts_with("out/capacity.csv: its grids hold 2001000 cells"), "{e}");
        // 100,000 rows, each its own boom and radius: 10^10 cells asked for
        // without the bound.
        let hostile = csv_of((0..100_000).map(|i| (i as f64, i as f64)));
        let e = CapacityTable::from_csv_bytes(p, &hostile).unwrap_err();
        assert!(e.contains("10000000000 cells"), "{e}");
    }

    /// A row's numbers are checked where the file has it, a cell's text
    /// running over two lines counted.
    #[test]
    fn a_negative_radius_or_boom_is_refused_at_its_line() {
        let p = Path::new("capacity.csv");
        let text = "config,boom_m,radius_m,capacity_kg,cell\n\"C\",12,3,1000,\"S!B2\nnote\"\nC,12,-4,900,S!B3\n";
        let e = CapacityTable::from_csv_bytes(p, text.as_bytes()).unwrap_err();
        assert_eq!(e, "capacity.csv:4: capacity, radius and boom must be finite and non-negative");
        let text = "config,boom_m,radius_m,capacity_kg,cell\nC,-12,3,1000,S!B2\n";
        let e = CapacityTable::from_csv_bytes(p, text.as_bytes()).unwrap_err();
        assert_eq!(e, "capacity.csv:2: capacity, radius and boom must be finite and non-negative");
        let text = "config,boom_m,radius_m,capacity_kg,cell\nC,12,three,1000,S!B2\n";
        let e = CapacityTable::from_csv_bytes(p, text.as_bytes()).unwrap_err();
        assert!(e.starts_with("capacity.csv:2: "), "{e}");
    }
}
