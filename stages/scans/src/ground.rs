//! Ground extraction with the Simple Morphological Filter (SMRF; Pingel, Clarke &
//! McBride 2013, "An improved simple morphological filter for the terrain
//! classification of airborne LIDAR data").
//!
//! 1. minimum surface on a grid of `cell_m`, empty cells filled from neighbours;
//! 2. progressive morphological opening with windows growing to `window_m`; a cell
//!    rising above the opened surface by more than `slope * window` is an object;
//! 3. the ground surface is re-interpolated from the non-object cells;
//! 4. a point is ground (LAS class 2) when it lies within
//!    `threshold_m + scalar * local slope * cell_m` of that surface.
//!
//! The result also gives a ground-height grid (ESRI ASCII, `ground.asc`) for the
//! crane set-up check; cells without any measurement are NODATA.

use liftplan_core::artifact::write_atomic;
use liftplan_core::cloud::{PointCloud, class};
use rayon::prelude::*;
use std::path::Path;

#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct GroundSettings {
    pub enabled: bool,
    /// Grid cell (m).
    pub cell_m: f64,
    /// Largest terrain slope expected (rise over run).
    pub slope: f64,
    /// Largest object footprint to remove (m).
    pub window_m: f64,
    /// Height above the ground surface still counted as ground (m).
    pub threshold_m: f64,
    /// Extra tolerance per unit of local slope.
    pub scalar: f64,
}

impl Default for GroundSettings {
    fn default() -> Self {
        GroundSettings { enabled: true, cell_m: 1.0, slope: 0.15, window_m: 18.0, threshold_m: 0.5, scalar: 1.25 }
    }
}

impl GroundSettings {
    pub fn check(&self) -> Result<(), String> {
        for (n, v) in [
            ("cell_m", self.cell_m),
            ("slope", self.slope),
            ("window_m", self.window_m),
            ("threshold_m", self.threshold_m),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(format!("ground.{n} must be positive, found {v}"));
            }
        }
        if !(self.scalar.is_finite() && self.scalar >= 0.0) {
            return Err("ground.scalar must be >= 0".into());
        }
        Ok(())
    }
}

/// A regular grid of heights in the site frame; `NaN` where unknown.
#[derive(Debug, Clone, PartialEq)]
pub struct HeightGrid {
    pub x0: f64,
    pub y0: f64,
    pub cell_m: f64,
    pub nx: usize,
    pub ny: usize,
    /// Row-major, row 0 at `y0` (south).
    pub z: Vec<f64>,
}

impl HeightGrid {
    fn at(&self, i: usize, j: usize) -> f64 {
        self.z[j * self.nx + i]
    }

    /// Bilinear height at (x, y), or `None` outside the grid.
    pub fn sample(&self, x: f64, y: f64) -> Option<f64> {
        let fx = (x - self.x0) / self.cell_m - 0.5;
        let fy = (y - self.y0) / self.cell_m - 0.5;
        if !(fx >= -0.5 && fy >= -0.5 && fx <= self.nx as f64 - 0.5 && fy <= self.ny as f64 - 0.5) {
            return None;
        }
        let i0 = fx.floor().clamp(0.0, (self.nx - 1) as f64) as usize;
        let j0 = fy.floor().clamp(0.0, (self.ny - 1) as f64) as usize;
        let i1 = (i0 + 1).min(self.nx - 1);
        let j1 = (j0 + 1).min(self.ny - 1);
        let tx = (fx - i0 as f64).clamp(0.0, 1.0);
        let ty = (fy - j0 as f64).clamp(0.0, 1.0);
        let v = self.at(i0, j0) * (1.0 - tx) * (1.0 - ty)
            + self.at(i1, j0) * tx * (1.0 - ty)
            + self.at(i0, j1) * (1.0 - tx) * ty
            + self.at(i1, j1) * tx * ty;
        v.is_finite().then_some(v)
    }

    /// ESRI ASCII grid (north row first), NODATA = -9999.
    pub fn write_asc(&self, path: &Path) -> std::io::Result<()> {
        let mut s = String::new();
        s.push_str(&format!(
            "ncols {}\nnrows {}\nxllcorner {}\nyllcorner {}\ncellsize {}\nNODATA_value -9999\n",
            self.nx, self.ny, self.x0, self.y0, self.cell_m
        ));
        for j in (0..self.ny).rev() {
            let row: Vec<String> = (0..self.nx)
                .map(|i| {
                    let v = self.at(i, j);
                    if v.is_finite() { format!("{v:.3}") } else { "-9999".into() }
                })
                .collect();
            s.push_str(&row.join(" "));
            s.push('\n');
        }
        write_atomic(path, s.as_bytes())
    }

