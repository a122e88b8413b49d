//! Development aid: print what an RVM file holds and time its tessellation.
fn main() {
    let path = std::env::args().nth(1).expect("usage: dump FILE.rvm [TOLERANCE]");
    let tol: f64 = std::env::args().nth(2).and_then(|s| s.parse().ok()).unwrap_or(0.01);
    let p = std::path::Path::new(&path);
    let t = std::time::Instant::now();
    let f = liftplan_plant::rvm::read(p).unwrap_or_else(|e| panic!("{e}"));
    let parse = t.elapsed();
    println!("groups {} prims {:?}", f.group_count(), f.primitive_counts());
    let s = liftplan_plant::Settings { tolerance: tol, ..Default::default() };
    let mut sum = liftplan_plant::Summary::default();
    let t = std::time::Instant::now();
    let m = liftplan_plant::rvm_to_mesh(p, &f, None, &s, &mut sum, liftplan_plant::MAX_TRIANGLES)
        .unwrap_or_else(|e| panic!("{e}"));
    let tt = t.elapsed();
    println!(
        "parse {parse:?} tessellate {tt:?}: {} triangles {} vertices, caps culled {}, bbox {:?}",
        m.triangle_count(),
        m.vertices.len(),
        sum.caps_culled,
        m.bbox().to_array()
    );
}
