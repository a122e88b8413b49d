//! A static hash grid over a point set for fixed-radius and nearest-within-radius
//! queries: the neighbour search behind normals, features and ICP.
//!
//! Cells are cubes of edge `cell`; a query with radius up to `cell` visits the 27
//! cells around the query point. Points are stored in cell order (CSR), so a query
//! touches contiguous memory.

use rustc_hash::FxHashMap;

pub struct Grid {
    inv: f64,
    r: f64,
    cells: FxHashMap<[i32; 3], (u32, u32)>,
    /// Point indices in cell order.
    order: Vec<u32>,
    pts: Vec<[f64; 3]>,
}

#[inline]
fn key(p: &[f64; 3], inv: f64) -> [i32; 3] {
    [(p[0] * inv).floor() as i32, (p[1] * inv).floor() as i32, (p[2] * inv).floor() as i32]
}

#[inline]
pub fn dist2(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    (a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)
}

impl Grid {
    pub fn new(pts: &[[f64; 3]], cell: f64) -> Grid {
        let inv = 1.0 / cell;
        let mut keyed: Vec<([i32; 3], u32)> = pts.iter().enumerate().map(|(i, p)| (key(p, inv), i as u32)).collect();
        keyed.sort_unstable();
        let mut cells = FxHashMap::default();
        let mut order = Vec::with_capacity(keyed.len());
        let mut i = 0;
        while i < keyed.len() {
            let k = keyed[i].0;
            let start = i;
            while i < keyed.len() && keyed[i].0 == k {
                order.push(keyed[i].1);
                i += 1;
            }
            cells.insert(k, (start as u32, (i - start) as u32));
        }
        Grid { inv, r: cell, cells, order, pts: pts.to_vec() }
    }

    pub fn points(&self) -> &[[f64; 3]] {
        &self.pts
    }

    /// Calls `f(index, squared distance)` for every point within `radius` of `q`
    /// (`radius` must not exceed the cell size).
    #[inline]
    pub fn for_each_within(&self, q: &[f64; 3], radius: f64, mut f: impl FnMut(u32, f64)) {
        debug_assert!(radius <= self.r + 1e-12);
        let r2 = radius * radius;
        let k = key(q, self.inv);
        for dz in -1..=1 {
            for dy in -1..=1 {
                for dx in -1..=1 {
                    if let Some(&(s, n)) = self.cells.get(&[k[0] + dx, k[1] + dy, k[2] + dz]) {
                        for &j in &self.order[s as usize..(s + n) as usize] {
                            let d2 = dist2(q, &self.pts[j as usize]);
                            if d2 <= r2 {
                                f(j, d2);
                            }
                        }
                    }
                }
            }
        }
    }

    /// The `k` nearest points within `max_radius` (any radius; searched ring by
    /// ring), nearest first, as (index, squared distance).
    pub fn knn(&self, q: &[f64; 3], k: usize, max_radius: f64, out: &mut Vec<(u32, f64)>) {
        out.clear();
        let c = key(q, self.inv);
        let max_ring = (max_radius * self.inv).ceil() as i32 + 1;
        let r2max = max_radius * max_radius;
        for ring in 0..=max_ring {
            for dz in -ring..=ring {
                for dy in -ring..=ring {
                    for dx in -ring..=ring {
                        if dx.abs().max(dy.abs()).max(dz.abs()) != ring {
                            continue;
                        }
                        if let Some(&(s, n)) = self.cells.get(&[c[0] + dx, c[1] + dy, c[2] + dz]) {
                            for &j in &self.order[s as usize..(s + n) as usize] {
                                let d2 = dist2(q, &self.pts[j as usize]);
                                if d2 <= r2max {
                                    out.push((j, d2));
                                }
                            }
                        }
                    }
                }
            }
            // Every point within `ring * cell` of q has been seen by now.
            if out.len() >= k {
                out.sort_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
                let reach = ring as f64 * self.r;
                if out[k - 1].1 <= reach * reach {
                    out.truncate(k);
                    return;
                }
            }
        }
        out.sort_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
        out.truncate(k);
    }

