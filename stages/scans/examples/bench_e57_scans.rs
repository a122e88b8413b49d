//! Times reading every scan of an E57 file that holds many small scans, two
//! ways side by side in one run: each scan through `read::stream` (which
//! opens the file for that scan alone, as the stage did before the
//! nineteenth stop) and all of them through one `read::ScanStreamer` (which
//! keeps the file open from one scan to the next, as the stage does now).
//! Both must deliver the same points; the example checks that.
//!
//! `cargo run --release -p liftplan-scans --example bench_e57_scans [SCANS...]`

use e57::{E57Writer, Record, RecordValue};
use liftplan_scans::read::{ScanStreamer, list_scans, stream};
use std::path::Path;
use std::time::Instant;

/// Writes `scans` scans of three points each, as a survey of many stations
/// exported to one file.
fn write_file(path: &Path, scans: usize) -> e57::Result<()> {
    let mut w = E57Writer::from_file(path, "liftplan-bench")?;
    for k in 0..scans {
        let prototype = vec![Record::CARTESIAN_X_F64, Record::CARTESIAN_Y_F64, Record::CARTESIAN_Z_F64];
        let mut pc = w.add_pointcloud(&format!("scan-{k}"), prototype)?;
        pc.set_name(Some(format!("station-{k}")));
        for i in 0..3 {
            let v = k as f64 + i as f64 * 0.1;
            pc.add_point(vec![RecordValue::Double(v), RecordValue::Double(i as f64), RecordValue::Double(1.0)])?;
        }
        pc.finalize()?;
    }
    w.finalize()
}

fn main() {
    let counts: Vec<usize> = std::env::args().skip(1).filter_map(|a| a.parse().ok()).collect();
    let counts = if counts.is_empty() { vec![100, 500, 1000, 2000] } else { counts };
    let dir = tempfile::tempdir().expect("a temporary folder");
    println!(
        "| scans in the file | file MB | a file opened per scan s | one file opened for its scans s | ratio | points (both) |"
    );
    println!("|---|---|---|---|---|---|");
    for n in counts {
        let path = dir.path().join(format!("stations-{n}.e57"));
        write_file(&path, n).expect("the E57 writer");
        let mb = std::fs::metadata(&path).map(|m| m.len()).unwrap_or(0) as f64 / 1e6;
        let scans = list_scans(&path).expect("the scans listed");
        let mut per_scan: Vec<[f64; 3]> = Vec::new();
        let t = Instant::now();
        for s in &scans {
            stream(s, &mut |c| {
                per_scan.extend_from_slice(&c.xyz);
                Ok(())
            })
            .expect("a scan read");
        }
        let opened_per_scan = t.elapsed().as_secs_f64();
        let mut kept_open: Vec<[f64; 3]> = Vec::new();
        let mut files = ScanStreamer::default();
        let t = Instant::now();
        for s in &scans {
            files
                .stream(s, &mut |c| {
                    kept_open.extend_from_slice(&c.xyz);
                    Ok(())
                })
                .expect("a scan read");
        }
        let opened_once = t.elapsed().as_secs_f64();
        assert_eq!(per_scan, kept_open, "the two ways read different points");
        println!(
            "| {n} | {mb:.1} | {opened_per_scan:.2} | {opened_once:.3} | {:.0}x | {} |",
            opened_per_scan / opened_once,
            kept_open.len()
        );
    }
}
