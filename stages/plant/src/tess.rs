//! Tessellation of RVM primitives with a chord tolerance, enclosing each one.
//!
//! **The mesh of a primitive encloses it**: no point of the primitive's solid
//! lies outside its mesh, and no point of the mesh lies farther than the
//! tolerance outside the primitive's surface. A mesh whose vertices lay on the
//! surface would cut inside it along every chord, by up to the tolerance, and
//! every clearance measured to the plant later would read that much too large.
//! So the polygons are circumscribed instead: a circle of radius `r` cut into
//! steps of `theta` has its vertices at `r / cos(theta / 2)`, which puts each
//! chord tangent to the circle at its middle, and the step is the largest for
//! which that stays within the tolerance, `cos(theta / 2) >= r / (r + tol)`
//! ([`segments`]). Doubly curved surfaces (sphere, dishes, circular torus) are
//! inflated for both directions (see their functions) and share the tolerance
//! between them. Boxes, pyramids and facet groups are drawn as given.
//!
//! Each closed convex primitive is one convex part; tori are split into one part
//! per segment, each of which is convex, so depth maps may fill parts between
//! their lowest and highest surfaces. Facet groups are surfaces. Caps that a
//! connected primitive hides can be left out ([`Caps`]).
//!
//! Must not: put a vertex where it would make the mesh smaller than the
//! primitive; the property tests below sample each shape's surface and check it
//! lies inside its mesh.

use crate::rvm::{Polygon, Primitive, Shape};
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// Which end caps to emit: [bottom/start, top/end].
pub type Caps = [bool; 2];

/// A tessellated primitive in its local frame (file units) plus its parts.
#[derive(Debug, Clone, Default)]
pub struct Tess {
    pub vertices: Vec<[f64; 3]>,
    pub triangles: Vec<[u32; 3]>,
    /// Per triangle: which part of this primitive it belongs to.
    pub part: Vec<u32>,
    /// Per part: whether it bounds a convex solid.
    pub convex: Vec<bool>,
}

