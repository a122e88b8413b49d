//! Mesh inputs from BIM tools: OBJ (`tobj`), PLY (`ply-rs`), STL (`stl_io`) and
//! glTF/GLB (`gltf`, node transforms applied). Each object, node or file becomes
//! a group; its triangles are surfaces (not assumed closed or convex).
//!
//! Units and up axis come from the settings; glTF is metres and Y-up by its
//! specification, so it ignores both.

use crate::error::{PlantError, Result};
use liftplan_core::Location;
use liftplan_core::mesh::{GroupIndex, TriMesh};
use std::collections::HashMap;
use std::path::Path;
use std::rc::Rc;

/// How to bring a mesh file into the site frame's units and axes.
#[derive(Debug, Clone, Copy)]
pub struct Import {
    /// File units to metres.
    pub scale: f64,
    /// The file is Y-up (rotate +90 degrees about X so Y becomes Z).
    pub y_up: bool,
}

impl Import {
    fn apply(&self, p: [f64; 3]) -> [f64; 3] {
        let s = self.scale;
        if self.y_up { [p[0] * s, -p[2] * s, p[1] * s] } else { [p[0] * s, p[1] * s, p[2] * s] }
    }
}

fn stem(path: &Path) -> String {
    path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "mesh".into())
}

fn check_finite(path: &Path, m: &TriMesh) -> Result<()> {
    m.validate().map_err(|e| PlantError::at(Location::file(path), e))
}

/// Counts the OBJ line (`l`) and point (`p`) elements in the bytes read
/// through it: tobj reads faces only, and what has no surface is left out
/// of the obstacles, which must be said. Counted as tobj reads, so that a
/// model of hundreds of megabytes is read once.
struct ElementsWithoutSurface<R> {
    inner: R,
    line: LineStart,
    count: usize,
}

/// Where [`ElementsWithoutSurface`] is in the current line.
#[derive(Clone, Copy)]
enum LineStart {
    /// Before its first non-blank byte.
    Blank,
    /// Just after a first `l` or `p`: an element if a blank follows.
    Candidate,
    /// Past its keyword.
    Rest,
}

impl<R: std::io::Read> std::io::Read for ElementsWithoutSurface<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.inner.read(buf)?;
        for &b in &buf[..n] {
            self.line = match (self.line, b) {
                (LineStart::Candidate, b) if b.is_ascii_whitespace() => {
                    self.count += 1;
                    if b == b'\n' { LineStart::Blank } else { LineStart::Rest }
                }
                (_, b'\n') => LineStart::Blank,
                (LineStart::Blank, b) if b.is_ascii_whitespace() => LineStart::Blank,
                (LineStart::Blank, b'l' | b'p') => LineStart::Candidate,
                _ => LineStart::Rest,
            };
        }
        Ok(n)
    }
}

/// The OBJ file's faces as a mesh, and how many line and point elements
/// it holds besides (not read: they have no surface).
pub fn read_obj(path: &Path, imp: Import) -> Result<(TriMesh, usize)> {
    let opts = tobj::LoadOptions { triangulate: true, single_index: true, ignore_points: true, ignore_lines: true };
    let file = std::fs::File::open(path).map_err(|e| PlantError::Io(Location::file(path), e))?;
    let mut counted = ElementsWithoutSurface { inner: file, line: LineStart::Blank, count: 0 };
    let mut r = std::io::BufReader::new(&mut counted);
    liftplan_core::byte_order_mark::skip(&mut r).map_err(|e| PlantError::Io(Location::file(path), e))?;
    let (models, _) = third_party(path, "the OBJ reader", || {
        tobj::load_obj_buf(&mut r, &opts, |_| Err(tobj::LoadError::OpenFileFailed))
    })?
    .map_err(|e| PlantError::at(Location::file(path), format!("cannot read OBJ: {e}")))?;
    let mut m = TriMesh::default();
    let mut groups = GroupIndex::of(&m);
    for model in &models {
        let name = if model.name.is_empty() { stem(path) } else { model.name.clone() };
        let g = groups.id(&mut m, &name);
        let pos = &model.mesh.positions;
        let verts: Vec<[f64; 3]> = pos
            .chunks(3)
            .filter(|c| c.len() == 3)
            .map(|c| imp.apply([c[0] as f64, c[1] as f64, c[2] as f64]))
            .collect();
        let mut tris = Vec::with_capacity(model.mesh.indices.len() / 3);
        for t in model.mesh.indices.chunks(3) {
            if t.len() == 3 {
                if t.iter().any(|&i| i as usize >= verts.len()) {
                    return Err(PlantError::at(
                        Location::item(path, &name),
                        "a face refers to a vertex that does not exist",
                    ));
                }
                tris.push([t[0], t[1], t[2]]);
            }
        }
        m.add_part(g, false, &verts, &tris);
    }
    check_finite(path, &m)?;
    drop(r);
    Ok((m, counted.count))
}