    /// Reads what [`HeightGrid::write_asc`] writes (any ESRI ASCII grid).
    pub fn read_asc(path: &Path, text: &str) -> Result<HeightGrid, String> {
        let mut lines = text.lines().enumerate();
        let mut hdr = std::collections::HashMap::new();
        for _ in 0..6 {
            let (n, l) = lines.next().ok_or_else(|| format!("{}: header ends early", path.display()))?;
            let mut it = l.split_whitespace();
            let (Some(k), Some(v)) = (it.next(), it.next()) else {
                return Err(format!("{}:{}: expected 'key value'", path.display(), n + 1));
            };
            let v: f64 = v.parse().map_err(|_| format!("{}:{}: '{v}' is not a number", path.display(), n + 1))?;
            hdr.insert(k.to_ascii_lowercase(), v);
        }
        let get = |k: &str| hdr.get(k).copied().ok_or_else(|| format!("{}: header lacks {k}", path.display()));
        let (nx, ny) = (get("ncols")? as usize, get("nrows")? as usize);
        if nx == 0 || ny == 0 || nx.saturating_mul(ny) > text.len() {
            return Err(format!("{}: grid size {nx} x {ny} does not match the file", path.display()));
        }
        let nodata = get("nodata_value").unwrap_or(-9999.0);
        let mut z = vec![f64::NAN; nx * ny];
        for r in 0..ny {
            let (n, l) = lines.next().ok_or_else(|| format!("{}: expected {ny} rows, found {r}", path.display()))?;
            let vals: Vec<&str> = l.split_whitespace().collect();
            if vals.len() != nx {
                return Err(format!("{}:{}: expected {nx} values, found {}", path.display(), n + 1, vals.len()));
            }
            for (i, v) in vals.iter().enumerate() {
                let v: f64 = v.parse().map_err(|_| format!("{}:{}: '{v}' is not a number", path.display(), n + 1))?;
                z[(ny - 1 - r) * nx + i] = if v == nodata { f64::NAN } else { v };
            }
        }
        Ok(HeightGrid { x0: get("xllcorner")?, y0: get("yllcorner")?, cell_m: get("cellsize")?, nx, ny, z })
    }
}

/// The 8 neighbours of cell `k` of an `nx` x `ny` grid that lie inside it, row
/// by row from the south-west (the order their heights are summed in).
fn neighbours(k: usize, nx: usize, ny: usize) -> impl Iterator<Item = usize> {
    let (i, j) = ((k % nx) as i64, (k / nx) as i64);
    (-1i64..=1).flat_map(move |dj| (-1i64..=1).map(move |di| (i + di, j + dj))).filter_map(move |(a, b)| {
        let inside = a >= 0 && b >= 0 && a < nx as i64 && b < ny as i64 && (a, b) != (i, j);
        inside.then(|| b as usize * nx + a as usize)
    })
}

/// Fills the empty (non-finite) cells ring by ring: each ring is the empty
/// cells next to a filled one, and takes the mean of those neighbours as they
/// were before the ring. Cells no ring reaches (a grid without any height)
/// get the lowest height, or 0. Only the ring's cells are visited each time,
/// so the cost is the grid's size, however far apart the measured patches lie
/// (with a pass over the whole grid per ring, the classification of two
/// patches 1.5 km apart in `examples/bench_ground` took 5.2 s; 0.46 s now).
fn fill_holes(z: &mut [f64], nx: usize, ny: usize) {
    let mut queued: Vec<bool> = z.iter().map(|v| v.is_finite()).collect();
    let mut ring: Vec<usize> =
        (0..z.len()).filter(|&k| !queued[k] && neighbours(k, nx, ny).any(|n| z[n].is_finite())).collect();
    for &k in &ring {
        queued[k] = true;
    }
    while !ring.is_empty() {
        let filled: Vec<f64> = ring
            .par_iter()
            .map(|&k| {
                let (mut s, mut c) = (0.0, 0.0);
                for v in neighbours(k, nx, ny).map(|n| z[n]).filter(|v| v.is_finite()) {
                    s += v;
                    c += 1.0;
                }
                s / c
            })
            .collect();
        for (&k, v) in ring.iter().zip(filled) {
            z[k] = v;
        }
        let mut next = Vec::new();
        for &k in &ring {
            for n in neighbours(k, nx, ny) {
                if !queued[n] {
                    queued[n] = true;
                    next.push(n);
                }
            }
        }
        ring = next;
    }
    let m = z.iter().copied().filter(|v| v.is_finite()).fold(f64::INFINITY, f64::min);
    for v in z.iter_mut() {
        if !v.is_finite() {
            *v = if m.is_finite() { m } else { 0.0 };
        }
    }
}

