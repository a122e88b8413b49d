//! Reader for AVEVA PDMS/E3D binary RVM exports.
//!
//! The format is little documented; what follows was checked field by field
//! against a real export (`shared/data/plant`) and the public parser
//! `cdyk/rvmparser`. All numbers are big-endian.
//!
//! ```text
//! chunk    = id (4 x u32, one ASCII letter in the low byte of each)
//!            next_chunk_offset (u32, absolute) unknown (u32, always 1)
//! string   = length in 4-byte words (u32), then that many words, NUL padded
//! HEAD     = version, info, note, date, user, [encoding if version >= 2]
//! MODL     = version, project, name
//! CNTB     = version, name, translation (3 x f32, mm), material (u32), children..., CNTE
//! CNTE     = version
//! PRIM     = version, kind, M (12 x f32, 3x4 column-major), bbox (6 x f32, local), params
//! OBST/INSU= as PRIM with a translucency u32 before the params (obstruction / insulation)
//! COLR     = kind, index, r, g, b, pad
//! END:     = end of file
//! ```
//!
//! Primitive kinds: 1 pyramid, 2 box, 3 rectangular torus, 4 circular torus,
//! 5 elliptical dish, 6 spherical dish, 7 snout, 8 cylinder, 9 sphere, 10 line,
//! 11 facet group. Every count is checked against the bytes left before anything
//! is allocated, every chunk's declared end against where its data actually ends,
//! and group nesting is limited, so a damaged or hostile file gives an error with
//! its byte offset, never a panic.

use crate::error::{PlantError, Result};
use liftplan_core::Location;
use std::path::Path;

const MAX_DEPTH: usize = 512;

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Kind {
    Pyramid,
    Box,
    RectangularTorus,
    CircularTorus,
    EllipticalDish,
    SphericalDish,
    Snout,
    Cylinder,
    Sphere,
    Line,
    FacetGroup,
}

impl Kind {
    pub const ALL: [Kind; 11] = [
        Kind::Pyramid,
        Kind::Box,
        Kind::RectangularTorus,
        Kind::CircularTorus,
        Kind::EllipticalDish,
        Kind::SphericalDish,
        Kind::Snout,
        Kind::Cylinder,
        Kind::Sphere,
        Kind::Line,
        Kind::FacetGroup,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Kind::Pyramid => "pyramid",
            Kind::Box => "box",
            Kind::RectangularTorus => "rectangular_torus",
            Kind::CircularTorus => "circular_torus",
            Kind::EllipticalDish => "elliptical_dish",
            Kind::SphericalDish => "spherical_dish",
            Kind::Snout => "snout",
            Kind::Cylinder => "cylinder",
            Kind::Sphere => "sphere",
            Kind::Line => "line",
            Kind::FacetGroup => "facet_group",
        }
    }
}

/// One polygon of a facet group: an outer contour and holes, each vertex with
/// its normal.
#[derive(Debug, Clone, PartialEq)]
pub struct Polygon {
    pub contours: Vec<Vec<([f32; 3], [f32; 3])>>,
}

/// A primitive's shape parameters, in its local frame (file units).
#[derive(Debug, Clone, PartialEq)]
pub enum Shape {
    /// Bottom and top rectangle sizes, offset of the top centre, height.
    Pyramid {
        bottom: [f32; 2],
        top: [f32; 2],
        offset: [f32; 2],
        height: f32,
    },
    Box {
        lengths: [f32; 3],
    },
    RectangularTorus {
        inner_radius: f32,
        outer_radius: f32,
        height: f32,
        angle: f32,
    },
    /// `offset`: distance of the tube centre from the axis; `radius`: tube radius.
    CircularTorus {
        offset: f32,
        radius: f32,
        angle: f32,
    },
    EllipticalDish {
        base_radius: f32,
        height: f32,
    },
    SphericalDish {
        base_radius: f32,
        height: f32,
    },
    /// Bottom and top radii, height, top-centre offset, shear angles of the
    /// bottom and top planes (radians, about y then x).
    Snout {
        radius_b: f32,
        radius_t: f32,
        height: f32,
        offset: [f32; 2],
        bshear: [f32; 2],
        tshear: [f32; 2],
    },
    Cylinder {
        radius: f32,
        height: f32,
    },
    Sphere {
        diameter: f32,
    },
    Line {
        a: f32,
        b: f32,
    },
    FacetGroup {
        polygons: Vec<Polygon>,
    },
}

