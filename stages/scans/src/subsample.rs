//! Thinning: voxel grid (centroid or nearest-to-centroid), minimum spacing, and
//! every-Nth. All three stream: they see one chunk at a time and keep memory in
//! proportion to what they output, never to what they read.
//!
//! **Voxel definition.** A point `p` belongs to voxel
//! `(floor(p.x / v), floor(p.y / v), floor(p.z / v))` with edge `v` metres, the
//! grid anchored at the site frame's origin. A voxel's output point is the mean of
//! its points (`centroid`; intensity and colour are averaged, the scan id is that
//! of its first point in input order) or the input point nearest that mean
//! (`nearest`, ties to the first in input order; a second pass over the input).
//! Output is ordered by voxel index (z, then y, then x), so it does not depend on
//! hashing or thread count.
//!
//! **Spacing**: a point is kept when no kept point lies within `d` of it, in input
//! order. **Every-Nth** keeps points 0, N, 2N, ... of each scan in input order.

use liftplan_core::cloud::PointCloud;
use rayon::prelude::*;
use rustc_hash::FxHashMap;

type Key = [i32; 3];

#[inline]
fn key(p: &[f64; 3], inv: f64) -> Option<Key> {
    let mut k = [0i32; 3];
    for i in 0..3 {
        let v = (p[i] * inv).floor();
        if !(v >= i32::MIN as f64 && v <= i32::MAX as f64) {
            return None;
        }
        k[i] = v as i32;
    }
    Some(k)
}

fn order(a: &Key, b: &Key) -> std::cmp::Ordering {
    (a[2], a[1], a[0]).cmp(&(b[2], b[1], b[0]))
}

#[derive(Clone, Copy)]
struct Acc {
    sum: [f64; 3],
    n: u32,
    isum: u64,
    rgb: [u64; 3],
    scan: u16,
}

/// Streaming voxel-centroid accumulator.
///
/// Voxels live in `SHARDS` hash maps chosen by a hash of the voxel index, so
/// one chunk is accumulated by all threads at once, each owning whole shards,
/// and every point is hashed into its final map exactly once. Within a shard,
/// points are added in input order, so sums (and the output) do not depend on
/// the number of threads.
pub struct VoxelGrid {
    inv: f64,
    shards: Vec<FxHashMap<Key, Acc>>,
    has_intensity: bool,
    has_rgb: bool,
}

/// Number of voxel shards; a power of two well above any core count we expect.
const SHARDS: usize = 64;

/// Shard of a voxel. Uses a hash unrelated to the maps' own (FxHash), so the
/// keys of one shard still spread over its map's buckets and control bytes.
#[inline]
fn shard_of(k: &Key) -> usize {
    let h = (k[0] as u32).wrapping_mul(0x9E37_79B1)
        ^ (k[1] as u32).wrapping_mul(0x85EB_CA77)
        ^ (k[2] as u32).wrapping_mul(0xC2B2_AE3D);
    (h >> (32 - SHARDS.trailing_zeros())) as usize
}

/// Points per parallel task when computing voxel indices; fixed so errors and
/// results do not depend on the number of threads.
const TASK_POINTS: usize = 65_536;

impl VoxelGrid {
    pub fn new(voxel_m: f64) -> Result<Self, String> {
        if !(voxel_m.is_finite() && voxel_m > 0.0) {
            return Err(format!("voxel edge must be a positive number of metres, found {voxel_m}"));
        }
        Ok(VoxelGrid {
            inv: 1.0 / voxel_m,
            shards: (0..SHARDS).map(|_| FxHashMap::default()).collect(),
            has_intensity: false,
            has_rgb: false,
        })
    }

    pub fn voxels(&self) -> usize {
        self.shards.iter().map(|m| m.len()).sum()
    }