pub fn read_stl(path: &Path, imp: Import) -> Result<TriMesh> {
    let mut f = std::fs::File::open(path).map_err(|e| PlantError::Io(Location::file(path), e))?;
    // A text STL with a byte order mark: the mark and then "solid" (a
    // binary file's 80-byte header may start with anything, the mark's
    // bytes too, but is then not taken for one).
    let mut head = [0u8; 8];
    let marked = std::io::Read::read_exact(&mut f, &mut head).is_ok()
        && head[..3] == liftplan_core::byte_order_mark::BYTES
        && head[3..].eq_ignore_ascii_case(b"solid");
    // The STL reader seeks back to the file's start: a marked file is read
    // from memory past its mark.
    let mesh = if marked {
        let bytes = std::fs::read(path).map_err(|e| PlantError::Io(Location::file(path), e))?;
        let mut text = std::io::Cursor::new(liftplan_core::byte_order_mark::strip(&bytes));
        third_party(path, "the STL reader", || stl_io::read_stl(&mut text))?
    } else {
        std::io::Seek::rewind(&mut f).map_err(|e| PlantError::Io(Location::file(path), e))?;
        third_party(path, "the STL reader", || stl_io::read_stl(&mut f))?
    }
    .map_err(|e| PlantError::at(Location::file(path), format!("cannot read STL: {e}")))?;
    let mut m = TriMesh::default();
    let g = m.group_id(&stem(path));
    let verts: Vec<[f64; 3]> =
        mesh.vertices.iter().map(|v| imp.apply([v[0] as f64, v[1] as f64, v[2] as f64])).collect();
    let tris: Vec<[u32; 3]> =
        mesh.faces.iter().map(|f| [f.vertices[0] as u32, f.vertices[1] as u32, f.vertices[2] as u32]).collect();
    m.add_part(g, false, &verts, &tris);
    check_finite(path, &m)?;
    Ok(m)
}

#[derive(Default)]
struct PlyVertex {
    p: [f64; 3],
}

impl ply_rs::ply::PropertyAccess for PlyVertex {
    fn new() -> Self {
        PlyVertex::default()
    }
    fn set_property(&mut self, key: String, p: ply_rs::ply::Property) {
        use ply_rs::ply::Property as P;
        let v = match p {
            P::Float(v) => v as f64,
            P::Double(v) => v,
            P::Int(v) => v as f64,
            P::UInt(v) => v as f64,
            P::Short(v) => v as f64,
            P::UShort(v) => v as f64,
            P::Char(v) => v as f64,
            P::UChar(v) => v as f64,
            _ => return,
        };
        // In any case: some tools write X, Y, Z.
        if let Some(axis) = ["x", "y", "z"].iter().position(|a| key.eq_ignore_ascii_case(a)) {
            self.p[axis] = v;
        }
    }
}

#[derive(Default)]
struct PlyFace {
    idx: Vec<u32>,
}