impl Shape {
    pub fn kind(&self) -> Kind {
        match self {
            Shape::Pyramid { .. } => Kind::Pyramid,
            Shape::Box { .. } => Kind::Box,
            Shape::RectangularTorus { .. } => Kind::RectangularTorus,
            Shape::CircularTorus { .. } => Kind::CircularTorus,
            Shape::EllipticalDish { .. } => Kind::EllipticalDish,
            Shape::SphericalDish { .. } => Kind::SphericalDish,
            Shape::Snout { .. } => Kind::Snout,
            Shape::Cylinder { .. } => Kind::Cylinder,
            Shape::Sphere { .. } => Kind::Sphere,
            Shape::Line { .. } => Kind::Line,
            Shape::FacetGroup { .. } => Kind::FacetGroup,
        }
    }
}

/// Which chunk a primitive came in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub enum Role {
    Primitive,
    Obstruction,
    Insulation,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Primitive {
    pub role: Role,
    /// Local to model transform, 3x4 column-major (three axis columns, then translation).
    pub matrix: [f32; 12],
    /// Local bounding box: min xyz, max xyz.
    pub bbox_local: [f32; 6],
    pub shape: Shape,
    /// Byte offset of the chunk, for error messages.
    pub offset: u64,
}

#[derive(Debug, Clone, PartialEq, Default)]
pub struct Group {
    pub name: String,
    /// Reference point of the group (mm in the file, as written).
    pub translation: [f32; 3],
    pub material: u32,
    pub children: Vec<Group>,
    pub primitives: Vec<Primitive>,
}

impl Group {
    /// Number of groups in this subtree, itself included.
    pub fn group_count(&self) -> usize {
        1 + self.children.iter().map(|c| c.group_count()).sum::<usize>()
    }
}

#[derive(Debug, Clone, PartialEq, Default)]
pub struct RvmFile {
    pub info: String,
    pub note: String,
    pub date: String,
    pub user: String,
    pub encoding: String,
    pub project: String,
    pub model: String,
    pub groups: Vec<Group>,
    /// Primitives outside any group (unusual, but allowed).
    pub loose: Vec<Primitive>,
    pub colors: Vec<(u32, u32, [u8; 3])>,
}

impl RvmFile {
    pub fn group_count(&self) -> usize {
        self.groups.iter().map(|g| g.group_count()).sum()
    }

    /// Calls `f(path, group)` for every group, depth first; `path` is the group
    /// names joined by '/'.
    pub fn walk<'a>(&'a self, f: &mut dyn FnMut(&[&'a str], &'a Group)) {
        fn go<'a>(g: &'a Group, path: &mut Vec<&'a str>, f: &mut dyn FnMut(&[&'a str], &'a Group)) {
            path.push(&g.name);
            f(path, g);
            for c in &g.children {
                go(c, path, f);
            }
            path.pop();
        }
        let mut path = Vec::new();
        for g in &self.groups {
            go(g, &mut path, f);
        }
    }

    pub fn primitive_counts(&self) -> std::collections::BTreeMap<Kind, usize> {
        let mut m = std::collections::BTreeMap::new();
        self.walk(&mut |_, g| {
            for p in &g.primitives {
                *m.entry(p.shape.kind()).or_insert(0) += 1;
            }
        });
        for p in &self.loose {
            *m.entry(p.shape.kind()).or_insert(0) += 1;
        }
        m
    }
}

struct Reader<'a> {
    b: &'a [u8],
    pos: usize,
    path: &'a Path,
}

fn chunk_id(word: [u8; 16]) -> Option<[u8; 4]> {
    let mut id = [0u8; 4];
    for i in 0..4 {
        if word[4 * i..4 * i + 3] != [0, 0, 0] {
            return None;
        }
        id[i] = word[4 * i + 3];
    }
    Some(id)
}

impl<'a> Reader<'a> {
    fn err(&self, at: usize, msg: impl Into<String>) -> PlantError {
        PlantError::at(Location::byte(self.path, at as u64), msg)
    }

