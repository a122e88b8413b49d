//! The RVM and ATT readers on damaged copies of the real PDMS sample export
//! (`fixtures/plant/`), and the mesh readers on part of its mesh written as
//! GLB, OBJ, STL (ASCII and binary) and PLY: bytes flipped, fields overwritten
//! with extreme values, the file cut short
//! ([`liftplan_core::testing::damaged`]). Each copy must give a mesh or an
//! error naming the file, never a panic, and a mesh within the triangle room
//! it was given. A thousand deterministic copies of the export, and a few
//! hundred of each mesh file, on every test run (`PROPTEST_CASES` for
//! more), beside the fuzz targets
//! (`fuzz/fuzz_targets/rvm.rs`, `att.rs`, `plant_mesh.rs`), which need a
//! nightly toolchain and so do not run in CI.

use liftplan_core::testing::{damaged, hide_panics_from, proptest_cases};
use std::path::Path;

fn fixture(name: &str) -> Vec<u8> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/plant").join(name);
    std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

#[test]
fn damaged_rvm_files_give_a_mesh_or_an_error() {
    const ROOM: u64 = 2_000_000;
    let original = fixture("plm-sample_11072013.rvm");
    let path = Path::new("damaged.rvm");
    let (mut meshes, mut errors) = (0, 0);
    for k in 0..u64::from(proptest_cases(1000)) {
        let bytes = damaged(&original, k);
        let file = match liftplan_plant::rvm::parse(path, &bytes) {
            Ok(file) => file,
            Err(e) => {
                assert!(e.to_string().contains("damaged.rvm"), "copy {k}: the error names the file: {e}");
                errors += 1;
                continue;
            }
        };
        let mut summary = liftplan_plant::Summary::default();
        match liftplan_plant::rvm_to_mesh(path, &file, None, &liftplan_plant::Settings::default(), &mut summary, ROOM) {
            Ok(mesh) => {
                assert!(mesh.triangle_count() as u64 <= ROOM, "copy {k}: {} triangles", mesh.triangle_count());
                meshes += 1;
            }
            Err(e) => {
                assert!(e.to_string().contains("damaged.rvm"), "copy {k}: the error names the file: {e}");
                errors += 1;
            }
        }
    }
    eprintln!("{meshes} meshes, {errors} errors");
    assert!(meshes > 0 && errors > 0, "the damage should be caught sometimes and harmless sometimes");
}

#[test]
fn damaged_att_files_give_attributes_or_an_error() {
    let original = fixture("plm-sample_11072013.att");
    let (mut read, mut errors) = (0, 0);
    for k in 0..u64::from(proptest_cases(1000)) {
        match liftplan_plant::att::parse(Path::new("damaged.att"), &damaged(&original, k)) {
            Ok(_) => read += 1,
            Err(e) => {
                assert!(e.to_string().contains("damaged.att"), "copy {k}: the error names the file: {e}");
                errors += 1;
            }
        }
    }
    eprintln!("{read} read, {errors} errors");
    assert!(read > 0, "most damage to a text file still reads");
}

/// Part of the sample export's mesh written as GLB, OBJ, ASCII and binary
/// STL and ASCII PLY: (file name, bytes).
fn mesh_files() -> Vec<(String, Vec<u8>)> {
    let path = Path::new("plm-sample_11072013.rvm");
    let file = liftplan_plant::rvm::parse(path, &fixture("plm-sample_11072013.rvm")).unwrap();
    let mut summary = liftplan_plant::Summary::default();
    let settings = liftplan_plant::Settings::default();
    let mesh = liftplan_plant::rvm_to_mesh(path, &file, None, &settings, &mut summary, 1_000_000).unwrap();
    let tris: Vec<[[f64; 3]; 3]> =
        mesh.triangles.iter().take(400).map(|t| t.map(|v| mesh.vertices[v as usize])).collect();
    let corner = |p: &[f64; 3]| format!("{:.4} {:.4} {:.4}", p[0], p[1], p[2]);
    let mut obj = String::new();
    let mut ply = format!(
        "ply\nformat ascii 1.0\nelement vertex {}\nproperty double x\nproperty double y\nproperty double z\nelement face {}\nproperty list uchar int vertex_indices\nend_header\n",
        3 * tris.len(),
        tris.len()
    );
    let mut stl = String::from("solid part\n");
    let mut binary = vec![0u8; 80];
    binary.extend((tris.len() as u32).to_le_bytes());
    for (k, t) in tris.iter().enumerate() {
        for p in t {
            obj += &format!("v {}\n", corner(p));
            ply += &format!("{}\n", corner(p));
        }
        obj += &format!("f {} {} {}\n", 3 * k + 1, 3 * k + 2, 3 * k + 3);
        stl += &format!(
            "facet normal 0 0 1\nouter loop\nvertex {}\nvertex {}\nvertex {}\nendloop\nendfacet\n",
            corner(&t[0]),
            corner(&t[1]),
            corner(&t[2])
        );
        binary.extend([0f32; 3].iter().flat_map(|v| v.to_le_bytes()));
        binary.extend(t.iter().flatten().flat_map(|v| (*v as f32).to_le_bytes()));
        binary.extend([0u8; 2]);
    }
    for k in 0..tris.len() {
        ply += &format!("3 {} {} {}\n", 3 * k, 3 * k + 1, 3 * k + 2);
    }
    stl += "endsolid part\n";
    let glb = glb(&tris);
    vec![
        ("part.glb".into(), glb),
        ("part.obj".into(), obj.into_bytes()),
        ("part.ply".into(), ply.into_bytes()),
        ("ascii.stl".into(), stl.into_bytes()),
        ("binary.stl".into(), binary),
    ]
}

