//! Oriented bounding boxes: the shape of every crane part and of the load.
//!
//! The planner, the C-space and the depth-map queries all see the crane as a few
//! OBBs (thesis ch. 4.4.1). This module gives the box itself and the exact
//! geometric facts the depth-map queries need: the box's footprint on the ground
//! plane and its exact height range above one grid cell. It holds no collision
//! policy; the independent validator does not use it for its own geometry.

use crate::frame::{Aabb, Mat3, Point3, Vec3};

/// A box with centre `center`, unit axes in the columns of `axes` and half sizes
/// `half` along those axes, all in the site frame (metres).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Obb {
    pub center: Point3,
    pub axes: Mat3,
    pub half: Vec3,
}

impl Obb {
    pub fn new(center: Point3, axes: Mat3, half: Vec3) -> Self {
        Obb { center, axes, half }
    }

    pub fn axis_aligned(center: Point3, half: Vec3) -> Self {
        Obb { center, axes: Mat3::identity(), half }
    }

    pub fn axis(&self, i: usize) -> Vec3 {
        self.axes.column(i).into_owned()
    }

    /// The box grown by `margin` on every side.
    pub fn expanded(&self, margin: f64) -> Obb {
        Obb { half: self.half.add_scalar(margin), ..*self }
    }

    /// The box grown to hold every point within `horizontal_m` horizontally and
    /// `vertical_m` vertically of it: the region a box sweeps when each of its
    /// points moves at most that far that way. Exact growth of the half sizes
    /// for upright boxes; any other box grows by the larger of the two on every side.
    pub fn expanded_by_motion(&self, horizontal_m: f64, vertical_m: f64) -> Obb {
        if !self.is_upright() {
            return self.expanded(horizontal_m.max(vertical_m));
        }
        let half = Vec3::new(self.half.x + horizontal_m, self.half.y + horizontal_m, self.half.z + vertical_m);
        Obb { half, ..*self }
    }

    /// The box with its underside raised by `by_m` (at most half its height),
    /// top unchanged: a part standing or resting on a surface, with that surface
    /// not counted as an obstacle. For boxes whose third axis is vertical (crane
    /// parts and loads are only ever turned about Z).
    pub fn with_underside_raised(&self, by_m: f64) -> Obb {
        let lift = by_m.min(self.half.z);
        let mut o = *self;
        o.center.z += lift / 2.0;
        o.half.z -= lift / 2.0;
        o
    }

    pub fn corners(&self) -> [Point3; 8] {
        let mut out = [self.center; 8];
        for (k, c) in out.iter_mut().enumerate() {
            let sx = if k & 1 == 0 { -1.0 } else { 1.0 };
            let sy = if k & 2 == 0 { -1.0 } else { 1.0 };
            let sz = if k & 4 == 0 { -1.0 } else { 1.0 };
            *c = self.center
                + self.axis(0) * (sx * self.half.x)
                + self.axis(1) * (sy * self.half.y)
                + self.axis(2) * (sz * self.half.z);
        }
        out
    }

    pub fn aabb(&self) -> Aabb {
        let mut ext = [0.0; 3];
        for (i, e) in ext.iter_mut().enumerate() {
            *e = (0..3).map(|j| self.axes[(i, j)].abs() * self.half[j]).sum();
        }
        Aabb {
            min: [self.center.x - ext[0], self.center.y - ext[1], self.center.z - ext[2]],
            max: [self.center.x + ext[0], self.center.y + ext[1], self.center.z + ext[2]],
        }
    }

    /// The point in box coordinates (along the box axes, from its centre).
    pub fn to_local(&self, p: &Point3) -> Vec3 {
        self.axes.transpose() * (p - self.center)
    }

    pub fn contains(&self, p: &Point3) -> bool {
        let l = self.to_local(p);
        (0..3).all(|i| l[i].abs() <= self.half[i])
    }

    /// Squared Euclidean distance from `p` to the solid box (0 inside).
    pub fn distance_sq_to_point(&self, p: &Point3) -> f64 {
        let l = self.to_local(p);
        (0..3).map(|i| (l[i].abs() - self.half[i]).max(0.0).powi(2)).sum()
    }

    /// Bounding radius about the centre.
    pub fn radius(&self) -> f64 {
        self.half.norm()
    }

    /// The plan extent of the box, the lows and highs of its footprint's x
    /// and y, without placing its corners: each axis's reach is the sum of
    /// its three half edges' reach along it.
    pub fn plan_extent(&self) -> ([f64; 2], [f64; 2]) {
        let reach = |row: usize| (0..3).map(|k| self.axes[(row, k)].abs() * self.half[k]).sum::<f64>();
        let (rx, ry) = (reach(0), reach(1));
        ([self.center.x - rx, self.center.y - ry], [self.center.x + rx, self.center.y + ry])
    }