    fn need(&self, n: usize, what: &str) -> Result<()> {
        if self.b.len() - self.pos < n {
            return Err(self.err(
                self.pos,
                format!("file ends inside {what}: {n} bytes needed, {} left (truncated file)", self.b.len() - self.pos),
            ));
        }
        Ok(())
    }

    fn u32(&mut self, what: &str) -> Result<u32> {
        self.need(4, what)?;
        let v =
            u32::from_be_bytes([self.b[self.pos], self.b[self.pos + 1], self.b[self.pos + 2], self.b[self.pos + 3]]);
        self.pos += 4;
        Ok(v)
    }

    fn f32(&mut self, what: &str) -> Result<f32> {
        let at = self.pos;
        let v = f32::from_bits(self.u32(what)?);
        if !v.is_finite() {
            return Err(self.err(at, format!("{what} is not a finite number ({v})")));
        }
        Ok(v)
    }

    fn f32s<const N: usize>(&mut self, what: &str) -> Result<[f32; N]> {
        let mut a = [0f32; N];
        for v in a.iter_mut() {
            *v = self.f32(what)?;
        }
        Ok(a)
    }

    fn string(&mut self, what: &str) -> Result<String> {
        let at = self.pos;
        let words = self.u32(what)? as usize;
        let n = words.checked_mul(4).ok_or_else(|| self.err(at, format!("{what}: absurd length")))?;
        if self.b.len() - self.pos < n {
            return Err(
                self.err(at, format!("{what} declares {n} bytes, only {} left in the file", self.b.len() - self.pos))
            );
        }
        let raw = &self.b[self.pos..self.pos + n];
        self.pos += n;
        let end = raw.iter().position(|&c| c == 0).unwrap_or(raw.len());
        // PDMS wrote Latin-1, E3D writes UTF-8.
        Ok(liftplan_core::names::utf8_or_latin1(&raw[..end]).into_owned())
    }

    /// A chunk header: (id, declared end offset, header offset).
    fn header(&mut self) -> Result<([u8; 4], usize, usize)> {
        let at = self.pos;
        self.need(24, "a chunk header")?;
        let mut w = [0u8; 16];
        w.copy_from_slice(&self.b[self.pos..self.pos + 16]);
        let id =
            chunk_id(w).ok_or_else(|| self.err(at, "expected a chunk id (four letters, each in a big-endian u32)"))?;
        self.pos += 16;
        let next = self.u32("chunk header")? as usize;
        let _unknown = self.u32("chunk header")?;
        Ok((id, next, at))
    }

    /// Checks that a chunk's data ended where its header said.
    fn check_end(&self, id: [u8; 4], start: usize, expected: usize) -> Result<()> {
        if self.pos != expected {
            return Err(self.err(
                start,
                format!(
                    "chunk {} declares its data ends at byte {expected}, but it ends at byte {}",
                    String::from_utf8_lossy(&id),
                    self.pos
                ),
            ));
        }
        Ok(())
    }
}

fn id_str(id: [u8; 4]) -> String {
    String::from_utf8_lossy(&id).into_owned()
}