impl ply_rs::ply::PropertyAccess for PlyFace {
    fn new() -> Self {
        PlyFace::default()
    }
    fn set_property(&mut self, key: String, p: ply_rs::ply::Property) {
        use ply_rs::ply::Property as P;
        if key != "vertex_indices" && key != "vertex_index" {
            return;
        }
        self.idx = match p {
            P::ListInt(v) => v.into_iter().map(|x| x.max(0) as u32).collect(),
            P::ListUInt(v) => v,
            P::ListShort(v) => v.into_iter().map(|x| x.max(0) as u32).collect(),
            P::ListUShort(v) => v.into_iter().map(|x| x as u32).collect(),
            P::ListUChar(v) => v.into_iter().map(|x| x as u32).collect(),
            P::ListChar(v) => v.into_iter().map(|x| x.max(0) as u32).collect(),
            _ => return,
        };
    }
}

pub fn read_ply(path: &Path, imp: Import) -> Result<TriMesh> {
    // ply-rs unwraps numbers in the header and panics on one too large for
    // 64 bits (found by the plant_mesh fuzz target).
    third_party(path, "the PLY reader", || read_ply_unguarded(path, imp))?
}

fn read_ply_unguarded(path: &Path, imp: Import) -> Result<TriMesh> {
    use ply_rs::parser::Parser;
    let f = std::fs::File::open(path).map_err(|e| PlantError::Io(Location::file(path), e))?;
    let mut r = std::io::BufReader::new(f);
    liftplan_core::byte_order_mark::skip(&mut r).map_err(|e| PlantError::Io(Location::file(path), e))?;
    let header = Parser::<ply_rs::ply::DefaultElement>::new()
        .read_header(&mut r)
        .map_err(|e| PlantError::at(Location::file(path), format!("cannot read PLY header: {e}")))?;
    let mut verts: Vec<[f64; 3]> = Vec::new();
    let mut faces: Vec<PlyFace> = Vec::new();
    for (name, def) in &header.elements {
        let loc = || Location::item(path, format!("element '{name}'"));
        match name.as_str() {
            "vertex" => {
                for axis in ["x", "y", "z"] {
                    if !def.properties.keys().any(|k| k.eq_ignore_ascii_case(axis)) {
                        return Err(PlantError::at(loc(), format!("no property '{axis}' (expected x, y and z)")));
                    }
                }
                let vs: Vec<PlyVertex> = Parser::<PlyVertex>::new()
                    .read_payload_for_element(&mut r, def, &header)
                    .map_err(|e| PlantError::at(loc(), e.to_string()))?;
                verts = vs.into_iter().map(|v| imp.apply(v.p)).collect();
            }
            "face" => {
                faces = Parser::<PlyFace>::new()
                    .read_payload_for_element(&mut r, def, &header)
                    .map_err(|e| PlantError::at(loc(), e.to_string()))?;
            }
            _ => {
                Parser::<ply_rs::ply::DefaultElement>::new()
                    .read_payload_for_element(&mut r, def, &header)
                    .map_err(|e| PlantError::at(loc(), e.to_string()))?;
            }
        }
    }
    let mut tris = Vec::new();
    for (i, f) in faces.iter().enumerate() {
        if f.idx.iter().any(|&k| k as usize >= verts.len()) {
            return Err(PlantError::at(
                Location::item(path, format!("face {i}")),
                "refers to a vertex that does not exist",
            ));
        }
        for k in 1..f.idx.len().saturating_sub(1) {
            tris.push([f.idx[0], f.idx[k], f.idx[k + 1]]);
        }
    }
    let mut m = TriMesh::default();
    let g = m.group_id(&stem(path));
    m.add_part(g, false, &verts, &tris);
    check_finite(path, &m)?;
    Ok(m)
}