    /// Adds a chunk whose points all come from scan `scan_id` (or carry their
    /// own `scan` column).
    pub fn add(&mut self, c: &PointCloud, scan_id: u16) -> Result<(), String> {
        self.has_intensity |= !c.intensity.is_empty();
        self.has_rgb |= !c.rgb.is_empty();
        let inv = self.inv;
        // Voxel index and shard per point; the first bad point in input order is reported.
        let mut keys: Vec<Key> = vec![[0; 3]; c.len()];
        let mut shard: Vec<u8> = vec![0; c.len()];
        keys.par_chunks_mut(TASK_POINTS).zip(shard.par_chunks_mut(TASK_POINTS)).enumerate().try_for_each(
            |(t, (out, sh))| -> Result<(), String> {
                for (j, (k, s)) in out.iter_mut().zip(sh.iter_mut()).enumerate() {
                    let p = &c.xyz[t * TASK_POINTS + j];
                    *k = key(p, inv).ok_or_else(|| {
                        format!("point {:?} is too far from the origin for a {} m voxel grid", p, 1.0 / inv)
                    })?;
                    *s = shard_of(k) as u8;
                }
                Ok(())
            },
        )?;
        // Counting sort of point indices by shard, keeping input order within one.
        let mut start = [0usize; SHARDS + 1];
        for &s in &shard {
            start[s as usize + 1] += 1;
        }
        for s in 0..SHARDS {
            start[s + 1] += start[s];
        }
        let mut fill = start;
        let mut order = vec![0usize; c.len()];
        for (i, &s) in shard.iter().enumerate() {
            order[fill[s as usize]] = i;
            fill[s as usize] += 1;
        }
        self.shards.par_iter_mut().enumerate().for_each(|(s, map)| {
            for &i in &order[start[s]..start[s + 1]] {
                let p = &c.xyz[i];
                let e = map.entry(keys[i]).or_insert(Acc {
                    sum: [0.0; 3],
                    n: 0,
                    isum: 0,
                    rgb: [0; 3],
                    scan: c.scan.get(i).copied().unwrap_or(scan_id),
                });
                e.sum[0] += p[0];
                e.sum[1] += p[1];
                e.sum[2] += p[2];
                e.n += 1;
                if let Some(v) = c.intensity.get(i) {
                    e.isum += *v as u64;
                }
                if let Some(v) = c.rgb.get(i) {
                    for j in 0..3 {
                        e.rgb[j] += v[j] as u64;
                    }
                }
            }
        });
        Ok(())
    }

    /// The voxel centroids, in voxel order.
    pub fn finish(self) -> PointCloud {
        let mut items: Vec<(Key, Acc)> = self.shards.into_iter().flatten().collect();
        items.par_sort_unstable_by(|a, b| order(&a.0, &b.0));
        let mut out = PointCloud {
            xyz: items
                .iter()
                .map(|(_, a)| {
                    let n = a.n as f64;
                    [a.sum[0] / n, a.sum[1] / n, a.sum[2] / n]
                })
                .collect(),
            ..Default::default()
        };
        if self.has_intensity {
            out.intensity = items.iter().map(|(_, a)| (a.isum / a.n as u64) as u16).collect();
        }
        if self.has_rgb {
            out.rgb = items
                .iter()
                .map(|(_, a)| {
                    let n = a.n as u64;
                    [(a.rgb[0] / n) as u16, (a.rgb[1] / n) as u16, (a.rgb[2] / n) as u16]
                })
                .collect();
        }
        out.scan = items.iter().map(|(_, a)| a.scan).collect();
        out
    }

    /// Centroids by voxel, for the second pass of nearest-to-centroid.
    pub fn into_nearest_picker(self) -> NearestPicker {
        let map = self
            .shards
            .into_iter()
            .flatten()
            .map(|(k, a)| {
                let n = a.n as f64;
                (k, Pick { centroid: [a.sum[0] / n, a.sum[1] / n, a.sum[2] / n], best_d2: f64::INFINITY, best: None })
            })
            .collect();
        NearestPicker { inv: self.inv, map, has_intensity: self.has_intensity, has_rgb: self.has_rgb }
    }
}

struct Pick {
    centroid: [f64; 3],
    best_d2: f64,
    best: Option<([f64; 3], u16, [u16; 3], u16)>,
}

/// Second pass of nearest-to-centroid: feed the same input again.
pub struct NearestPicker {
    inv: f64,
    map: FxHashMap<Key, Pick>,
    has_intensity: bool,
    has_rgb: bool,
}

impl NearestPicker {
    pub fn add(&mut self, c: &PointCloud, scan_id: u16) {
        for (i, p) in c.xyz.iter().enumerate() {
            let Some(k) = key(p, self.inv) else { continue };
            let Some(e) = self.map.get_mut(&k) else {
                continue;
            };
            let d2 = (p[0] - e.centroid[0]).powi(2) + (p[1] - e.centroid[1]).powi(2) + (p[2] - e.centroid[2]).powi(2);
            if d2 < e.best_d2 {
                e.best_d2 = d2;
                e.best = Some((
                    *p,
                    c.intensity.get(i).copied().unwrap_or(0),
                    c.rgb.get(i).copied().unwrap_or([0; 3]),
                    c.scan.get(i).copied().unwrap_or(scan_id),
                ));
            }
        }
    }

