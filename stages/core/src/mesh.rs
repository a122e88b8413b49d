//! Triangle meshes in the site frame, with the provenance the planner reports.
//!
//! Each triangle belongs to a **part**; a part belongs to a named **group** (an RVM
//! group such as `PIPE-RACK-2`, a glTF node, an OBJ object) and says whether its
//! triangles bound one convex solid. Depth maps fill convex solids (their column
//! range over a cell is exact) and keep surfaces of everything else, and a
//! collision is reported against the group name.
//!
//! The plant stage hands meshes to later stages as a `PLANTMSH` artifact
//! ([`TriMesh::to_artifact_bytes`]); users get the same mesh as binary PLY
//! ([`TriMesh::write_ply`]).

use crate::artifact::{self, ArtifactError, ByteReader, ByteWriter};
use crate::frame::{Aabb, Point3, Pose};
use std::io::Write;
use std::path::Path;

pub const ARTIFACT_KIND: &str = "PLANTMSH";
pub const ARTIFACT_VERSION: u32 = 1;

/// The most characters of a plant model's group name kept: a name is
/// words on the plan's pages (what a crane part comes closest to, what is
/// left out), and one of thousands of characters (a model's file can state
/// any length) would fill them. PDMS and BIM names are far shorter.
pub const MAX_GROUP_NAME_CHARS: usize = 200;

/// The most parts' boxes the plant stage keeps (RVM primitives, a mesh's
/// connected pieces) over all the groups it leaves out: past it a group
/// keeps only its own box (a model left out whole would otherwise write a
/// box per primitive).
pub const MAX_MODEL_BOX_PARTS: usize = 20_000;

/// A group's name as the plant stage keeps it
/// ([`crate::names::kept`] to [`MAX_GROUP_NAME_CHARS`]): two names that
/// agree in their first characters still read apart on the plan's pages,
/// where a crane part is said to come closest to one of them.
pub fn group_name_kept(name: &str) -> std::borrow::Cow<'_, str> {
    crate::names::kept(name, MAX_GROUP_NAME_CHARS)
}

/// The group ids of a mesh by name, for a reader that names many groups:
/// [`TriMesh::group_id`] searches the names one by one, so naming G groups
/// that way cost G squared (100,000 RVM groups took the plant stage 12 s).
/// Ids are those `group_id` gives: the first group of a name, else a new one.
/// Valid for the mesh it was made of, while groups are added only through it.
#[derive(Debug, Default)]
pub struct GroupIndex {
    ids: std::collections::HashMap<String, u32>,
}

impl GroupIndex {
    pub fn of(mesh: &TriMesh) -> GroupIndex {
        let mut ids = std::collections::HashMap::with_capacity(mesh.groups.len());
        for (i, g) in mesh.groups.iter().enumerate() {
            ids.entry(g.clone()).or_insert(i as u32);
        }
        GroupIndex { ids }
    }

    /// Index of `mesh`'s group called `name`, added if new.
    pub fn id(&mut self, mesh: &mut TriMesh, name: &str) -> u32 {
        if let Some(&i) = self.ids.get(name) {
            return i;
        }
        let i = mesh.groups.len() as u32;
        mesh.groups.push(name.to_string());
        self.ids.insert(name.to_string(), i);
        i
    }
}

/// A part of a mesh: a run of triangles from one primitive or one mesh object.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct MeshPart {
    /// Index into [`TriMesh::groups`].
    pub group: u32,
    /// The part's triangles bound one convex solid.
    pub convex_solid: bool,
}

#[derive(Debug, Clone, Default, PartialEq)]
pub struct TriMesh {
    pub vertices: Vec<[f64; 3]>,
    pub triangles: Vec<[u32; 3]>,
    /// Per triangle: index into `parts`.
    pub part_of: Vec<u32>,
    pub parts: Vec<MeshPart>,
    /// Group names (full paths, e.g. `/SITE/ZONE-A/PIPE-RACK-2`).
    pub groups: Vec<String>,
}

