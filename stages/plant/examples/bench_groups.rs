//! Times the plant stage's reading of models with many groups, and prints a
//! hash of each mesh so that a build can be checked to give the same:
//!
//! - an RVM file of N groups of one box each;
//! - an OBJ file of N objects of one triangle each, read whole and with
//!   `[plant] exclude` leaving one object out;
//! - side by side in one run, naming N groups one by one
//!   (`TriMesh::group_id`, what the readers did before the nineteenth stop)
//!   and through a `GroupIndex` (what they do now);
//! - side by side in one run, appending F meshes of 500 groups each (the
//!   plant stage's many input files) with `TriMesh::append`, which indexes
//!   the growing mesh's groups again for each, and with `append_with` and one
//!   index (what the stage does since the twentieth stop).
//!
//! `cargo run --release -p liftplan-plant --example bench_groups [N...]`

use liftplan_core::mesh::{GroupIndex, TriMesh};
use liftplan_plant::rvm::{Group, Primitive, Role, RvmFile, Shape};
use std::hash::{Hash, Hasher};
use std::path::Path;
use std::time::Instant;

fn rvm_file(dir: &Path, n: usize) -> std::path::PathBuf {
    let matrix = [0.001f32, 0.0, 0.0, 0.0, 0.001, 0.0, 0.0, 0.0, 0.001, 1.0, 2.0, 3.0];
    let pipe = |k: usize| Group {
        name: format!("/PIPE-{k:06}"),
        primitives: vec![Primitive {
            role: Role::Primitive,
            matrix,
            bbox_local: [-1.0, -1.0, -1.0, 1.0, 1.0, 1.0],
            shape: Shape::Box { lengths: [1.0, 2.0, 3.0] },
            offset: 0,
        }],
        ..Default::default()
    };
    let site = Group { name: "/SITE".into(), children: (0..n).map(pipe).collect(), ..Default::default() };
    let file = RvmFile { info: "bench".into(), model: "/M".into(), groups: vec![site], ..Default::default() };
    let path = dir.join(format!("pipes-{n}.rvm"));
    std::fs::write(&path, liftplan_plant::rvm::write(&file)).expect("the RVM file written");
    path
}

fn obj_file(dir: &Path, n: usize) -> std::path::PathBuf {
    let mut text = String::new();
    for k in 0..n {
        text += &format!("o PART-{k:06}\nv {k} 0 0\nv {k} 1 0\nv {k} 0 1\nf -3 -2 -1\n");
    }
    let path = dir.join(format!("parts-{n}.obj"));
    std::fs::write(&path, text).expect("the OBJ file written");
    path
}

fn mesh_hash(m: &TriMesh) -> String {
    let mut h = std::collections::hash_map::DefaultHasher::new();
    format!("{:?}{:?}{:?}{:?}{:?}", m.vertices, m.triangles, m.part_of, m.parts, m.groups).hash(&mut h);
    format!("{:016x}", h.finish())
}

fn main() {
    let counts: Vec<usize> = std::env::args().skip(1).filter_map(|a| a.parse().ok()).collect();
    let counts = if counts.is_empty() { vec![5_000, 20_000, 100_000] } else { counts };
    let dir = tempfile::tempdir().expect("a temporary folder");
    println!("| model | groups | read s | triangles | mesh hash |");
    println!("|---|---|---|---|---|");
    for &n in &counts {
        let cases = [
            ("RVM, one box per group", rvm_file(dir.path(), n), vec![]),
            ("OBJ, one triangle per object", obj_file(dir.path(), n), vec![]),
            ("OBJ, exclude one object", obj_file(dir.path(), n), vec!["PART-000000".to_string()]),
        ];
        for (what, path, exclude) in cases {
            // The OBJ files are written in metres, Z up, as the project says.
            let settings = liftplan_plant::Settings {
                exclude,
                unit: Some(liftplan_core::units::LengthUnit::M),
                up_axis: Some(liftplan_plant::UpAxis::Z),
                ..Default::default()
            };
            let mut summary = liftplan_plant::Summary::default();
            let t = Instant::now();
            let mesh = liftplan_plant::read_file(&path, &settings, &mut summary).expect("the model read");
            let s = t.elapsed().as_secs_f64();
            println!("| {what} | {n} | {s:.3} | {} | {} |", mesh.triangle_count(), mesh_hash(&mesh));
        }
    }
    println!();
    println!("| groups named | one by one s | through an index s | ratio | same ids |");
    println!("|---|---|---|---|---|");
    for &n in &counts {
        let names: Vec<String> = (0..n).map(|k| format!("/SITE/ZONE-{}/PIPE-{k:06}", k % 7)).collect();
        let mut one_by_one = TriMesh::default();
        let t = Instant::now();
        let a: Vec<u32> = names.iter().map(|g| one_by_one.group_id(g)).collect();
        let slow = t.elapsed().as_secs_f64();
        let mut indexed = TriMesh::default();
        let t = Instant::now();
        let mut index = GroupIndex::of(&indexed);
        let b: Vec<u32> = names.iter().map(|g| index.id(&mut indexed, g)).collect();
        let fast = t.elapsed().as_secs_f64();
        let same = a == b && one_by_one.groups == indexed.groups;
        println!("| {n} | {slow:.3} | {fast:.4} | {:.0}x | {} |", slow / fast, if same { "yes" } else { "NO" });
    }
    println!();
    println!("| files of 500 groups appended | indexed per append s | one index s | ratio | same mesh |");
    println!("|---|---|---|---|---|");
    for files in [50, 200, 500] {
        let meshes: Vec<TriMesh> = (0..files)
            .map(|f| {
                let mut m = TriMesh::default();
                for k in 0..500 {
                    let g = m.group_id(&format!("/SITE/AREA-{f:03}/PIPE-{k:03}"));
                    m.add_part(
                        g,
                        false,
                        &[[k as f64, 0.0, 0.0], [k as f64, 1.0, 0.0], [k as f64, 0.0, 1.0]],
                        &[[0, 1, 2]],
                    );
                }
                m
            })
            .collect();
        let t = Instant::now();
        let mut each = TriMesh::default();
        for m in &meshes {
            each.append(m);
        }
        let slow = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let mut once = TriMesh::default();
        let mut index = GroupIndex::of(&once);
        for m in &meshes {
            once.append_with(m, &mut index);
        }
        let fast = t.elapsed().as_secs_f64();
        let same = if each == once { "yes" } else { "NO" };
        println!("| {files} | {slow:.3} | {fast:.3} | {:.1}x | {same} |", slow / fast);
    }
}