    /// Convex hull of the box projected on the ground plane, counter-clockwise.
    pub fn footprint(&self) -> Vec<[f64; 2]> {
        let pts: Vec<[f64; 2]> = self.corners().iter().map(|c| [c.x, c.y]).collect();
        convex_hull_2d(&pts)
    }

    /// Exact height range of the box inside the vertical column above the
    /// rectangle `[x0, x1] x [y0, y1]`, or `None` when the box does not reach the
    /// column.
    ///
    /// The intersection of the box and the column is a convex polytope, so its
    /// lowest and highest points are vertices of it. Those vertices are box corners
    /// inside the column, crossings of box edges with the column's side planes, and
    /// crossings of the column's vertical edges with the box; all three are tried.
    pub fn z_range_over_rect(&self, x0: f64, x1: f64, y0: f64, y1: f64) -> Option<(f64, f64)> {
        let eps = 1e-9;
        if self.is_upright() {
            // Upright (turned about z only, like the load, hook and crane body):
            // its height range is the same over every column it reaches, and it
            // reaches the column when its footprint meets the rectangle, a 2D
            // separating-axis test.
            let a = self.axes;
            let (u, v) = ([a[(0, 0)], a[(1, 0)]], [a[(0, 1)], a[(1, 1)]]);
            let (hx, hy) = (self.half.x, self.half.y);
            let (ex, ey) = (0.5 * (x1 - x0), 0.5 * (y1 - y0));
            let d = [self.center.x - 0.5 * (x0 + x1), self.center.y - 0.5 * (y0 + y1)];
            let apart = d[0].abs() > ex + hx * u[0].abs() + hy * v[0].abs() + eps
                || d[1].abs() > ey + hx * u[1].abs() + hy * v[1].abs() + eps
                || (d[0] * u[0] + d[1] * u[1]).abs() > hx + ex * u[0].abs() + ey * u[1].abs() + eps
                || (d[0] * v[0] + d[1] * v[1]).abs() > hy + ex * v[0].abs() + ey * v[1].abs() + eps;
            return (!apart).then_some((self.center.z - self.half.z, self.center.z + self.half.z));
        }
        self.z_range_over_rect_by_vertices(x0, x1, y0, y1)
    }

    /// [`Obb::z_range_over_rect`] for any box, by the polytope's vertices.
    fn z_range_over_rect_by_vertices(&self, x0: f64, x1: f64, y0: f64, y1: f64) -> Option<(f64, f64)> {
        let eps = 1e-9;
        let inside = |x: f64, y: f64| x >= x0 - eps && x <= x1 + eps && y >= y0 - eps && y <= y1 + eps;
        let mut lo = f64::INFINITY;
        let mut hi = f64::NEG_INFINITY;
        let mut take = |z: f64| {
            lo = lo.min(z);
            hi = hi.max(z);
        };
        let c = self.corners();
        for p in &c {
            if inside(p.x, p.y) {
                take(p.z);
            }
        }
        // The 12 edges join corners differing in exactly one index bit.
        for a in 0..8usize {
            for bit in [1usize, 2, 4] {
                let b = a | bit;
                if b == a {
                    continue;
                }
                let (p, q) = (c[a], c[b]);
                let d = q - p;
                for (axis, val) in [(0usize, x0), (0, x1), (1, y0), (1, y1)] {
                    let den = d[axis];
                    if den.abs() < 1e-15 {
                        continue;
                    }
                    let t = (val - p[axis]) / den;
                    if !(-eps..=1.0 + eps).contains(&t) {
                        continue;
                    }
                    let r = p + d * t;
                    if inside(r.x, r.y) {
                        take(r.z);
                    }
                }
            }
        }
        // Vertical column edges through the box, by slab clipping in box coordinates.
        let ez = self.axes.transpose() * Vec3::z();
        for (x, y) in [(x0, y0), (x1, y0), (x0, y1), (x1, y1)] {
            let o = self.to_local(&Point3::new(x, y, self.center.z));
            let mut t0 = f64::NEG_INFINITY;
            let mut t1 = f64::INFINITY;
            let mut hit = true;
            for i in 0..3 {
                if ez[i].abs() < 1e-15 {
                    if o[i].abs() > self.half[i] {
                        hit = false;
                        break;
                    }
                } else {
                    let a = (-self.half[i] - o[i]) / ez[i];
                    let b = (self.half[i] - o[i]) / ez[i];
                    t0 = t0.max(a.min(b));
                    t1 = t1.min(a.max(b));
                }
            }
            if hit && t0 <= t1 {
                take(self.center.z + t0);
                take(self.center.z + t1);
            }
        }
        (lo <= hi).then_some((lo, hi))
    }

    /// The box with its top raised by `by_m`, underside unchanged (for boxes
    /// whose third axis is vertical).
    pub fn with_top_raised(&self, by_m: f64) -> Obb {
        let mut o = *self;
        o.center.z += by_m / 2.0;
        o.half.z += by_m / 2.0;
        o
    }