/// The scene's buffers, in order. A file beside the glTF is read once however
/// many buffers name it: a few hundred bytes of JSON naming one large file
/// thousands of times would otherwise hold it in memory thousands of times.
fn load_buffers(path: &Path, doc: &gltf::Document, blob: Option<Vec<u8>>) -> Result<Vec<Rc<[u8]>>> {
    use base64::Engine;
    let mut out = Vec::new();
    let mut files: HashMap<String, Rc<[u8]>> = HashMap::new();
    let mut blob = blob;
    for b in doc.buffers() {
        let data: Rc<[u8]> = match b.source() {
            gltf::buffer::Source::Bin => blob
                .take()
                .ok_or_else(|| PlantError::at(Location::file(path), "GLB buffer without a binary chunk"))?
                .into(),
            gltf::buffer::Source::Uri(uri) => {
                if let Some(rest) = uri.strip_prefix("data:") {
                    let b64 = rest
                        .split_once(";base64,")
                        .map(|x| x.1)
                        .ok_or_else(|| PlantError::at(Location::file(path), "data URI buffer is not base64"))?;
                    base64::engine::general_purpose::STANDARD
                        .decode(b64)
                        .map_err(|e| PlantError::at(Location::file(path), format!("bad base64 buffer: {e}")))?
                        .into()
                } else if let Some(data) = files.get(uri) {
                    data.clone()
                } else {
                    if uri.contains("..") || uri.starts_with('/') || uri.contains("://") {
                        return Err(PlantError::at(
                            Location::file(path),
                            format!("buffer URI '{uri}' must be a file beside the glTF"),
                        ));
                    }
                    let p = path.parent().unwrap_or(Path::new(".")).join(uri);
                    let data: Rc<[u8]> = std::fs::read(&p).map_err(|e| PlantError::Io(Location::file(&p), e))?.into();
                    files.insert(uri.to_string(), data.clone());
                    data
                }
            }
        };
        if data.len() < b.length() {
            return Err(PlantError::at(
                Location::file(path),
                format!("buffer {} holds {} bytes, the file says {}", b.index(), data.len(), b.length()),
            ));
        }
        out.push(data);
    }
    Ok(out)
}

/// Reads a glTF or GLB scene, refusing it once its meshes, placed by its
/// nodes, pass `max_triangles` (a scene may place one mesh many times, so
/// the file's size does not bound the model's).
pub fn read_gltf(path: &Path, max_triangles: u64) -> Result<TriMesh> {
    read_gltf_noting(path, max_triangles, &mut Vec::new())
}

/// [`read_gltf`], adding to `skipped` a line for each primitive drawn as
/// points or lines, which has no surface to keep (what is left out of the
/// obstacles must be said where the plan's signer reads it).
pub fn read_gltf_noting(path: &Path, max_triangles: u64, skipped: &mut Vec<String>) -> Result<TriMesh> {
    // The gltf crate's validation indexes accessors it has not checked yet and
    // panics on such a file (found by the plant_mesh fuzz target).
    third_party(path, "the glTF reader", || read_gltf_unguarded(path, max_triangles, skipped))?
}

/// The triangles of a primitive's index list in its drawing mode: a list,
/// a strip (every three consecutive corners, every other one turned round)
/// or a fan (the first corner with every two consecutive others); `None`
/// for points and lines. Triangles with a repeated corner (a strip's
/// restarts) have no area and are left out.
fn triangles_of(mode: gltf::mesh::Mode, idx: &[u32]) -> Option<Vec<[u32; 3]>> {
    use gltf::mesh::Mode;
    let tris: Vec<[u32; 3]> = match mode {
        Mode::Triangles => idx.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect(),
        Mode::TriangleStrip => idx
            .windows(3)
            .enumerate()
            .map(|(k, w)| if k % 2 == 0 { [w[0], w[1], w[2]] } else { [w[1], w[0], w[2]] })
            .collect(),
        Mode::TriangleFan => idx.windows(2).skip(1).map(|w| [idx[0], w[0], w[1]]).collect(),
        Mode::Points | Mode::Lines | Mode::LineLoop | Mode::LineStrip => return None,
    };
    Some(tris.into_iter().filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2]).collect())
}

/// Calls a third-party parser (or a reader built on one), turning a panic
/// inside it into an error naming the file (see [`liftplan_core::guard`]).
/// The fuzzers found the gltf crate and ply-rs panicking; OBJ's and STL's
/// parsers have not, but a damaged file should be that file's error whatever
/// its parser does.
fn third_party<T>(path: &Path, what: &str, parse: impl FnOnce() -> T) -> Result<T> {
    liftplan_core::guard::run_reader(what, parse).map_err(|why| PlantError::at(Location::file(path), why))
}