/// Buffers the morphological filters reuse from one window to the next (a
/// grid's worth each, which the system would otherwise hand out and zero
/// again for every filter).
#[derive(Default)]
struct Scratch {
    across: Vec<f64>,
    strips: Vec<Vec<f64>>,
}

/// Square-window min (erode) or max (dilate) filter of radius `r` cells of the
/// `nx` x `ny` grid `z` into `out`, separable, the window cut off at the
/// grid's edges.
fn morph(z: &[f64], out: &mut [f64], nx: usize, ny: usize, r: usize, max: bool, scratch: &mut Scratch) {
    scratch.across.resize(z.len(), 0.0);
    if max {
        let window = Window { r, pick: f64::max, never: f64::NEG_INFINITY };
        filter_rows(z, &mut scratch.across, nx, &window);
        filter_columns(&scratch.across, out, nx, ny, &window, &mut scratch.strips);
    } else {
        let window = Window { r, pick: f64::min, never: f64::INFINITY };
        filter_rows(z, &mut scratch.across, nx, &window);
        filter_columns(&scratch.across, out, nx, ny, &window, &mut scratch.strips);
    }
}

/// A filter's window: `r` cells each way, and which extreme it takes
/// (`pick`: `f64::min` or `f64::max`; `never` never wins).
struct Window<P> {
    r: usize,
    pick: P,
    never: f64,
}

/// The extreme of each row's cells within the window of each cell, rows of
/// `nx` cells, into `out`.
/// Rows are taken eight at a time, laid side by side (cell `i` of the eight
/// rows one after another), so that [`running_extremes`] steps along eight
/// independent runs at once instead of waiting on one.
fn filter_rows<P: Fn(f64, f64) -> f64 + Copy + Sync + Send>(z: &[f64], out: &mut [f64], nx: usize, window: &Window<P>) {
    const ROWS: usize = 8;
    let Window { r, pick, never } = *window;
    let steps = nx + 2 * r;
    out.par_chunks_mut(ROWS * nx).zip(z.par_chunks(ROWS * nx)).for_each_init(Vec::new, |runs, (out, lines)| {
        let width = lines.len() / nx;
        runs.clear();
        runs.resize(r * width, never);
        for i in 0..nx {
            runs.extend((0..width).map(|k| lines[k * nx + i]));
        }
        runs.resize(steps * width, never);
        running_extremes(runs, steps, width, r, pick);
        let (ahead, behind) = runs.split_at(steps * width);
        for (k, out) in out.chunks_exact_mut(nx).enumerate() {
            for (i, o) in out.iter_mut().enumerate() {
                *o = pick(behind[i * width + k], ahead[(i + 2 * r) * width + k]);
            }
        }
    });
}

/// [`filter_rows`] down the columns of an `nx` x `ny` grid, on strips of 64
/// columns side by side: each step of the running extremes is one row of the
/// strip, read in order. `strips` holds each strip's runs.
fn filter_columns<P: Fn(f64, f64) -> f64 + Copy + Sync + Send>(
    z: &[f64],
    out: &mut [f64],
    nx: usize,
    ny: usize,
    window: &Window<P>,
    strips: &mut Vec<Vec<f64>>,
) {
    const STRIP: usize = 64;
    let Window { r, pick, never } = *window;
    let steps = ny + 2 * r;
    let width = |s: usize| ((s + 1) * STRIP).min(nx) - s * STRIP;
    strips.resize_with(nx.div_ceil(STRIP), Vec::new);
    strips.par_iter_mut().enumerate().for_each(|(s, runs)| {
        let (c0, width) = (s * STRIP, width(s));
        runs.clear();
        runs.resize(r * width, never);
        for row in z.chunks_exact(nx) {
            runs.extend_from_slice(&row[c0..c0 + width]);
        }
        runs.resize(steps * width, never);
        running_extremes(runs, steps, width, r, pick);
    });
    out.par_chunks_mut(nx).enumerate().for_each(|(j, row)| {
        for (s, runs) in strips.iter().enumerate() {
            let width = width(s);
            let (ahead, behind) = runs.split_at(steps * width);
            let (b, a) = (&behind[j * width..][..width], &ahead[(j + 2 * r) * width..][..width]);
            for (o, (b, a)) in row[s * STRIP..][..width].iter_mut().zip(b.iter().zip(a)) {
                *o = pick(*b, *a);
            }
        }
    });
}