    /// Turned about the vertical only: the third axis is exactly up.
    pub fn is_upright(&self) -> bool {
        let a = self.axes;
        a[(0, 2)] == 0.0 && a[(1, 2)] == 0.0 && a[(2, 2)] == 1.0 && a[(2, 0)] == 0.0 && a[(2, 1)] == 0.0
    }

    /// Separating-axis test between two solid boxes.
    pub fn intersects(&self, o: &Obb) -> bool {
        let t = o.center - self.center;
        let mut axes: Vec<Vec3> = Vec::with_capacity(15);
        for i in 0..3 {
            axes.push(self.axis(i));
            axes.push(o.axis(i));
        }
        for i in 0..3 {
            for j in 0..3 {
                let c = self.axis(i).cross(&o.axis(j));
                if c.norm_squared() > 1e-18 {
                    axes.push(c.normalize());
                }
            }
        }
        for l in axes {
            let ra: f64 = (0..3).map(|i| self.half[i] * self.axis(i).dot(&l).abs()).sum();
            let rb: f64 = (0..3).map(|i| o.half[i] * o.axis(i).dot(&l).abs()).sum();
            if t.dot(&l).abs() > ra + rb {
                return false;
            }
        }
        true
    }
}

/// Whether the convex `footprint` comes within `within_m` of `area`, a
/// simple polygon with its corners in order either way round: one holds a
/// corner of the other, or an edge of one passes within `within_m` of an
/// edge of the other (crossing it or not).
pub fn footprint_near_area(footprint: &[[f64; 2]], area: &[[f64; 2]], within_m: f64) -> bool {
    if footprint.is_empty() || area.len() < 3 {
        return false;
    }
    // Far apart in plan: nothing to test edge by edge.
    if let (Some(f), Some(a)) = (plan_bounds(footprint), plan_bounds(area))
        && bounds_apart(f, a, within_m)
    {
        return false;
    }
    if in_polygon_2d(area, footprint[0]) || (footprint.len() >= 3 && in_polygon_2d(footprint, area[0])) {
        return true;
    }
    edges_2d(footprint).any(|(a, b)| edges_2d(area).any(|(c, d)| segment_distance_2d(a, b, c, d) <= within_m))
}

/// Whether the convex `footprint` lies within `area`, a simple polygon with
/// its corners in order either way round, clear of its edges: every corner
/// inside it and no edge of either touching or crossing an edge of the
/// other (an edge of a notch may cross the footprint between its corners).
pub fn footprint_within_area(footprint: &[[f64; 2]], area: &[[f64; 2]]) -> bool {
    !footprint.is_empty()
        && area.len() >= 3
        && footprint.iter().all(|&p| in_polygon_2d(area, p))
        && edges_2d(footprint).all(|(a, b)| edges_2d(area).all(|(c, d)| segment_distance_2d(a, b, c, d) > 0.0))
}

/// Whether two plan extents (lows, highs) lie more than `within_m` apart
/// along x or y: then nothing of either comes within `within_m` of the other.
pub fn bounds_apart(a: ([f64; 2], [f64; 2]), b: ([f64; 2], [f64; 2]), within_m: f64) -> bool {
    (0..2).any(|k| a.0[k] > b.1[k] + within_m || b.0[k] > a.1[k] + within_m)
}

/// A closed polygon's edges, the last back to the first.
fn edges_2d(p: &[[f64; 2]]) -> impl Iterator<Item = ([f64; 2], [f64; 2])> + '_ {
    let n = p.len();
    (0..n).map(move |i| (p[i], p[(i + 1) % n]))
}

/// The least and greatest x and y of plan points, `None` where there are
/// none.
pub fn plan_bounds<'a>(pts: impl IntoIterator<Item = &'a [f64; 2]>) -> Option<([f64; 2], [f64; 2])> {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in pts {
        for a in 0..2 {
            (lo[a], hi[a]) = (lo[a].min(p[a]), hi[a].max(p[a]));
        }
    }
    (lo[0] <= hi[0] && lo[1] <= hi[1]).then_some((lo, hi))
}

/// Whether `p` lies inside the simple polygon `poly` (the even-odd rule).
pub fn in_polygon_2d(poly: &[[f64; 2]], p: [f64; 2]) -> bool {
    let mut inside = false;
    let n = poly.len();
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        if (a[1] > p[1]) != (b[1] > p[1]) && p[0] < a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0]) {
            inside = !inside;
        }
    }
    inside
}