impl TriMesh {
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    pub fn bbox(&self) -> Aabb {
        Aabb::from_points(&self.vertices)
    }

    /// Index of the group called `name`, added if new. It searches the names
    /// one by one: a reader naming many groups uses a [`GroupIndex`].
    pub fn group_id(&mut self, name: &str) -> u32 {
        if let Some(i) = self.groups.iter().position(|g| g == name) {
            return i as u32;
        }
        self.groups.push(name.to_string());
        (self.groups.len() - 1) as u32
    }

    /// Adds a part made of `vertices` and `triangles` (indices into `vertices`).
    pub fn add_part(&mut self, group: u32, convex_solid: bool, vertices: &[[f64; 3]], triangles: &[[u32; 3]]) {
        if triangles.is_empty() {
            return;
        }
        let base = self.vertices.len() as u32;
        let part = self.parts.len() as u32;
        self.parts.push(MeshPart { group, convex_solid });
        self.vertices.extend_from_slice(vertices);
        for t in triangles {
            self.triangles.push([t[0] + base, t[1] + base, t[2] + base]);
            self.part_of.push(part);
        }
    }

    /// Adds an axis-aligned box from `lo` to `hi` as a closed convex part
    /// (outward-facing triangles).
    pub fn add_box(&mut self, group: u32, lo: [f64; 3], hi: [f64; 3]) {
        let v: Vec<[f64; 3]> = (0..8)
            .map(|i| {
                [
                    if i & 1 == 0 { lo[0] } else { hi[0] },
                    if i & 2 == 0 { lo[1] } else { hi[1] },
                    if i & 4 == 0 { lo[2] } else { hi[2] },
                ]
            })
            .collect();
        const T: [[u32; 3]; 12] = [
            [0, 2, 3],
            [0, 3, 1],
            [4, 5, 7],
            [4, 7, 6],
            [0, 1, 5],
            [0, 5, 4],
            [2, 6, 7],
            [2, 7, 3],
            [0, 4, 6],
            [0, 6, 2],
            [1, 3, 7],
            [1, 7, 5],
        ];
        self.add_part(group, true, &v, &T);
    }

    /// Adds several parts that share one vertex array: `part_of[k]` indexes
    /// `convex` for triangle `k`.
    pub fn add_parts(
        &mut self,
        group: u32,
        convex: &[bool],
        vertices: &[[f64; 3]],
        triangles: &[[u32; 3]],
        part_of: &[u32],
    ) {
        if triangles.is_empty() {
            return;
        }
        let base = self.vertices.len() as u32;
        let pbase = self.parts.len() as u32;
        self.parts.extend(convex.iter().map(|&c| MeshPart { group, convex_solid: c }));
        self.vertices.extend_from_slice(vertices);
        for (t, p) in triangles.iter().zip(part_of) {
            self.triangles.push([t[0] + base, t[1] + base, t[2] + base]);
            self.part_of.push(pbase + p);
        }
    }

    /// Appends another mesh, merging groups by name.
    pub fn append(&mut self, other: &TriMesh) {
        self.append_with(other, &mut GroupIndex::of(self));
    }

    /// [`TriMesh::append`] through `index`, this mesh's [`GroupIndex`]: a
    /// caller appending many meshes keeps one index instead of indexing every
    /// group again for each.
    pub fn append_with(&mut self, other: &TriMesh, index: &mut GroupIndex) {
        let gmap: Vec<u32> = other.groups.iter().map(|g| index.id(self, g)).collect();
        let vbase = self.vertices.len() as u32;
        let pbase = self.parts.len() as u32;
        self.vertices.extend_from_slice(&other.vertices);
        for p in &other.parts {
            self.parts.push(MeshPart { group: gmap[p.group as usize], convex_solid: p.convex_solid });
        }
        for (t, p) in other.triangles.iter().zip(&other.part_of) {
            self.triangles.push([t[0] + vbase, t[1] + vbase, t[2] + vbase]);
            self.part_of.push(p + pbase);
        }
    }