    pub fn finish(self) -> PointCloud {
        let mut items: Vec<(Key, ([f64; 3], u16, [u16; 3], u16))> =
            self.map.into_iter().filter_map(|(k, p)| p.best.map(|b| (k, b))).collect();
        items.par_sort_unstable_by(|a, b| order(&a.0, &b.0));
        let mut out = PointCloud { xyz: items.iter().map(|x| x.1.0).collect(), ..Default::default() };
        if self.has_intensity {
            out.intensity = items.iter().map(|x| x.1.1).collect();
        }
        if self.has_rgb {
            out.rgb = items.iter().map(|x| x.1.2).collect();
        }
        out.scan = items.iter().map(|x| x.1.3).collect();
        out
    }
}

/// Streaming minimum-spacing filter.
pub struct SpacingFilter {
    d: f64,
    d2: f64,
    cells: FxHashMap<Key, Vec<u32>>,
    kept: PointCloud,
}

impl SpacingFilter {
    pub fn new(spacing_m: f64) -> Result<Self, String> {
        if !(spacing_m.is_finite() && spacing_m > 0.0) {
            return Err(format!("spacing must be a positive number of metres, found {spacing_m}"));
        }
        Ok(SpacingFilter {
            d: spacing_m,
            d2: spacing_m * spacing_m,
            cells: FxHashMap::default(),
            kept: PointCloud::default(),
        })
    }

    pub fn add(&mut self, c: &PointCloud, scan_id: u16) -> Result<(), String> {
        let inv = 1.0 / self.d;
        for (i, p) in c.xyz.iter().enumerate() {
            let k = key(p, inv).ok_or_else(|| format!("point {p:?} is too far from the origin"))?;
            let mut near = false;
            'search: for dz in -1..=1 {
                for dy in -1..=1 {
                    for dx in -1..=1 {
                        let n = [k[0].wrapping_add(dx), k[1].wrapping_add(dy), k[2].wrapping_add(dz)];
                        if let Some(list) = self.cells.get(&n) {
                            for &j in list {
                                let q = self.kept.xyz[j as usize];
                                if (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2) < self.d2 {
                                    near = true;
                                    break 'search;
                                }
                            }
                        }
                    }
                }
            }
            if !near {
                let j = self.kept.len() as u32;
                self.kept.xyz.push(*p);
                if !c.intensity.is_empty() {
                    self.kept.intensity.push(c.intensity[i]);
                }
                if !c.rgb.is_empty() {
                    self.kept.rgb.push(c.rgb[i]);
                }
                self.kept.scan.push(c.scan.get(i).copied().unwrap_or(scan_id));
                self.cells.entry(k).or_default().push(j);
            }
        }
        Ok(())
    }

    pub fn finish(self) -> PointCloud {
        let mut k = self.kept;
        // Columns seen only in some chunks are padded to full length.
        if !k.intensity.is_empty() && k.intensity.len() != k.xyz.len() {
            k.intensity.resize(k.xyz.len(), 0);
        }
        if !k.rgb.is_empty() && k.rgb.len() != k.xyz.len() {
            k.rgb.resize(k.xyz.len(), [0; 3]);
        }
        k
    }
}

/// Every-Nth decimation of one scan's stream.
pub struct EveryNth {
    n: u64,
    counter: u64,
    kept: PointCloud,
}

impl EveryNth {
    pub fn new(n: u64) -> Result<Self, String> {
        if n == 0 {
            return Err("every_nth must be 1 or more".into());
        }
        Ok(EveryNth { n, counter: 0, kept: PointCloud::default() })
    }

    /// Restarts the count for a new scan.
    pub fn next_scan(&mut self) {
        self.counter = 0;
    }

    pub fn add(&mut self, c: &PointCloud, scan_id: u16) {
        let idx: Vec<usize> = (0..c.len()).filter(|i| (self.counter + *i as u64).is_multiple_of(self.n)).collect();
        self.counter += c.len() as u64;
        let mut s = c.select(&idx);
        if s.scan.is_empty() {
            s.scan = vec![scan_id; s.len()];
        }
        self.kept.append(&s);
    }

    pub fn finish(self) -> PointCloud {
        self.kept
    }
}