impl Tess {
    fn vertex(&mut self, p: [f64; 3]) -> u32 {
        self.vertices.push(p);
        (self.vertices.len() - 1) as u32
    }
    fn tri(&mut self, a: u32, b: u32, c: u32, part: u32) {
        self.triangles.push([a, b, c]);
        self.part.push(part);
    }
    fn quad(&mut self, a: u32, b: u32, c: u32, d: u32, part: u32) {
        self.tri(a, b, c, part);
        self.tri(a, c, d, part);
    }
    /// Faces joining a ring (or a single pole vertex) to the next ring below it.
    fn band(&mut self, prev: &[u32], ring: &[u32], part: u32) {
        let n = ring.len();
        if prev.len() == 1 {
            for i in 0..n {
                self.tri(prev[0], ring[i], ring[(i + 1) % n], part);
            }
        } else {
            for i in 0..n {
                let j = (i + 1) % n;
                self.quad(prev[i], ring[i], ring[j], prev[j], part);
            }
        }
    }
    /// A quad that may not be planar (a tapered snout with sheared ends), cut
    /// along the diagonal that folds outwards, so that the two triangles are
    /// the outer side of the four corners' hull and the surface between the
    /// corners' lines stays inside.
    fn outer_quad(&mut self, a: u32, b: u32, c: u32, d: u32, part: u32) {
        let [pa, pb, pc, pd] = [a, b, c, d].map(|i| self.vertices[i as usize]);
        let sub = |p: [f64; 3], q: [f64; 3]| [p[0] - q[0], p[1] - q[1], p[2] - q[2]];
        let (u, v, w) = (sub(pb, pa), sub(pc, pa), sub(pd, pa));
        let n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
        let above = n[0] * w[0] + n[1] * w[1] + n[2] * w[2];
        let size = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt() * (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
        if above > 1e-9 * size {
            // `d` lies outside the plane of a, b, c: the other diagonal is the ridge.
            self.tri(a, b, d, part);
            self.tri(b, c, d, part);
        } else {
            self.quad(a, b, c, d, part);
        }
    }
    /// A closed ring of vertex indices as a fan (convex planar polygon); `flip`
    /// reverses the winding.
    fn disc(&mut self, ring: &[u32], flip: bool, part: u32) {
        for i in 1..ring.len().saturating_sub(1) {
            if flip {
                self.tri(ring[0], ring[i + 1], ring[i], part);
            } else {
                self.tri(ring[0], ring[i], ring[i + 1], part);
            }
        }
    }
}

/// Steps for `arc` radians of a circle of radius `r_m` (metres) such that its
/// circumscribed polygon (vertices at [`circumscribed`]) stays within `tol_m`
/// outside it; at least `min`, and no step over a third of a turn (where the
/// vertices would run off to twice the radius and beyond), at most 4096.
pub fn segments(arc: f64, r_m: f64, tol_m: f64, min: usize) -> usize {
    let min = if arc > 0.0 { min.max((arc / (TAU / 3.0)).ceil().min(4096.0) as usize) } else { min };
    if !(r_m > 0.0) || !(arc > 0.0) {
        return min.min(4096);
    }
    // cos(theta / 2) = r / (r + tol): the vertex radius r / cos(theta / 2) is r + tol.
    let theta = 2.0 * (r_m / (r_m + tol_m)).clamp(-1.0, 1.0).acos();
    let n = (arc / theta).ceil();
    (if n.is_finite() { n.min(4096.0) as usize } else { 4096 }).max(min).min(4096)
}

/// The radius to put the vertices of a polygon at, with steps of `step`
/// radians, so that its edges touch the circle of radius `r` and lie outside it.
pub fn circumscribed(r: f64, step: f64) -> f64 {
    r / (step / 2.0).cos()
}

/// The part of a tolerance `tol` each of two directions may take when both
/// inflate the same radius `r`: `(1 + t / r)^2 = 1 + tol / r`, so the two
/// factors together move the surface out by `tol` at most.
fn shared_tolerance(r: f64, tol: f64) -> f64 {
    if r > 0.0 { r * ((1.0 + tol / r).sqrt() - 1.0) } else { tol / 2.0 }
}

/// Scale of a 3x4 matrix: the largest column length (file units to metres).
pub fn matrix_scale(m: &[f32; 12]) -> f64 {
    (0..3)
        .map(|c| ((m[3 * c] as f64).powi(2) + (m[3 * c + 1] as f64).powi(2) + (m[3 * c + 2] as f64).powi(2)).sqrt())
        .fold(0.0, f64::max)
}

/// Applies a 3x4 column-major matrix.
pub fn transform(m: &[f32; 12], p: [f64; 3]) -> [f64; 3] {
    let c = |i: usize| m[i] as f64;
    [
        c(0) * p[0] + c(3) * p[1] + c(6) * p[2] + c(9),
        c(1) * p[0] + c(4) * p[1] + c(7) * p[2] + c(10),
        c(2) * p[0] + c(5) * p[1] + c(8) * p[2] + c(11),
    ]
}

/// Tessellates a primitive in its local frame; `tol_local` is the tolerance in
/// file units (metres divided by the matrix scale). Returns `None` for shapes
/// without a surface (lines).
pub fn tessellate(p: &Primitive, tol_local: f64, caps: Caps) -> Option<Tess> {
    let t = match form(&p.shape)? {
        Form::Box(h) => boxed(h),
        Form::Pyramid { bottom, top, offset, height } => pyramid(bottom, top, offset, height),
        Form::Snout { rb, rt, h, offset, bshear, tshear } => snout(rb, rt, h, offset, bshear, tshear, tol_local, caps),
        Form::SphereCap { r, arc, shift_z, scale_z } => sphere_cap(r, arc, shift_z, scale_z, tol_local),
        Form::CircularTorus { offset, radius, angle } => circular_torus(offset, radius, angle, tol_local, caps),
        Form::RectangularTorus { ri, ro, h, angle } => rectangular_torus(ri, ro, h, angle, tol_local, caps),
        Form::Facets(polygons) => facets(polygons),
    };
    Some(t)
}

/// How many triangles [`tessellate`] makes of `p`, found without making them,
/// so that a stage can refuse a model too large to hold before it allocates
/// (an RVM file of a few hundred bytes per primitive can ask for millions of
/// triangles each). Exact for the analytic shapes; for facet groups an upper
/// bound (ear clipping a polygon of `v` vertices and `h` holes makes at most
/// `v + 2h - 2` triangles, fewer where it drops degenerate ones).
pub fn triangle_count(p: &Primitive, tol_local: f64, caps: Caps) -> u64 {
    let cap = |on: bool, ring: u64| if on { ring.saturating_sub(2) } else { 0 };
    match form(&p.shape) {
        None => 0,
        Some(Form::Box(_) | Form::Pyramid { .. }) => 12,
        Some(Form::Snout { rb, rt, .. }) => {
            let n = snout_segments(rb, rt, tol_local) as u64;
            2 * n + cap(caps[0] && rb > 0.0, n) + cap(caps[1] && rt > 0.0, n)
        }
        Some(Form::SphereCap { r, arc, scale_z, .. }) => {
            let Some((n_lon, n_lat, full)) = sphere_segments(r, arc, scale_z, tol_local) else { return 0 };
            let (n_lon, n_lat) = (n_lon as u64, n_lat as u64);
            // Fans at the top pole and (full) the bottom pole, quads between
            // rings, (shallow dishes) a band down to the base plane, and
            // (dishes) the flat base.
            let drop = if dish_drops(arc, full) { 2 * n_lon } else { 0 };
            if full { 2 * n_lon * (n_lat - 1) } else { n_lon + 2 * n_lon * (n_lat - 1) + drop + cap(true, n_lon) }
        }
        Some(Form::CircularTorus { offset, radius, angle }) => {
            let (n_u, n_v) = circular_torus_segments(offset, radius, angle, tol_local);
            let (n_u, n_v) = (n_u as u64, n_v as u64);
            let open = !(angle >= TAU - 1e-6) && radius > 0.0;
            2 * n_u * n_v + cap(open && caps[0], n_v) + cap(open && caps[1], n_v)
        }
        Some(Form::RectangularTorus { ro, angle, .. }) => {
            let n_u = segments(angle, ro, tol_local, 1) as u64;
            let open = angle < TAU - 1e-6;
            8 * n_u + if open && caps[0] { 2 } else { 0 } + if open && caps[1] { 2 } else { 0 }
        }
        Some(Form::Facets(polys)) => polys
            .iter()
            .map(|poly| {
                let contours = poly.contours.iter().filter(|c| c.len() >= 3);
                let (v, n) = contours.fold((0u64, 0u64), |(v, n), c| (v + c.len() as u64, n + 1));
                // Each hole is bridged to the outer contour: 2 more triangles.
                (v + 2 * n.saturating_sub(1)).saturating_sub(2)
            })
            .sum(),
    }
}

/// A primitive's shape as the surface the tessellation draws: the RVM
/// parameters turned into the few analytic forms, in f64 file units.
enum Form<'a> {
    /// Half lengths.
    Box([f64; 3]),
    Pyramid {
        bottom: [f32; 2],
        top: [f32; 2],
        offset: [f32; 2],
        height: f32,
    },
    Snout {
        rb: f64,
        rt: f64,
        h: f64,
        offset: [f64; 2],
        bshear: [f64; 2],
        tshear: [f64; 2],
    },
    SphereCap {
        r: f64,
        arc: f64,
        shift_z: f64,
        scale_z: f64,
    },
    CircularTorus {
        offset: f64,
        radius: f64,
        angle: f64,
    },
    RectangularTorus {
        ri: f64,
        ro: f64,
        h: f64,
        angle: f64,
    },
    Facets(&'a [Polygon]),
}

fn form(shape: &Shape) -> Option<Form<'_>> {
    Some(match shape {
        Shape::Box { lengths } => Form::Box(lengths.map(|v| v as f64 / 2.0)),
        Shape::Pyramid { bottom, top, offset, height } => {
            Form::Pyramid { bottom: *bottom, top: *top, offset: *offset, height: *height }
        }
        Shape::Cylinder { radius, height } => Form::Snout {
            rb: *radius as f64,
            rt: *radius as f64,
            h: *height as f64,
            offset: [0.0; 2],
            bshear: [0.0; 2],
            tshear: [0.0; 2],
        },
        Shape::Snout { radius_b, radius_t, height, offset, bshear, tshear } => Form::Snout {
            rb: *radius_b as f64,
            rt: *radius_t as f64,
            h: *height as f64,
            offset: offset.map(|v| v as f64),
            bshear: bshear.map(|v| v as f64),
            tshear: tshear.map(|v| v as f64),
        },
        Shape::Sphere { diameter } => {
            Form::SphereCap { r: *diameter as f64 / 2.0, arc: PI, shift_z: 0.0, scale_z: 1.0 }
        }
        Shape::EllipticalDish { base_radius, height } => {
            let r = *base_radius as f64;
            let scale_z = if r > 0.0 { *height as f64 / r } else { 0.0 };
            Form::SphereCap { r, arc: FRAC_PI_2, shift_z: 0.0, scale_z }
        }
        Shape::SphericalDish { base_radius, height } => {
            let (rc, h) = (*base_radius as f64, *height as f64);
            if !(h > 0.0) {
                Form::SphereCap { r: rc, arc: 0.0, shift_z: 0.0, scale_z: 1.0 }
            } else {
                let rs = (rc * rc + h * h) / (2.0 * h);
                let mut arc = (rc / rs).clamp(-1.0, 1.0).asin();
                if rc < h {
                    arc = PI - arc;
                }
                Form::SphereCap { r: rs, arc, shift_z: h - rs, scale_z: 1.0 }
            }
        }
        Shape::CircularTorus { offset, radius, angle } => {
            // A sweep past a full turn is the full torus.
            Form::CircularTorus { offset: *offset as f64, radius: *radius as f64, angle: (*angle as f64).min(TAU) }
        }
        Shape::RectangularTorus { inner_radius, outer_radius, height, angle } => Form::RectangularTorus {
            ri: *inner_radius as f64,
            ro: *outer_radius as f64,
            h: *height as f64,
            angle: (*angle as f64).min(TAU),
        },
        Shape::FacetGroup { polygons } => Form::Facets(polygons),
        Shape::Line { .. } => return None,
    })
}

fn boxed(h: [f64; 3]) -> Tess {
    let mut t = Tess { convex: vec![true], ..Default::default() };
    let v: Vec<u32> = (0..8)
        .map(|k| {
            t.vertex([
                if k & 1 == 0 { -h[0] } else { h[0] },
                if k & 2 == 0 { -h[1] } else { h[1] },
                if k & 4 == 0 { -h[2] } else { h[2] },
            ])
        })
        .collect();
    for q in [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]] {
        t.quad(v[q[0]], v[q[1]], v[q[2]], v[q[3]], 0);
    }
    t
}