    /// Drops vertices no triangle uses (parts are added with their whole vertex
    /// arrays) and renumbers the rest, keeping their order.
    pub fn compact(&mut self) {
        let mut used = vec![false; self.vertices.len()];
        for t in &self.triangles {
            for &i in t {
                used[i as usize] = true;
            }
        }
        if used.iter().all(|u| *u) {
            return;
        }
        let mut map = vec![u32::MAX; self.vertices.len()];
        let mut out = Vec::with_capacity(self.vertices.len());
        for (i, v) in self.vertices.iter().enumerate() {
            if used[i] {
                map[i] = out.len() as u32;
                out.push(*v);
            }
        }
        self.vertices = out;
        for t in &mut self.triangles {
            for i in t.iter_mut() {
                *i = map[*i as usize];
            }
        }
    }

    pub fn transform(&mut self, pose: &Pose) {
        for v in &mut self.vertices {
            let q = pose * Point3::new(v[0], v[1], v[2]);
            *v = [q.x, q.y, q.z];
        }
    }

    /// Group name of triangle `t`.
    pub fn group_of_triangle(&self, t: usize) -> &str {
        let p = self.part_of[t] as usize;
        &self.groups[self.parts[p].group as usize]
    }

    /// Total surface area in square metres.
    pub fn area(&self) -> f64 {
        self.triangles.iter().map(|t| tri_area(self.v(t[0]), self.v(t[1]), self.v(t[2]))).sum()
    }

    /// Signed enclosed volume (divergence theorem); meaningful for closed,
    /// outward-oriented meshes.
    pub fn signed_volume(&self) -> f64 {
        self.triangles
            .iter()
            .map(|t| {
                let (a, b, c) = (self.v(t[0]), self.v(t[1]), self.v(t[2]));
                a.coords.dot(&b.coords.cross(&c.coords)) / 6.0
            })
            .sum()
    }

    fn v(&self, i: u32) -> Point3 {
        let p = self.vertices[i as usize];
        Point3::new(p[0], p[1], p[2])
    }

    /// Checks indices and columns; a mesh from a file must pass before use.
    pub fn validate(&self) -> Result<(), String> {
        let nv = self.vertices.len() as u32;
        if self.part_of.len() != self.triangles.len() {
            return Err(format!("{} part indices for {} triangles", self.part_of.len(), self.triangles.len()));
        }
        for (i, t) in self.triangles.iter().enumerate() {
            if t.iter().any(|&k| k >= nv) {
                return Err(format!("triangle {i} refers to a vertex past the {nv} vertices"));
            }
        }
        if let Some(i) = self.part_of.iter().position(|&p| p as usize >= self.parts.len()) {
            return Err(format!("triangle {i} refers to a missing part"));
        }
        if let Some(i) = self.parts.iter().position(|p| p.group as usize >= self.groups.len()) {
            return Err(format!("part {i} refers to a missing group"));
        }
        if let Some(i) = self.vertices.iter().position(|v| v.iter().any(|c| !c.is_finite())) {
            return Err(format!("vertex {i} is not finite"));
        }
        Ok(())
    }

    pub fn to_artifact_bytes(&self) -> Vec<u8> {
        let mut w = ByteWriter::new();
        w.u64(self.groups.len() as u64);
        for g in &self.groups {
            w.str(g);
        }
        w.u64(self.parts.len() as u64);
        for p in &self.parts {
            w.u32(p.group);
            w.u8(p.convex_solid as u8);
        }
        w.u64(self.vertices.len() as u64);
        for v in &self.vertices {
            for c in v {
                w.f64(*c);
            }
        }
        w.u64(self.triangles.len() as u64);
        for (t, p) in self.triangles.iter().zip(&self.part_of) {
            w.u32(t[0]);
            w.u32(t[1]);
            w.u32(t[2]);
            w.u32(*p);
        }
        artifact::encode(ARTIFACT_KIND, ARTIFACT_VERSION, &w.buf)
    }