fn read_gltf_unguarded(path: &Path, max_triangles: u64, skipped: &mut Vec<String>) -> Result<TriMesh> {
    let bytes = std::fs::read(path).map_err(|e| PlantError::Io(Location::file(path), e))?;
    // A .gltf is JSON text, which a Windows tool may save with a mark (a
    // .glb starts with "glTF", never with one).
    let g = gltf::Gltf::from_slice(liftplan_core::byte_order_mark::strip(&bytes))
        .map_err(|e| PlantError::at(Location::file(path), format!("cannot read glTF: {e}")))?;
    let buffers = load_buffers(path, &g.document, g.blob.clone())?;
    let imp = Import { scale: 1.0, y_up: true };
    let mut m = TriMesh::default();
    let mut groups = GroupIndex::of(&m);
    let scene = g.document.default_scene().or_else(|| g.document.scenes().next());
    let Some(scene) = scene else { return Ok(m) };
    let mut stack: Vec<(gltf::Node, nalgebra::Matrix4<f64>)> =
        scene.nodes().map(|n| (n, nalgebra::Matrix4::identity())).collect();
    // glTF nodes form trees. A node reached twice (a cycle, or a node with
    // two parents) would be walked without end or place its subtree once per
    // path to it, which grows exponentially with depth.
    let mut reached = vec![false; g.document.nodes().len()];
    while let Some((node, parent)) = stack.pop() {
        if std::mem::replace(&mut reached[node.index()], true) {
            return Err(PlantError::at(
                Location::item(path, format!("node {}", node.index())),
                "the node is reached twice in the scene (a cycle, or a node with two parents); glTF nodes must form trees",
            ));
        }
        let local = nalgebra::Matrix4::from_column_slice(
            &node.transform().matrix().concat().iter().map(|v| *v as f64).collect::<Vec<_>>(),
        );
        let world = parent * local;
        if let Some(mesh) = node.mesh() {
            let name = node
                .name()
                .or(mesh.name())
                .map(String::from)
                .unwrap_or_else(|| format!("{} node {}", stem(path), node.index()));
            let gid = groups.id(&mut m, &name);
            for prim in mesh.primitives() {
                if triangles_of(prim.mode(), &[]).is_none() {
                    skipped.push(format!("{name} ({:?})", prim.mode()));
                    continue;
                }
                // Counted before the positions are read, since the scene may
                // place this mesh many times. Positions count too: a mesh of
                // a few indices into millions of positions is read whole at
                // every place.
                let count = |a: Option<gltf::Accessor>| a.map_or(0, |a| a.count() as u64);
                let corners = count(prim.indices()).max(count(prim.get(&gltf::Semantic::Positions)));
                let most = match prim.mode() {
                    gltf::mesh::Mode::Triangles => corners / 3,
                    _ => corners.saturating_sub(2),
                };
                if m.triangle_count() as u64 + most > max_triangles {
                    return Err(PlantError::at(
                        Location::item(path, &name),
                        format!(
                            "the scene's meshes, as its nodes place them, make more than {max_triangles} \
                             triangles, the room the plant has left of the {} it may have; simplify the model",
                            crate::MAX_TRIANGLES
                        ),
                    ));
                }
                let reader = prim.reader(|b| buffers.get(b.index()).map(|d| &d[..]));
                let Some(pos) = reader.read_positions() else { continue };
                let verts: Vec<[f64; 3]> = pos
                    .map(|p| {
                        let v = world * nalgebra::Vector4::new(p[0] as f64, p[1] as f64, p[2] as f64, 1.0);
                        imp.apply([v.x, v.y, v.z])
                    })
                    .collect();
                let idx: Vec<u32> = match reader.read_indices() {
                    Some(i) => i.into_u32().collect(),
                    None => (0..verts.len() as u32).collect(),
                };
                if idx.iter().any(|&i| i as usize >= verts.len()) {
                    return Err(PlantError::at(
                        Location::item(path, &name),
                        "an index refers to a vertex that does not exist",
                    ));
                }
                let tris = triangles_of(prim.mode(), &idx).unwrap_or_default();
                m.add_part(gid, false, &verts, &tris);
            }
        }
        for c in node.children() {
            stack.push((c, world));
        }
    }
    check_finite(path, &m)?;
    Ok(m)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Found by the plant_mesh fuzz target: a glTF whose mesh names a
    /// position accessor (5) that does not exist. The gltf crate's validation
    /// indexed it and panicked; the reader now refuses the file.
    #[test]
    fn a_gltf_naming_a_missing_accessor_is_refused() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/plant/damaged-accessor.gltf");
        let e = read_gltf(&path, crate::MAX_TRIANGLES).unwrap_err().to_string();
        assert!(e.contains("damaged-accessor.gltf") && e.contains("failed on damaged data"), "{e}");
        // The same file naming accessor 0 reads.
        let d = tempfile::tempdir().unwrap();
        let good = d.path().join("tet.gltf");
        let text = std::fs::read_to_string(&path).unwrap().replace("\"POSITION\": 5", "\"POSITION\": 0");
        std::fs::write(&good, text).unwrap();
        assert_eq!(read_gltf(&good, crate::MAX_TRIANGLES).unwrap().triangles.len(), 4);
    }
    /// The fixture's tetrahedron (4 triangles) with `nodes` as the scene's
    /// node list and the scene's roots `roots`.
    fn tet_scene(dir: &Path, nodes: &str, roots: &str) -> std::path::PathBuf {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/plant/damaged-accessor.gltf");
        let text = std::fs::read_to_string(&path).unwrap().replace("\"POSITION\": 5", "\"POSITION\": 0");
        let old_nodes = r#""nodes": [{"mesh": 0, "name": "VESSEL-1", "translation": [1.0, 0.0, 0.0]}]"#;
        assert!(text.contains(old_nodes) && text.contains(r#""nodes": [0]"#));
        let text = text.replace(old_nodes, &format!(r#""nodes": {nodes}"#)).replace(r#""nodes": [0]"#, roots);
        let out = dir.join("scene.gltf");
        std::fs::write(&out, text).unwrap();
        out
    }

    /// Triangle strips and fans are surfaces: their triangles are kept (they
    /// were skipped, with a warning on the console only). Points and lines
    /// have no surface: skipped, and said.
    #[test]
    fn gltf_strips_and_fans_are_read_and_lines_are_said() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/plant/damaged-accessor.gltf");
        let tet = std::fs::read_to_string(&path).unwrap().replace("\"POSITION\": 5", "\"POSITION\": 0");
        let d = tempfile::tempdir().unwrap();
        // No index list: the four corners (0,0,0), (1,0,0), (0,1,0), (0,0,1) in order.
        let drawn = |mode: u32| {
            let text = tet.replace(", \"indices\": 1}", &format!(", \"mode\": {mode}}}"));
            assert_ne!(text, tet);
            let out = d.path().join(format!("mode{mode}.gltf"));
            std::fs::write(&out, text).unwrap();
            let mut skipped = Vec::new();
            let m = read_gltf_noting(&out, crate::MAX_TRIANGLES, &mut skipped).unwrap();
            (m, skipped)
        };
        // Strip: (0, 1, 2), (2, 1, 3); fan: (0, 1, 2), (0, 2, 3). Either
        // way two triangles over all four corners.
        for mode in [5, 6] {
            let (m, skipped) = drawn(mode);
            assert!(skipped.is_empty());
            assert_eq!(m.triangles.len(), 2, "mode {mode}: {:?}", m.triangles);
            let mut used: Vec<[u64; 3]> =
                m.triangles.iter().flatten().map(|&v| m.vertices[v as usize].map(f64::to_bits)).collect();
            used.sort_unstable();
            used.dedup();
            assert_eq!(used.len(), 4, "mode {mode}: {:?}", m.triangles);
        }
        let (m, skipped) = drawn(1);
        assert!(m.triangles.is_empty());
        assert_eq!(skipped, vec!["VESSEL-1 (Lines)".to_string()]);
    }

    /// OBJ line and point elements, which tobj does not read, are counted
    /// so that the stage can say they are not obstacles.
    #[test]
    fn obj_lines_and_points_are_counted() {
        let d = tempfile::tempdir().unwrap();
        let path = d.path().join("cable.obj");
        let long_face = format!("f {}\n", "1 2 3 ".repeat(2000));
        std::fs::write(
            &path,
            format!("o mast\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n{long_face}  l 1 2\np 3\nlo 1\n# l 1 2\n"),
        )
        .unwrap();
        let (m, without_surface) = read_obj(&path, Import { scale: 1.0, y_up: false }).unwrap();
        assert!(!m.triangles.is_empty());
        assert_eq!(without_surface, 2);
        // Counted the same whatever the reads' sizes (a keyword split
        // between two), "l" alone on a line too.
        let text = b"l 1 2\n\tp\t3\r\nl\nlp 1\n pl\nf 1 2 3\n";
        for chunk in [1, 2, 3, 7, 64] {
            let mut r = ElementsWithoutSurface { inner: &text[..], line: LineStart::Blank, count: 0 };
            let mut buf = vec![0u8; chunk];
            while std::io::Read::read(&mut r, &mut buf).unwrap() > 0 {}
            assert_eq!(r.count, 3, "reads of {chunk} bytes");
        }
    }

    /// Text meshes saved with a UTF-8 byte order mark (a Windows tool's) read
    /// as without it: the OBJ reader lost the first vertex to it (and
    /// refused the face naming it), the PLY, STL and glTF readers refused
    /// the file.
    #[test]
    fn text_meshes_with_a_byte_order_mark_read() {
        let d = tempfile::tempdir().unwrap();
        let imp = Import { scale: 1.0, y_up: false };
        let marked = |name: &str, text: &str| {
            let path = d.path().join(name);
            std::fs::write(&path, [&liftplan_core::byte_order_mark::BYTES[..], text.as_bytes()].concat()).unwrap();
            path
        };
        let obj = marked("a.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
        assert_eq!(read_obj(&obj, imp).unwrap().0.triangles.len(), 1);
        let ply = marked(
            "a.ply",
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n\
             element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
        );
        assert_eq!(read_ply(&ply, imp).unwrap().triangles.len(), 1);
        let stl = marked(
            "a.stl",
            "solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid a\n",
        );
        assert_eq!(read_stl(&stl, imp).unwrap().triangles.len(), 1);
        let fixture = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/plant/damaged-accessor.gltf");
        let tet = std::fs::read_to_string(&fixture).unwrap().replace("\"POSITION\": 5", "\"POSITION\": 0");
        let gltf = marked("a.gltf", &tet);
        assert!(!read_gltf(&gltf, crate::MAX_TRIANGLES).unwrap().triangles.is_empty());
    }

    /// glTF nodes must form trees. A chain of nodes each naming the next one
    /// twice as its child would be walked 2^40 times; a cycle for ever.
    #[test]
    fn a_gltf_node_reached_twice_is_refused() {
        let d = tempfile::tempdir().unwrap();
        let chain: Vec<String> = (0..40).map(|i| format!(r#"{{"children": [{0}, {0}]}}"#, i + 1)).collect();
        let nodes = format!(r#"[{}, {{"mesh": 0}}]"#, chain.join(", "));
        let e = read_gltf(&tet_scene(d.path(), &nodes, r#""nodes": [0]"#), crate::MAX_TRIANGLES).unwrap_err();
        assert!(e.to_string().contains("scene.gltf (node 40): the node is reached twice"), "{e}");
        let cycle = r#"[{"children": [1]}, {"mesh": 0, "children": [0]}]"#;
        let e = read_gltf(&tet_scene(d.path(), cycle, r#""nodes": [0]"#), crate::MAX_TRIANGLES).unwrap_err();
        assert!(e.to_string().contains("reached twice"), "{e}");
        // One mesh placed by three nodes of a tree is fine.
        let tree = r#"[{"children": [1, 2, 3]}, {"mesh": 0}, {"mesh": 0}, {"mesh": 0}]"#;
        assert_eq!(read_gltf(&tet_scene(d.path(), tree, r#""nodes": [0]"#), 12).unwrap().triangles.len(), 12);
    }

    /// Buffers naming the same file beside the glTF share one read of it.
    #[test]
    fn a_gltf_buffer_file_named_twice_is_read_once() {
        use base64::Engine;
        let d = tempfile::tempdir().unwrap();
        let fixture = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/plant/damaged-accessor.gltf");
        let text = std::fs::read_to_string(&fixture).unwrap().replace("\"POSITION\": 5", "\"POSITION\": 0");
        let (head, rest) = text.split_once(r#""uri": "data:application/octet-stream;base64,"#).unwrap();
        let (b64, tail) = rest.split_once('"').unwrap();
        std::fs::write(d.path().join("tet.bin"), base64::engine::general_purpose::STANDARD.decode(b64).unwrap())
            .unwrap();
        let text = format!(r#"{head}"uri": "tet.bin"}}, {{"byteLength": 72, "uri": "tet.bin"{tail}"#)
            .replace(r#"{"buffer": 0, "byteOffset": 48"#, r#"{"buffer": 1, "byteOffset": 48"#);
        let path = d.path().join("scene.gltf");
        std::fs::write(&path, &text).unwrap();
        assert_eq!(read_gltf(&path, crate::MAX_TRIANGLES).unwrap().triangles.len(), 4);
        let g = gltf::Gltf::from_slice(text.as_bytes()).unwrap();
        let buffers = load_buffers(&path, &g.document, None).unwrap();
        assert_eq!(buffers.len(), 2);
        assert!(Rc::ptr_eq(&buffers[0], &buffers[1]));
    }

    /// A scene placing a mesh many times is counted against the plant's
    /// room before each placement is read.
    #[test]
    fn a_gltf_scene_is_counted_as_its_nodes_place_it() {
        let d = tempfile::tempdir().unwrap();
        let placed: Vec<String> = (0..5).map(|_| r#"{"mesh": 0}"#.to_string()).collect();
        let path = tet_scene(d.path(), &format!("[{}]", placed.join(", ")), r#""nodes": [0, 1, 2, 3, 4]"#);
        assert_eq!(read_gltf(&path, 20).unwrap().triangles.len(), 20);
        let e = read_gltf(&path, 19).unwrap_err().to_string();
        assert!(e.contains("scene.gltf") && e.contains("make more than 19 triangles"), "{e}");
    }

    /// A PLY mesh whose vertices' properties are named in capitals (`X`,
    /// `Y`, `Z`) reads as one in lower case (it was refused: "no property
    /// 'x'").
    #[test]
    fn a_ply_meshs_axes_in_capitals_read() {
        let d = tempfile::tempdir().unwrap();
        let path = d.path().join("capitals.ply");
        let text = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float X\nproperty float Y\nproperty float Z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 2\n3 0 1 2\n";
        std::fs::write(&path, text).unwrap();
        let m = read_ply(&path, Import { scale: 1.0, y_up: false }).unwrap();
        assert_eq!(m.triangles.len(), 1);
        assert_eq!(m.vertices[2], [0.0, 1.0, 2.0]);
    }

    /// Found by the plant_mesh fuzz target: ply-rs unwraps the header's
    /// numbers and panicked on one too large for 64 bits.
    #[test]
    fn a_ply_header_number_too_large_is_refused() {
        let d = tempfile::tempdir().unwrap();
        let path = d.path().join("huge.ply");
        let text = "ply\nformat ascii 1.0\nelement vertex 99999999999999999999999\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
        std::fs::write(&path, text).unwrap();
        let e = read_ply(&path, Import { scale: 1.0, y_up: false }).unwrap_err().to_string();
        assert!(e.contains("huge.ply") && e.contains("PLY reader failed on damaged data"), "{e}");
    }
}