/// The least distance between segments `ab` and `cd` in the plane.
fn segment_distance_2d(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> f64 {
    let cross = |o: [f64; 2], p: [f64; 2], q: [f64; 2]| (p[0] - o[0]) * (q[1] - o[1]) - (p[1] - o[1]) * (q[0] - o[0]);
    let (d1, d2, d3, d4) = (cross(c, d, a), cross(c, d, b), cross(a, b, c), cross(a, b, d));
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0)) && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0)) {
        return 0.0;
    }
    let to_segment = point_segment_distance_2d;
    to_segment(a, c, d).min(to_segment(b, c, d)).min(to_segment(c, a, b)).min(to_segment(d, a, b))
}

/// The least distance in the plane from `p` to the segment `s`-`e`.
pub fn point_segment_distance_2d(p: [f64; 2], s: [f64; 2], e: [f64; 2]) -> f64 {
    let (vx, vy) = (e[0] - s[0], e[1] - s[1]);
    let len2 = vx * vx + vy * vy;
    let t = if len2 > 0.0 { (((p[0] - s[0]) * vx + (p[1] - s[1]) * vy) / len2).clamp(0.0, 1.0) } else { 0.0 };
    (p[0] - s[0] - t * vx).hypot(p[1] - s[1] - t * vy)
}

/// Convex hull (Andrew's monotone chain), counter-clockwise, without repeats.
pub fn convex_hull_2d(points: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let mut p: Vec<[f64; 2]> = points.to_vec();
    p.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    p.dedup();
    if p.len() < 3 {
        return p;
    }
    let cross = |o: [f64; 2], a: [f64; 2], b: [f64; 2]| (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
    let mut hull: Vec<[f64; 2]> = Vec::with_capacity(2 * p.len());
    for &pt in &p {
        while hull.len() >= 2 && cross(hull[hull.len() - 2], hull[hull.len() - 1], pt) <= 0.0 {
            hull.pop();
        }
        hull.push(pt);
    }
    let lower_len = hull.len() + 1;
    for &pt in p.iter().rev().skip(1) {
        while hull.len() >= lower_len && cross(hull[hull.len() - 2], hull[hull.len() - 1], pt) <= 0.0 {
            hull.pop();
        }
        hull.push(pt);
    }
    hull.pop();
    hull
}

/// The upright box (turned about Z only) of least footprint holding every
/// finite point of `points`, its first axis along the footprint's longer
/// side; `None` where no point is finite. What stands in a plant model as a
/// group is compared so with a load's box, whatever way the model turns it.
///
/// The least-area rectangle around a convex polygon has a side on one of its
/// edges; where the hull has more edges than [`MAX_HULL_EDGES_TRIED`], every
/// tenth of a degree is tried instead (a rectangle at most a few millimetres
/// per metre larger), so that the work stays bounded.
pub fn smallest_upright_box(points: &[[f64; 3]]) -> Option<Obb> {
    let finite: Vec<&[f64; 3]> = points.iter().filter(|p| p.iter().all(|v| v.is_finite())).collect();
    let (z_lo, z_hi) =
        finite.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| (lo.min(p[2]), hi.max(p[2])));
    if finite.is_empty() {
        return None;
    }
    let hull = convex_hull_2d(&finite.iter().map(|p| [p[0], p[1]]).collect::<Vec<_>>());
    let quarter = std::f64::consts::FRAC_PI_2;
    let mut angles: Vec<f64> = if hull.len() <= MAX_HULL_EDGES_TRIED {
        (0..hull.len())
            .map(|i| {
                let (a, b) = (hull[i], hull[(i + 1) % hull.len()]);
                (b[1] - a[1]).atan2(b[0] - a[0]).rem_euclid(quarter)
            })
            .collect()
    } else {
        (0..900).map(|k| k as f64 * quarter / 900.0).collect()
    };
    angles.push(0.0);
    angles.sort_by(f64::total_cmp);
    // Along direction `a` and across it: each extent's low and high end.
    let extents = |a: f64| {
        let (u, v) = ([a.cos(), a.sin()], [-a.sin(), a.cos()]);
        hull.iter().fold([f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY], |e, p| {
            let (pu, pv) = (p[0] * u[0] + p[1] * u[1], p[0] * v[0] + p[1] * v[1]);
            [e[0].min(pu), e[1].max(pu), e[2].min(pv), e[3].max(pv)]
        })
    };
    let area = |e: &[f64; 4]| (e[1] - e[0]) * (e[3] - e[2]);
    // The least area, and of (nearly) equal areas the smallest angle: one answer.
    let (a, e) =
        angles.iter().map(|&a| (a, extents(a))).fold(None, |best: Option<(f64, [f64; 4])>, (a, e)| match best {
            Some((_, b)) if area(&b) <= area(&e) * (1.0 + 1e-9) + 1e-12 => best,
            _ => Some((a, e)),
        })?;
    let (mut half_u, mut half_v) = ((e[1] - e[0]) / 2.0, (e[3] - e[2]) / 2.0);
    let (cu, cv) = ((e[0] + e[1]) / 2.0, (e[2] + e[3]) / 2.0);
    let (u, v) = (Vec3::new(a.cos(), a.sin(), 0.0), Vec3::new(-a.sin(), a.cos(), 0.0));
    let center = Point3::new(u.x * cu + v.x * cv, u.y * cu + v.y * cv, (z_lo + z_hi) / 2.0);
    let mut yaw = a;
    if half_v > half_u {
        std::mem::swap(&mut half_u, &mut half_v);
        yaw += quarter;
    }
    // The long side's direction, in (-90, 90] degrees.
    if yaw > quarter {
        yaw -= std::f64::consts::PI;
    }
    Some(Obb::new(center, crate::frame::rot_z(yaw), Vec3::new(half_u, half_v, (z_hi - z_lo) / 2.0)))
}