/// van Herk's and Gil and Werman's running extremes, on `width` lines side
/// by side: `runs` holds `steps` steps of `width` values (the lines, padded
/// with `r` steps that never win at each end). It is doubled into `ahead`
/// and `behind` (returned as its two halves): cut into blocks of `2r + 1`
/// steps, `ahead` runs each block's extreme from its start and `behind` from
/// its end. A window of `2r + 1` steps spans at most two blocks, so the
/// extreme of steps `i..=i + 2r` (cell `i` of the line, whose padded window
/// that is) is `pick(behind[i], ahead[i + 2r])`. Three passes whatever `r`:
/// walking every window made a filter cost `r` per cell, and the opening
/// `window_m` squared. Exact: it picks among the same values.
fn running_extremes<P: Fn(f64, f64) -> f64>(runs: &mut Vec<f64>, steps: usize, width: usize, r: usize, pick: P) {
    let w = 2 * r + 1;
    runs.extend_from_within(..steps * width);
    let (ahead, behind) = runs.split_at_mut(steps * width);
    for q in 1..steps {
        if q % w != 0 {
            let (before, here) = ahead.split_at_mut(q * width);
            for (h, b) in here[..width].iter_mut().zip(&before[(q - 1) * width..]) {
                *h = pick(*b, *h);
            }
        }
    }
    for q in (0..steps - 1).rev() {
        if q % w != w - 1 {
            let (here, after) = behind.split_at_mut((q + 1) * width);
            for (h, a) in here[q * width..].iter_mut().zip(&after[..width]) {
                *h = pick(*a, *h);
            }
        }
    }
}

/// The most cells a ground grid may have: a 5 km square site at the default
/// 1 m cell; about 1.1 GB while it is classified.
pub const MAX_GROUND_CELLS: usize = 25_000_000;

