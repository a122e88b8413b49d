//! Parse + tessellate time and triangle count of an RVM file at three chord
//! tolerances (median of repeated runs, in one process):
//!
//!   cargo run --release -p liftplan-plant --example bench_plant -- FILE.rvm > reports/plant.md

use std::time::Instant;

fn main() {
    let path = std::path::PathBuf::from(std::env::args().nth(1).expect("usage: bench_plant FILE.rvm"));
    let bytes = std::fs::read(&path).expect("read");
    let att = path.with_extension("att");
    let attrs = std::fs::read(&att).ok().and_then(|b| liftplan_plant::att::parse(&att, &b).ok());
    println!("# Plant stage: parse + tessellate {}\n", path.file_name().unwrap().to_string_lossy());
    println!(
        "{} bytes; median of 21 runs per row; one thread of this machine. The reference figure is the issue's: the established C++ RVM tool tessellates this file at 0.01 m in about 5 ms giving about 24k triangles.\n",
        bytes.len()
    );
    println!("| tolerance m | parse ms | tessellate ms | total ms | triangles | ratio to the C++ tool's 5 ms |");
    println!("|---|---|---|---|---|---|");
    for tol in [0.1, 0.01, 0.001] {
        let s = liftplan_plant::Settings { tolerance: tol, ..Default::default() };
        let mut parse = vec![];
        let mut tess = vec![];
        let mut tris = 0;
        for _ in 0..21 {
            let t0 = Instant::now();
            let f = liftplan_plant::rvm::parse(&path, &bytes).expect("parse");
            let t1 = Instant::now();
            let mut summary = liftplan_plant::Summary::default();
            let m =
                liftplan_plant::rvm_to_mesh(&path, &f, attrs.as_ref(), &s, &mut summary, liftplan_plant::MAX_TRIANGLES)
                    .expect("tessellate");
            let t2 = Instant::now();
            tris = m.triangle_count();
            parse.push((t1 - t0).as_secs_f64() * 1e3);
            tess.push((t2 - t1).as_secs_f64() * 1e3);
        }
        parse.sort_by(f64::total_cmp);
        tess.sort_by(f64::total_cmp);
        let (p, t) = (parse[10], tess[10]);
        println!("| {tol} | {p:.2} | {t:.2} | {:.2} | {tris} | {:.2} |", p + t, (p + t) / 5.0);
    }
}