    pub fn write_artifact(&self, path: &Path) -> Result<(), ArtifactError> {
        artifact::write_atomic(path, &self.to_artifact_bytes())
            .map_err(|e| ArtifactError::Io(crate::Location::file(path), e))
    }

    pub fn read_artifact(path: &Path) -> Result<TriMesh, ArtifactError> {
        let bytes = std::fs::read(path).map_err(|e| ArtifactError::Io(crate::Location::file(path), e))?;
        Self::from_artifact_bytes(path, &bytes)
    }

    pub fn from_artifact_bytes(path: &Path, bytes: &[u8]) -> Result<TriMesh, ArtifactError> {
        let payload = artifact::decode(path, bytes, ARTIFACT_KIND, ARTIFACT_VERSION)?;
        let mut r = ByteReader::new(path, payload, 32);
        let ng = r.count(4)?;
        let mut m = TriMesh::default();
        for _ in 0..ng {
            m.groups.push(r.str()?);
        }
        let np = r.count(5)?;
        for _ in 0..np {
            let group = r.u32()?;
            let convex_solid = r.u8()? != 0;
            m.parts.push(MeshPart { group, convex_solid });
        }
        let nv = r.count(24)?;
        m.vertices.reserve(nv);
        for _ in 0..nv {
            m.vertices.push([r.f64()?, r.f64()?, r.f64()?]);
        }
        let nt = r.count(16)?;
        m.triangles.reserve(nt);
        m.part_of.reserve(nt);
        for _ in 0..nt {
            m.triangles.push([r.u32()?, r.u32()?, r.u32()?]);
            m.part_of.push(r.u32()?);
        }
        r.finish()?;
        m.validate().map_err(|e| r.error(e))?;
        Ok(m)
    }

    /// Binary little-endian PLY with a `part` and `group` index per face, readable
    /// by MeshLab, CloudCompare and Blender. Vertices are written as `double` so
    /// georeferenced coordinates keep their precision.
    pub fn write_ply(&self, path: &Path) -> std::io::Result<()> {
        artifact::write_atomic_with(path, |w| {
            writeln!(w, "ply")?;
            writeln!(w, "format binary_little_endian 1.0")?;
            writeln!(w, "comment liftplan merged plant mesh")?;
            for (i, g) in self.groups.iter().enumerate() {
                writeln!(w, "comment group {i} {}", g.replace(['\n', '\r'], " "))?;
            }
            writeln!(w, "element vertex {}", self.vertices.len())?;
            writeln!(w, "property double x")?;
            writeln!(w, "property double y")?;
            writeln!(w, "property double z")?;
            writeln!(w, "element face {}", self.triangles.len())?;
            writeln!(w, "property list uchar uint vertex_indices")?;
            writeln!(w, "property uint part")?;
            writeln!(w, "property uint group")?;
            writeln!(w, "end_header")?;
            for v in &self.vertices {
                for c in v {
                    w.write_all(&c.to_le_bytes())?;
                }
            }
            for (t, p) in self.triangles.iter().zip(&self.part_of) {
                w.write_all(&[3u8])?;
                for i in t {
                    w.write_all(&i.to_le_bytes())?;
                }
                w.write_all(&p.to_le_bytes())?;
                w.write_all(&self.parts[*p as usize].group.to_le_bytes())?;
            }
            Ok(())
        })
    }
}