/// Classifies `cloud` in place (class 2 ground, 1 other) and returns the ground
/// surface grid. A grid over [`MAX_GROUND_CELLS`] is refused, with the extent
/// and the cell that make it.
pub fn classify(cloud: &mut PointCloud, s: &GroundSettings) -> Result<Option<HeightGrid>, String> {
    let bb = cloud.bbox();
    if bb.is_empty() {
        return Ok(None);
    }
    let c = s.cell_m;
    let x0 = (bb.min[0] / c).floor() * c;
    let y0 = (bb.min[1] / c).floor() * c;
    let (cols, rows) = (((bb.max[0] - x0) / c).floor() + 1.0, ((bb.max[1] - y0) / c).floor() + 1.0);
    if cols * rows > MAX_GROUND_CELLS as f64 {
        return Err(format!(
            "ground.cell_m = {c} m over the cloud's {:.0} m x {:.0} m extent needs a ground grid of {cols} x {rows} \
             cells, more than the {MAX_GROUND_CELLS} it may have: raise the cell ([scans.ground] cell_m, or \
             --ground-cell) or leave ground classification out ([scans.ground] enabled = false, or --no-ground); a \
             few stray points far from the site also stretch the extent",
            bb.max[0] - bb.min[0],
            bb.max[1] - bb.min[1]
        ));
    }
    let (nx, ny) = (cols as usize, rows as usize);
    let cell_of = |p: &[f64; 3]| -> Option<usize> {
        let i = ((p[0] - x0) / c).floor();
        let j = ((p[1] - y0) / c).floor();
        (i >= 0.0 && j >= 0.0 && (i as usize) < nx && (j as usize) < ny).then(|| j as usize * nx + i as usize)
    };
    let mut zmin = vec![f64::NAN; nx * ny];
    for p in &cloud.xyz {
        if let Some(k) = cell_of(p)
            && !(zmin[k] <= p[2])
        {
            zmin[k] = p[2];
        }
    }
    let measured: Vec<bool> = zmin.iter().map(|v| v.is_finite()).collect();
    // The surface being opened, window by window: first the lowest points,
    // holes filled.
    let mut cur = zmin.clone();
    fill_holes(&mut cur, nx, ny);
    let mut object = vec![false; nx * ny];
    // Past the grid's side a window covers the whole grid: the opened
    // surface is flat, and wider windows find nothing more.
    let wmax = ((s.window_m / c).ceil().max(1.0) as usize).min(nx.max(ny));
    let (mut eroded, mut opened) = (vec![0.0; cur.len()], vec![0.0; cur.len()]);
    let mut scratch = Scratch::default();
    for r in 1..=wmax {
        morph(&cur, &mut eroded, nx, ny, r, false, &mut scratch);
        morph(&eroded, &mut opened, nx, ny, r, true, &mut scratch);
        let thr = s.slope * r as f64 * c;
        for k in 0..cur.len() {
            if cur[k] - opened[k] > thr {
                object[k] = true;
            }
        }
        std::mem::swap(&mut cur, &mut opened);
    }
    let mut ground = zmin.clone();
    for k in 0..ground.len() {
        if object[k] {
            ground[k] = f64::NAN;
        }
    }
    fill_holes(&mut ground, nx, ny);
    let grid = HeightGrid { x0, y0, cell_m: c, nx, ny, z: ground };
    let slope_at = |i: usize, j: usize| -> f64 {
        let z = |a: usize, b: usize| grid.at(a.min(nx - 1), b.min(ny - 1));
        let gx = (z(i + 1, j) - z(i.saturating_sub(1), j)) / (2.0 * c);
        let gy = (z(i, j + 1) - z(i, j.saturating_sub(1))) / (2.0 * c);
        (gx * gx + gy * gy).sqrt()
    };
    cloud.class = cloud
        .xyz
        .iter()
        .map(|p| {
            let (Some(k), Some(g)) = (cell_of(p), grid.sample(p[0], p[1])) else {
                return class::UNCLASSIFIED;
            };
            let tol = s.threshold_m + s.scalar * slope_at(k % nx, k / nx) * c;
            if (p[2] - g).abs() <= tol { class::GROUND } else { class::UNCLASSIFIED }
        })
        .collect();
    let mut out = grid;
    for (k, m) in measured.iter().enumerate() {
        if !m {
            out.z[k] = f64::NAN;
        }
    }
    Ok(Some(out))
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The filters as first written, walking every window and passing over
    /// the whole grid per ring: the references the fast ones must equal, bit
    /// for bit.
    fn walked_morph(z: &[f64], nx: usize, ny: usize, r: usize, max: bool) -> Vec<f64> {
        let pick = |a: f64, b: f64| if max { a.max(b) } else { a.min(b) };
        let at = |z: &[f64], i: usize, j: usize| z[j * nx + i];
        let across: Vec<f64> = (0..nx * ny)
            .map(|k| (k % nx, k / nx))
            .map(|(i, j)| (i.saturating_sub(r)..=(i + r).min(nx - 1)).fold(at(z, i, j), |v, a| pick(v, at(z, a, j))))
            .collect();
        (0..nx * ny)
            .map(|k| (k % nx, k / nx))
            .map(|(i, j)| {
                (j.saturating_sub(r)..=(j + r).min(ny - 1)).fold(at(&across, i, j), |v, b| pick(v, at(&across, i, b)))
            })
            .collect()
    }

    fn walked_fill_holes(z: &mut [f64], nx: usize, ny: usize) {
        let mut todo = z.iter().filter(|v| !v.is_finite()).count();
        let mut passes = 0;
        while todo > 0 && passes < nx + ny {
            passes += 1;
            let prev = z.to_vec();
            for k in 0..z.len() {
                if prev[k].is_finite() {
                    continue;
                }
                let (mut s, mut c) = (0.0, 0.0);
                for n in neighbours(k, nx, ny) {
                    if prev[n].is_finite() {
                        s += prev[n];
                        c += 1.0;
                    }
                }
                if c > 0.0 {
                    z[k] = s / c;
                    todo -= 1;
                }
            }
        }
        let m = z.iter().copied().filter(|v| v.is_finite()).fold(f64::INFINITY, f64::min);
        for v in z.iter_mut() {
            if !v.is_finite() {
                *v = if m.is_finite() { m } else { 0.0 };
            }
        }
    }

    /// A grid of up to 40 x 40 cells: heights in steps of 0.25 m (ties are
    /// common, and both signed zeros), some of them empty (NaN).
    fn random_grid() -> impl Strategy<Value = (usize, usize, Vec<f64>)> {
        (1usize..40, 1usize..40, 0u32..100).prop_flat_map(|(nx, ny, empty_pct)| {
            let cell = (0u32..100, -8i32..9).prop_map(move |(e, h)| match h {
                _ if e < empty_pct => f64::NAN,
                0 if e % 2 == 1 => -0.0,
                h => h as f64 * 0.25,
            });
            proptest::collection::vec(cell, nx * ny).prop_map(move |z| (nx, ny, z))
        })
    }

    fn bits(z: &[f64]) -> Vec<u64> {
        z.iter().map(|v| v.to_bits()).collect()
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(500))]
        #[test]
        fn the_running_window_filter_equals_the_walked_one((nx, ny, z) in random_grid(), r in 0usize..45, max: bool) {
            let mut filled = z.clone();
            fill_holes(&mut filled, nx, ny);
            // The scratch buffers as a wider window left them.
            let (mut out, mut scratch) = (vec![0.0; filled.len()], Scratch::default());
            morph(&filled, &mut out, nx, ny, r + 3, !max, &mut scratch);
            morph(&filled, &mut out, nx, ny, r, max, &mut scratch);
            prop_assert_eq!(out, walked_morph(&filled, nx, ny, r, max));
        }

        #[test]
        fn ring_by_ring_filling_equals_whole_grid_passes((nx, ny, z) in random_grid()) {
            let (mut fast, mut walked) = (z.clone(), z);
            fill_holes(&mut fast, nx, ny);
            walked_fill_holes(&mut walked, nx, ny);
            prop_assert_eq!(bits(&fast), bits(&walked));
        }
    }

    /// A cloud whose extent needs more ground cells than allowed is refused,
    /// naming the cell and the extent, instead of classifying only part of it.
    #[test]
    fn a_ground_grid_too_large_is_refused() {
        let xyz = vec![[0.0, 0.0, 0.0], [6000.0, 5000.0, 1.0]];
        let mut c = PointCloud { xyz, ..Default::default() };
        let e = classify(&mut c, &GroundSettings::default()).unwrap_err();
        assert!(
            e.starts_with(
                "ground.cell_m = 1 m over the cloud's 6000 m x 5000 m extent needs a ground grid of 6001 x 5001 cells"
            ),
            "{e}"
        );
    }

    #[test]
    fn separates_box_from_sloped_ground() {
        let mut xyz = Vec::new();
        for i in 0..120 {
            for j in 0..120 {
                let (x, y) = (i as f64 * 0.5, j as f64 * 0.5);
                xyz.push([x, y, 0.05 * x]);
            }
        }
        let n_ground = xyz.len();
        for i in 0..30 {
            for j in 0..30 {
                xyz.push([20.0 + i as f64 * 0.3, 20.0 + j as f64 * 0.3, 1.0 + 6.0]);
            }
        }
        let mut c = PointCloud { xyz, ..Default::default() };
        let g = classify(&mut c, &GroundSettings::default()).unwrap().unwrap();
        let ground_ok = c.class[..n_ground].iter().filter(|&&k| k == class::GROUND).count();
        let roof_wrong = c.class[n_ground..].iter().filter(|&&k| k == class::GROUND).count();
        assert!(ground_ok as f64 > 0.97 * n_ground as f64, "{ground_ok} of {n_ground}");
        assert_eq!(roof_wrong, 0);
        let z = g.sample(25.0, 25.0).unwrap();
        assert!((z - 1.25).abs() < 0.3, "{z}");
        let d = tempfile::tempdir().unwrap();
        let p = d.path().join("g.asc");
        g.write_asc(&p).unwrap();
        let back = HeightGrid::read_asc(&p, &std::fs::read_to_string(&p).unwrap()).unwrap();
        assert_eq!((back.nx, back.ny), (g.nx, g.ny));
    }
}
