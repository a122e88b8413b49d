//! Mesh inputs from BIM tools: OBJ (`tobj`), PLY (`ply-rs`), STL (`stl_io`) and
//! glTF/GLB (`gltf`, node transforms applied). Each object, node or file becomes
//! a group; its triangles are surfaces (not assumed closed or convex).
//!
//! Units and up axis come from the settings; glTF is metres and Y-up by its
//! specification, so it ignores both.

use crate::error::{PlantError, Result};
use liftplan_core::Location;
use liftplan_core::mesh::TriMesh;
use std::path::Path;

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

pub fn read_obj(path: &Path, imp: Import) -> Result<TriMesh> {
    let opts = tobj::LoadOptions { triangulate: true, single_index: true, ignore_points: true, ignore_lines: true };
    let file = std::fs::File::open(path).map_err(|e| PlantError::Io(Location::file(path), e))?;
    let mut r = std::io::BufReader::new(file);
    let (models, _) = tobj::load_obj_buf(&mut r, &opts, |_| Err(tobj::LoadError::OpenFileFailed))
        .map_err(|e| PlantError::at(Location::file(path), format!("cannot read OBJ: {e}")))?;
    let mut m = TriMesh::default();
    for model in &models {
        let name = if model.name.is_empty() { stem(path) } else { model.name.clone() };
        let g = m.group_id(&name);
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
    Ok(m)
}

pub fn read_stl(path: &Path, imp: Import) -> Result<TriMesh> {
    let mut f = std::fs::File::open(path).map_err(|e| PlantError::Io(Location::file(path), e))?;
    let mesh =
        stl_io::read_stl(&mut f).map_err(|e| PlantError::at(Location::file(path), format!("cannot read STL: {e}")))?;
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
        match key.as_str() {
            "x" => self.p[0] = v,
            "y" => self.p[1] = v,
            "z" => self.p[2] = v,
            _ => {}
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
    guarded(path, "the PLY reader", || read_ply_unguarded(path, imp))
}

fn read_ply_unguarded(path: &Path, imp: Import) -> Result<TriMesh> {
    use ply_rs::parser::Parser;
    let f = std::fs::File::open(path).map_err(|e| PlantError::Io(Location::file(path), e))?;
    let mut r = std::io::BufReader::new(f);
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
                    if !def.properties.contains_key(axis) {
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

fn load_buffers(path: &Path, doc: &gltf::Document, blob: Option<Vec<u8>>) -> Result<Vec<Vec<u8>>> {
    use base64::Engine;
    let mut out = Vec::new();
    let mut blob = blob;
    for b in doc.buffers() {
        let data = match b.source() {
            gltf::buffer::Source::Bin => {
                blob.take().ok_or_else(|| PlantError::at(Location::file(path), "GLB buffer without a binary chunk"))?
            }
            gltf::buffer::Source::Uri(uri) => {
                if let Some(rest) = uri.strip_prefix("data:") {
                    let b64 = rest
                        .split_once(";base64,")
                        .map(|x| x.1)
                        .ok_or_else(|| PlantError::at(Location::file(path), "data URI buffer is not base64"))?;
                    base64::engine::general_purpose::STANDARD
                        .decode(b64)
                        .map_err(|e| PlantError::at(Location::file(path), format!("bad base64 buffer: {e}")))?
                } else {
                    if uri.contains("..") || uri.starts_with('/') || uri.contains("://") {
                        return Err(PlantError::at(
                            Location::file(path),
                            format!("buffer URI '{uri}' must be a file beside the glTF"),
                        ));
                    }
                    let p = path.parent().unwrap_or(Path::new(".")).join(uri);
                    std::fs::read(&p).map_err(|e| PlantError::Io(Location::file(&p), e))?
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

pub fn read_gltf(path: &Path) -> Result<TriMesh> {
    // The gltf crate's validation indexes accessors it has not checked yet and
    // panics on such a file (found by the plant_mesh fuzz target).
    guarded(path, "the glTF reader", || read_gltf_unguarded(path))
}

/// Runs a reader built on a third-party parser, turning a panic inside it
/// into an error naming the file (see [`liftplan_core::guard`]).
fn guarded(path: &Path, what: &str, read: impl FnOnce() -> Result<TriMesh>) -> Result<TriMesh> {
    liftplan_core::guard::run_reader(what, read).unwrap_or_else(|why| Err(PlantError::at(Location::file(path), why)))
}

fn read_gltf_unguarded(path: &Path) -> Result<TriMesh> {
    let bytes = std::fs::read(path).map_err(|e| PlantError::Io(Location::file(path), e))?;
    let g = gltf::Gltf::from_slice(&bytes)
        .map_err(|e| PlantError::at(Location::file(path), format!("cannot read glTF: {e}")))?;
    let buffers = load_buffers(path, &g.document, g.blob.clone())?;
    let imp = Import { scale: 1.0, y_up: true };
    let mut m = TriMesh::default();
    let scene = g.document.default_scene().or_else(|| g.document.scenes().next());
    let Some(scene) = scene else { return Ok(m) };
    let mut stack: Vec<(gltf::Node, nalgebra::Matrix4<f64>, usize)> =
        scene.nodes().map(|n| (n, nalgebra::Matrix4::identity(), 0)).collect();
    while let Some((node, parent, depth)) = stack.pop() {
        if depth > 256 {
            return Err(PlantError::at(Location::file(path), "node hierarchy deeper than 256 levels (a cycle?)"));
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
            let gid = m.group_id(&name);
            for prim in mesh.primitives() {
                if prim.mode() != gltf::mesh::Mode::Triangles {
                    tracing::warn!("{}: {name}: skipping a primitive drawn as {:?}", path.display(), prim.mode());
                    continue;
                }
                let reader = prim.reader(|b| buffers.get(b.index()).map(|d| d.as_slice()));
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
                let tris: Vec<[u32; 3]> = idx.chunks(3).filter(|c| c.len() == 3).map(|c| [c[0], c[1], c[2]]).collect();
                m.add_part(gid, false, &verts, &tris);
            }
        }
        for c in node.children() {
            stack.push((c, world, depth + 1));
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
        let e = read_gltf(&path).unwrap_err().to_string();
        assert!(e.contains("damaged-accessor.gltf") && e.contains("failed on damaged data"), "{e}");
        // The same file naming accessor 0 reads.
        let d = tempfile::tempdir().unwrap();
        let good = d.path().join("tet.gltf");
        let text = std::fs::read_to_string(&path).unwrap().replace("\"POSITION\": 5", "\"POSITION\": 0");
        std::fs::write(&good, text).unwrap();
        assert_eq!(read_gltf(&good).unwrap().triangles.len(), 4);
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
