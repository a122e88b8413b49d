//! The pipeline's own files, a depth map (`site.mdm`), a plant mesh
//! (`plant.mesh`) and the site cloud (`site.laz`), on damaged copies
//! ([`liftplan_core::testing::damaged`]): as a disk or a copy may damage them (the checksum refuses the copy), and
//! damaged inside a correct frame, as a bug in a writer would (the reader's
//! own checks must refuse it). Each copy must read or give an error naming
//! the file, never panic. A few hundred deterministic copies on every test
//! run (`PROPTEST_CASES` for more), beside the fuzz target
//! (`fuzz/fuzz_targets/artifacts.rs`), which needs a nightly toolchain and so
//! does not run in CI.

use liftplan_core::artifact;
use liftplan_core::mesh::{self, TriMesh};
use liftplan_core::testing::{damaged, proptest_cases};
use liftplan_depthmap::mdm::{self, Mdm};
use liftplan_depthmap::{Inputs, Settings, build_cpu};
use std::path::Path;

/// A small site: points on a slope and a few boxes of two groups.
fn site() -> Inputs {
    let mut inp = Inputs::default();
    for k in 0..2000 {
        let (x, y) = ((k % 50) as f64 * 0.7, (k / 50) as f64 * 0.9);
        inp.points.push([x, y, 0.05 * x + if k % 7 == 0 { 3.0 } else { 0.0 }]);
        inp.ground.push(k % 7 != 0);
    }
    let rack = inp.mesh.group_id("/SITE/PIPE-RACK-1");
    let tank = inp.mesh.group_id("/SITE/TANK-2");
    for k in 0..6 {
        let x = 4.0 * k as f64;
        inp.mesh.add_box(if k % 2 == 0 { rack } else { tank }, [x, 5.0, 0.0], [x + 1.5, 6.0, 4.0 + k as f64]);
    }
    inp
}

/// Reads `bytes` with `read` for every damaged copy, framed as they are and
/// framed anew around a damaged payload; counts (read, refused).
fn check<T, E: std::fmt::Display>(
    name: &str,
    framed: &[u8],
    kind: &str,
    version: u32,
    read: impl Fn(&Path, &[u8]) -> Result<T, E>,
) -> (usize, usize) {
    let path = Path::new(name);
    let payload = artifact::decode(path, framed, kind, version).unwrap();
    read(path, framed).unwrap_or_else(|e| panic!("{name} as written: {e}"));
    let (mut ok, mut refused) = (0, 0);
    for k in 0..u64::from(proptest_cases(300)) {
        let copy = if k % 2 == 0 { damaged(framed, k) } else { artifact::encode(kind, version, &damaged(payload, k)) };
        match read(path, &copy) {
            Ok(_) => ok += 1,
            Err(e) => {
                let e = e.to_string();
                assert!(e.contains(name), "copy {k} of {name}: the error names the file: {e}");
                refused += 1;
            }
        }
    }
    eprintln!("{name}: {ok} read, {refused} refused");
    (ok, refused)
}

#[test]
fn damaged_depth_maps_read_or_give_an_error() {
    let inp = site();
    let (map, _) = build_cpu(&inp, &Settings { cell_m: 0.5, ..Settings::default() }).unwrap();
    let (_, refused) = check("site.mdm", &map.to_bytes(), mdm::ARTIFACT_KIND, mdm::ARTIFACT_VERSION, Mdm::from_bytes);
    assert!(refused > 0);
}

#[test]
fn damaged_plant_meshes_read_or_give_an_error() {
    let bytes = site().mesh.to_artifact_bytes();
    let read = TriMesh::from_artifact_bytes;
    let (_, refused) = check("plant.mesh", &bytes, mesh::ARTIFACT_KIND, mesh::ARTIFACT_VERSION, read);
    assert!(refused > 0);
}

/// The site's points written as the scans stage writes `site.laz` (its own
/// writer), those [`site`] does not class ground unclassified.
fn site_laz(path: &Path, inp: &Inputs) {
    use liftplan_core::cloud::{PointCloud, class};
    let cloud = PointCloud {
        xyz: inp.points.clone(),
        class: inp.ground.iter().map(|&g| if g { class::GROUND } else { 1 }).collect(),
        ..PointCloud::default()
    };
    liftplan_scans::write::write_las(path, &cloud).unwrap();
}

/// The scans stage's `site.laz`, as the depth map, plan and docs stages read
/// it back: damaged copies, and the LAZ files the scan fuzz target found
/// making the `las` and `laz` crates panic (`fixtures/scans/damaged-*.laz`),
/// read or give an error naming the file, never a panic.
#[test]
fn damaged_site_clouds_read_or_give_an_error() {
    let dir = tempfile::tempdir().unwrap();
    let written = dir.path().join("written.laz");
    let site = site();
    site_laz(&written, &site);
    let mut read = Inputs::default();
    liftplan_depthmap::read_cloud(&written, &[], &mut read).unwrap();
    assert_eq!(read.points.len(), site.points.len());
    assert_eq!(read.ground, site.ground);
    let bytes = std::fs::read(&written).unwrap();
    let (mut ok, mut refused) = (0, 0);
    let path = dir.path().join("site.laz");
    for k in 0..u64::from(proptest_cases(300)) {
        std::fs::write(&path, damaged(&bytes, k)).unwrap();
        match liftplan_depthmap::read_cloud(&path, &[], &mut Inputs::default()) {
            Ok(_) => ok += 1,
            Err(e) => {
                assert!(e.to_string().contains("site.laz"), "copy {k}: the error names the file: {e}");
                refused += 1;
            }
        }
    }
    eprintln!("site.laz: {ok} read, {refused} refused");
    assert!(refused > 0);
    let fixtures = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/scans");
    for name in ["damaged-chunk-table.laz", "damaged-decoder-panic.laz", "damaged-gps-recursion.laz"] {
        let e = liftplan_depthmap::read_cloud(&fixtures.join(name), &[], &mut Inputs::default()).unwrap_err();
        assert!(e.to_string().contains(name), "{name}: {e}");
    }
}