/// Parses a whole RVM file held in memory.
pub fn parse(path: &Path, bytes: &[u8]) -> Result<RvmFile> {
    let mut r = Reader { b: bytes, pos: 0, path };
    let mut f = RvmFile::default();
    if bytes.is_empty() {
        return Err(r.err(0, "the file is empty"));
    }
    let (id, next, at) = r.header()?;
    if &id != b"HEAD" {
        return Err(r.err(at, format!("expected chunk HEAD at the start of an RVM file, found '{}'", id_str(id))));
    }
    let version = r.u32("HEAD version")?;
    f.info = r.string("HEAD info")?;
    f.note = r.string("HEAD note")?;
    f.date = r.string("HEAD date")?;
    f.user = r.string("HEAD user")?;
    if version >= 2 {
        f.encoding = r.string("HEAD encoding")?;
    }
    r.check_end(id, at, next)?;
    let (id, next, at) = r.header()?;
    if &id != b"MODL" {
        return Err(r.err(at, format!("expected chunk MODL after HEAD, found '{}'", id_str(id))));
    }
    let _v = r.u32("MODL version")?;
    f.project = r.string("MODL project")?;
    f.model = r.string("MODL name")?;
    r.check_end(id, at, next)?;

    // Groups nest; an explicit stack keeps hostile nesting off the call stack.
    let mut stack: Vec<Group> = Vec::new();
    loop {
        if r.pos >= bytes.len() {
            return Err(r.err(r.pos, "file ends without an END: chunk (truncated file)"));
        }
        let (id, next, at) = r.header()?;
        match &id {
            b"END:" => break,
            b"CNTB" => {
                if stack.len() >= MAX_DEPTH {
                    return Err(r.err(at, format!("groups nest deeper than {MAX_DEPTH} levels")));
                }
                let _v = r.u32("CNTB version")?;
                let name = r.string("group name")?;
                let translation = r.f32s::<3>("group translation")?;
                let material = r.u32("group material")?;
                r.check_end(id, at, next)?;
                stack.push(Group { name, translation, material, children: vec![], primitives: vec![] });
            }
            b"CNTE" => {
                let _v = r.u32("CNTE version")?;
                let Some(g) = stack.pop() else {
                    return Err(r.err(at, "CNTE without a matching CNTB"));
                };
                match stack.last_mut() {
                    Some(parent) => parent.children.push(g),
                    None => f.groups.push(g),
                }
            }
            b"PRIM" | b"OBST" | b"INSU" => {
                let p = parse_prim(&mut r, id, at)?;
                r.check_end(id, at, next)?;
                match stack.last_mut() {
                    Some(g) => g.primitives.push(p),
                    None => f.loose.push(p),
                }
            }
            b"COLR" => {
                let kind = r.u32("COLR kind")?;
                let index = r.u32("COLR index")?;
                r.need(4, "COLR colour")?;
                let rgb = [bytes[r.pos], bytes[r.pos + 1], bytes[r.pos + 2]];
                r.pos += 4;
                r.check_end(id, at, next)?;
                f.colors.push((kind, index, rgb));
            }
            _ => {
                return Err(r.err(
                    at,
                    format!("unknown chunk '{}' (expected CNTB, CNTE, PRIM, OBST, INSU, COLR or END:)", id_str(id)),
                ));
            }
        }
    }
    if let Some(g) = stack.last() {
        return Err(r.err(r.pos, format!("group '{}' is not closed (CNTE missing) before END:", g.name)));
    }
    Ok(f)
}

fn parse_prim(r: &mut Reader, id: [u8; 4], at: usize) -> Result<Primitive> {
    let _v = r.u32("primitive version")?;
    let kind_at = r.pos;
    let kind = r.u32("primitive kind")?;
    let matrix = r.f32s::<12>("primitive matrix")?;
    let bbox_local = r.f32s::<6>("primitive bounding box")?;
    let role = match &id {
        b"OBST" => Role::Obstruction,
        b"INSU" => Role::Insulation,
        _ => Role::Primitive,
    };
    if role != Role::Primitive {
        let _translucency = r.u32("translucency")?;
    }
    let shape = match kind {
        1 => {
            let a = r.f32s::<7>("pyramid parameters")?;
            Shape::Pyramid { bottom: [a[0], a[1]], top: [a[2], a[3]], offset: [a[4], a[5]], height: a[6] }
        }
        2 => Shape::Box { lengths: r.f32s::<3>("box lengths")? },
        3 => {
            let a = r.f32s::<4>("rectangular torus parameters")?;
            Shape::RectangularTorus { inner_radius: a[0], outer_radius: a[1], height: a[2], angle: a[3] }
        }
        4 => {
            let a = r.f32s::<3>("circular torus parameters")?;
            Shape::CircularTorus { offset: a[0], radius: a[1], angle: a[2] }
        }
        5 => {
            let a = r.f32s::<2>("elliptical dish parameters")?;
            Shape::EllipticalDish { base_radius: a[0], height: a[1] }
        }
        6 => {
            let a = r.f32s::<2>("spherical dish parameters")?;
            Shape::SphericalDish { base_radius: a[0], height: a[1] }
        }
        7 => {
            let a = r.f32s::<9>("snout parameters")?;
            Shape::Snout {
                radius_b: a[0],
                radius_t: a[1],
                height: a[2],
                offset: [a[3], a[4]],
                bshear: [a[5], a[6]],
                tshear: [a[7], a[8]],
            }
        }
        8 => {
            let a = r.f32s::<2>("cylinder parameters")?;
            Shape::Cylinder { radius: a[0], height: a[1] }
        }
        9 => Shape::Sphere { diameter: r.f32("sphere diameter")? },
        10 => {
            let a = r.f32s::<2>("line parameters")?;
            Shape::Line { a: a[0], b: a[1] }
        }
        11 => Shape::FacetGroup { polygons: parse_facets(r)? },
        k => return Err(r.err(kind_at, format!("unknown primitive kind {k} (expected 1 to 11)"))),
    };
    Ok(Primitive { role, matrix, bbox_local, shape, offset: at as u64 })
}

