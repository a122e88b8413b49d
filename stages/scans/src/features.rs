//! Surface normals (PCA of the neighbourhood) and FPFH descriptors (Rusu et al.
//! 2009, "Fast Point Feature Histograms for 3D registration"), the input of the
//! coarse, pose-free alignment.
//!
//! Normals are oriented towards the scanner, which sits at the origin of each
//! scan's own frame, so both sides of a thin wall get opposite, consistent normals.

use crate::grid::Grid;
use nalgebra::{Matrix3, SymmetricEigen, Vector3};
use rayon::prelude::*;

pub const FPFH_BINS: usize = 33;
pub type Fpfh = [f32; FPFH_BINS];

/// Unit normal per point from its `k` nearest neighbours within `max_radius`
/// (zero where fewer than 5 neighbours or the neighbourhood is degenerate). A
/// neighbour count rather than a radius, because scan density falls with range.
pub fn normals(pts: &[[f64; 3]], k: usize, max_radius: f64, cell: f64, viewpoint: [f64; 3]) -> Vec<[f64; 3]> {
    let g = Grid::new(pts, cell);
    pts.par_iter()
        .map_init(Vec::new, |nb, p| {
            g.knn(p, k, max_radius, nb);
            if nb.len() < 5 {
                return [0.0; 3];
            }
            let mut mean = Vector3::zeros();
            for &(j, _) in nb.iter() {
                let q = g.points()[j as usize];
                mean += Vector3::new(q[0], q[1], q[2]);
            }
            mean /= nb.len() as f64;
            let mut cov = Matrix3::zeros();
            for &(j, _) in nb.iter() {
                let q = g.points()[j as usize];
                let d = Vector3::new(q[0], q[1], q[2]) - mean;
                cov += d * d.transpose();
            }
            let eig = SymmetricEigen::new(cov);
            let (imin, lmin) = eig
                .eigenvalues
                .iter()
                .enumerate()
                .fold((0, f64::INFINITY), |acc, (i, &v)| if v < acc.1 { (i, v) } else { acc });
            // Surface variation (Pauly et al. 2002): edges, corners and clutter
            // have no reliable normal.
            let sum: f64 = eig.eigenvalues.iter().sum();
            if !(sum > 0.0) || lmin / sum > 0.05 {
                return [0.0; 3];
            }
            let mut nv: Vector3<f64> = eig.eigenvectors.column(imin).into_owned();
            if !nv.iter().all(|v| v.is_finite()) || nv.norm() < 1e-12 {
                return [0.0; 3];
            }
            nv.normalize_mut();
            let to_view = Vector3::new(viewpoint[0] - p[0], viewpoint[1] - p[1], viewpoint[2] - p[2]);
            if nv.dot(&to_view) < 0.0 {
                nv = -nv;
            }
            [nv.x, nv.y, nv.z]
        })
        .collect()
}

#[inline]
fn sub(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
#[inline]
fn dot(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
#[inline]
fn cross(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

/// The three Darboux-frame angles of a point pair, or `None` if degenerate.
fn pair_features(p1: &[f64; 3], n1: &[f64; 3], p2: &[f64; 3], n2: &[f64; 3]) -> Option<[f64; 3]> {
    let mut d = sub(p2, p1);
    let len = dot(&d, &d).sqrt();
    if len == 0.0 {
        return None;
    }
    let a1 = dot(n1, &d) / len;
    let a2 = dot(n2, &d) / len;
    let (u, nt, f3) = if a1.abs().acos() > a2.abs().acos() {
        d = [-d[0], -d[1], -d[2]];
        (n2, n1, -a2)
    } else {
        (n1, n2, a1)
    };
    let mut v = cross(&d, u);
    let vn = dot(&v, &v).sqrt();
    if vn == 0.0 {
        return None;
    }
    v = [v[0] / vn, v[1] / vn, v[2] / vn];
    let w = cross(u, &v);
    let f2 = dot(&v, nt);
    let f1 = dot(&w, nt).atan2(dot(u, nt));
    Some([f1, f2, f3])
}

#[inline]
fn bin(v: f64, lo: f64, hi: f64) -> usize {
    (((v - lo) / (hi - lo) * 11.0).floor() as isize).clamp(0, 10) as usize
}

/// FPFH descriptor per point (points without a normal get an all-zero one).
pub fn fpfh(pts: &[[f64; 3]], normals: &[[f64; 3]], radius: f64) -> Vec<Fpfh> {
    let g = Grid::new(pts, radius);
    let has_n = |i: usize| normals[i] != [0.0; 3];
    let spfh: Vec<[f64; FPFH_BINS]> = (0..pts.len())
        .into_par_iter()
        .map(|i| {
            let mut h = [0.0f64; FPFH_BINS];
            if !has_n(i) {
                return h;
            }
            let mut n = 0.0;
            g.for_each_within(&pts[i], radius, |j, _| {
                let j = j as usize;
                if j == i || !has_n(j) {
                    return;
                }
                if let Some(f) = pair_features(&pts[i], &normals[i], &pts[j], &normals[j]) {
                    h[bin(f[0], -std::f64::consts::PI, std::f64::consts::PI)] += 1.0;
                    h[11 + bin(f[1], -1.0, 1.0)] += 1.0;
                    h[22 + bin(f[2], -1.0, 1.0)] += 1.0;
                    n += 1.0;
                }
            });
            if n > 0.0 {
                for v in h.iter_mut() {
                    *v *= 100.0 / n;
                }
            }
            h
        })
        .collect();
    (0..pts.len())
        .into_par_iter()
        .map(|i| {
            let mut out = [0f32; FPFH_BINS];
            if !has_n(i) {
                return out;
            }
            let mut acc = spfh[i];
            let mut sum = [0.0f64; 3];
            g.for_each_within(&pts[i], radius, |j, d2| {
                let j = j as usize;
                if j == i || !has_n(j) || d2 == 0.0 {
                    return;
                }
                let w = 1.0 / d2;
                for b in 0..FPFH_BINS {
                    acc[b] += spfh[j][b] * w;
                }
            });
            for b in 0..FPFH_BINS {
                sum[b / 11] += acc[b];
            }
            for b in 0..FPFH_BINS {
                let s = sum[b / 11];
                out[b] = if s > 0.0 { (acc[b] * 100.0 / s) as f32 } else { 0.0 };
            }
            out
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plane_normals_face_the_viewpoint() {
        let pts: Vec<[f64; 3]> = (0..400).map(|i| [(i % 20) as f64 * 0.1, (i / 20) as f64 * 0.1, 0.0]).collect();
        let n = normals(&pts, 12, 1.0, 0.2, [1.0, 1.0, 5.0]);
        for v in &n {
            assert!((v[2] - 1.0).abs() < 1e-9, "{v:?}");
        }
        let f = fpfh(&pts, &n, 0.5);
        // A plane: every pair has n1 = n2, so f1 and f2 fall in their middle bins.
        assert!(f[210][5] > 99.0 && f[210][16] > 99.0, "{:?}", &f[210][..]);
    }
}