    /// The nearest point within `max_radius` of `q` (any radius), searching
    /// outwards ring by ring and stopping as soon as nothing closer can exist.
    /// Ties go to the lower index.
    #[inline]
    pub fn nearest(&self, q: &[f64; 3], max_radius: f64) -> Option<(u32, f64)> {
        let c = key(q, self.inv);
        let max_ring = (max_radius * self.inv).ceil() as i32 + 1;
        let mut best: Option<(u32, f64)> = None;
        let r2max = max_radius * max_radius;
        for ring in 0..=max_ring {
            for dz in -ring..=ring {
                for dy in -ring..=ring {
                    let edge = dz.abs() == ring || dy.abs() == ring;
                    let step = if edge { 1 } else { 2 * ring.max(1) };
                    let mut dx = -ring;
                    while dx <= ring {
                        if let Some(&(s, n)) = self.cells.get(&[c[0] + dx, c[1] + dy, c[2] + dz]) {
                            for &j in &self.order[s as usize..(s + n) as usize] {
                                let d2 = dist2(q, &self.pts[j as usize]);
                                if d2 <= r2max && best.is_none_or(|(bj, bd)| d2 < bd || (d2 == bd && j < bj)) {
                                    best = Some((j, d2));
                                }
                            }
                        }
                        dx += step;
                    }
                }
            }
            // Points in rings beyond this one are at least ring * cell away.
            if let Some((_, bd)) = best {
                let reach = ring as f64 * self.r;
                if bd <= reach * reach {
                    break;
                }
            }
        }
        best
    }

    /// The nearest point within `radius` (ties to the lower index).
    #[inline]
    pub fn nearest_within(&self, q: &[f64; 3], radius: f64) -> Option<(u32, f64)> {
        let mut best: Option<(u32, f64)> = None;
        self.for_each_within(q, radius, |j, d2| match best {
            Some((bj, bd)) if bd < d2 || (bd == d2 && bj < j) => {}
            _ => best = Some((j, d2)),
        });
        best
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn knn_matches_brute_force() {
        let pts: Vec<[f64; 3]> = (0..800)
            .map(|i| {
                let t = i as f64;
                [(t * 0.37).sin() * 5.0, (t * 0.71).cos() * 5.0, (t * 0.13).sin()]
            })
            .collect();
        let g = Grid::new(&pts, 0.3);
        let mut out = Vec::new();
        for q in [[0.0, 0.0, 0.0], [2.0, -1.0, 0.5], [9.0, 9.0, 0.0]] {
            g.knn(&q, 7, 20.0, &mut out);
            let mut want: Vec<(u32, f64)> = pts.iter().enumerate().map(|(i, p)| (i as u32, dist2(&q, p))).collect();
            want.sort_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
            want.truncate(7);
            assert_eq!(out, want);
        }
    }

    #[test]
    fn nearest_matches_brute_force() {
        let pts: Vec<[f64; 3]> = (0..500)
            .map(|i| {
                let t = i as f64;
                [(t * 0.37).sin() * 5.0, (t * 0.71).cos() * 5.0, (t * 0.13).sin()]
            })
            .collect();
        let g = Grid::new(&pts, 1.0);
        for q in [[0.0, 0.0, 0.0], [2.0, -1.0, 0.5], [4.9, 4.9, 0.0]] {
            let want = pts
                .iter()
                .enumerate()
                .map(|(i, p)| (i as u32, dist2(&q, p)))
                .filter(|x| x.1 <= 1.0)
                .min_by(|a, b| a.1.total_cmp(&b.1));
            assert_eq!(g.nearest_within(&q, 1.0).map(|x| x.0), want.map(|x| x.0));
            let g2 = Grid::new(&pts, 0.2);
            assert_eq!(g2.nearest(&q, 1.0).map(|x| x.0), want.map(|x| x.0));
        }
    }
}