fn pyramid(bottom: [f32; 2], top: [f32; 2], offset: [f32; 2], height: f32) -> Tess {
    let (bx, by) = (bottom[0] as f64 / 2.0, bottom[1] as f64 / 2.0);
    let (tx, ty) = (top[0] as f64 / 2.0, top[1] as f64 / 2.0);
    let (ox, oy) = (offset[0] as f64 / 2.0, offset[1] as f64 / 2.0);
    let h2 = height as f64 / 2.0;
    let mut t = Tess { convex: vec![true], ..Default::default() };
    let b: Vec<u32> =
        [(-bx, -by), (bx, -by), (bx, by), (-bx, by)].iter().map(|(x, y)| t.vertex([x - ox, y - oy, -h2])).collect();
    let u: Vec<u32> =
        [(-tx, -ty), (tx, -ty), (tx, ty), (-tx, ty)].iter().map(|(x, y)| t.vertex([x + ox, y + oy, h2])).collect();
    for i in 0..4 {
        let j = (i + 1) % 4;
        t.quad(b[i], b[j], u[j], u[i], 0);
    }
    t.quad(b[3], b[2], b[1], b[0], 0);
    t.quad(u[0], u[1], u[2], u[3], 0);
    t
}

/// Snout (cylinder when radii are equal and there is no offset or shear).
fn snout_segments(rb: f64, rt: f64, tol: f64) -> usize {
    segments(TAU, rb.max(rt), tol, 3)
}

/// Both end rings are circumscribed with the same factor; the ring points stay
/// in their (sheared) end planes. At any angle the surface runs straight from
/// the bottom ring to the top one, so it lies in the wedge spanned by the two
/// neighbouring vertices of each ring and the two centres, inside the mesh
/// (whose side quads fold outwards, [`Tess::outer_quad`]).
fn snout(rb: f64, rt: f64, h: f64, offset: [f64; 2], bshear: [f64; 2], tshear: [f64; 2], tol: f64, caps: Caps) -> Tess {
    let n = snout_segments(rb, rt, tol);
    let out = circumscribed(1.0, TAU / n as f64);
    let (rb, rt) = (rb * out, rt * out);
    let (ox, oy) = (offset[0] / 2.0, offset[1] / 2.0);
    let (mb, mt) = ([bshear[0].tan(), bshear[1].tan()], [tshear[0].tan(), tshear[1].tan()]);
    let mut t = Tess { convex: vec![true], ..Default::default() };
    let mut bot = Vec::with_capacity(n);
    let mut topr = Vec::with_capacity(n);
    for i in 0..n {
        let a = TAU * i as f64 / n as f64;
        let (c, s) = (a.cos(), a.sin());
        bot.push(t.vertex([rb * c - ox, rb * s - oy, -h / 2.0 + mb[0] * rb * c + mb[1] * rb * s]));
        topr.push(t.vertex([rt * c + ox, rt * s + oy, h / 2.0 + mt[0] * rt * c + mt[1] * rt * s]));
    }
    for i in 0..n {
        let j = (i + 1) % n;
        t.outer_quad(bot[i], bot[j], topr[j], topr[i], 0);
    }
    if caps[0] && rb > 0.0 {
        t.disc(&bot, true, 0);
    }
    if caps[1] && rt > 0.0 {
        t.disc(&topr, false, 0);
    }
    t
}

/// Longitudes and latitude rings of [`sphere_cap`], and whether it is a full
/// sphere; `None` when it has no surface. The two directions share the
/// tolerance ([`shared_tolerance`]) at the larger of the radii the z scale gives.
fn sphere_segments(r: f64, arc: f64, scale_z: f64, tol: f64) -> Option<(usize, usize, bool)> {
    if !(r > 0.0) || !(arc > 0.0) {
        return None;
    }
    let reff = r * scale_z.max(1.0);
    let t = shared_tolerance(reff, tol);
    let n_lon = segments(TAU, reff, t, 3);
    let full = arc >= PI - 1e-9;
    let n_lat = segments(arc, reff, t, if full { 2 } else { 1 });
    Some((n_lon, n_lat, full))
}

/// Whether a dish of `arc` gets a ring dropped from its last latitude ring to
/// its base plane: the inflated ring of a dish shallower than a hemisphere lies
/// above the plane its solid stands on.
fn dish_drops(arc: f64, full: bool) -> bool {
    !full && arc < FRAC_PI_2
}

/// A sphere-based shape: the part of a sphere of radius `r` within `arc` of its
/// top pole, centre at z = `shift_z`, z scaled by `scale_z`, closed by a flat base
/// when `arc` < pi (dishes).
///
/// The vertices lie on a sphere of radius `r / (cos(dlat / 2) cos(dlon / 2))`:
/// in the meridian plane the latitude polygon then circumscribes a circle of
/// `r / cos(dlon / 2)`, and halfway between two longitudes, where the flat faces
/// come closest to the axis, they are `cos(dlon / 2)` nearer to it, which leaves
/// the sphere of radius `r` inside. The z scale is applied last; an affine map
/// keeps one solid inside another. A dish shallower than a hemisphere drops its
/// last ring straight down to the true base plane.
fn sphere_cap(r: f64, arc: f64, shift_z: f64, scale_z: f64, tol: f64) -> Tess {
    let mut t = Tess { convex: vec![true], ..Default::default() };
    let Some((n_lon, n_lat, full)) = sphere_segments(r, arc, scale_z, tol) else { return t };
    let out = circumscribed(circumscribed(r, arc / n_lat as f64), TAU / n_lon as f64);
    let ring_at = |t: &mut Tess, rho: f64, z: f64| -> Vec<u32> {
        (0..n_lon)
            .map(|i| {
                let a = TAU * i as f64 / n_lon as f64;
                t.vertex([rho * a.cos(), rho * a.sin(), z * scale_z + shift_z])
            })
            .collect()
    };
    let top = t.vertex([0.0, 0.0, out * scale_z + shift_z]);
    let mut prev: Vec<u32> = vec![top];
    for k in 1..=n_lat {
        let th = arc * k as f64 / n_lat as f64;
        if full && k == n_lat {
            let bottom = t.vertex([0.0, 0.0, -out * scale_z + shift_z]);
            for i in 0..prev.len() {
                let j = (i + 1) % prev.len();
                t.tri(prev[j], prev[i], bottom, 0);
            }
            return t;
        }
        let ring = ring_at(&mut t, out * th.sin(), out * th.cos());
        t.band(&prev, &ring, 0);
        prev = ring;
    }
    if dish_drops(arc, full) {
        let ring = ring_at(&mut t, out * arc.sin(), r * arc.cos());
        t.band(&prev, &ring, 0);
        prev = ring;
    }
    // Flat base closing a dish.
    t.disc(&prev, true, 0);
    t
}

/// Segments along (u) and around (v) a circular torus. With the tube's step
/// taking `t` of the tolerance at the tube radius and the sweep's `t / 2` at
/// the outer radius, the mesh lies at most `2t + t^2 / (2r)` outside the
/// surface (outermost at the rings' vertices and, halfway along a segment, on
/// the side facing the axis), within the tolerance by [`shared_tolerance`].
///
/// A tube nearly as fat as its sweep, at a tolerance near its radius, would
/// put the inflated rings across the axis, where the segments fold through each
/// other and no longer bound a solid; the tolerance is then halved until the
/// rings stay on their side (possible whenever the tube is thinner than the
/// sweep, as every real elbow is).
fn circular_torus_segments(offset: f64, radius: f64, angle: f64, tol: f64) -> (usize, usize) {
    let mut t = shared_tolerance(radius, tol);
    loop {
        let n_u = segments(angle, offset + radius, t / 2.0, 1);
        let n_v = segments(TAU, radius, t, 3);
        let clear = torus_tube_radius(offset, radius, angle, n_u, n_v) < offset.abs();
        if clear || radius >= offset.abs() || (n_u >= 4096 && n_v >= 4096) || !(t > 0.0) {
            return (n_u, n_v);
        }
        t /= 2.0;
    }
}

