//! The pipeline backbone: project folder, cached stages, out/ refresh, errors.

use crate::util::*;

#[test]
fn init_drop_laz_run_gives_thinned_cloud_then_all_fresh() {
    let t = tempfile::tempdir().unwrap();
    let dir = t.path().join("site-a");
    project_with_scan(&dir, 300);
    let rep = run_json(&dir);
    assert_eq!(rep["ok"], true);
    let scans = stage(&rep, "scans");
    assert_eq!(scans["status"], "ran");
    assert!(scans["key"].as_str().unwrap().len() >= 32);
    let outputs: Vec<&str> = scans["outputs"].as_array().unwrap().iter().map(|o| o.as_str().unwrap()).collect();
    assert!(outputs.contains(&"out/site.laz"), "{outputs:?}");

    // The thinned cloud holds one point per occupied 5 cm voxel of the input.
    let input =
        liftplan_scans::read::read_all(&liftplan_scans::read::list_scans(&dir.join("scans/north.laz")).unwrap()[0])
            .unwrap();
    let expected = voxel_count(&input.xyz, 0.05);
    assert_eq!(read_las_count(&dir.join("out/site.laz")) as usize, expected);

    // Second run: every stage fresh, no file in out/ rewritten.
    let before = out_stamps(&dir);
    let rep2 = run_json(&dir);
    for s in rep2["stages"].as_array().unwrap() {
        assert!(s["status"] == "fresh" || s["status"] == "skipped", "{s}");
    }
    assert_eq!(stage(&rep2, "scans")["key"], scans["key"]);
    assert_eq!(out_stamps(&dir), before);
    // Each run is recorded.
    assert!(dir.join(".liftplan/runs/2.json").exists());
}

#[test]
fn touch_keeps_fresh_and_changing_voxel_reruns() {
    let t = tempfile::tempdir().unwrap();
    let dir = t.path().join("p");
    project_with_scan(&dir, 200);
    let first = run_json(&dir);
    // Rewrite the scan with the same bytes: new mtime, same content.
    let f = dir.join("scans/north.laz");
    let bytes = std::fs::read(&f).unwrap();
    std::thread::sleep(std::time::Duration::from_millis(20));
    std::fs::write(&f, &bytes).unwrap();
    let st = ok(&["status", dir.to_str().unwrap(), "--json"]);
    let st: serde_json::Value = serde_json::from_slice(&st.stdout).unwrap();
    assert_eq!(st[0]["state"], "fresh", "{st}");
    let again = run_json(&dir);
    assert_eq!(stage(&again, "scans")["status"], "fresh");

    set_toml(&dir, "voxel = 0.05", "voxel = 0.1");
    let st = ok(&["status", dir.to_str().unwrap()]);
    let text = String::from_utf8_lossy(&st.stdout);
    assert!(text.contains("stale") && text.contains("voxel"), "{text}");
    let rerun = run_json(&dir);
    assert_eq!(stage(&rerun, "scans")["status"], "ran");
    assert_ne!(stage(&rerun, "scans")["key"], stage(&first, "scans")["key"]);
    let n = read_las_count(&dir.join("out/site.laz")) as usize;
    let input = liftplan_scans::read::read_all(&liftplan_scans::read::list_scans(&f).unwrap()[0]).unwrap();
    assert_eq!(n, voxel_count(&input.xyz, 0.1));
}

