//! Development aid: render a plant artifact (`plant.mesh`) to PNG.
fn main() {
    let a: Vec<String> = std::env::args().collect();
    let m = liftplan_core::mesh::TriMesh::read_artifact(std::path::Path::new(&a[1])).unwrap();
    let mut scene = liftplan_docs::render::Scene::default();
    scene.triangles.push(liftplan_docs::render::mesh_batch(&m, [170, 180, 200]));
    let (lo, hi) = scene.bounds();
    let az: f32 = a.get(3).and_then(|s| s.parse().ok()).unwrap_or(-60.0);
    let cam = liftplan_docs::render::Camera::framing(lo, hi, az, 30.0, 35.0, 1.5);
    let t = std::time::Instant::now();
    let im = liftplan_docs::render::render_cpu(&scene, &cam, 900, 600, 3);
    eprintln!("rendered in {:?}", t.elapsed());
    im.write_png(std::path::Path::new(&a[2])).unwrap();
}