/// The radius of the rings' vertices around the tube's centre (see [`circular_torus`]).
fn torus_tube_radius(offset: f64, radius: f64, angle: f64, n_u: usize, n_v: usize) -> f64 {
    let half_u = (angle / n_u as f64 / 2.0).cos();
    let section = (radius + offset.abs() * (1.0 - half_u)) / half_u;
    circumscribed(section, TAU / n_v as f64)
}

/// Rings of the tube's section at `n_u + 1` sweep angles. Halfway between two
/// rings the faces come `cos(du / 2)` nearer to the axis than the rings (both
/// the tube's centre and its section shrink towards the axis), so the rings'
/// circumscribed radius is raised until that shrunken section still holds the
/// true one: `(r + R (1 - cos(du / 2))) / cos(du / 2)`, for a tube of radius
/// `r` swept at `R`.
fn circular_torus(offset: f64, radius: f64, angle: f64, tol: f64, caps: Caps) -> Tess {
    let mut t = Tess::default();
    let (n_u, n_v) = circular_torus_segments(offset, radius, angle, tol);
    let tube = torus_tube_radius(offset, radius, angle, n_u, n_v);
    let rings: Vec<Vec<u32>> = (0..=n_u)
        .map(|k| {
            let u = angle * k as f64 / n_u as f64;
            (0..n_v)
                .map(|i| {
                    let v = TAU * i as f64 / n_v as f64;
                    let w = offset + tube * v.cos();
                    t.vertex([w * u.cos(), w * u.sin(), tube * v.sin()])
                })
                .collect()
        })
        .collect();
    for k in 0..n_u {
        t.convex.push(true);
        for i in 0..n_v {
            let j = (i + 1) % n_v;
            t.quad(rings[k][i], rings[k + 1][i], rings[k + 1][j], rings[k][j], k as u32);
        }
    }
    let closed = angle >= TAU - 1e-6;
    if !closed && radius > 0.0 {
        if caps[0] {
            t.disc(&rings[0], false, 0);
        }
        if caps[1] {
            t.disc(&rings[n_u], true, (n_u - 1) as u32);
        }
    }
    t
}

fn rectangular_torus(ri: f64, ro: f64, h: f64, angle: f64, tol: f64, caps: Caps) -> Tess {
    let mut t = Tess::default();
    let n_u = segments(angle, ro, tol, 1);
    // The outer wall's chords would cut into the solid: circumscribe it. The
    // inner wall's chords run into the hole, outside the solid.
    let ro = circumscribed(ro, angle / n_u as f64);
    let corners = [(ro, -h / 2.0), (ri, -h / 2.0), (ri, h / 2.0), (ro, h / 2.0)];
    let rings: Vec<[u32; 4]> = (0..=n_u)
        .map(|k| {
            let u = angle * k as f64 / n_u as f64;
            corners.map(|(r, z)| t.vertex([r * u.cos(), r * u.sin(), z]))
        })
        .collect();
    for k in 0..n_u {
        t.convex.push(true);
        for c in 0..4 {
            let d = (c + 1) % 4;
            t.quad(rings[k][c], rings[k][d], rings[k + 1][d], rings[k + 1][c], k as u32);
        }
    }
    if angle < TAU - 1e-6 {
        if caps[0] {
            let r = rings[0];
            t.quad(r[0], r[3], r[2], r[1], 0);
        }
        if caps[1] {
            let r = rings[n_u];
            t.quad(r[0], r[1], r[2], r[3], (n_u - 1) as u32);
        }
    }
    t
}