/// Each stage keeps the `[cache] keep` most recently used entries: settings
/// that come back find theirs while it is kept, and rerun once it is not.
#[test]
fn the_cache_keeps_the_most_recently_used_entries() {
    let t = tempfile::tempdir().unwrap();
    let dir = t.path().join("p");
    project_with_scan(&dir, 60);
    set_toml(&dir, "keep = 3", "keep = 2");
    let entries = || {
        let mut keys: Vec<String> = std::fs::read_dir(dir.join(".liftplan/cache/scans"))
            .unwrap()
            .flatten()
            .map(|e| e.file_name().to_string_lossy().into_owned())
            .collect();
        keys.sort();
        keys
    };
    let mut voxel = "0.05".to_string();
    let mut scans_with = |v: &str| {
        set_toml(&dir, &format!("voxel = {voxel}"), &format!("voxel = {v}"));
        voxel = v.to_string();
        let rep = run_json(&dir);
        let scans = stage(&rep, "scans");
        (scans["status"].as_str().unwrap().to_string(), scans["key"].as_str().unwrap().to_string())
    };
    let (_, a) = scans_with("0.05");
    let (_, b) = scans_with("0.1");
    assert_eq!(entries(), sorted(&[&a, &b]));
    let (status, c) = scans_with("0.2");
    assert_eq!((status.as_str(), entries()), ("ran", sorted(&[&b, &c])));
    // 0.1 is kept and now the most recently used; 0.05 was dropped.
    assert_eq!(scans_with("0.1").0, "fresh");
    let (status, a2) = scans_with("0.05");
    assert_eq!((status.as_str(), &a2), ("ran", &a));
    assert_eq!(entries(), sorted(&[&a, &b]));
    assert_eq!(scans_with("0.1").0, "fresh");
    assert_eq!(scans_with("0.2").0, "ran");

    set_toml(&dir, "keep = 2", "keep = 0");
    let out = liftplan(&["run", dir.to_str().unwrap()]);
    let text = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success() && text.contains("liftplan.toml:") && text.contains("[cache] keep = 0"), "{text}");
}

fn sorted(keys: &[&String]) -> Vec<String> {
    let mut v: Vec<String> = keys.iter().map(|k| k.to_string()).collect();
    v.sort();
    v
}

#[test]
fn killed_run_leaves_no_trusted_partial_result() {
    use std::process::{Command, Stdio};
    let t = tempfile::tempdir().unwrap();
    let dir = t.path().join("k");
    project_with_scan(&dir, 1500);
    let mut child = Command::new(bin())
        .args(["run", dir.to_str().unwrap(), "-q"])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    // Wait until the scans stage is working in its temporary folder, then kill.
    let cache = dir.join(".liftplan/cache/scans");
    let start = std::time::Instant::now();
    loop {
        let busy = std::fs::read_dir(&cache)
            .map(|r| r.flatten().any(|e| e.file_name().to_string_lossy().starts_with(".tmp-")))
            .unwrap_or(false);
        if busy || start.elapsed().as_secs() > 60 {
            break;
        }
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    std::thread::sleep(std::time::Duration::from_millis(150));
    unsafe {
        libc::kill(child.id() as i32, libc::SIGKILL);
    }
    let status = child.wait().unwrap();
    assert!(!status.success());
    // Nothing trusted: no finished cache entry, no published output.
    let entries: Vec<String> = std::fs::read_dir(&cache)
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| !n.starts_with('.'))
        .collect();
    assert!(entries.is_empty(), "a killed run left cache entries {entries:?}");
    assert!(!dir.join("out/site.laz").exists());
    let st = ok(&["status", dir.to_str().unwrap(), "--json"]);
    assert!(String::from_utf8_lossy(&st.stdout).contains("stale"));

    // The next run produces the same output as an undisturbed run.
    let rep = run_json(&dir);
    assert_eq!(stage(&rep, "scans")["status"], "ran");
    let clean = t.path().join("clean");
    ok(&["init", clean.to_str().unwrap()]);
    std::fs::copy(dir.join("scans/north.laz"), clean.join("scans/north.laz")).unwrap();
    run_json(&clean);
    let a = std::fs::read(dir.join("out/site.laz")).unwrap();
    let b = std::fs::read(clean.join("out/site.laz")).unwrap();
    assert!(a == b, "outputs after a killed run differ from a clean run");
    // The killed run's temporary folder was swept.
    assert!(
        !std::fs::read_dir(&cache).unwrap().flatten().any(|e| e.file_name().to_string_lossy().starts_with(".tmp-"))
    );
}

fn expect_project_error(dir: &std::path::Path, needle: &str, line: usize) {
    let o = liftplan(&["run", dir.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2), "{}", String::from_utf8_lossy(&o.stderr));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains(needle), "expected '{needle}' in: {err}");
    assert!(err.contains(&format!("liftplan.toml:{line}:")), "expected line {line} in: {err}");
    assert!(!err.contains("panicked"), "{err}");
}