fn parse_facets(r: &mut Reader) -> Result<Vec<Polygon>> {
    let at = r.pos;
    let n_poly = r.u32("facet group polygon count")? as usize;
    // Every polygon needs at least its contour count (4 bytes).
    if n_poly.saturating_mul(4) > r.b.len() - r.pos {
        return Err(r.err(at, format!("facet group declares {n_poly} polygons, more than the file can hold")));
    }
    let mut polys = Vec::with_capacity(n_poly);
    for _ in 0..n_poly {
        let at = r.pos;
        let n_cont = r.u32("polygon contour count")? as usize;
        if n_cont.saturating_mul(4) > r.b.len() - r.pos {
            return Err(r.err(at, format!("polygon declares {n_cont} contours, more than the file can hold")));
        }
        let mut contours = Vec::with_capacity(n_cont);
        for _ in 0..n_cont {
            let at = r.pos;
            let n_v = r.u32("contour vertex count")? as usize;
            if n_v.saturating_mul(24) > r.b.len() - r.pos {
                return Err(r.err(at, format!("contour declares {n_v} vertices, more than the file can hold")));
            }
            let mut vs = Vec::with_capacity(n_v);
            for _ in 0..n_v {
                let p = r.f32s::<3>("facet vertex")?;
                let n = r.f32s::<3>("facet normal")?;
                vs.push((p, n));
            }
            contours.push(vs);
        }
        polys.push(Polygon { contours });
    }
    Ok(polys)
}

/// Reads and parses an RVM file.
pub fn read(path: &Path) -> Result<RvmFile> {
    let bytes = std::fs::read(path).map_err(|e| PlantError::Io(Location::file(path), e))?;
    parse(path, &bytes)
}