/// Polygons with holes: projected on their own plane (Newell normal) and cut
/// into triangles by ear clipping.
fn facets(polys: &[Polygon]) -> Tess {
    let mut t = Tess { convex: vec![false], ..Default::default() };
    let mut ec = earcut::Earcut::<f64>::new();
    let mut out: Vec<u32> = Vec::new();
    for poly in polys {
        let contours: Vec<&Vec<([f32; 3], [f32; 3])>> = poly.contours.iter().filter(|c| c.len() >= 3).collect();
        if contours.is_empty() {
            continue;
        }
        let pts: Vec<[f64; 3]> = contours.iter().flat_map(|c| c.iter().map(|(p, _)| p.map(|v| v as f64))).collect();
        if contours.len() == 1 && pts.len() == 3 {
            let a = t.vertex(pts[0]);
            let b = t.vertex(pts[1]);
            let c = t.vertex(pts[2]);
            t.tri(a, b, c, 0);
            continue;
        }
        // Newell normal of the outer contour picks the projection plane.
        let outer = contours[0];
        let mut n = [0.0f64; 3];
        for i in 0..outer.len() {
            let (p, q) = (outer[i].0.map(|v| v as f64), outer[(i + 1) % outer.len()].0.map(|v| v as f64));
            n[0] += (p[1] - q[1]) * (p[2] + q[2]);
            n[1] += (p[2] - q[2]) * (p[0] + q[0]);
            n[2] += (p[0] - q[0]) * (p[1] + q[1]);
        }
        let drop = (0..3).max_by(|&a, &b| n[a].abs().total_cmp(&n[b].abs())).unwrap_or(2);
        let (i0, i1) = match drop {
            0 => (1, 2),
            1 => (2, 0),
            _ => (0, 1),
        };
        let flat: Vec<[f64; 2]> = pts.iter().map(|p| [p[i0], p[i1]]).collect();
        let mut holes: Vec<u32> = Vec::new();
        let mut acc = 0u32;
        for c in &contours[..contours.len() - 1] {
            acc += c.len() as u32;
            holes.push(acc);
        }
        ec.earcut(flat.iter().copied(), &holes, &mut out);
        let base = t.vertices.len() as u32;
        t.vertices.extend_from_slice(&pts);
        // Face every triangle the way the contour winds (its Newell normal).
        for tri in out.chunks(3) {
            if tri.len() == 3 {
                let (p, q, r) = (pts[tri[0] as usize], pts[tri[1] as usize], pts[tri[2] as usize]);
                let u = [q[0] - p[0], q[1] - p[1], q[2] - p[2]];
                let v = [r[0] - p[0], r[1] - p[1], r[2] - p[2]];
                let c = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
                let (a, b, c2) = (base + tri[0], base + tri[1], base + tri[2]);
                if c[0] * n[0] + c[1] * n[1] + c[2] * n[2] < 0.0 { t.tri(a, c2, b, 0) } else { t.tri(a, b, c2, 0) }
            }
        }
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rvm::{Primitive, Role, Shape};
    use proptest::prelude::*;

    const IDENTITY: [f32; 12] = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0];

    fn prim(shape: Shape) -> Primitive {
        Primitive { role: Role::Primitive, matrix: IDENTITY, bbox_local: [0.0; 6], shape, offset: 0 }
    }

    fn volume(t: &Tess) -> f64 {
        t.triangles
            .iter()
            .map(|tr| {
                let (a, b, c) = (t.vertices[tr[0] as usize], t.vertices[tr[1] as usize], t.vertices[tr[2] as usize]);
                (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                    + a[2] * (b[0] * c[1] - b[1] * c[0]))
                    / 6.0
            })
            .sum()
    }

    fn area(t: &Tess) -> f64 {
        t.triangles
            .iter()
            .map(|tr| {
                let (a, b, c) = (t.vertices[tr[0] as usize], t.vertices[tr[1] as usize], t.vertices[tr[2] as usize]);
                let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
                let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
                let x = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
                0.5 * (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt()
            })
            .sum()
    }

    /// Largest distance from sampled points of every triangle (and every vertex)
    /// to the analytic surface, given by `dist`.
    fn max_error(t: &Tess, dist: &dyn Fn([f64; 3]) -> f64) -> f64 {
        let mut worst: f64 = 0.0;
        const N: usize = 6;
        for tr in &t.triangles {
            let (a, b, c) = (t.vertices[tr[0] as usize], t.vertices[tr[1] as usize], t.vertices[tr[2] as usize]);
            for i in 0..=N {
                for j in 0..=(N - i) {
                    let (u, v) = (i as f64 / N as f64, j as f64 / N as f64);
                    let w = 1.0 - u - v;
                    let p = [
                        a[0] * w + b[0] * u + c[0] * v,
                        a[1] * w + b[1] * u + c[1] * v,
                        a[2] * w + b[2] * u + c[2] * v,
                    ];
                    worst = worst.max(dist(p));
                }
            }
        }
        worst
    }

    fn cyl_dist(r: f64, h: f64) -> impl Fn([f64; 3]) -> f64 {
        move |p: [f64; 3]| {
            let rho = (p[0] * p[0] + p[1] * p[1]).sqrt();
            let side = if p[2].abs() <= h / 2.0 + 1e-9 { (rho - r).abs() } else { f64::INFINITY };
            let cap = if rho <= r + 1e-9 { (p[2].abs() - h / 2.0).abs() } else { f64::INFINITY };
            side.min(cap)
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(liftplan_core::testing::proptest_cases(40)))]

        #[test]
        fn cylinder_within_tolerance(r in 0.0f64..3.0, h in 0.0f64..5.0, tol in 0.001f64..0.2) {
            let t = tessellate(&prim(Shape::Cylinder { radius: r as f32, height: h as f32 }), tol, [true, true]).unwrap();
            let (r, h) = (r as f32 as f64, h as f32 as f64);
            prop_assert!(max_error(&t, &cyl_dist(r, h)) <= tol * 1.0001 + 1e-6);
            // The vertices lie outside the side (or on the caps' planes), never inside.
            for v in &t.vertices {
                let rho = (v[0] * v[0] + v[1] * v[1]).sqrt();
                prop_assert!(rho >= r * (1.0 - 1e-12) || (v[2].abs() - h / 2.0).abs() < 1e-9, "{v:?}");
            }
        }

        #[test]
        fn sphere_within_tolerance(d in 0.0f64..6.0, tol in 0.001f64..0.2) {
            let t = tessellate(&prim(Shape::Sphere { diameter: d as f32 }), tol, [true, true]).unwrap();
            let r = d as f32 as f64 / 2.0;
            let dist = |p: [f64; 3]| ((p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt() - r).abs();
            prop_assert!(max_error(&t, &dist) <= tol * 1.0001 + 1e-6);
        }

        #[test]
        fn torus_within_tolerance(big in 0.2f64..3.0, small_frac in 0.0f64..0.9, angle in 0.01f64..6.2, tol in 0.001f64..0.2) {
            let r = big * small_frac;
            let t = tessellate(&prim(Shape::CircularTorus { offset: big as f32, radius: r as f32, angle: angle as f32 }), tol, [true, true]).unwrap();
            let (big, r, angle) = (big as f32 as f64, r as f32 as f64, angle as f32 as f64);
            let dist = |p: [f64; 3]| {
                // A fat tube's inflated rings may reach past the axis: a point
                // there belongs to the half-plane opposite its own.
                let tube_at = |u: f64, w: f64| {
                    if u.rem_euclid(TAU) <= angle + 1e-6 || angle >= TAU - 1e-6 { (((w - big).powi(2) + p[2].powi(2)).sqrt() - r).abs() } else { f64::INFINITY }
                };
                let (u, rho) = (p[1].atan2(p[0]), (p[0] * p[0] + p[1] * p[1]).sqrt());
                let tube = tube_at(u, rho).min(tube_at(u + PI, -rho));
                // End caps: discs in the planes at u = 0 and u = angle.
                let cap = |a: f64| {
                    let (c, s) = (a.cos(), a.sin());
                    let along = p[0] * c + p[1] * s;
                    let off = -p[0] * s + p[1] * c;
                    let radial = ((along - big).powi(2) + p[2].powi(2)).sqrt();
                    if radial <= r + 1e-9 { off.abs() } else { f64::INFINITY }
                };
                tube.min(cap(0.0)).min(cap(angle))
            };
            prop_assert!(max_error(&t, &dist) <= tol * 1.0001 + 1e-6);
        }

        #[test]
        fn dishes_within_tolerance(rb in 0.01f64..3.0, hf in 0.01f64..1.5, tol in 0.001f64..0.2) {
            let h = rb * hf;
            let t = tessellate(&prim(Shape::SphericalDish { base_radius: rb as f32, height: h as f32 }), tol, [true, true]).unwrap();
            let (rc, h) = (rb as f32 as f64, h as f32 as f64);
            let rs = (rc * rc + h * h) / (2.0 * h);
            let dist = |p: [f64; 3]| {
                let rho = (p[0] * p[0] + p[1] * p[1]).sqrt();
                let dome = if p[2] >= -1e-9 { ((p[0] * p[0] + p[1] * p[1] + (p[2] - (h - rs)).powi(2)).sqrt() - rs).abs() } else { f64::INFINITY };
                // Below the base plane (a dish deeper than a hemisphere puts its
                // last ring there): the distance to the base disc.
                let base = ((rho - rc).max(0.0).powi(2) + p[2].powi(2)).sqrt();
                dome.min(base)
            };
            prop_assert!(max_error(&t, &dist) <= tol * 1.0001 + 1e-6);
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(liftplan_core::testing::proptest_cases(40)))]

        #[test]
        fn rectangular_torus_within_tolerance(ri in 0.0f64..3.0, w in 0.01f64..2.0, h in 0.01f64..2.0, angle in 0.01f64..6.3, tol in 0.001f64..0.2) {
            let shape = Shape::RectangularTorus { inner_radius: ri as f32, outer_radius: (ri + w) as f32, height: h as f32, angle: angle as f32 };
            let t = tessellate(&prim(shape), tol, [true, true]).unwrap();
            let (ri, ro, h, angle) = (ri as f32 as f64, (ri + w) as f32 as f64, h as f32 as f64, (angle as f32 as f64).min(TAU));
            // Distance to the solid (an annular sector of a slab), zero inside.
            let dist = |p: [f64; 3]| {
                let rho = (p[0] * p[0] + p[1] * p[1]).sqrt();
                let u = p[1].atan2(p[0]).rem_euclid(TAU);
                let dz = (p[2].abs() - h / 2.0).max(0.0);
                if u <= angle + 1e-9 || angle >= TAU - 1e-6 {
                    let dr = (ri - rho).max(rho - ro).max(0.0);
                    (dr * dr + dz * dz).sqrt()
                } else {
                    // Past an end: the distance to that end's plane at most.
                    let off = |a: f64| (-p[0] * a.sin() + p[1] * a.cos()).abs();
                    off(0.0).min(off(angle)).max(dz)
                }
            };
            prop_assert!(max_error(&t, &dist) <= tol * 1.0001 + 1e-6);
        }
    }

    use liftplan_core::testing::unit_stream;

    /// Points spread over the surface of a primitive's true (untessellated)
    /// solid, from its RVM parameters: the sides, the caps and the bases.
    fn surface_points(shape: &Shape, n: usize, rng: &mut impl FnMut() -> f64) -> Vec<[f64; 3]> {
        let mut pts = Vec::with_capacity(n);
        let Some(f) = form(shape) else { return pts };
        for k in 0..n {
            let (x, y) = (rng(), rng());
            // A third of the points on the rims, where sides meet caps.
            let edge = k % 3 == 0;
            let p = match f {
                Form::Snout { rb, rt, h, offset, bshear, tshear } => {
                    let a = TAU * x;
                    let (ox, oy) = (offset[0] / 2.0, offset[1] / 2.0);
                    let (c, s) = (a.cos(), a.sin());
                    let b = [rb * c - ox, rb * s - oy, -h / 2.0 + bshear[0].tan() * rb * c + bshear[1].tan() * rb * s];
                    let tp = [rt * c + ox, rt * s + oy, h / 2.0 + tshear[0].tan() * rt * c + tshear[1].tan() * rt * s];
                    let lerp = |p: [f64; 3], q: [f64; 3], w: f64| {
                        [p[0] + (q[0] - p[0]) * w, p[1] + (q[1] - p[1]) * w, p[2] + (q[2] - p[2]) * w]
                    };
                    match k % 4 {
                        0 | 1 => lerp(b, tp, if edge { (k % 2) as f64 } else { y }),
                        2 => lerp([-ox, -oy, -h / 2.0], b, y.sqrt()),
                        _ => lerp([ox, oy, h / 2.0], tp, y.sqrt()),
                    }
                }
                Form::SphereCap { r, arc, shift_z, scale_z } => {
                    let phi = TAU * x;
                    if k % 4 == 3 && arc < PI - 1e-9 {
                        let rho = r * arc.sin() * y.sqrt();
                        [rho * phi.cos(), rho * phi.sin(), r * arc.cos() * scale_z + shift_z]
                    } else {
                        let th = if edge { arc } else { arc * y };
                        [r * th.sin() * phi.cos(), r * th.sin() * phi.sin(), r * th.cos() * scale_z + shift_z]
                    }
                }
                Form::CircularTorus { offset, radius, angle } => {
                    let v = TAU * y;
                    let (u, rr) = match k % 5 {
                        3 => (0.0, radius * x.sqrt()),
                        4 => (angle, radius * x.sqrt()),
                        _ => (angle * x, radius),
                    };
                    let w = offset + rr * v.cos();
                    [w * u.cos(), w * u.sin(), rr * v.sin()]
                }
                Form::RectangularTorus { ri, ro, h, angle } => {
                    let u = if k % 5 == 4 { angle * (k % 2) as f64 } else { angle * x };
                    let (rho, z) = match k % 4 {
                        0 => (ro, h * (y - 0.5)),
                        1 => (ri, h * (y - 0.5)),
                        2 => (ri + (ro - ri) * y, h / 2.0),
                        _ => (ri + (ro - ri) * y, -h / 2.0),
                    };
                    [rho * u.cos(), rho * u.sin(), z]
                }
                Form::Box(_) | Form::Pyramid { .. } | Form::Facets(_) => return pts,
            };
            pts.push(p);
        }
        pts
    }

    /// Generalised winding number of a closed mesh about `p` (1 inside, 0 outside).
    fn winding(t: &Tess, p: [f64; 3]) -> f64 {
        let mut omega = 0.0;
        for tr in &t.triangles {
            let [a, b, c] = tr.map(|i| {
                let v = t.vertices[i as usize];
                [v[0] - p[0], v[1] - p[1], v[2] - p[2]]
            });
            let dot = |u: [f64; 3], w: [f64; 3]| u[0] * w[0] + u[1] * w[1] + u[2] * w[2];
            let len = |u: [f64; 3]| dot(u, u).sqrt();
            let bxc = [b[1] * c[2] - b[2] * c[1], b[2] * c[0] - b[0] * c[2], b[0] * c[1] - b[1] * c[0]];
            let den = len(a) * len(b) * len(c) + dot(a, b) * len(c) + dot(a, c) * len(b) + dot(b, c) * len(a);
            omega += 2.0 * dot(a, bxc).atan2(den);
        }
        omega / (4.0 * PI)
    }

    /// Distance from `p` to the nearest triangle of `t`.
    fn distance_to_mesh(t: &Tess, p: [f64; 3]) -> f64 {
        let sub = |u: [f64; 3], w: [f64; 3]| [u[0] - w[0], u[1] - w[1], u[2] - w[2]];
        let dot = |u: [f64; 3], w: [f64; 3]| u[0] * w[0] + u[1] * w[1] + u[2] * w[2];
        let seg = |a: [f64; 3], b: [f64; 3]| {
            let ab = sub(b, a);
            let l = dot(ab, ab);
            let s = if l > 0.0 { (dot(sub(p, a), ab) / l).clamp(0.0, 1.0) } else { 0.0 };
            let d = sub(p, [a[0] + ab[0] * s, a[1] + ab[1] * s, a[2] + ab[2] * s]);
            dot(d, d).sqrt()
        };
        let mut best = f64::INFINITY;
        for tr in &t.triangles {
            let [a, b, c] = tr.map(|i| t.vertices[i as usize]);
            let (u, v) = (sub(b, a), sub(c, a));
            let n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
            let nn = dot(n, n);
            let mut d = seg(a, b).min(seg(b, c)).min(seg(c, a));
            if nn > 0.0 {
                // The foot of the perpendicular, if it falls inside the triangle.
                let h = dot(sub(p, a), n) / nn;
                let q = [p[0] - n[0] * h, p[1] - n[1] * h, p[2] - n[2] * h];
                let side = |x: [f64; 3], y: [f64; 3]| {
                    let (e, f) = (sub(y, x), sub(q, x));
                    dot([e[1] * f[2] - e[2] * f[1], e[2] * f[0] - e[0] * f[2], e[0] * f[1] - e[1] * f[0]], n) >= 0.0
                };
                if side(a, b) && side(b, c) && side(c, a) {
                    d = d.min(h.abs() * nn.sqrt());
                }
            }
            best = best.min(d);
        }
        best
    }

    /// Whether a snout's top end lies wholly above its bottom end's plane and
    /// the bottom wholly below the top's; a sheared snout whose ends cross
    /// (a far offset, a steep shear) has no inside to speak of.
    fn snout_is_upright(shape: &Shape) -> bool {
        let Some(Form::Snout { rb, rt, h, offset, bshear, tshear }) = form(shape) else { return true };
        let (ox, oy) = (offset[0] / 2.0, offset[1] / 2.0);
        let plane = |sh: [f64; 2], cz: f64, cx: f64, cy: f64, x: f64, y: f64| {
            cz + sh[0].tan() * (x - cx) + sh[1].tan() * (y - cy)
        };
        (0..64).all(|k| {
            let a = TAU * k as f64 / 64.0;
            let (c, s) = (a.cos(), a.sin());
            let top = [rt * c + ox, rt * s + oy, h / 2.0 + tshear[0].tan() * rt * c + tshear[1].tan() * rt * s];
            let bot = [rb * c - ox, rb * s - oy, -h / 2.0 + bshear[0].tan() * rb * c + bshear[1].tan() * rb * s];
            top[2] > plane(bshear, -h / 2.0, -ox, -oy, top[0], top[1])
                && bot[2] < plane(tshear, h / 2.0, ox, oy, bot[0], bot[1])
        })
    }

    /// Every curved shape RVM has, with sizes from a millimetre to metres,
    /// offsets, shears and partial sweeps.
    fn curved_shape() -> impl Strategy<Value = Shape> {
        let size = 0.01f32..3.0;
        let shear = -0.6f32..0.6;
        prop_oneof![
            (size.clone(), size.clone()).prop_map(|(radius, height)| Shape::Cylinder { radius, height }),
            (
                size.clone(),
                0.0f32..3.0,
                size.clone(),
                [-1.0f32..1.0, -1.0f32..1.0],
                [shear.clone(), shear.clone()],
                [shear.clone(), shear]
            )
                .prop_map(|(radius_b, radius_t, height, offset, bshear, tshear)| Shape::Snout {
                    radius_b,
                    radius_t,
                    height,
                    offset,
                    bshear,
                    tshear
                }),
            size.clone().prop_map(|diameter| Shape::Sphere { diameter }),
            (size.clone(), size.clone())
                .prop_map(|(base_radius, height)| Shape::EllipticalDish { base_radius, height }),
            (size.clone(), 0.05f32..2.0)
                .prop_map(|(base_radius, f)| Shape::SphericalDish { base_radius, height: base_radius * f }),
            (0.05f32..3.0, 0.05f32..0.95, prop_oneof![Just(std::f32::consts::TAU), 0.01f32..6.3])
                .prop_map(|(offset, f, angle)| Shape::CircularTorus { offset, radius: offset * f, angle }),
            (0.0f32..3.0, size.clone(), size, prop_oneof![Just(std::f32::consts::TAU), 0.01f32..6.3]).prop_map(
                |(inner_radius, w, height, angle)| Shape::RectangularTorus {
                    inner_radius,
                    outer_radius: inner_radius + w,
                    height,
                    angle
                }
            ),
        ]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(liftplan_core::testing::proptest_cases(60)))]

        /// The safety property of the module: the true solid never pokes out of
        /// its mesh, so a distance measured to the mesh is never more than the
        /// distance to the primitive. Fails with the vertices put on the surface.
        #[test]
        fn every_primitive_lies_inside_its_mesh(shape in curved_shape(), tol in 0.002f64..0.2, seed in any::<u64>()) {
            // A snout whose sheared ends cross is taken without its shears
            // (always upright), not rejected: a soak then runs every case.
            let shape = match shape {
                Shape::Snout { radius_b, radius_t, height, offset, .. } if !snout_is_upright(&shape) => {
                    Shape::Snout { radius_b, radius_t, height, offset, bshear: [0.0; 2], tshear: [0.0; 2] }
                }
                other => other,
            };
            prop_assert!(snout_is_upright(&shape));
            let t = tessellate(&prim(shape.clone()), tol, [true, true]).unwrap();
            let mut rng = unit_stream(seed);
            for p in surface_points(&shape, 240, &mut rng) {
                let size = p.iter().fold(1.0f64, |m, c| m.max(c.abs()));
                if winding(&t, p) < 0.5 {
                    let d = distance_to_mesh(&t, p);
                    prop_assert!(d <= 1e-9 * size, "{shape:?} at tol {tol}: {p:?} is {d} m outside its mesh");
                }
            }
        }
    }

    /// The containment property on a real PDMS export: every curved primitive
    /// of the sample file, at the default tolerance in its own units, has no
    /// sampled surface point outside its mesh.
    #[test]
    fn every_primitive_of_the_pdms_sample_lies_inside_its_mesh() {
        let path =
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/plant/plm-sample_11072013.rvm");
        let bytes = std::fs::read(&path).unwrap();
        let file = crate::rvm::parse(&path, &bytes).unwrap();
        fn walk<'a>(g: &'a crate::rvm::Group, out: &mut Vec<&'a Primitive>) {
            out.extend(g.primitives.iter());
            for c in &g.children {
                walk(c, out);
            }
        }
        let mut prims: Vec<&Primitive> = file.loose.iter().collect();
        for g in &file.groups {
            walk(g, &mut prims);
        }
        let mut rng = unit_stream(0x9e37_79b9_7f4a_7c15);
        let mut checked = 0;
        for p in prims {
            let scale = matrix_scale(&p.matrix);
            let tol_local = 0.01 / scale.max(1e-12);
            let pts = surface_points(&p.shape, 60, &mut rng);
            if pts.is_empty() || !snout_is_upright(&p.shape) {
                continue;
            }
            let t = tessellate(p, tol_local, [true, true]).unwrap();
            for q in pts {
                if winding(&t, q) < 0.5 {
                    let d = distance_to_mesh(&t, q) * scale;
                    assert!(d <= 1e-9, "{:?} at {q:?}: {d} m outside its mesh", p.shape);
                }
            }
            checked += 1;
        }
        // 139 cylinders, 22 snouts, 38 + 74 tori, 2 dishes.
        assert_eq!(checked, 275);
    }

    fn close(a: f64, b: f64, rel: f64) -> bool {
        (a - b).abs() <= rel * b.abs().max(1e-12)
    }

    #[test]
    fn volumes_and_areas_converge() {
        let pi = PI;
        type Case = (Shape, f64, Option<f64>);
        let cases: Vec<Case> = vec![
            (Shape::Box { lengths: [1.0, 2.0, 3.0] }, 6.0, Some(22.0)),
            (
                Shape::Pyramid { bottom: [2.0, 2.0], top: [1.0, 1.0], offset: [0.3, 0.0], height: 3.0 },
                3.0 / 6.0 * (4.0 + 4.0 * 2.25 + 1.0),
                None,
            ),
            (Shape::Cylinder { radius: 1.0, height: 2.0 }, pi * 2.0, Some(2.0 * pi * 2.0 + 2.0 * pi)),
            (
                Shape::Snout {
                    radius_b: 1.0,
                    radius_t: 0.5,
                    height: 2.0,
                    offset: [0.4, 0.2],
                    bshear: [0.0; 2],
                    tshear: [0.0; 2],
                },
                pi * 2.0 / 3.0 * (1.0 + 0.5 + 0.25),
                None,
            ),
            (Shape::Sphere { diameter: 2.0 }, 4.0 / 3.0 * pi, Some(4.0 * pi)),
            (Shape::EllipticalDish { base_radius: 1.0, height: 0.5 }, 2.0 / 3.0 * pi * 0.5, None),
            (
                Shape::SphericalDish { base_radius: 1.0, height: 0.4 },
                {
                    let rs: f64 = (1.0 + 0.16) / 0.8;
                    pi * 0.16 * (3.0 * rs - 0.4) / 3.0
                },
                None,
            ),
            (
                Shape::CircularTorus { offset: 2.0, radius: 0.5, angle: FRAC_PI_2 as f32 },
                pi * 0.25 * 2.0 * FRAC_PI_2,
                Some(2.0 * pi * 0.5 * 2.0 * FRAC_PI_2 + 2.0 * pi * 0.25),
            ),
            (
                Shape::RectangularTorus { inner_radius: 1.0, outer_radius: 2.0, height: 0.5, angle: PI as f32 },
                PI / 2.0 * 3.0 * 0.5,
                Some(PI * 2.0 * 0.5 + PI * 1.0 * 0.5 + 2.0 * PI / 2.0 * 3.0 + 2.0 * 0.5),
            ),
        ];
        for (shape, v_exact, a_exact) in cases {
            let mut last_err = f64::INFINITY;
            for tol in [0.1, 0.01, 0.001, 0.0001] {
                let t = tessellate(&prim(shape.clone()), tol, [true, true]).unwrap();
                let v = volume(&t);
                assert!(v > 0.0, "{shape:?}: triangles must face outwards (volume {v})");
                let err = (v - v_exact).abs() / v_exact;
                assert!(err <= last_err + 1e-12, "{shape:?}: error grew from {last_err} to {err} at tol {tol}");
                last_err = err;
                // The faces lie within `tol` of the surface, so the volume between
                // them is at most the area times `tol`.
                assert!(
                    (v - v_exact).abs() <= tol * area(&t) + 1e-12,
                    "{shape:?}: volume {v} vs {v_exact} at tol {tol}"
                );
                if tol == 0.0001
                    && let Some(a) = a_exact
                {
                    assert!(close(area(&t), a, 1e-3), "{shape:?}: area {} vs {a}", area(&t));
                }
            }
        }
    }

    /// A shape of any kind with sizes from degenerate (0, negative) to large,
    /// angles past a full turn, and facet polygons with holes.
    fn any_shape() -> impl Strategy<Value = Shape> {
        let size = prop_oneof![Just(0.0f32), Just(-1.0f32), 0.001f32..5.0, 5.0f32..50.0];
        let angle = prop_oneof![Just(0.0f32), Just(std::f32::consts::TAU), 0.001f32..7.0];
        let v2 = || [size.clone(), size.clone()];
        // Contours of 2 vertices are left out by the tessellation, and counted as such.
        let ring = proptest::collection::vec(([-5.0f32..5.0, -5.0f32..5.0, -0.1f32..0.1], Just([0.0f32; 3])), 2..9);
        let polygon = proptest::collection::vec(ring, 1..4).prop_map(|contours| Polygon { contours });
        prop_oneof![
            [size.clone(), size.clone(), size.clone()].prop_map(|lengths| Shape::Box { lengths }),
            (v2(), v2(), v2(), size.clone()).prop_map(|(bottom, top, offset, height)| Shape::Pyramid {
                bottom,
                top,
                offset,
                height
            }),
            (size.clone(), size.clone()).prop_map(|(radius, height)| Shape::Cylinder { radius, height }),
            (size.clone(), size.clone(), size.clone(), v2(), [-0.5f32..0.5, -0.5f32..0.5]).prop_map(
                |(radius_b, radius_t, height, offset, bshear)| Shape::Snout {
                    radius_b,
                    radius_t,
                    height,
                    offset,
                    bshear,
                    tshear: [bshear[1], bshear[0]],
                }
            ),
            size.clone().prop_map(|diameter| Shape::Sphere { diameter }),
            (size.clone(), size.clone())
                .prop_map(|(base_radius, height)| Shape::EllipticalDish { base_radius, height }),
            (size.clone(), size.clone()).prop_map(|(base_radius, height)| Shape::SphericalDish { base_radius, height }),
            (size.clone(), size.clone(), angle.clone()).prop_map(|(offset, radius, angle)| Shape::CircularTorus {
                offset,
                radius,
                angle
            }),
            (size.clone(), size.clone(), size.clone(), angle).prop_map(
                |(inner_radius, outer_radius, height, angle)| Shape::RectangularTorus {
                    inner_radius,
                    outer_radius,
                    height,
                    angle
                }
            ),
            proptest::collection::vec(polygon, 0..4).prop_map(|polygons| Shape::FacetGroup { polygons }),
        ]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(liftplan_core::testing::proptest_cases(400)))]

        /// The count a stage budgets with is the tessellation's own: exact for
        /// the analytic shapes, never below it for facet groups.
        #[test]
        fn triangle_count_is_the_tessellations(
            shape in any_shape(),
            tol in 0.002f64..0.2,
            caps in [any::<bool>(), any::<bool>()],
        ) {
            let p = prim(shape.clone());
            let made = tessellate(&p, tol, caps).map_or(0, |t| t.triangles.len() as u64);
            let counted = triangle_count(&p, tol, caps);
            if matches!(shape, Shape::FacetGroup { .. }) {
                prop_assert!(made <= counted, "{made} made, {counted} counted");
            } else {
                prop_assert_eq!(made, counted);
            }
        }
    }

    /// Where the tolerance asks for more segments than a circle may have, the
    /// count follows the tessellation's cap too.
    #[test]
    fn triangle_count_at_the_segment_cap() {
        let p = prim(Shape::Cylinder { radius: 100.0, height: 1.0 });
        let t = tessellate(&p, 1e-9, [true, true]).unwrap();
        assert_eq!(t.triangles.len(), 2 * 4096 + 2 * 4094);
        assert_eq!(triangle_count(&p, 1e-9, [true, true]), t.triangles.len() as u64);
    }

    #[test]
    fn degenerate_shapes_do_not_panic() {
        for shape in [
            Shape::Cylinder { radius: 0.0, height: 1.0 },
            Shape::Cylinder { radius: 1.0, height: 0.0 },
            Shape::Sphere { diameter: 0.0 },
            Shape::CircularTorus { offset: 1.0, radius: 0.0, angle: 1.0 },
            Shape::CircularTorus { offset: 1.0, radius: 0.5, angle: 1e-6 },
            Shape::SphericalDish { base_radius: 1.0, height: 0.0 },
            Shape::EllipticalDish { base_radius: 0.0, height: 1.0 },
            Shape::RectangularTorus { inner_radius: 1.0, outer_radius: 1.0, height: 0.0, angle: 0.0 },
            Shape::Snout {
                radius_b: 0.0,
                radius_t: 0.0,
                height: 0.0,
                offset: [0.0; 2],
                bshear: [0.0; 2],
                tshear: [0.0; 2],
            },
            Shape::Pyramid { bottom: [0.0; 2], top: [0.0; 2], offset: [0.0; 2], height: 0.0 },
            Shape::Box { lengths: [0.0; 3] },
            Shape::FacetGroup { polygons: vec![] },
        ] {
            let t = tessellate(&prim(shape.clone()), 0.01, [true, true]).unwrap();
            assert!(t.vertices.iter().all(|v| v.iter().all(|c| c.is_finite())), "{shape:?}");
            assert!(t.triangles.iter().all(|tr| tr.iter().all(|&i| (i as usize) < t.vertices.len())), "{shape:?}");
        }
        assert!(tessellate(&prim(Shape::Line { a: 0.0, b: 1.0 }), 0.01, [true, true]).is_none());
    }

    #[test]
    fn facet_polygon_with_hole() {
        let v = |x: f32, y: f32| ([x, y, 0.0], [0.0, 0.0, 1.0]);
        let poly = Polygon {
            contours: vec![
                vec![v(0.0, 0.0), v(4.0, 0.0), v(4.0, 4.0), v(0.0, 4.0)],
                vec![v(1.0, 1.0), v(1.0, 3.0), v(3.0, 3.0), v(3.0, 1.0)],
            ],
        };
        let t = tessellate(&prim(Shape::FacetGroup { polygons: vec![poly] }), 0.01, [true, true]).unwrap();
        assert!((area(&t) - 12.0).abs() < 1e-9, "{}", area(&t));
        // Every triangle faces +z like the outer contour.
        for tr in &t.triangles {
            let (a, b, c) = (t.vertices[tr[0] as usize], t.vertices[tr[1] as usize], t.vertices[tr[2] as usize]);
            assert!((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]) > 0.0);
        }
    }
}