/// A group the plant stage left out of the mesh (`[plant] exclude`), as the
/// smallest upright box around it in the site frame
/// ([`crate::obb::smallest_upright_box`]): most often the equipment a lift
/// installs, drawn in the model where it is installed, which the planner
/// compares with the lift's set position. Not an obstacle.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ModelBox {
    pub name: String,
    pub center_m: [f64; 3],
    /// Half sizes along the box's axes: the first along its longer side.
    pub half_m: [f64; 3],
    /// The first axis' direction, counter-clockwise from the site's +X, in
    /// (-90, 90] degrees.
    pub yaw_deg: f64,
    /// The boxes around its parts (an RVM group's primitives, a mesh's
    /// connected pieces, each its own smallest upright box), where it has
    /// more than one and they are not too many: tighter than the one box
    /// around an L-shaped or sparse group.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub parts: Vec<ModelBox>,
}

impl ModelBox {
    /// The box around `points` (site frame), or `None` where none is finite.
    pub fn around(name: &str, points: &[[f64; 3]]) -> Option<ModelBox> {
        let b = crate::obb::smallest_upright_box(points)?;
        Some(ModelBox {
            name: name.to_string(),
            center_m: [b.center.x, b.center.y, b.center.z],
            half_m: [b.half.x, b.half.y, b.half.z],
            yaw_deg: b.axes[(1, 0)].atan2(b.axes[(0, 0)]).to_degrees(),
            parts: Vec::new(),
        })
    }

    /// The boxes of the groups the plant stage left out, from its plant.json
    /// (none in one written before it had them), as it writes them
    /// ([`ModelBox::not_as_written`]); an error says where the file is not.
    pub fn left_out_in_plant_json(bytes: &[u8]) -> Result<Vec<ModelBox>, String> {
        #[derive(serde::Deserialize)]
        struct PlantJson {
            #[serde(default)]
            excluded_boxes: Vec<ModelBox>,
        }
        let j: PlantJson =
            serde_json::from_slice(bytes).map_err(|e| format!("line {}, column {}: {e}", e.line(), e.column()))?;
        match ModelBox::not_as_written(&j.excluded_boxes) {
            Some(problem) => Err(format!("{problem}; rerun the plant stage (liftplan run --force plant)")),
            None => Ok(j.excluded_boxes),
        }
    }

    /// What is wrong with `boxes` read back (the plant stage's plant.json,
    /// edited or damaged) where they are not as the plant stage writes them:
    /// a name longer than it keeps ([`group_name_kept`]), a negative size, a
    /// long side shorter than the short one, a yaw past 90° either way, a
    /// part with parts of its own, or more parts than
    /// [`MAX_MODEL_BOX_PARTS`] all told; named by the box's place.
    pub fn not_as_written(boxes: &[ModelBox]) -> Option<String> {
        let parts: usize = boxes.iter().map(|b| b.parts.len()).sum();
        if parts > MAX_MODEL_BOX_PARTS {
            return Some(format!(
                "{parts} parts' boxes, more than the plant stage keeps (at most {MAX_MODEL_BOX_PARTS} over all the groups it leaves out)"
            ));
        }
        let one = |b: &ModelBox| -> Option<String> {
            if b.name.chars().any(char::is_control) {
                return Some("its name holds control characters, which the plant stage does not keep".to_string());
            }
            if group_name_kept(&b.name) != b.name {
                return Some(format!(
                    "its name is {} characters long, not as the plant stage keeps a long name (its first {MAX_GROUP_NAME_CHARS} characters, \"... #\" and eight hex digits)",
                    b.name.chars().count()
                ));
            }
            let [long, short, height] = b.half_m;
            if !(long >= short && short >= 0.0 && height >= 0.0) {
                return Some(format!(
                    "half_m {:?}: half sizes are not negative, the long side's first (as the plant stage writes them)",
                    b.half_m
                ));
            }
            if !(b.yaw_deg.abs() <= 90.0 + 1e-9) {
                return Some(format!("yaw_deg {}: the plant stage writes a box's yaw in (-90, 90] degrees", b.yaw_deg));
            }
            None
        };
        boxes.iter().enumerate().find_map(|(k, b)| {
            let said = |at: String, problem: String| {
                let name: String = b.name.chars().take(80).collect();
                format!("excluded_boxes[{k}]{at} ('{}'): {problem}", group_name_kept(&name))
            };
            if let Some(problem) = one(b) {
                return Some(said(String::new(), problem));
            }
            b.parts.iter().enumerate().find_map(|(n, part)| {
                let problem =
                    if part.parts.is_empty() { one(part)? } else { "a part with parts of its own".to_string() };
                Some(said(format!(".parts[{n}]"), problem))
            })
        })
    }