/// Writes an RVM file (used for test inputs and the demo's plant export). The
/// output reads back with [`parse`] to the same structure.
pub fn write(f: &RvmFile) -> Vec<u8> {
    struct W {
        b: Vec<u8>,
    }
    impl W {
        fn u32(&mut self, v: u32) {
            self.b.extend_from_slice(&v.to_be_bytes());
        }
        fn f32(&mut self, v: f32) {
            self.b.extend_from_slice(&v.to_bits().to_be_bytes());
        }
        fn string(&mut self, s: &str) {
            // As E3D writes: UTF-8, which reads back as itself.
            let bytes = s.as_bytes().to_vec();
            let words = bytes.len() / 4 + 1;
            self.u32(words as u32);
            let mut padded = bytes;
            padded.resize(words * 4, 0);
            self.b.extend_from_slice(&padded);
        }
        /// Starts a chunk; returns where to patch its end offset.
        fn header(&mut self, id: &[u8; 4]) -> usize {
            for c in id {
                self.u32(*c as u32);
            }
            let at = self.b.len();
            self.u32(0);
            self.u32(1);
            at
        }
        fn patch(&mut self, at: usize) {
            let end = self.b.len() as u32;
            self.b[at..at + 4].copy_from_slice(&end.to_be_bytes());
        }
    }
    fn prim(w: &mut W, p: &Primitive) {
        let id = match p.role {
            Role::Primitive => b"PRIM",
            Role::Obstruction => b"OBST",
            Role::Insulation => b"INSU",
        };
        let at = w.header(id);
        w.u32(1);
        let kind = Kind::ALL.iter().position(|k| *k == p.shape.kind()).unwrap_or(0) as u32 + 1;
        w.u32(kind);
        for v in p.matrix {
            w.f32(v);
        }
        for v in p.bbox_local {
            w.f32(v);
        }
        if p.role != Role::Primitive {
            w.u32(0);
        }
        let fs: Vec<f32> = match &p.shape {
            Shape::Pyramid { bottom, top, offset, height } => {
                vec![bottom[0], bottom[1], top[0], top[1], offset[0], offset[1], *height]
            }
            Shape::Box { lengths } => lengths.to_vec(),
            Shape::RectangularTorus { inner_radius, outer_radius, height, angle } => {
                vec![*inner_radius, *outer_radius, *height, *angle]
            }
            Shape::CircularTorus { offset, radius, angle } => vec![*offset, *radius, *angle],
            Shape::EllipticalDish { base_radius, height } | Shape::SphericalDish { base_radius, height } => {
                vec![*base_radius, *height]
            }
            Shape::Snout { radius_b, radius_t, height, offset, bshear, tshear } => {
                vec![*radius_b, *radius_t, *height, offset[0], offset[1], bshear[0], bshear[1], tshear[0], tshear[1]]
            }
            Shape::Cylinder { radius, height } => vec![*radius, *height],
            Shape::Sphere { diameter } => vec![*diameter],
            Shape::Line { a, b } => vec![*a, *b],
            Shape::FacetGroup { polygons } => {
                w.u32(polygons.len() as u32);
                for poly in polygons {
                    w.u32(poly.contours.len() as u32);
                    for c in &poly.contours {
                        w.u32(c.len() as u32);
                        for (p, n) in c {
                            for v in p.iter().chain(n) {
                                w.f32(*v);
                            }
                        }
                    }
                }
                vec![]
            }
        };
        for v in fs {
            w.f32(v);
        }
        w.patch(at);
    }
    fn group(w: &mut W, g: &Group) {
        let at = w.header(b"CNTB");
        w.u32(1);
        w.string(&g.name);
        for v in g.translation {
            w.f32(v);
        }
        w.u32(g.material);
        w.patch(at);
        for c in &g.children {
            group(w, c);
        }
        for p in &g.primitives {
            prim(w, p);
        }
        let at = w.header(b"CNTE");
        w.u32(1);
        w.patch(at);
    }
    let mut w = W { b: Vec::new() };
    let at = w.header(b"HEAD");
    w.u32(2);
    w.string(&f.info);
    w.string(&f.note);
    w.string(&f.date);
    w.string(&f.user);
    w.string(&f.encoding);
    w.patch(at);
    let at = w.header(b"MODL");
    w.u32(1);
    w.string(&f.project);
    w.string(&f.model);
    w.patch(at);
    for p in &f.loose {
        prim(&mut w, p);
    }
    for g in &f.groups {
        group(&mut w, g);
    }
    let at = w.header(b"END:");
    w.patch(at);
    w.b
}

#[cfg(test)]
mod tests {
    use super::*;

    const SAMPLE: &[u8] = include_bytes!("../../../fixtures/plant/plm-sample_11072013.rvm");

