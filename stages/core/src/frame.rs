//! Coordinate frames and the small geometric types shared by every stage.
//!
//! The **site frame** is right-handed, Z up, in metres, with its origin near the
//! site (the scans stage records the offset to any georeference so coordinates stay
//! small and `f32` GPU buffers keep millimetre precision). A crane's **crane frame**
//! has its origin on the slewing axis at ground level, X along the carrier's
//! heading. Poses map from a local frame into the site frame.

use nalgebra as na;

pub type Vec3 = na::Vector3<f64>;
pub type Point3 = na::Point3<f64>;
pub type Mat3 = na::Matrix3<f64>;
/// A rigid transform from a local frame into its parent frame.
pub type Pose = na::Isometry3<f64>;

/// An axis-aligned box in the site frame.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Aabb {
    pub min: [f64; 3],
    pub max: [f64; 3],
}

impl Aabb {
    /// The empty box: the identity of [`Aabb::grow`].
    pub fn empty() -> Self {
        Aabb { min: [f64::INFINITY; 3], max: [f64::NEG_INFINITY; 3] }
    }

    pub fn is_empty(&self) -> bool {
        (0..3).any(|i| self.min[i] > self.max[i])
    }

    pub fn grow(&mut self, p: [f64; 3]) {
        for i in 0..3 {
            self.min[i] = self.min[i].min(p[i]);
            self.max[i] = self.max[i].max(p[i]);
        }
    }

    pub fn union(&self, o: &Aabb) -> Aabb {
        let mut r = *self;
        if !o.is_empty() {
            r.grow(o.min);
            r.grow(o.max);
        }
        r
    }

    pub fn from_points<'a>(pts: impl IntoIterator<Item = &'a [f64; 3]>) -> Aabb {
        let mut b = Aabb::empty();
        for p in pts {
            b.grow(*p);
        }
        b
    }

    pub fn expanded(&self, m: f64) -> Aabb {
        Aabb {
            min: [self.min[0] - m, self.min[1] - m, self.min[2] - m],
            max: [self.max[0] + m, self.max[1] + m, self.max[2] + m],
        }
    }

    pub fn intersects(&self, o: &Aabb) -> bool {
        (0..3).all(|i| self.min[i] <= o.max[i] && o.min[i] <= self.max[i])
    }

    pub fn center(&self) -> [f64; 3] {
        [0.5 * (self.min[0] + self.max[0]), 0.5 * (self.min[1] + self.max[1]), 0.5 * (self.min[2] + self.max[2])]
    }

    /// `[minx, miny, minz, maxx, maxy, maxz]`, the order `inspect --json` prints.
    pub fn to_array(&self) -> [f64; 6] {
        [self.min[0], self.min[1], self.min[2], self.max[0], self.max[1], self.max[2]]
    }
}

/// Rotation about Z by `yaw_rad`, counter-clockwise seen from above.
pub fn rot_z(yaw_rad: f64) -> Mat3 {
    let (s, c) = yaw_rad.sin_cos();
    Mat3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0)
}

/// A pose from a translation and a yaw about Z.
pub fn pose_xyz_yaw(x: f64, y: f64, z: f64, yaw_rad: f64) -> Pose {
    Pose::from_parts(na::Translation3::new(x, y, z), na::UnitQuaternion::from_axis_angle(&Vec3::z_axis(), yaw_rad))
}

/// A 4x4 row-major matrix as written in registration.json.
pub fn pose_to_rows(p: &Pose) -> [[f64; 4]; 4] {
    let m = p.to_homogeneous();
    let mut r = [[0.0; 4]; 4];
    for (i, row) in r.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate() {
            *v = m[(i, j)];
        }
    }
    r
}

/// The inverse of [`pose_to_rows`]; the rotation part is re-orthonormalised.
pub fn pose_from_rows(r: &[[f64; 4]; 4]) -> Pose {
    let rot = Mat3::new(r[0][0], r[0][1], r[0][2], r[1][0], r[1][1], r[1][2], r[2][0], r[2][1], r[2][2]);
    let q = na::UnitQuaternion::from_matrix(&rot);
    Pose::from_parts(na::Translation3::new(r[0][3], r[1][3], r[2][3]), q)
}

/// Rotation angle of a pose in radians (0 for the identity).
pub fn rotation_angle(p: &Pose) -> f64 {
    p.rotation.angle()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pose_rows_roundtrip() {
        let p = pose_xyz_yaw(1.0, 2.0, 3.0, 0.7);
        let q = pose_from_rows(&pose_to_rows(&p));
        assert!((p.translation.vector - q.translation.vector).norm() < 1e-12);
        assert!(p.rotation.angle_to(&q.rotation) < 1e-12);
    }

    #[test]
    fn aabb_grow() {
        let b = Aabb::from_points(&[[0.0, 1.0, 2.0], [-1.0, 5.0, 0.0]]);
        assert_eq!(b.to_array(), [-1.0, 1.0, 0.0, 0.0, 5.0, 2.0]);
        assert!(Aabb::empty().is_empty());
    }
}