/// Voxel centroids of an in-memory cloud (same definition as [`VoxelGrid`]).
pub fn voxel_centroids(c: &PointCloud, voxel_m: f64) -> Result<PointCloud, String> {
    let mut g = VoxelGrid::new(voxel_m)?;
    for start in (0..c.len()).step_by(crate::read::CHUNK_POINTS.max(1)) {
        let end = (start + crate::read::CHUNK_POINTS).min(c.len());
        let idx: Vec<usize> = (start..end).collect();
        g.add(&c.select(&idx), 0)?;
    }
    Ok(g.finish())
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use std::collections::BTreeMap;

    /// Brute force by the documented definition: group by floored index, average.
    fn brute(points: &[[f64; 3]], v: f64) -> Vec<[f64; 3]> {
        let mut groups: BTreeMap<(i64, i64, i64), Vec<[f64; 3]>> = BTreeMap::new();
        for p in points {
            let k = ((p[2] / v).floor() as i64, (p[1] / v).floor() as i64, (p[0] / v).floor() as i64);
            groups.entry(k).or_default().push(*p);
        }
        groups
            .values()
            .map(|g| {
                let n = g.len() as f64;
                [
                    g.iter().map(|p| p[0]).sum::<f64>() / n,
                    g.iter().map(|p| p[1]).sum::<f64>() / n,
                    g.iter().map(|p| p[2]).sum::<f64>() / n,
                ]
            })
            .collect()
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(liftplan_core::testing::proptest_cases(48)))]
        #[test]
        fn voxel_equals_brute_force(
            pts in proptest::collection::vec((-20.0f64..20.0, -20.0f64..20.0, -5.0f64..5.0), 1..3000),
            v in 0.05f64..2.0,
        ) {
            let xyz: Vec<[f64; 3]> = pts.iter().map(|p| [p.0, p.1, p.2]).collect();
            let cloud = PointCloud { xyz: xyz.clone(), ..Default::default() };
            let got = voxel_centroids(&cloud, v).unwrap();
            let want = brute(&xyz, v);
            prop_assert_eq!(got.len(), want.len());
            for (a, b) in got.xyz.iter().zip(&want) {
                for i in 0..3 {
                    prop_assert!((a[i] - b[i]).abs() < 1e-9, "{:?} vs {:?}", a, b);
                }
            }
        }
    }

    #[test]
    fn nearest_picks_input_points() {
        let c = PointCloud {
            xyz: vec![[0.1, 0.1, 0.1], [0.2, 0.2, 0.2], [0.9, 0.9, 0.9], [1.5, 0.0, 0.0]],
            ..Default::default()
        };
        let mut g = VoxelGrid::new(1.0).unwrap();
        g.add(&c, 3).unwrap();
        let mut p = g.into_nearest_picker();
        p.add(&c, 3);
        let out = p.finish();
        assert_eq!(out.xyz, vec![[0.2, 0.2, 0.2], [1.5, 0.0, 0.0]]);
        assert_eq!(out.scan, vec![3, 3]);
    }

    #[test]
    fn spacing_keeps_no_close_pairs() {
        let xyz: Vec<[f64; 3]> = (0..2000)
            .map(|i| {
                let t = i as f64 * 0.7315;
                [t.sin() * 3.0, (t * 1.3).cos() * 3.0, (t * 0.1).sin()]
            })
            .collect();
        let mut f = SpacingFilter::new(0.3).unwrap();
        f.add(&PointCloud { xyz, ..Default::default() }, 0).unwrap();
        let k = f.finish();
        for i in 0..k.len() {
            for j in (i + 1)..k.len() {
                let (a, b) = (k.xyz[i], k.xyz[j]);
                let d2 = (a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2);
                assert!(d2 >= 0.09 - 1e-12);
            }
        }
    }

    #[test]
    fn every_nth_counts_across_chunks() {
        let mut f = EveryNth::new(3).unwrap();
        let c = |a: f64, b: f64| PointCloud {
            xyz: (0..5).map(|i| [a + i as f64 * b, 0.0, 0.0]).collect(),
            ..Default::default()
        };
        f.add(&c(0.0, 1.0), 0);
        f.add(&c(5.0, 1.0), 0);
        let k = f.finish();
        assert_eq!(k.xyz.iter().map(|p| p[0]).collect::<Vec<_>>(), vec![0.0, 3.0, 6.0, 9.0]);
    }
}
