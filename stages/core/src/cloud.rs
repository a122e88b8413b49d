//! Point clouds in the site frame.
//!
//! A [`PointCloud`] is plain columns: coordinates in metres (f64, site frame) and
//! optional per-point attributes. An attribute column is either empty (absent) or
//! exactly as long as `xyz`. Readers and filters live in the scans stage; this
//! module only holds the data and the operations every stage needs.

use crate::frame::{Aabb, Point3, Pose};

/// LAS classification codes used by liftplan (ASPRS LAS 1.4, table 17).
pub mod class {
    pub const UNCLASSIFIED: u8 = 1;
    pub const GROUND: u8 = 2;
}

#[derive(Debug, Clone, Default, PartialEq)]
pub struct PointCloud {
    pub xyz: Vec<[f64; 3]>,
    pub intensity: Vec<u16>,
    pub rgb: Vec<[u16; 3]>,
    /// LAS classification per point.
    pub class: Vec<u8>,
    /// Which scan (0-based, in input order) each point came from.
    pub scan: Vec<u16>,
}

impl PointCloud {
    pub fn len(&self) -> usize {
        self.xyz.len()
    }

    pub fn is_empty(&self) -> bool {
        self.xyz.is_empty()
    }

    pub fn bbox(&self) -> Aabb {
        Aabb::from_points(&self.xyz)
    }

    /// Moves every point by `pose` (local frame to site frame).
    pub fn transform(&mut self, pose: &Pose) {
        for p in &mut self.xyz {
            let q = pose * Point3::new(p[0], p[1], p[2]);
            *p = [q.x, q.y, q.z];
        }
    }

    /// Keeps attribute columns consistent: each is empty or as long as `xyz`.
    pub fn check_columns(&self) -> Result<(), String> {
        let n = self.xyz.len();
        for (name, len) in [
            ("intensity", self.intensity.len()),
            ("rgb", self.rgb.len()),
            ("class", self.class.len()),
            ("scan", self.scan.len()),
        ] {
            if len != 0 && len != n {
                return Err(format!("column {name} has {len} values for {n} points"));
            }
        }
        Ok(())
    }

    /// Appends another cloud; attribute columns present in only one of them are
    /// filled with zeros (or `class::UNCLASSIFIED`) for the other.
    pub fn append(&mut self, other: &PointCloud) {
        let n0 = self.len();
        let n1 = other.len();
        fn merge<T: Copy>(a: &mut Vec<T>, b: &[T], n0: usize, n1: usize, fill: T) {
            if a.is_empty() && b.is_empty() {
                return;
            }
            if a.is_empty() {
                a.resize(n0, fill);
            }
            if b.is_empty() {
                a.extend(std::iter::repeat_n(fill, n1));
            } else {
                a.extend_from_slice(b);
            }
        }
        merge(&mut self.intensity, &other.intensity, n0, n1, 0);
        merge(&mut self.rgb, &other.rgb, n0, n1, [0; 3]);
        merge(&mut self.class, &other.class, n0, n1, class::UNCLASSIFIED);
        merge(&mut self.scan, &other.scan, n0, n1, 0);
        self.xyz.extend_from_slice(&other.xyz);
    }

    /// A new cloud holding the points at `idx`, in that order.
    pub fn select(&self, idx: &[usize]) -> PointCloud {
        fn pick<T: Copy>(v: &[T], idx: &[usize]) -> Vec<T> {
            if v.is_empty() { Vec::new() } else { idx.iter().map(|&i| v[i]).collect() }
        }
        PointCloud {
            xyz: pick(&self.xyz, idx),
            intensity: pick(&self.intensity, idx),
            rgb: pick(&self.rgb, idx),
            class: pick(&self.class, idx),
            scan: pick(&self.scan, idx),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn append_fills_missing_columns() {
        let mut a = PointCloud { xyz: vec![[0.0; 3]; 2], intensity: vec![5, 6], ..Default::default() };
        let b = PointCloud { xyz: vec![[1.0; 3]; 3], class: vec![2, 2, 2], ..Default::default() };
        a.append(&b);
        assert_eq!(a.len(), 5);
        assert_eq!(a.intensity, vec![5, 6, 0, 0, 0]);
        assert_eq!(a.class, vec![1, 1, 2, 2, 2]);
        a.check_columns().unwrap();
    }
}