#[test]
fn bad_project_files_name_line_and_column() {
    let t = tempfile::tempdir().unwrap();
    let dir = t.path().join("bad");
    ok(&["init", dir.to_str().unwrap()]);
    let f = dir.join("liftplan.toml");
    std::fs::write(&f, "[project]\nname = \"x\"\n\n[scans]\nvoxl = 0.05\n").unwrap();
    expect_project_error(&dir, "voxl", 5);
    std::fs::write(&f, "[scans]\nvoxel = \"fine\"\n").unwrap();
    expect_project_error(&dir, "invalid type", 2);
    std::fs::write(&f, "[paths]\nscans = \"surveys\"\n").unwrap();
    expect_project_error(&dir, "does not exist", 2);
    // A Windows path: an escape to TOML in double quotes, a file of that
    // name in single quotes; each says to write it with '/'.
    std::fs::write(&f, "[scans]\nstations = \"scans\\stations.toml\"\n").unwrap();
    expect_project_error(&dir, "starts an escape: write a path with '/'", 2);
    std::fs::write(&f, "[scans]\nstations = 'scans\\stations.toml'\n").unwrap();
    expect_project_error(&dir, "does not exist ('\\' separates no folders here: write the path with '/'", 2);
    std::fs::write(&f, "[paths]\nscans = \"../elsewhere\"\n").unwrap();
    expect_project_error(&dir, "leaves the project folder", 2);
    std::fs::write(&f, "[paths]\nallow_outside = true\nscans = \"../bad/scans\"\n").unwrap();
    let o = liftplan(&["run", dir.to_str().unwrap(), "-q"]);
    assert_eq!(o.status.code(), Some(0), "{}", String::from_utf8_lossy(&o.stderr));
    std::fs::write(&f, "[scans]\nvoxel = -1.0\n").unwrap();
    expect_project_error(&dir, "voxel must be a positive", 1);
    // A project named in more than 100 characters (on every page's foot).
    std::fs::write(&f, format!("\n[project]\nname = \"{}\"\n", "n".repeat(101))).unwrap();
    expect_project_error(&dir, "[project] name is longer than 100 characters (101)", 2);
    // Planner settings that would make a NaN fitness or unbounded work are
    // refused at their own table.
    std::fs::write(&f, "[plan]\nplanner = \"prm\"\n\n[plan.baselines]\nprm_samples = 1000000000000\n").unwrap();
    expect_project_error(&dir, "prm_samples must be 2..20000", 4);
    std::fs::write(&f, "[plan.ga]\nlambda2 = inf\n").unwrap();
    expect_project_error(&dir, "[plan.ga] lambda1 must be positive, lambda2 non-negative (both finite)", 1);
    std::fs::write(&f, "[plan.ga.weights]\nswing_per_deg = nan\n").unwrap();
    expect_project_error(&dir, "weights must be finite", 1);
    std::fs::write(&f, "[depthmap]\nmargin_m = inf\n").unwrap();
    expect_project_error(&dir, "margin_m must be zero or positive (and finite)", 1);
    // An obstacle placed by hand that is not a box on site: its own table's line.
    let truck = "[[obstacle]]\nname = \"truck\"\ncenter_m = [1.0, 2.0]\nbase_z_m = 0.0\nsize_m = [10.0, 2.5, 4.0]\n";
    std::fs::write(&f, format!("{truck}\n{}", truck.replace("truck", "crane mat stack").replace("4.0]", "0.0]")))
        .unwrap();
    expect_project_error(&dir, "obstacle 'crane mat stack': size_m must be its length, width and height", 7);
    std::fs::write(&f, format!("{truck}\n{truck}")).unwrap();
    expect_project_error(&dir, "obstacle 'truck' is named twice", 7);
    std::fs::write(&f, truck.replace("base_z_m", "base_z")).unwrap();
    expect_project_error(&dir, "unknown field `base_z`", 4);
    std::fs::write(&f, format!("{truck}lifts = [\"V-2\"]\n")).unwrap();
    expect_project_error(&dir, "obstacle 'truck' is for lift 'V-2', which the project does not have", 1);
    // A power line that cannot be one: its own table's line.
    let line = "[[power_line]]\nname = \"feeder\"\npoints_m = [[0.0, 30.0, 9.0], [50.0, 30.0, 9.0]]\nsag_m = 1.0\nvoltage_kv = 11.0\n";
    std::fs::write(
        &f,
        format!("{truck}\n{line}\n{}", line.replace("feeder", "trunk").replace("sag_m = 1.0", "sag_m = -1.0")),
    )
    .unwrap();
    expect_project_error(&dir, "power line 'trunk': sag_m must be 0 to 100 m", 13);
    std::fs::write(&f, line.replace("11.0", "1200.0")).unwrap();
    expect_project_error(&dir, "power line 'feeder' is over 1,000 kV (1200 kV), beyond OSHA 1926.1408 Table A", 1);
    std::fs::write(&f, "this is not toml").unwrap();
    let o = liftplan(&["run", dir.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    // Usage errors are exit code 2 as well.
    assert_eq!(liftplan(&["run", "--frobnicate"]).status.code(), Some(2));
    assert_eq!(liftplan(&["run", dir.to_str().unwrap(), "--until", "nosuch"]).status.code(), Some(2));
}

#[test]
fn bad_scan_fails_the_stage_naming_the_file() {
    let t = tempfile::tempdir().unwrap();
    let dir = t.path().join("b");
    project_with_scan(&dir, 100);
    let good = std::fs::read(dir.join("scans/north.laz")).unwrap();
    std::fs::write(dir.join("scans/south.laz"), &good[..good.len() / 2]).unwrap();
    let o = liftplan(&["run", dir.to_str().unwrap(), "--json", "-q"]);
    assert_eq!(o.status.code(), Some(1));
    let rep: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let s = stage(&rep, "scans");
    assert_eq!(s["status"], "failed");
    assert!(s["error"].as_str().unwrap().contains("south.laz"), "{s}");
    assert!(!dir.join("out/site.laz").exists());
    // A plant file in a unit not stated, in the same run: the plant stage
    // still runs and says so (it was skipped, "an earlier stage failed",
    // and found one run later); what reads the scans is not run.
    std::fs::write(dir.join("plant/skid.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    let o = liftplan(&["run", dir.to_str().unwrap(), "--json", "-q"]);
    assert_eq!(o.status.code(), Some(1));
    let rep: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(stage(&rep, "scans")["status"], "failed");
    let plant = stage(&rep, "plant");
    assert!(plant["status"] == "failed" && plant["error"].as_str().unwrap().contains("skid.obj"), "{plant}");
    let depthmap = stage(&rep, "depthmap");
    assert!(depthmap["status"] == "skipped" && depthmap["reason"] == "the scans stage it reads failed", "{depthmap}");
}

#[test]
fn inspect_scan_prints_summary_json() {
    let t = tempfile::tempdir().unwrap();
    let f = t.path().join("a.laz");
    write_scan(&f, &small_scan(3, 50));
    let o = ok(&["inspect", f.to_str().unwrap(), "--json"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["kind"], "scan");
    assert_eq!(v["format"], "laz");
    assert_eq!(v["points"], 2500);
    assert_eq!(v["bbox"].as_array().unwrap().len(), 6);
    let o = liftplan(&["inspect", t.path().join("nope.laz").to_str().unwrap()]);
    assert!(!o.status.success());
}

/// A damaged file that makes a third-party reader panic (the gltf crate, on
/// this fixture) is one error naming the file, not a crash report followed by
/// an error.
#[test]
fn a_reader_panic_on_a_damaged_file_reads_as_one_error() {
    let f = concat!(env!("CARGO_MANIFEST_DIR"), "/fixtures/plant/damaged-accessor.gltf");
    let o = liftplan(&["inspect", f]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("damaged-accessor.gltf") && err.contains("failed on damaged data"), "{err}");
    assert!(!err.contains("panicked"), "{err}");

    // The LAZ decompressor panics on one of rayon's worker threads, not on
    // the thread that called it.
    let t = tempfile::tempdir().unwrap();
    let f = concat!(env!("CARGO_MANIFEST_DIR"), "/fixtures/scans/damaged-decoder-panic.laz");
    let o = liftplan(&["scans", f, "-o", t.path().join("site.ply").to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("damaged-decoder-panic.laz (point 0)") && err.contains("failed on damaged data"), "{err}");
    assert!(!err.contains("panicked"), "{err}");
}

/// A cloud too wide for a ground grid at the default cell is refused with
/// the cell, the extent and what to change; a larger cell, or no ground
/// classification, reads it.
#[test]
fn a_cloud_too_wide_for_its_ground_grid_says_what_to_change() {
    let t = tempfile::tempdir().unwrap();
    let f = t.path().join("far.xyz");
    std::fs::write(&f, "0 0 0\n1 1 0\n2 2 0\n6000 5000 1\n").unwrap();
    let out = t.path().join("site.laz");
    let scans = |extra: &[&str]| {
        let mut args = vec!["scans", f.to_str().unwrap(), "-o", out.to_str().unwrap(), "--register", "none", "-q"];
        args.extend_from_slice(extra);
        liftplan(&args)
    };
    let o = scans(&[]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("ground.cell_m = 1 m over the cloud's 6000 m x 5000 m extent needs a ground grid of 6001 x 5001")
            && err.contains("--ground-cell")
            && err.contains("--no-ground"),
        "{err}"
    );
    assert!(!out.exists());
    for extra in [&["--ground-cell", "3"][..], &["--no-ground"][..]] {
        let o = scans(extra);
        assert!(o.status.success(), "{extra:?}: {}", String::from_utf8_lossy(&o.stderr));
        assert_eq!(read_las_count(&out), 4, "{extra:?}");
    }
}

#[test]
fn clean_and_version() {
    let t = tempfile::tempdir().unwrap();
    let dir = t.path().join("c");
    project_with_scan(&dir, 50);
    run_json(&dir);
    ok(&["clean", dir.to_str().unwrap()]);
    assert!(!dir.join(".liftplan").exists() && !dir.join("out").exists());
    // The plans kept by revision stay, and the clean says so.
    run_json(&dir);
    let kept = dir.join("out").join("revisions").join("V-1").join("0fb8698c.plan.json");
    std::fs::create_dir_all(kept.parent().unwrap()).unwrap();
    std::fs::write(&kept, "{}").unwrap();
    let o = ok(&["clean", dir.to_str().unwrap()]);
    assert!(String::from_utf8_lossy(&o.stdout).contains("the plans kept by revision stay in out/revisions/"), "{o:?}");
    assert!(kept.exists() && !dir.join(".liftplan").exists());
    let left: Vec<_> = std::fs::read_dir(dir.join("out")).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert_eq!(left, ["revisions"]);
    let v = ok(&["--version"]);
    assert!(String::from_utf8_lossy(&v.stdout).starts_with("liftplan "));
}

/// `liftplan options` gives every stage's section of liftplan.toml with its
/// defaults (it gave only the scans' and the plant's), and what it prints
/// reads back as a project file.
#[test]
fn options_list_every_stages_settings_as_a_project_file() {
    let o = ok(&["options"]);
    let text = String::from_utf8_lossy(&o.stdout).to_string();
    for section in [
        "[scans]",
        "[plant]",
        "[charts]",
        "[depthmap]",
        "[plan]",
        "[plan.ga]",
        "[plan.cspace]",
        "[docs]",
        "[gpu]",
        "[cache]",
    ] {
        assert!(text.contains(&format!("\n{section}\n")), "no {section} in:\n{text}");
    }
    assert!(text.contains("load_cutout_m = 0.1"), "{text}");
    let t = tempfile::tempdir().unwrap();
    let dir = t.path().join("p");
    ok(&["init", dir.to_str().unwrap()]);
    std::fs::write(dir.join("liftplan.toml"), &text).unwrap();
    ok(&["status", dir.to_str().unwrap()]);
    let one = ok(&["options", "plan"]);
    let one = String::from_utf8_lossy(&one.stdout);
    assert!(one.contains("[plan]") && !one.contains("[scans]"), "{one}");
}

/// `liftplan chart --lookup` reads one capacity: boom and radius for a
/// chart with boom columns, the radius alone for a tower crane's chart of
/// one column (which it printed as "boom 0 m, column 0 m"); a length that
/// is not a finite number is refused. `liftplan chart` says what reading
/// the chart warned of.
#[test]
fn chart_lookup_takes_the_radius_alone_for_a_chart_of_one_column() {
    let t = tempfile::tempdir().unwrap();
    let (mobile, tower) = (t.path().join("ac700.xlsx"), t.path().join("tower.xlsx"));
    liftplan_fixtures::chart::write_demo_chart(&mobile).unwrap();
    liftplan_fixtures::chart::write_demo_tower_chart(&tower).unwrap();
    let csv = t.path().join("c.csv");
    let c = csv.to_str().unwrap();
    let o = ok(&["chart", tower.to_str().unwrap(), "-o", c, "--lookup", "radius=37.6"]);
    let said = String::from_utf8_lossy(&o.stdout);
    assert!(said.starts_with("18.900 t at radius 37.6 m (chart row 38 m, one column for any boom or jib"), "{said}");
    let o =
        ok(&["chart", mobile.to_str().unwrap(), "-o", c, "--config", "Main boom 360", "--lookup", "boom=40,radius=29"]);
    let said = String::from_utf8_lossy(&o.stdout);
    assert!(said.starts_with("33.400 t at boom 40 m, radius 29 m (chart row 30 m, column 41.8 m"), "{said}");
    let o =
        liftplan(&["chart", mobile.to_str().unwrap(), "-o", c, "--config", "Main boom 360", "--lookup", "radius=29"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("expects boom=B,radius=R"));
    // NaN and inf parse as numbers, but are no length (NaN was looked up
    // and said to be "beyond the chart's largest radius").
    for q in ["boom=40,radius=NaN", "boom=inf,radius=29"] {
        let o = liftplan(&["chart", mobile.to_str().unwrap(), "-o", c, "--config", "Main boom 360", "--lookup", q]);
        assert_eq!(o.status.code(), Some(2), "{q}");
        assert!(String::from_utf8_lossy(&o.stderr).contains("expects boom=B,radius=R"), "{q}");
    }
    // What reading the chart warned of is said (it was in the JSON only).
    liftplan_fixtures::chart::write_demo_chart_with(&mobile, Some((21, 6, "41,5"))).unwrap();
    let o = ok(&["chart", mobile.to_str().unwrap(), "-o", c]);
    // Each configuration's line says the units read, as a run's does.
    let lines = String::from_utf8_lossy(&o.stdout);
    assert!(lines.contains("'Main boom 360': ") && lines.contains("(capacity in t, radius in m"), "{lines}");
    let said = String::from_utf8_lossy(&o.stderr);
    assert!(
        said.contains(
            "warning: 'Main boom 360': Main boom 360!H28: '41,5' written as text with a decimal comma, read as 41.5\n"
        ),
        "{said}"
    );
}

/// `liftplan inspect` reads the .toml inputs too: a crane model (its boxes,
/// whose dimensions every clearance rests on) and a station file; the
/// project file is pointed to `status` and `options`.
#[test]
fn inspect_shows_a_crane_model_and_a_station_file() {
    let t = tempfile::tempdir().unwrap();
    let crane = t.path().join("my-crane.toml");
    std::fs::write(&crane, liftplan_core::crane::builtin_text("ltm-1100").unwrap()).unwrap();
    let o = ok(&["inspect", crane.to_str().unwrap(), "--json"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["kind"], "crane model", "{v}");
    assert_eq!(v["name"], "LTM 1100-5.2 (approx.)", "{v}");
    assert_eq!(v["crane"]["outriggers"]["spread_length_m"], 8.7, "{v}");
    let stations = t.path().join("stations.toml");
    std::fs::write(&stations, "[[station]]\nscan = \"north\"\nx_m = 1.0\ny_m = 2.0\nz_m = 3.0\n").unwrap();
    let o = ok(&["inspect", stations.to_str().unwrap(), "--json"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["stations"][0]["scan"], "north", "{v}");
    let project = t.path().join("liftplan.toml");
    std::fs::write(&project, "").unwrap();
    let o = liftplan(&["inspect", project.to_str().unwrap()]);
    assert!(String::from_utf8_lossy(&o.stderr).contains("a project file; `liftplan status`"));
}
