//! The RVM and ATT readers on damaged copies of the real PDMS sample export
//! (`fixtures/plant/`), and the mesh readers on part of its mesh written as
//! OBJ, STL (ASCII and binary) and PLY: bytes flipped, fields overwritten
//! with extreme values, the file cut short
//! ([`liftplan_core::testing::damaged`]). Each copy must give a mesh or an
//! error naming the file, never a panic, and a mesh within the triangle room
//! it was given. A thousand deterministic copies of the export, and a few
//! hundred of each mesh file, on every test run (`PROPTEST_CASES` for
//! more), beside the fuzz targets
//! (`fuzz/fuzz_targets/rvm.rs`, `att.rs`, `plant_mesh.rs`), which need a
//! nightly toolchain and so do not run in CI.

use liftplan_core::testing::{damaged, proptest_cases};
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

/// Part of the sample export's mesh written as OBJ, ASCII and binary STL
/// and ASCII PLY: (file name, bytes).
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
    vec![
        ("part.obj".into(), obj.into_bytes()),
        ("part.ply".into(), ply.into_bytes()),
        ("ascii.stl".into(), stl.into_bytes()),
        ("binary.stl".into(), binary),
    ]
}

#[test]
fn damaged_mesh_files_give_a_mesh_or_an_error() {
    let dir = tempfile::tempdir().unwrap();
    let settings = liftplan_plant::Settings::default();
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