/// Triangles as a binary glTF (GLB): one mesh of `f32` positions and
/// `u32` indices, as an exporter writes it.
fn glb(tris: &[[[f64; 3]; 3]]) -> Vec<u8> {
    let mut bin: Vec<u8> = tris.iter().flatten().flatten().flat_map(|v| (*v as f32).to_le_bytes()).collect();
    let positions = bin.len();
    bin.extend((0..3 * tris.len() as u32).flat_map(|i| i.to_le_bytes()));
    let (mut lo, mut hi) = ([f32::MAX; 3], [f32::MIN; 3]);
    for p in tris.iter().flatten() {
        for a in 0..3 {
            lo[a] = lo[a].min(p[a] as f32);
            hi[a] = hi[a].max(p[a] as f32);
        }
    }
    let n = 3 * tris.len();
    let json = format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0,"name":"PART-1"}}],"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}},"indices":1}}]}}],"accessors":[{{"bufferView":0,"componentType":5126,"count":{n},"type":"VEC3","min":[{},{},{}],"max":[{},{},{}]}},{{"bufferView":1,"componentType":5125,"count":{n},"type":"SCALAR"}}],"bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":{positions}}},{{"buffer":0,"byteOffset":{positions},"byteLength":{}}}],"buffers":[{{"byteLength":{}}}]}}"#,
        lo[0],
        lo[1],
        lo[2],
        hi[0],
        hi[1],
        hi[2],
        bin.len() - positions,
        bin.len()
    );
    let mut json = json.into_bytes();
    while json.len() % 4 != 0 {
        json.push(b' ');
    }
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut out = Vec::with_capacity(total);
    out.extend(b"glTF");
    out.extend(2u32.to_le_bytes());
    out.extend((total as u32).to_le_bytes());
    out.extend((json.len() as u32).to_le_bytes());
    out.extend(b"JSON");
    out.extend(json);
    out.extend((bin.len() as u32).to_le_bytes());
    out.extend(b"BIN\0");
    out.extend(bin);
    out
}

#[test]
fn damaged_mesh_files_give_a_mesh_or_an_error() {
    // The gltf crate panics on some damaged files; the reader catches those
    // panics (`liftplan_core::guard`) and reports an error. Keep them out of
    // the test's output, and every other panic in it.
    hide_panics_from("/gltf-");
    let dir = tempfile::tempdir().unwrap();
    let settings = liftplan_plant::Settings {
        unit: Some(liftplan_core::units::LengthUnit::M),
        up_axis: Some(liftplan_plant::UpAxis::Z),
        ..Default::default()
    };
    // As the fuzz target: the room left is what the budget leaves over
    // earlier files, 2 M triangles here.
    let before = liftplan_plant::MAX_TRIANGLES as usize - 2_000_000;
    let read = |path: &Path| {
        let mut summary = liftplan_plant::Summary { triangles: before, ..Default::default() };
        let mesh = liftplan_plant::read_file(path, &settings, &mut summary).map_err(|e| e.to_string())?;
        assert!(summary.triangles <= liftplan_plant::MAX_TRIANGLES as usize);
        Ok::<_, String>(mesh)
    };
    for (name, bytes) in mesh_files() {
        let path = dir.path().join(&name);
        std::fs::write(&path, &bytes).unwrap();
        let mesh = read(&path).unwrap_or_else(|e| panic!("{name} as written: {e}"));
        assert_eq!(mesh.triangle_count(), 400, "{name} as written");
        let (mut meshes, mut errors) = (0, 0);
        for k in 0..u64::from(proptest_cases(300)) {
            let path = dir.path().join(format!("damaged-{k}-{name}"));
            std::fs::write(&path, damaged(&bytes, k)).unwrap();
            match read(&path) {
                Ok(_) => meshes += 1,
                Err(e) => {
                    let file = path.file_name().unwrap().to_string_lossy().to_string();
                    assert!(e.contains(&file), "copy {k} of {name}: the error names the file: {e}");
                    errors += 1;
                }
            }
            std::fs::remove_file(&path).unwrap();
        }
        eprintln!("{name}: {meshes} meshes, {errors} errors");
    }
}