/// Past this many hull edges [`smallest_upright_box`] tries fixed angles.
pub const MAX_HULL_EDGES_TRIED: usize = 2048;

/// The x-range covered by a convex polygon inside the horizontal strip
/// `y0 <= y <= y1`, or `None` when the polygon misses the strip.
pub fn strip_x_range(poly: &[[f64; 2]], y0: f64, y1: f64) -> Option<(f64, f64)> {
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    let n = poly.len();
    for i in 0..n {
        let a = poly[i];
        if a[1] >= y0 && a[1] <= y1 {
            lo = lo.min(a[0]);
            hi = hi.max(a[0]);
        }
        if n < 2 {
            continue;
        }
        let b = poly[(i + 1) % n];
        let dy = b[1] - a[1];
        if dy.abs() < 1e-15 {
            continue;
        }
        for y in [y0, y1] {
            let t = (y - a[1]) / dy;
            if (0.0..=1.0).contains(&t) {
                let x = a[0] + t * (b[0] - a[0]);
                lo = lo.min(x);
                hi = hi.max(x);
            }
        }
    }
    (lo <= hi).then_some((lo, hi))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frame::rot_z;
    use proptest::prelude::*;

    /// A footprint over an area, in it, holding it, crossing a thin strip
    /// of it with no corner inside either, near an L-shaped area's notch
    /// but not over it, and within a distance of its edge.
    #[test]
    fn a_footprint_near_an_area_is_found_however_they_meet() {
        let square = |x: f64, y: f64, h: f64| vec![[x - h, y - h], [x + h, y - h], [x + h, y + h], [x - h, y + h]];
        let area = square(0.0, 0.0, 5.0);
        assert!(footprint_near_area(&square(1.0, 1.0, 1.0), &area, 0.0));
        assert!(footprint_near_area(&square(0.0, 0.0, 9.0), &area, 0.0));
        assert!(footprint_near_area(&square(5.5, 0.0, 1.0), &area, 0.0));
        assert!(!footprint_near_area(&square(7.0, 0.0, 1.0), &area, 0.0));
        assert!(!footprint_near_area(&square(7.0, 0.0, 1.0), &area, 0.99));
        assert!(footprint_near_area(&square(7.0, 0.0, 1.0), &area, 1.01));
        // A long footprint across a strip, no corner of either inside the other.
        let strip = vec![[-0.2, -10.0], [0.2, -10.0], [0.2, 10.0], [-0.2, 10.0]];
        let across = vec![[-3.0, -0.5], [3.0, -0.5], [3.0, 0.5], [-3.0, 0.5]];
        assert!(footprint_near_area(&across, &strip, 0.0));
        // An L (clockwise): a footprint in its notch is not over it.
        let l = vec![[0.0, 0.0], [0.0, 10.0], [2.0, 10.0], [2.0, 2.0], [10.0, 2.0], [10.0, 0.0]];
        assert!(!footprint_near_area(&square(6.0, 6.0, 1.0), &l, 0.0));
        assert!(footprint_near_area(&square(6.0, 1.0, 0.5), &l, 0.0));
        assert!(footprint_near_area(&square(6.0, 6.0, 1.0), &l, 3.0));
        assert!(!footprint_near_area(&[], &l, 1.0) && !footprint_near_area(&square(0.0, 0.0, 1.0), &l[..2], 1.0));
    }

    /// Lattice samples of the box volume inside the column: every one must lie
    /// within the exact range.
    fn lattice_z_range(b: &Obb, x0: f64, x1: f64, y0: f64, y1: f64) -> Option<(f64, f64)> {
        let n = 16;
        let mut lo = f64::INFINITY;
        let mut hi = f64::NEG_INFINITY;
        for i in 0..=n {
            for j in 0..=n {
                for k in 0..=n {
                    let l = Vec3::new(
                        (2.0 * i as f64 / n as f64 - 1.0) * b.half.x,
                        (2.0 * j as f64 / n as f64 - 1.0) * b.half.y,
                        (2.0 * k as f64 / n as f64 - 1.0) * b.half.z,
                    );
                    let p = b.center + b.axes * l;
                    if p.x >= x0 && p.x <= x1 && p.y >= y0 && p.y <= y1 {
                        lo = lo.min(p.z);
                        hi = hi.max(p.z);
                    }
                }
            }
        }
        (lo <= hi).then_some((lo, hi))
    }

    /// Vertical lines on a fine grid over the rectangle, each clipped exactly by
    /// the box, and points finely along the box's edges where they stand over
    /// the rectangle: an independent estimate of the range from inside.
    ///
    /// The range's extremes lie at vertices of the box clipped to the column:
    /// box corners, box edges crossing the column's sides, and the column's
    /// corner lines (on the grid, clipped exactly) meeting box faces. The lines
    /// alone miss a vertex between them by the spacing times the slope there,
    /// which is steep by a box face near vertical (a 6 mm spacing has missed
    /// 5 cm); the edge samples miss one by at most a 2000th of an edge.
    fn lines_z_range(b: &Obb, x0: f64, x1: f64, y0: f64, y1: f64) -> Option<(f64, f64)> {
        let n = 80;
        let mut lo = f64::INFINITY;
        let mut hi = f64::NEG_INFINITY;
        let ez = b.axes.transpose() * Vec3::z();
        for i in 0..=n {
            for j in 0..=n {
                let x = x0 + (x1 - x0) * i as f64 / n as f64;
                let y = y0 + (y1 - y0) * j as f64 / n as f64;
                let o = b.to_local(&Point3::new(x, y, b.center.z));
                let (mut t0, mut t1) = (f64::NEG_INFINITY, f64::INFINITY);
                let mut ok = true;
                for a in 0..3 {
                    if ez[a].abs() < 1e-12 {
                        ok &= o[a].abs() <= b.half[a];
                    } else {
                        let p = (-b.half[a] - o[a]) / ez[a];
                        let q = (b.half[a] - o[a]) / ez[a];
                        t0 = t0.max(p.min(q));
                        t1 = t1.min(p.max(q));
                    }
                }
                if ok && t0 <= t1 {
                    lo = lo.min(b.center.z + t0);
                    hi = hi.max(b.center.z + t1);
                }
            }
        }
        let m = 2000;
        for a in 0..3 {
            let (a1, a2) = ((a + 1) % 3, (a + 2) % 3);
            for (s1, s2) in [(-1.0, -1.0), (-1.0, 1.0), (1.0, -1.0), (1.0, 1.0)] {
                for t in 0..=m {
                    let mut l = Vec3::zeros();
                    l[a] = (2.0 * t as f64 / m as f64 - 1.0) * b.half[a];
                    l[a1] = s1 * b.half[a1];
                    l[a2] = s2 * b.half[a2];
                    let p = b.center + b.axes * l;
                    if p.x >= x0 && p.x <= x1 && p.y >= y0 && p.y <= y1 {
                        lo = lo.min(p.z);
                        hi = hi.max(p.z);
                    }
                }
            }
        }
        (lo <= hi).then_some((lo, hi))
    }

    fn tilted(yaw: f64, pitch: f64) -> Mat3 {
        let ry = nalgebra::Rotation3::from_axis_angle(&Vec3::y_axis(), pitch).into_inner();
        rot_z(yaw) * ry
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(crate::testing::proptest_cases(96)))]
        #[test]
        fn z_range_contains_every_sample(
            yaw in -3.2f64..3.2, pitch in -1.5f64..1.5,
            hx in 0.1f64..3.0, hy in 0.1f64..2.0, hz in 0.1f64..2.0,
            cx in -2.0f64..2.0, cy in -2.0f64..2.0,
        ) {
            let b = Obb::new(Point3::new(cx, cy, 5.0), tilted(yaw, pitch), Vec3::new(hx, hy, hz));
            let (x0, x1, y0, y1) = (0.0, 0.5, 0.0, 0.5);
            let exact = b.z_range_over_rect(x0, x1, y0, y1);
            if let Some((blo, bhi)) = lattice_z_range(&b, x0, x1, y0, y1) {
                let (lo, hi) = exact.expect("samples inside the column, exact says empty");
                prop_assert!(lo <= blo + 1e-9 && hi >= bhi - 1e-9);
            }
            match (exact, lines_z_range(&b, x0, x1, y0, y1)) {
                (Some((lo, hi)), Some((llo, lhi))) => {
                    // The line grid approaches the true extremes from inside.
                    prop_assert!(lo <= llo + 1e-9 && hi >= lhi - 1e-9);
                    prop_assert!(llo - lo < 0.05 && hi - lhi < 0.05, "{lo} {hi} vs lines {llo} {lhi}");
                }
                (None, None) => {}
                (e, l) => prop_assert!(false, "exact {e:?} vs lines {l:?}"),
            }
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(crate::testing::proptest_cases(200)))]
        #[test]
        fn the_plan_extent_is_the_footprints_bounds(
            yaw in -3.2f64..3.2, pitch in -1.5f64..1.5,
            hx in 0.05f64..30.0, hy in 0.05f64..2.0, hz in 0.05f64..2.0,
            cx in -50.0f64..50.0, cy in -50.0f64..50.0,
        ) {
            let b = Obb::new(Point3::new(cx, cy, 5.0), tilted(yaw, pitch), Vec3::new(hx, hy, hz));
            let (lo, hi) = b.plan_extent();
            let (flo, fhi) = plan_bounds(&b.footprint()).unwrap();
            for k in 0..2 {
                prop_assert!((lo[k] - flo[k]).abs() < 1e-9 && (hi[k] - fhi[k]).abs() < 1e-9, "{lo:?} {hi:?} vs {flo:?} {fhi:?}");
            }
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(crate::testing::proptest_cases(200)))]
        #[test]
        fn upright_fast_path_matches_samples(
            yaw in -3.2f64..3.2,
            hx in 0.05f64..3.0, hy in 0.05f64..2.0, hz in 0.1f64..2.0,
            cx in -3.0f64..3.0, cy in -3.0f64..3.0,
        ) {
            let b = Obb::new(Point3::new(cx, cy, 5.0), tilted(yaw, 0.0), Vec3::new(hx, hy, hz));
            prop_assert!(b.is_upright());
            let (x0, x1, y0, y1) = (0.0, 0.5, 0.0, 0.5);
            match (b.z_range_over_rect(x0, x1, y0, y1), lines_z_range(&b, x0, x1, y0, y1)) {
                (Some((lo, hi)), Some((llo, lhi))) => {
                    prop_assert!(lo <= llo + 1e-9 && hi >= lhi - 1e-9);
                    prop_assert!(llo - lo < 1e-9 && hi - lhi < 1e-9);
                }
                (None, Some(l)) => prop_assert!(false, "fast path misses a column the box reaches: {l:?}"),
                // A footprint that only grazes the rectangle between the sample lines.
                (Some(_), None) | (None, None) => {}
            }
            prop_assert_eq!(b.z_range_over_rect(x0, x1, y0, y1).is_some(), b.z_range_over_rect_by_vertices(x0, x1, y0, y1).is_some());
            if let (Some(f), Some(v)) = (b.z_range_over_rect(x0, x1, y0, y1), b.z_range_over_rect_by_vertices(x0, x1, y0, y1)) {
                prop_assert!((f.0 - v.0).abs() < 1e-9 && (f.1 - v.1).abs() < 1e-9, "{f:?} vs {v:?}");
            }
        }
    }

    #[test]
    fn axis_aligned_column() {
        let b = Obb::axis_aligned(Point3::new(0.0, 0.0, 2.0), Vec3::new(1.0, 1.0, 1.0));
        assert_eq!(b.z_range_over_rect(0.2, 0.4, 0.2, 0.4), Some((1.0, 3.0)));
        assert_eq!(b.z_range_over_rect(1.2, 1.4, 0.2, 0.4), None);
        assert_eq!(b.z_range_over_rect(-5.0, 5.0, -5.0, 5.0), Some((1.0, 3.0)));
    }

    #[test]
    fn sat() {
        let a = Obb::axis_aligned(Point3::origin(), Vec3::new(1.0, 1.0, 1.0));
        let b = Obb::new(Point3::new(2.5, 0.0, 0.0), rot_z(0.785), Vec3::new(1.0, 1.0, 1.0));
        assert!(!a.intersects(&b));
        let c = Obb::new(Point3::new(2.2, 0.0, 0.0), rot_z(0.785), Vec3::new(1.0, 1.0, 1.0));
        assert!(a.intersects(&c));
    }

    #[test]
    fn hull_and_strip() {
        let h = convex_hull_2d(&[[0.0, 0.0], [1.0, 0.0], [0.5, 0.5], [1.0, 1.0], [0.0, 1.0]]);
        assert_eq!(h.len(), 4);
        let r = strip_x_range(&[[0.0, 0.0], [2.0, 0.0], [0.0, 2.0]], 1.0, 1.5).unwrap();
        assert!((r.0 - 0.0).abs() < 1e-12 && (r.1 - 1.0).abs() < 1e-12);
        assert!(strip_x_range(&[[0.0, 0.0], [2.0, 0.0], [0.0, 2.0]], 3.0, 4.0).is_none());
    }

    proptest! {
        #![proptest_config({
            let cases = crate::testing::proptest_cases(256);
            ProptestConfig { max_global_rejects: crate::testing::proptest_rejects(cases), ..ProptestConfig::with_cases(cases) }
        })]
        /// The corners of an upright box, and points inside it, give the box
        /// back: its centre, its sizes (the longer first) and its long side's
        /// direction (a half turn is the same box).
        #[test]
        fn the_smallest_upright_box_of_a_box_is_that_box(
            cx in -50.0..50.0f64, cy in -50.0..50.0f64, cz in -5.0..20.0f64,
            hx in 0.2..6.0f64, hy in 0.2..6.0f64, hz in 0.1..3.0f64,
            yaw in -3.2..3.2f64, inside in proptest::collection::vec((-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64), 0..20),
        ) {
            prop_assume!((hx - hy).abs() > 0.01);
            let b = Obb::new(Point3::new(cx, cy, cz), rot_z(yaw), Vec3::new(hx, hy, hz));
            let mut pts: Vec<[f64; 3]> = b.corners().iter().map(|c| [c.x, c.y, c.z]).collect();
            pts.extend(inside.iter().map(|&(u, v, w)| {
                let p = b.center + b.axis(0) * (u * hx) + b.axis(1) * (v * hy) + b.axis(2) * (w * hz);
                [p.x, p.y, p.z]
            }));
            let found = smallest_upright_box(&pts).unwrap();
            prop_assert!((found.center - b.center).norm() < 1e-6, "{found:?}");
            let (long, short) = if hx > hy { (hx, hy) } else { (hy, hx) };
            prop_assert!((found.half - Vec3::new(long, short, hz)).norm() < 1e-6, "{found:?}");
            let long_axis = if hx > hy { b.axis(0) } else { b.axis(1) };
            prop_assert!(found.axis(0).dot(&long_axis).abs() > 1.0 - 1e-9);
            let yaw_found = found.axes[(1, 0)].atan2(found.axes[(0, 0)]);
            prop_assert!(yaw_found > -std::f64::consts::FRAC_PI_2 - 1e-12 && yaw_found <= std::f64::consts::FRAC_PI_2 + 1e-12);
        }
    }

    #[test]
    fn the_smallest_upright_box_leaves_out_what_is_not_finite_and_stays_bounded() {
        assert!(smallest_upright_box(&[]).is_none());
        assert!(smallest_upright_box(&[[f64::NAN, 0.0, 0.0], [f64::INFINITY, 1.0, 1.0]]).is_none());
        let one = smallest_upright_box(&[[1.0, 2.0, 3.0], [f64::NAN, 0.0, 0.0]]).unwrap();
        assert_eq!((one.center, one.half), (Point3::new(1.0, 2.0, 3.0), Vec3::zeros()));
        // A cylinder's rim of 100,000 points: more hull edges than are tried
        // one by one; a box of the circle's diameter all the same.
        let n = 100_000;
        let rim: Vec<[f64; 3]> = (0..n)
            .map(|k| {
                let a = k as f64 / n as f64 * std::f64::consts::TAU;
                [10.0 + 2.0 * a.cos(), -3.0 + 2.0 * a.sin(), (k % 2) as f64]
            })
            .collect();
        let b = smallest_upright_box(&rim).unwrap();
        assert!((b.center - Point3::new(10.0, -3.0, 0.5)).norm() < 1e-6, "{b:?}");
        assert!((b.half.x - 2.0).abs() < 1e-3 && (b.half.y - 2.0).abs() < 1e-3 && b.half.z == 0.5, "{b:?}");
    }

    /// A footprint lies within an area with every corner inside it and no
    /// edge of the area touching or crossing its own: a notch of the area
    /// across it, between its corners, leaves it outside.
    #[test]
    fn a_footprint_within_an_area_is_clear_of_its_edges() {
        let rect = [[0.0, 0.0], [4.0, 0.0], [4.0, 2.0], [0.0, 2.0]];
        let area = [[-1.0, -1.0], [10.0, -1.0], [10.0, 5.0], [-1.0, 5.0]];
        assert!(footprint_within_area(&rect, &area));
        // A corner outside; an edge of the area on its edge.
        assert!(!footprint_within_area(&rect, &[[0.5, -1.0], [10.0, -1.0], [10.0, 5.0], [0.5, 5.0]]));
        assert!(!footprint_within_area(&rect, &[[0.0, -1.0], [10.0, -1.0], [10.0, 5.0], [0.0, 5.0]]));
        // A U whose slot (x 1.5 to 2.5) runs across it: its corners are in the arms.
        let u = [[-1.0, -1.0], [1.5, -1.0], [1.5, 4.0], [2.5, 4.0], [2.5, -1.0], [6.0, -1.0], [6.0, 5.0], [-1.0, 5.0]];
        assert!(rect.iter().all(|&p| in_polygon_2d(&u, p)));
        assert!(!footprint_within_area(&rect, &u));
        // Either way round; too few corners or none.
        let mut back = area;
        back.reverse();
        assert!(footprint_within_area(&rect, &back));
        assert!(!footprint_within_area(&rect, &area[..2]) && !footprint_within_area(&[], &area));
    }
}