    /// The boxes that hold it: its parts' where it has them, else itself.
    pub fn boxes(&self) -> &[ModelBox] {
        if self.parts.is_empty() { std::slice::from_ref(self) } else { &self.parts }
    }

    pub fn obb(&self) -> crate::obb::Obb {
        crate::obb::Obb::new(
            Point3::from(self.center_m),
            crate::frame::rot_z(self.yaw_deg.to_radians()),
            crate::frame::Vec3::from(self.half_m),
        )
    }
}

pub fn tri_area(a: Point3, b: Point3, c: Point3) -> f64 {
    0.5 * (b - a).cross(&(c - a)).norm()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube() -> TriMesh {
        let mut m = TriMesh::default();
        let g = m.group_id("/CUBE");
        let v: Vec<[f64; 3]> = (0..8).map(|k| [(k & 1) as f64, ((k >> 1) & 1) as f64, ((k >> 2) & 1) as f64]).collect();
        let quads = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]];
        let mut t = Vec::new();
        for q in quads {
            t.push([q[0], q[1], q[2]]);
            t.push([q[0], q[2], q[3]]);
        }
        m.add_part(g, true, &v, &t);
        m
    }

    #[test]
    fn group_names_kept_to_their_first_200_characters() {
        assert_eq!(group_name_kept("/PIPE-RACK-2"), "/PIPE-RACK-2");
        let longer = "/A".repeat(50_000);
        assert_eq!(group_name_kept(&longer), crate::names::kept(&longer, MAX_GROUP_NAME_CHARS));
        assert_eq!(group_name_kept(&longer).chars().count(), MAX_GROUP_NAME_CHARS + crate::names::TAG_CHARS);
    }

    /// Boxes as the plant stage writes them (around points, with parts, a
    /// name kept short) are taken; each thing it never writes is named with
    /// the box's place.
    #[test]
    fn model_boxes_not_as_the_plant_stage_writes_them_are_named() {
        let points = |x: f64| [[x, 0.0, 0.0], [x + 4.0, 1.0, 0.0], [x + 3.0, -2.0, 2.0], [x - 1.0, 0.5, 1.0]];
        let name = group_name_kept(&"/V-101".repeat(100)).into_owned();
        let mut group = ModelBox::around(&name, &[points(0.0), points(9.0)].concat()).unwrap();
        group.parts = [0.0, 9.0].map(|x| ModelBox::around(&name, &points(x)).unwrap()).to_vec();
        let written = vec![ModelBox::around("/P-1", &points(-20.0)).unwrap(), group];
        assert_eq!(ModelBox::not_as_written(&written), None);
        let wrong = |edit: &dyn Fn(&mut Vec<ModelBox>)| {
            let mut boxes = written.clone();
            edit(&mut boxes);
            ModelBox::not_as_written(&boxes).unwrap_or_default()
        };
        let said = wrong(&|b| b[0].half_m[2] = -0.5);
        assert!(said.starts_with("excluded_boxes[0] ('/P-1'): half_m [") && said.contains("-0.5]"), "{said}");
        let said = wrong(&|b| b[1].parts[1].half_m.swap(0, 1));
        assert!(said.starts_with("excluded_boxes[1].parts[1] ('/V-101/V-101"), "{said}");
        assert!(wrong(&|b| b[0].yaw_deg = 90.5).contains("yaw_deg 90.5: the plant stage writes"));
        let said = wrong(&|b| b[0].name = "/P".repeat(101));
        assert!(said.contains("its name is 202 characters long, not as the plant stage keeps"), "{said}");
        let said = wrong(&|b| b[0].name = "/P-1\r".into());
        assert!(said.ends_with("its name holds control characters, which the plant stage does not keep"), "{said}");
        let said = wrong(&|b| b[1].parts[0].parts = vec![b[0].clone()]);
        assert!(
            said.starts_with("excluded_boxes[1].parts[0]") && said.ends_with("a part with parts of its own"),
            "{said}"
        );
        let said = wrong(&|b| b[0].parts = vec![b[0].clone(); MAX_MODEL_BOX_PARTS]);
        assert!(said.starts_with(&format!("{} parts' boxes, more than", MAX_MODEL_BOX_PARTS + 2)), "{said}");
    }

    /// The demo's plant.json (the `plant_json` fuzz target's seed) is read:
    /// its one box left out, the vessel the demo lifts.
    #[test]
    fn the_demos_plant_json_is_read() {
        let demo = include_bytes!("../../../fuzz/seeds/plant_json/demo-plant.json");
        let boxes = ModelBox::left_out_in_plant_json(demo).unwrap();
        assert_eq!(boxes.iter().map(|b| b.name.as_str()).collect::<Vec<_>>(), ["/V-101"]);
        let e = ModelBox::left_out_in_plant_json(&demo[..demo.len() / 2]).unwrap_err();
        assert!(e.starts_with("line "), "{e}");
    }

    #[test]
    fn volume_area_roundtrip() {
        let m = cube();
        assert!((m.signed_volume() - 1.0).abs() < 1e-12);
        assert!((m.area() - 6.0).abs() < 1e-12);
        let d = tempfile::tempdir().unwrap();
        let p = d.path().join("m.bin");
        m.write_artifact(&p).unwrap();
        assert_eq!(TriMesh::read_artifact(&p).unwrap(), m);
        m.write_ply(&d.path().join("m.ply")).unwrap();
    }

    #[test]
    fn group_index_gives_group_id_s_ids() {
        let mut by_index = TriMesh { groups: ["A", "B", "A"].map(String::from).to_vec(), ..Default::default() };
        let mut by_name = by_index.clone();
        let mut index = GroupIndex::of(&by_index);
        for name in ["A", "B", "C", "A", "C", "D"] {
            assert_eq!(index.id(&mut by_index, name), by_name.group_id(name), "{name}");
        }
        assert_eq!(by_index.groups, ["A", "B", "A", "C", "D"]);
        assert_eq!(by_index, by_name);
    }

    #[test]
    fn appending_through_one_index_is_appending() {
        let parts = |names: &[&str]| {
            let mut m = cube();
            for n in names {
                let g = m.group_id(n);
                m.add_part(g, false, &[[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], &[[0, 1, 2]]);
            }
            m
        };
        let meshes = [parts(&["A", "B"]), parts(&["B", "C", "A"]), parts(&[]), parts(&["D", "C"])];
        let (mut each, mut once) = (parts(&["C"]), parts(&["C"]));
        let mut index = GroupIndex::of(&once);
        for m in &meshes {
            each.append(m);
            once.append_with(m, &mut index);
        }
        assert_eq!(once, each);
        assert_eq!(once.groups.len(), 5, "{:?}", once.groups);
    }

    #[test]
    fn append_merges_groups() {
        let mut a = cube();
        let b = cube();
        a.append(&b);
        assert_eq!(a.groups.len(), 1);
        assert_eq!(a.triangle_count(), 24);
        a.validate().unwrap();
        assert_eq!(a.group_of_triangle(20), "/CUBE");
    }
}
