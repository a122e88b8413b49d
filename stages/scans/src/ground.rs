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

fn fill_holes(z: &mut [f64], nx: usize, ny: usize) {
    let mut todo = z.iter().filter(|v| !v.is_finite()).count();
    let mut guard = 0;
    while todo > 0 && guard < nx + ny {
        guard += 1;
        let prev = z.to_vec();
        for j in 0..ny {
            for i in 0..nx {
                if prev[j * nx + i].is_finite() {
                    continue;
                }
                let (mut s, mut c) = (0.0, 0.0);
                for dj in -1i64..=1 {
                    for di in -1i64..=1 {
                        let (a, b) = (i as i64 + di, j as i64 + dj);
                        if a < 0 || b < 0 || a >= nx as i64 || b >= ny as i64 {
                            continue;
                        }
                        let v = prev[b as usize * nx + a as usize];
                        if v.is_finite() {
                            s += v;
                            c += 1.0;
                        }
                    }
                }
                if c > 0.0 {
                    z[j * nx + i] = s / c;
                    todo -= 1;
                }
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

/// Square-window min (erode) or max (dilate) filter of radius `r` cells, separable.
fn morph(z: &[f64], nx: usize, ny: usize, r: usize, max: bool) -> Vec<f64> {
    let pick = |a: f64, b: f64| if max { a.max(b) } else { a.min(b) };
    let mut tmp = vec![0.0; z.len()];
    for j in 0..ny {
        for i in 0..nx {
            let mut v = z[j * nx + i];
            for k in i.saturating_sub(r)..=(i + r).min(nx - 1) {
                v = pick(v, z[j * nx + k]);
            }
            tmp[j * nx + i] = v;
        }
    }
    let mut out = vec![0.0; z.len()];
    for j in 0..ny {
        for i in 0..nx {
            let mut v = tmp[j * nx + i];
            for k in j.saturating_sub(r)..=(j + r).min(ny - 1) {
                v = pick(v, tmp[k * nx + i]);
            }
            out[j * nx + i] = v;
        }
    }
    out
}

/// Classifies `cloud` in place (class 2 ground, 1 other) and returns the ground
/// surface grid.
pub fn classify(cloud: &mut PointCloud, s: &GroundSettings) -> Option<HeightGrid> {
    let bb = cloud.bbox();
    if bb.is_empty() {
        return None;
    }
    let c = s.cell_m;
    let x0 = (bb.min[0] / c).floor() * c;
    let y0 = (bb.min[1] / c).floor() * c;
    let nx = (((bb.max[0] - x0) / c).floor() as usize + 1).min(20_000);
    let ny = (((bb.max[1] - y0) / c).floor() as usize + 1).min(20_000);
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
    let mut surface = zmin.clone();
    fill_holes(&mut surface, nx, ny);
    let mut object = vec![false; nx * ny];
    let wmax = (s.window_m / c).ceil().max(1.0) as usize;
    let mut cur = surface.clone();
    for r in 1..=wmax {
        let opened = morph(&morph(&cur, nx, ny, r, false), nx, ny, r, true);
        let thr = s.slope * r as f64 * c;
        for k in 0..cur.len() {
            if cur[k] - opened[k] > thr {
                object[k] = true;
            }
        }
        cur = opened;
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
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

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
        let g = classify(&mut c, &GroundSettings::default()).unwrap();
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