    fn small() -> RvmFile {
        let m = [0.001f32, 0.0, 0.0, 0.0, 0.001, 0.0, 0.0, 0.0, 0.001, 1.0, 2.0, 3.0];
        let p = |shape: Shape| Primitive {
            role: Role::Primitive,
            matrix: m,
            bbox_local: [-1.0, -1.0, -1.0, 1.0, 1.0, 1.0],
            shape,
            offset: 0,
        };
        let poly = Polygon {
            contours: vec![vec![
                ([0.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
                ([1.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
                ([0.0, 1.0, 0.0], [0.0, 0.0, 1.0]),
            ]],
        };
        RvmFile {
            info: "test".into(),
            model: "/M".into(),
            project: "P".into(),
            groups: vec![Group {
                name: "/SITE".into(),
                children: vec![Group {
                    name: "/RACK-1 Ø2 Behälter".into(),
                    primitives: vec![
                        p(Shape::Box { lengths: [1.0, 2.0, 3.0] }),
                        p(Shape::FacetGroup { polygons: vec![poly] }),
                    ],
                    ..Default::default()
                }],
                primitives: vec![p(Shape::Cylinder { radius: 100.0, height: 500.0 })],
                ..Default::default()
            }],
            ..Default::default()
        }
    }

    #[test]
    fn write_then_read_back() {
        let f = small();
        let bytes = write(&f);
        let mut back = parse(Path::new("x.rvm"), &bytes).unwrap();
        fn clear(g: &mut Group) {
            for p in &mut g.primitives {
                p.offset = 0;
            }
            g.children.iter_mut().for_each(clear);
        }
        back.groups.iter_mut().for_each(clear);
        assert_eq!(back.groups, f.groups);
        assert_eq!(back.group_count(), 2);
        // A name in Latin-1, as PDMS wrote it, reads as the same name
        // (its two bytes fewer are padding).
        let utf8 = "Ø2 Behälter".as_bytes();
        let at = bytes.windows(utf8.len()).position(|w| w == utf8).unwrap();
        let mut latin1 = bytes.clone();
        latin1.splice(at..at + utf8.len(), b"\xd82 Beh\xe4lter\0\0".iter().copied());
        let back = parse(Path::new("x.rvm"), &latin1).unwrap();
        assert_eq!(back.groups[0].children[0].name, "/RACK-1 Ø2 Behälter");
    }

    #[test]
    fn real_sample_counts() {
        let f = parse(Path::new("sample.rvm"), SAMPLE).unwrap();
        assert_eq!(f.group_count(), 315);
        let c = f.primitive_counts();
        let get = |k| c.get(&k).copied().unwrap_or(0);
        assert_eq!(
            [
                get(Kind::Pyramid),
                get(Kind::Box),
                get(Kind::RectangularTorus),
                get(Kind::CircularTorus),
                get(Kind::EllipticalDish),
                get(Kind::Snout),
                get(Kind::Cylinder),
                get(Kind::FacetGroup),
                get(Kind::Line)
            ],
            [118, 173, 74, 38, 2, 22, 139, 80, 12]
        );
        assert_eq!(c.values().sum::<usize>(), 658);
    }

    #[test]
    fn every_truncation_is_an_error_with_an_offset() {
        let bytes = write(&small());
        for n in (0..bytes.len()).step_by(7) {
            let e = parse(Path::new("t.rvm"), &bytes[..n]).unwrap_err().to_string();
            assert!(e.contains("t.rvm"), "{e}");
        }
        for n in (0..SAMPLE.len()).step_by(4099) {
            assert!(parse(Path::new("s.rvm"), &SAMPLE[..n]).is_err());
        }
    }

    #[test]
    fn hostile_fields() {
        let mut bytes = write(&small());
        // An unknown chunk id where the first CNTB starts.
        let cntb =
            bytes.windows(16).position(|w| w == [0, 0, 0, b'C', 0, 0, 0, b'N', 0, 0, 0, b'T', 0, 0, 0, b'B']).unwrap();
        let mut unknown = bytes.clone();
        unknown[cntb + 3] = b'X';
        let e = parse(Path::new("u.rvm"), &unknown).unwrap_err().to_string();
        assert!(e.contains("unknown chunk 'XNTB'") && e.contains(&format!("at byte {cntb}")), "{e}");
        // An absurd polygon count in the facet group.
        // polygons 1, contours 1, vertices 3: patch the polygon count.
        let fg = bytes.windows(12).rposition(|w| w == [0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 3]).unwrap();
        let mut absurd = bytes.clone();
        absurd[fg..fg + 4].copy_from_slice(&0x7fff_ffffu32.to_be_bytes());
        let e = parse(Path::new("a.rvm"), &absurd).unwrap_err().to_string();
        assert!(e.contains("declares 2147483647 polygons"), "{e}");
        // A NaN in a matrix.
        let prim =
            bytes.windows(16).position(|w| w == [0, 0, 0, b'P', 0, 0, 0, b'R', 0, 0, 0, b'I', 0, 0, 0, b'M']).unwrap();
        let m0 = prim + 24 + 8;
        bytes[m0..m0 + 4].copy_from_slice(&f32::NAN.to_bits().to_be_bytes());
        let e = parse(Path::new("n.rvm"), &bytes).unwrap_err().to_string();
        assert!(e.contains("not a finite number") && e.contains(&format!("at byte {m0}")), "{e}");
    }
}
