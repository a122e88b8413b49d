//! The whole pipeline, scans to PDF, on the demo project.

use crate::util::{liftplan, run_json, stage};

#[test]
fn demo_end_to_end_pdf_then_fresh_then_mass_change_replans() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("demo");
    let d = dir.to_str().unwrap();
    // Without a desktop session's XDG_RUNTIME_DIR, as in CI: Mesa's Vulkan
    // driver, probed for an adapter, must not get libwayland to print its
    // "error: XDG_RUNTIME_DIR is invalid" lines among liftplan's output.
    let out = std::process::Command::new(crate::util::bin())
        .args(["demo", d])
        .env_remove("XDG_RUNTIME_DIR")
        .output()
        .expect("run liftplan");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "liftplan demo failed:\n{stderr}");
    assert!(!stderr.contains("XDG_RUNTIME_DIR"), "{stderr}");
    let stdout = String::from_utf8_lossy(&out.stdout);
    let pdf_path = dir.join("out").join("V-101.pdf");
    assert!(stdout.contains(&format!("lift plan: {}", pdf_path.display())), "{stdout}");

    // The PDF parses, has cover, inputs, step table, one page per step and the sign-off,
    // and holds every step of steps.csv.
    let steps_csv = std::fs::read_to_string(dir.join("out").join("V-101.steps.csv")).unwrap();
    let steps: Vec<Vec<String>> =
        steps_csv.lines().skip(1).map(|l| l.split(',').map(str::to_string).collect()).collect();
    assert!(steps.len() >= 3, "{steps_csv}");
    let doc = lopdf::Document::load(&pdf_path).unwrap();
    let pages: Vec<u32> = doc.get_pages().keys().copied().collect();
    let text = doc.extract_text(&pages).unwrap();
    // The demo has more inputs (files, settings and code of six stages) than
    // the inputs page shows: all of them are on a last page.
    assert!(text.contains("are listed on the last pages"), "the demo's inputs fit on page 2 now: {text}");
    // The scanned load cut out of the checks at pick is said, with its count.
    assert!(text.contains("is not an obstacle to its own lift"), "{text}");
    // The cover names what the sign-off page asks to check (the demo's
    // scans leave a shadow beside the foundation).
    let cover = cover_text(&doc);
    assert!(
        cover.contains("CHECK FIRST ground under the load that no scan saw; the wind speed the load may be lifted in (less than the chart's) (sign-off page)"),
        "{cover}"
    );
    // The wind speed the vessel may be lifted in: its 24 m² side at cW 1.2
    // on 16 t of hook load (12 t, 0.5 t of slings, the 3.5 t hook block),
    // 9.8 m/s · √(1.2 · 16 / 28.8) = 8.0 m/s, the chart's 9.8 m/s read from
    // its sheet's note; on the cover and the sign-off page, where the cover
    // sends the signer.
    assert!(
        cover.contains("Wind AT MOST 8.0 m/s FOR THIS LOAD, less than the chart's: the chart's 9.8 m/s (Main boom 360!A51) holds for up to 1.2 m² of wind area per tonne of hook load; this load catches 28.8 m²"),
        "{cover}"
    );
    // The demo's whole summary is on the cover itself (in type a little
    // smaller than the other rows'), the wind next to the utilisation, not
    // run on to the next page.
    let first_page = doc.extract_text(&pages[..1]).unwrap().replace('\n', " ");
    assert!(!text.contains("Summary (continued from the cover)"), "{first_page}");
    for row in [
        "CHECK FIRST",
        "Max utilisation",
        "Critical lift",
        "Wind AT MOST",
        "Min clearance",
        "Slings",
        "Reeving",
        "Outrigger pads",
    ] {
        assert!(first_page.contains(row), "{row}: {first_page}");
    }
    assert!(first_page.find("Critical lift") < first_page.find("Wind AT MOST"), "{first_page}");
    assert!(first_page.find("Wind AT MOST") < first_page.find("Min clearance"), "{first_page}");
    // It is the gust at the boom head: the highest the lift raises it, and
    // the mean wind at 10 m above the ground that gusts to 8.0 m/s there.
    let lead = "it is the 3 s gust at the boom head, which rises to ";
    let head = &cover[cover.find(lead).unwrap_or_else(|| panic!("{cover}")) + lead.len()..];
    let head_m: f64 = head[..head.find(" m above the crane's ground").unwrap()].parse().unwrap();
    let mean = &head[head.find("a 10-minute mean wind of ").unwrap() + "a 10-minute mean wind of ".len()..];
    let mean_ms: f64 = mean[..mean.find(" m/s at 10 m above the ground gusts to ").unwrap()].parse().unwrap();
    let want = 8.0 / liftplan_core::wind::gust_factor(head_m);
    assert!(head_m > 20.0 && head_m < 45.0 && (mean_ms - want).abs() < 0.06, "{head_m} m, {mean_ms} m/s: {cover}");
    // How far the wind at that speed pushes the load off plumb where it
    // hangs longest: ρ v² (A_W + A_R / 2) / (2 m_H g) per metre, the hoist
    // rope's 6 falls of 28 mm up to 35 m catching A_R, twice that for a
    // sudden gust, within the demo's 1.0 m clearance.
    let number_after = |text: &str, lead: &str, unit: &str| -> f64 {
        let at = &text[text.find(lead).unwrap_or_else(|| panic!("{lead}: {text}")) + lead.len()..];
        at[..at.find(unit).unwrap()].parse().unwrap()
    };
    let off_m = number_after(&cover, "at that speed the wind holds the load ", " m off plumb");
    let hang_m = number_after(&cover, "m off plumb where it hangs longest in this lift, ", " m below the boom head");
    let swing_m = number_after(&cover, "and a sudden gust can swing it ", " m (tan θ");
    let v_ms = 9.8 * (1.2f64 * 16.0 / 28.8).sqrt();
    let rope_m2 = 6.0 * 0.028 * 35.0 * 1.2;
    assert!(cover.contains("; the hoist rope's 6 falls of 28 mm, up to 35.0 m below the boom head, catch A_R = 7.1 m² at cW 1.2; at that speed"), "{cover}");
    let per_m = 0.5 * 1.25 * v_ms * v_ms * (28.8 + rope_m2 / 2.0) / (16_000.0 * 9.80665);
    assert!((off_m - hang_m * per_m).abs() < 0.006 && (swing_m - 2.0 * hang_m * per_m).abs() < 0.006, "{cover}");
    assert!(hang_m > 20.0 && hang_m < head_m && swing_m < 1.0 && !cover.contains("A GUST CAN SWING"), "{cover}");
    // The plan keeps its clearance with the load so swung (the lift gives
    // its wind, and plan_for_swing is on unless turned off): the validator
    // measured what hangs swung that far, and the cover and the steps' page
    // say so.
    let plan: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("out").join("plan.json")).unwrap()).unwrap();
    let planned_per_m = plan["lifts"][0]["gust_swing_per_m"].as_f64().unwrap_or_else(|| panic!("{plan}"));
    assert!((planned_per_m - 2.0 * per_m).abs() < 1e-9, "{planned_per_m} against {}", 2.0 * per_m);
    assert!(
        cover.contains("; the plan keeps its 1.00 m clearance with the load swung so (wind plan_for_swing)"),
        "{cover}"
    );
    let swung = format!(
        "the rope, hook and load measured swung sideways as far as a sudden gust at the permissible wind can swing them, {:.1} cm per metre they hang below the boom head (wind plan_for_swing), and the load and rigging 0.10 m off along its x and y, where its centre of gravity may lie (load cog_tolerance_m), but in the lift-off and set-down",
        100.0 * planned_per_m
    );
    assert!(cover.contains(&format!("over landing zones; {swung}")), "{cover}");
    let flat = text.replace('\n', " ");
    assert!(flat.contains("on site and the wind (AT MOST 8.0 m/s FOR THIS LOAD: cover)"), "{text}");
    assert!(
        flat.contains(&format!("at any moment of the step ({swung}), between the validator's samples too")),
        "{text}"
    );
    // The circle the AC 700's superstructure sweeps, its counterweight's
    // back corners out (the built-in model's), and the ground under the
    // load's path, to keep people out of.
    let ac700 = liftplan_core::crane::builtin("ac-700").unwrap();
    let placed =
        liftplan_core::crane::Placement { x_m: 0.0, y_m: 0.0, z_m: 0.0, heading_rad: 0.0, boom_length_m: 40.0 };
    let (tail_m, _) = liftplan_core::crane::CraneSetup::new(ac700, placed).unwrap().tail_swing_m().unwrap();
    assert!(
        cover.contains(&format!("crane at the pick position, its tail's swing in magenta (counterweight {tail_m:.2} m from the slewing axis), load path in red, the ground under it, as far as a gust may swing it, in pink (")),
        "{cover}"
    );
    assert!(
        cover.contains("; keep people out of the tail's swing, and from under the load while it moves."),
        "{cover}"
    );
    // The outrigger pads at their most, estimated from the built-in crane
    // file's masses, and the pressure under the demo's mats: on the cover,
    // on the steps' pages and on the sign-off page.
    let pads = "104.2 t (1022 kN) on the rear left pad (x -3.25 m, y 5.75 m); 163 kPa under its 2.50 x 2.50 m mat, allowable 200 kPa";
    assert!(cover.contains(&format!("Outrigger pads in step 1, the most: {pads}; an estimate")), "{cover}");
    // ... with the counterweight the chart's sheet states in its title.
    assert!(cover.contains("with the 140.0 t counterweight its chart's sheet states (Main boom 360!A3)"), "{cover}");
    assert!(flat.contains(&format!("Outrigger pads the most: {pads}")), "{text}");
    assert!(
        flat.contains("Outrigger pads at their most (an estimate from the crane file's masses): step 1, 104.2 t on the rear left pad; 163 kPa"),
        "{text}"
    );
    // Whose boxes the crane's are: every clearance is measured from them.
    assert!(text.contains("crane: 'ac-700', built into liftplan"), "{text}");
    // The demo's vessel was scanned on its trailer as its box says.
    assert!(text.contains("The load as scanned at its pick position:"), "{text}");
    assert!(text.contains("agree with the scans"), "{text}");
    // The crane's set-up level, checked against the scanned ground under it.
    assert!(text.contains("scanned ground points under its carrier and outriggers"), "{text}");
    // The demo's vessel is set down on its foundation, not above it, where
    // the plant model (which draws it, left out of the obstacles) has it.
    assert!(text.contains("At its set position the load rests on"), "{text}");
    assert!(flat.contains("the plant model's /V-101 (left out as the load) stands at the set position"), "{text}");
    // ... with its centre of gravity over the foundation, wherever its 0.1 m
    // tolerance puts it (1.26 m inside as given).
    assert!(
        flat.contains("Its centre of gravity, anywhere within 0.10 m of where the lift gives it (load cog_tolerance_m), lies at least 1.16 m inside the edge of what holds it"),
        "{text}"
    );
    // The demo's plant model stands where its scans put the site.
    assert!(text.contains("Plant model against the scans"), "{text}");
    // What the lift passes over that no scan saw (the demo's scans leave a
    // shadow beside the foundation).
    assert!(text.contains("What the lift passes over: the load passes over"), "{text}");
    assert_eq!(
        pages.len(),
        steps.len() + 7,
        "cover, the site overview (the demo's cover has no room for it), inputs, steps table, rigging, {} step pages, sign-off, inputs",
        steps.len()
    );
    // The rigging page: each leg from its lift point, its length as the
    // cover's Slings row gives it, its angle as rigged.
    assert!(flat.contains("Drawn to scale in the load's frame as the plan takes it"), "{flat}");
    assert!(
        flat.contains("1 (-4.00, 0.00, 1.50) hook block 5.80 46.4° 8.38 — —")
            && flat.contains("2 (4.00, 0.00, 1.50) hook block 5.52 43.5° 8.79 — —"),
        "{flat}"
    );
    let last = doc.extract_text(&[*pages.last().unwrap()]).unwrap();
    for input in ["file:scans/scan-4.laz", "settings of the scans stage", "code of the docs stage"] {
        assert!(last.contains(input), "{input} missing from the last page:\n{last}");
    }
    for s in &steps {
        let op = &s[1];
        let line = format!("Step {} of {}", s[0], steps.len());
        assert!(text.contains(&line), "no page '{line}' in the PDF");
        assert!(text.contains(op.as_str()), "operation {op} missing");
    }
    assert!(text.contains("VALIDATED"));
    assert!(text.contains("What this plan does not model"), "the sign-off must say what the plan leaves out");
    assert!(text.contains('°'), "degree signs must survive as text");

    // Nothing changed: everything fresh.
    let r = run_json(&dir);
    for s in r["stages"].as_array().unwrap() {
        assert_eq!(s["status"], "fresh", "{s}");
    }

    // The depth map rebuilt on a GPU (any adapter: Mesa's lavapipe in CI) is
    // the CPU's, byte for byte, so the plan after it stays fresh; only the
    // pictures, whose renderer `[gpu] use` picks, are drawn again.
    let toml_path = dir.join("liftplan.toml");
    let t = std::fs::read_to_string(&toml_path).unwrap();
    let map_path = dir.join("out").join("site.mdm");
    let cpu_map = std::fs::read(&map_path).unwrap();
    std::fs::write(&toml_path, format!("{t}\n[gpu]\nuse = \"require\"\n")).unwrap();
    let o = liftplan(&["run", d, "--force", "depthmap", "--json", "-q"]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    if o.status.success() {
        let r: serde_json::Value = serde_json::from_slice(&o.stdout).expect("run --json prints JSON");
        assert_eq!(stage(&r, "depthmap")["status"], "ran", "{r}");
        let summary: serde_json::Value =
            serde_json::from_slice(&std::fs::read(dir.join("out").join("depthmap.json")).unwrap()).unwrap();
        let backend = summary["backend"].as_str().unwrap_or_default();
        assert!(backend.starts_with("gpu: "), "the depth map must have run on the GPU: {backend:?}");
        assert!(std::fs::read(&map_path).unwrap() == cpu_map, "the GPU's site.mdm differs from the CPU's");
        for (name, want) in [("plan", "fresh"), ("docs", "ran")] {
            assert_eq!(stage(&r, name)["status"], want, "{name}: {}", stage(&r, name));
        }
    } else {
        assert!(stderr.contains("[gpu] use = \"require\" but"), "the GPU run failed otherwise:\n{stderr}");
        eprintln!("SKIPPED: no GPU adapter, the demo's depth map is not built on one here: {stderr}");
    }
    std::fs::write(&toml_path, &t).unwrap();

    // A C-space picture damaged in the plan stage's cache entry, which the
    // docs stage reads it from, stops the docs stage with an error naming
    // it (not a document left without it, unsaid), and the last good
    // document is kept.
    let cached_pictures = cached_files(&dir, "plan", "V-101.cspace.png");
    let good_pdf = std::fs::read(&pdf_path).unwrap();
    for (p, good) in &cached_pictures {
        std::fs::write(p, &good[..good.len() / 2]).unwrap();
    }
    let o = liftplan(&["run", d, "--force", "docs", "-q"]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && stderr.contains("V-101.cspace.png"), "{stderr}");
    assert!(std::fs::read(&pdf_path).unwrap() == good_pdf, "the last good PDF is kept");
    for (p, good) in &cached_pictures {
        std::fs::write(p, good).unwrap();
    }

    // The plan.json the docs stage reads there: one whose steps are not one
    // a move in order (step n is drawn with move n) stops it with an error
    // naming the file, the last good document kept; the fuzz target
    // `plan_document`'s seed, the demo's plan kept in fuzz/seeds/, is one
    // it draws, so the fuzzer starts from a plan the stage takes.
    let cached_plans: Vec<(std::path::PathBuf, Vec<u8>)> = cached_pictures
        .iter()
        .map(|(p, _)| p.with_file_name("plan.json"))
        .map(|p| {
            let good = std::fs::read(&p).unwrap();
            (p, good)
        })
        .collect();
    for (p, good) in &cached_plans {
        let mut plans: serde_json::Value = serde_json::from_slice(good).unwrap();
        plans["lifts"][0]["steps"][1]["n"] = 7.into();
        std::fs::write(p, serde_json::to_vec(&plans).unwrap()).unwrap();
    }
    let o = liftplan(&["run", d, "--force", "docs", "-q"]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && stderr.contains("plan.json") && stderr.contains("its step 2 is numbered 7"),
        "{stderr}"
    );
    assert!(std::fs::read(&pdf_path).unwrap() == good_pdf, "the last good PDF is kept");
    let seed = std::fs::read(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz/seeds/plan_document/demo-V-101.plan.json"),
    )
    .unwrap();
    for (p, _) in &cached_plans {
        std::fs::write(p, &seed).unwrap();
    }
    let o = liftplan(&["run", d, "--force", "docs", "-q"]);
    assert!(o.status.success(), "the fuzz seed's plan is not drawn: {}", String::from_utf8_lossy(&o.stderr));
    // A step whose words run long (the numbers where its crane ends and its
    // pad's load 1e300, which a damaged plan.json may hold) has its picture
    // on the next page, whole (it was drawn past the footer, which debug
    // builds caught as a panic).
    for (p, _) in &cached_plans {
        let mut plans: serde_json::Value = serde_json::from_slice(&seed).unwrap();
        for joint in ["swing_rad", "radial", "hoist_m", "load_yaw_rad"] {
            plans["lifts"][0]["steps"][0]["end"][joint] = 1e300.into();
        }
        plans["lifts"][0]["steps"][0]["pads"]["load_kg"] = 1e300.into();
        std::fs::write(p, serde_json::to_vec(&plans).unwrap()).unwrap();
    }
    let o = liftplan(&["run", d, "--force", "docs", "-q"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let doc = lopdf::Document::load(&pdf_path).unwrap();
    let step_pages: Vec<String> =
        doc.get_pages().keys().map(|&n| doc.extract_text(&[n]).unwrap()).filter(|t| t.contains("Step 1 of ")).collect();
    assert!(
        step_pages.len() == 2 && step_pages[1].contains("(continued)") && !step_pages[1].contains("Crane at the end"),
        "{step_pages:?}"
    );
    // A step's words edited to say another move stop it, naming the step.
    for (p, _) in &cached_plans {
        let mut plans: serde_json::Value = serde_json::from_slice(&seed).unwrap();
        plans["lifts"][0]["steps"][2]["text"] = "swing +90.0° (counter-clockwise)".into();
        std::fs::write(p, serde_json::to_vec(&plans).unwrap()).unwrap();
    }
    let o = liftplan(&["run", d, "--force", "docs", "-q"]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && stderr.contains("its step 3 is not in the words its move is said in"), "{stderr}");
    // A move of 1e300 m in its own words heads its page on three lines and
    // runs the steps' table long (the words under the table went past the
    // footer), and what the steps name as long as the plan stage writes
    // them: drawn within the pages (debug builds check).
    for (p, _) in &cached_plans {
        let mut plans: serde_json::Value = serde_json::from_slice(&seed).unwrap();
        let lift = &mut plans["lifts"][0];
        assert_eq!(
            (lift["moves"][1]["joint"].as_str(), lift["steps"][1]["operation"].as_str()),
            (Some("hoist"), Some("Hoist up"))
        );
        lift["moves"][1]["to"]["hoist_m"] = (-1e300).into();
        lift["steps"][1]["amount"] = 1e300.into();
        lift["steps"][1]["text"] = format!("hoist up {:.2} m", 1e300).into();
        lift["steps"][2]["clearance_to"] = format!("/PIPE-{}", "A".repeat(994)).into();
        lift["steps"][2]["chart_cell"] = "x".repeat(1000).into();
        std::fs::write(p, serde_json::to_vec(&plans).unwrap()).unwrap();
    }
    let o = liftplan(&["run", d, "--force", "docs", "-q"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let doc = lopdf::Document::load(&pdf_path).unwrap();
    let text: Vec<String> = doc.get_pages().keys().map(|&n| doc.extract_text(&[n]).unwrap()).collect();
    assert!(text.iter().any(|t| t.contains("Step 2 of ") && t.contains("459400540160.00 m")), "{text:?}");
    for (p, good) in &cached_plans {
        std::fs::write(p, good).unwrap();
    }
    // The document of the demo's own plan again, in out/ and the docs
    // stage's cache.
    let o = liftplan(&["run", d, "--force", "docs", "-q"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));

    // The chart.json the plan and docs stages read from the charts stage's
    // cache entry: a wind speed no sheet states (1e300 m/s swung the load to
    // infinity and panicked building the C-space) stops the plan stage with
    // an error naming the file and the value's place, the last good
    // document kept.
    let cached_charts = cached_files(&dir, "charts", "chart.json");
    let good_pdf = std::fs::read(&pdf_path).unwrap();
    for (p, good) in &cached_charts {
        let mut chart: serde_json::Value = serde_json::from_slice(good).unwrap();
        chart["configs"][0]["wind_ms"][0]["value"] = 1e300.into();
        std::fs::write(p, serde_json::to_vec(&chart).unwrap()).unwrap();
    }
    let o = liftplan(&["run", d, "--force", "plan", "-q"]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success()
            && stderr.contains("chart.json: configs[0] ('Main boom 360'), wind_ms[0] (Main boom 360!A51): 1e300 m/s"),
        "{stderr}"
    );
    assert!(std::fs::read(&pdf_path).unwrap() == good_pdf, "the last good PDF is kept");
    for (p, good) in &cached_charts {
        std::fs::write(p, good).unwrap();
    }

    // A heavier load: charts, plan and docs rerun; scans, plant and the depth map do not.
    let plan_12t = plan["lifts"][0]["summary"]["revision"].as_str().unwrap().to_string();
    std::fs::write(&toml_path, t.replace("mass_t = 12.0", "mass_t = 13.0")).unwrap();
    let r = run_json(&dir);
    // The run says what differs in the plan that replaces the last, and
    // what it was made from: the lifts' settings, which the charts stage
    // reads too; not the scans or the plant.
    let replaced: Vec<&str> =
        stage(&r, "plan")["replaced"].as_array().into_iter().flatten().filter_map(|l| l.as_str()).collect();
    assert_eq!(replaced.len(), 1, "{r}");
    assert!(
        replaced[0].contains(&format!(" replaces plan {plan_12t}: gross load, "))
            && replaced[0]
                .contains("; what it was made from differs: the charts stage's settings, the plan stage's settings (")
            && replaced[0].contains(&format!("(liftplan revisions --compare {plan_12t} ")),
        "{}",
        replaced[0]
    );
    for (name, want) in [
        ("scans", "fresh"),
        ("plant", "fresh"),
        ("depthmap", "fresh"),
        ("charts", "ran"),
        ("plan", "ran"),
        ("docs", "ran"),
    ] {
        assert_eq!(stage(&r, name)["status"], want, "{name}: {}", stage(&r, name));
    }
    let plan: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("out").join("plan.json")).unwrap()).unwrap();
    // 13 t, 0.5 t of rigging, the 3.5 t block and the hoist rope: 6 falls
    // of 35 m (the lift's longest rope) at 3.9 kg/m, 819 kg.
    assert!((plan["lifts"][0]["gross_kg"].as_f64().unwrap() - 17_819.0).abs() < 1e-6);
    // The demo's vessel hangs on two legs of 10 t to the ends of its top,
    // each by a 12 t shackle; its centre of gravity, 0.2 m along from the
    // middle, known to 0.1 m: at its worst 0.3 m along and 0.1 m off the
    // legs' line, the near leg (3.7 m along, 4 m down) carries 9.52 t.
    let doc = lopdf::Document::load(&pdf_path).unwrap();
    let text13 = doc.extract_text(&doc.get_pages().keys().copied().collect::<Vec<u32>>()).unwrap().replace('\n', " ");
    assert!(
        text13.contains("Slings 2 legs at the middles of the top's short edges, up to 47.1° from the vertical; the most on one leg (leg 2) 9.52 t"),
        "{text13}"
    );
    assert!(
        text13.contains("of its 10.00 t working load limit: 95 %, and of its lift point's shackle's 12.00 t (in line): 79 %; legs 5.80 and 5.52 m long from lift point to hook, for the load to hang level; the worst with the centre of gravity within 0.10 m along x and y (load cog_tolerance_m, the worst over that square worked out; the most on a leg with it at (0.30, -0.10) m), the lengths for it as given: on two legs a load whose centre of gravity lies off hangs up to 5.1° off level; along the line through its lift points the legs' lengths set it level, across it no length does (it hangs with its centre of gravity under that line): at the trial lift, set the legs for it to hang level along the line and CHECK that it hangs level across it, as the plan takes it, and where it does not, find its centre of gravity"),
        "{text13}"
    );
    // Reeved with 6 falls of the crane file's 10 t: the hook load of 17.82 t
    // (13 t, 0.5 t of rigging, the 3.5 t block, 0.82 t of rope) needs 2.
    assert!(
        text13.contains("Reeving hook load 17.82 t (load, rigging, hook block and 0.82 t of hoist rope); on 6 falls of 10.00 t each: 60.00 t, 30 % (at least 2 needed); the hook block rated 100.00 t, carrying 13.50 t of load and rigging: 14 %; the hoist rope's 600 m (less 20.0 m to the boom's foot and the 40.0 m boom) on 6 falls lets the hook hang 90.00 m below the boom head, more than the lift's own longest rope (35.00 m, crane longest_rope_m); the 0.82 t of hoist rope: 6 falls of up to 35.00 m below the boom head (crane longest_rope_m) at 3.90 kg/m"),
        "{text13}"
    );
    assert!(
        text13.contains("Gross load 17.82 t (load + rigging + hook block + 0.82 t of hoist rope + deductions)"),
        "{text13}"
    );
    // The crew's copy: every page names the plan's revision, as plan.json
    // gives it.
    let crews_plan = plan["lifts"][0]["summary"]["revision"].as_str().unwrap().to_string();
    assert_eq!(crews_plan.len(), 8, "{crews_plan}");
    for (n, _) in doc.get_pages() {
        let page = doc.extract_text(&[n]).unwrap().replace('\n', " ");
        assert!(page.contains(&format!("lift V-101, plan {crews_plan} — issued")), "page {n}: {page}");
    }
    // So does every row of the steps' file.
    let rows = std::fs::read_to_string(dir.join("out").join("V-101.steps.csv")).unwrap();
    assert!(rows.lines().next().unwrap().ends_with(",max_pad_kg,max_pad,plan"), "{rows}");
    assert!(rows.lines().skip(1).all(|r| r.ends_with(&format!(",{crews_plan}"))), "{rows}");

    // A raised work platform parked since the survey, where the load swings
    // from the trailer to the foundation: placed by hand, only the plan and
    // its document are made again, and the new plan keeps the load clear
    // of it where the last one took it through.
    let t13 = t.replace("mass_t = 12.0", "mass_t = 13.0");
    let steps_csv = dir.join("out").join("V-101.steps.csv");
    let (platform_xy, platform_half, platform_top) = ([19.4, -13.6], 1.5, 20.0);
    let through =
        load_comes_near(&std::fs::read_to_string(&steps_csv).unwrap(), platform_xy, platform_half, platform_top);
    let (through_step, _) = through.expect("the platform must stand on the plan made without it");
    let after_step = (through_step - 1).to_string();
    let resume = |revision: &str| liftplan(&["resume", d, "V-101", "--plan", revision, "--after-step", &after_step]);
    // The crew stopped before that step: where the load hangs, read off
    // the plan they follow, which is the last plan yet.
    let o = resume(&crews_plan);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let printed_from_last = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(printed_from_last.contains(&format!("plan {crews_plan}, the last, from")), "{printed_from_last}");
    let o = liftplan(&["resume", d, "V-101", "--plan", &crews_plan, "--after-step", "99"]);
    assert!(String::from_utf8_lossy(&o.stderr).contains("--after-step must be 1 to"), "{o:?}");
    let with_platform = format!(
        "{t13}\n[[obstacle]]\nname = \"raised work platform\"\ncenter_m = [{}, {}]\nbase_z_m = 0.0\nsize_m = [3.0, 3.0, {platform_top}]\n",
        platform_xy[0], platform_xy[1]
    );
    std::fs::write(&toml_path, &with_platform).unwrap();
    let r = run_json(&dir);
    for (name, want) in [("depthmap", "fresh"), ("charts", "fresh"), ("plan", "ran"), ("docs", "ran")] {
        assert_eq!(stage(&r, name)["status"], want, "{name}: {}", stage(&r, name));
    }
    let doc = lopdf::Document::load(&pdf_path).unwrap();
    let pages: Vec<u32> = doc.get_pages().keys().copied().collect();
    let text = doc.extract_text(&pages).unwrap().replace('\n', " ");
    let near = load_comes_near(&std::fs::read_to_string(&steps_csv).unwrap(), platform_xy, platform_half, platform_top);
    assert_eq!(near, None, "the plan made with the platform takes the load near it");
    let plan: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("out").join("plan.json")).unwrap()).unwrap();
    assert_eq!(
        plan["lifts"][0]["summary"]["obstacles"][0],
        "raised work platform, 3.00 x 3.00 x 20.00 m at x 19.40, y -13.60 m, underside at z 0.00 m"
    );
    assert!(text.contains("Placed by hand raised work platform, 3.00 x 3.00 x 20.00 m"), "{text}");
    assert!(text.contains("obstacles placed by hand in teal"), "{text}");
    assert!(text.contains("CHECK ON SITE that each stands where given"), "{text}");
    assert!(text.contains("CHECK FIRST the obstacle placed by hand, where it stands"), "{text}");
    // What differs in the new plan from the crew's, for the engineer asked
    // to sign it: the platform, and the path from the step it changes.
    let new_plan = plan["lifts"][0]["summary"]["revision"].as_str().unwrap().to_string();
    let o = crate::util::ok(&["revisions", d, "--compare", &crews_plan, &new_plan]);
    let said = String::from_utf8_lossy(&o.stdout);
    assert!(said.starts_with(&format!("V-101: plan {new_plan} against plan {crews_plan}:\n")), "{said}");
    assert!(
        said.contains("\n  Obstacles placed by hand: none; now raised work platform, 3.00 x 3.00 x 20.00 m at x 19.40, y -13.60 m, underside at z 0.00 m\n"),
        "{said}"
    );
    assert!(said.contains("\n  The path differs from step "), "{said}");
    assert!(!said.contains("Gross load"), "the same load: {said}");
    // Made from the same scans, plant and charts: only the project's
    // settings (the platform is placed there) differ.
    assert!(
        said.trim_end().ends_with("\n  Made from: the plan stage's settings (those besides the lifts, not V-101's own) (the project's lifts, any of them, power lines, obstacles and [plan], [cspace]) (settings) differs"),
        "{said}"
    );
    let o = liftplan(&["revisions", d, "--compare", &crews_plan, "0000abcd"]);
    assert!(
        !o.status.success() && String::from_utf8_lossy(&o.stderr).contains("plan 0000abcd is not kept there"),
        "{o:?}"
    );

    // The crew's PDF is kept beside their plan, as issued (its pages name
    // their plan), though out/ now holds the plan made with the platform.
    let issued =
        lopdf::Document::load(dir.join("out").join("revisions").join("V-101").join(format!("{crews_plan}.pdf")))
            .unwrap();
    let first = issued.extract_text(&[1]).unwrap().replace('\n', " ");
    assert!(first.contains(&format!("lift V-101, plan {crews_plan} — issued")), "{first}");
    // The platform is placed and the plan made again, but the crew still
    // holds the plan without it: resume reads theirs, kept by its revision
    // in out/revisions/, not the last plan, and says so. Another revision
    // is refused naming the last; so is the crane set up elsewhere since.
    let plan: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("out").join("plan.json")).unwrap()).unwrap();
    let last_plan = plan["lifts"][0]["summary"]["revision"].as_str().unwrap().to_string();
    assert_ne!(last_plan, crews_plan);
    let o = resume(&crews_plan);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let printed = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(printed.starts_with(&format!("# lift V-101 after step {after_step}")), "{printed}");
    assert!(printed.contains(&format!("plan {crews_plan}, not the last ({last_plan}), from")), "{printed}");
    assert!(printed.contains(&format!("revisions/V-101/{crews_plan}.plan.json")), "{printed}");
    // The steps are said in their moves' own words, not the kept file's:
    // words edited to run on to a line of their own are not printed, to be
    // pasted into the project file.
    let kept = dir.join("out").join("revisions").join("V-101").join(format!("{crews_plan}.plan.json"));
    let as_kept = std::fs::read(&kept).unwrap();
    let mut edited: serde_json::Value = serde_json::from_slice(&as_kept).unwrap();
    for step in edited["lifts"][0]["steps"].as_array_mut().unwrap() {
        step["text"] = "lower 0.10 m\nresume_from = { swing_deg = 0.0 }".into();
    }
    std::fs::write(&kept, serde_json::to_vec(&edited).unwrap()).unwrap();
    let o = resume(&crews_plan);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(String::from_utf8_lossy(&o.stdout), printed);
    std::fs::write(&kept, &as_kept).unwrap();
    let pasted = |printed: &str| printed.lines().filter(|l| !l.starts_with('#')).collect::<Vec<_>>().join("\n");
    let resume_line = pasted(&printed);
    assert_eq!(resume_line, pasted(&printed_from_last), "{printed}\n{printed_from_last}");
    assert!(
        resume_line
            .starts_with(&format!("resumes_plan = {{ revision = \"{crews_plan}\", after_step = {after_step} }}\n")),
        "{resume_line}"
    );
    let hangs: toml::Value = toml::from_str(&resume_line).unwrap();
    let hangs = &hangs["resume_from"];
    let at = |key: &str| hangs[key].as_float().unwrap_or_else(|| panic!("{key} in {resume_line}"));
    let o = resume("0000abcd");
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && e.contains("has no plan 0000abcd: its last plan"), "{e}");
    assert!(e.contains(&format!("is plan {last_plan}")), "{e}");
    let o = resume("V-101");
    assert!(String::from_utf8_lossy(&o.stderr).contains("the 8 hex digits after \"plan\""), "{o:?}");
    // The crew's crane set up elsewhere, or another model, in the project now.
    for (from, to, said) in [
        (
            "position_m = [0.0, 0.0]",
            "position_m = [0.5, 0.0]",
            ["had the crane at (0.00, 0.00) m", "the project sets it up at (0.50, 0.00) m", "where it stood"],
        ),
        (
            "model = \"ac-700\"",
            "model = \"ltm-1100\"",
            ["was made for the AC 700", "the project gives the", "the crane holding the load is the plan's"],
        ),
    ] {
        let changed = with_platform.replace(from, to);
        assert_ne!(changed, with_platform);
        std::fs::write(&toml_path, &changed).unwrap();
        let o = resume(&crews_plan);
        let e = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success() && said.iter().all(|s| e.contains(s)), "{e}");
    }
    std::fs::write(&toml_path, &with_platform).unwrap();

    // The lift stopped where `liftplan resume` said: re-planned from there,
    // with no lift-off. The steps file gives each step's end under
    // resume_from's names.
    let set_line = "set = { x_m = 30.0, y_m = 2.0, z_m = 1.2, yaw_deg = 0.0 }\n";
    let resumed = with_platform.replace(set_line, &format!("{set_line}{resume_line}\n"));
    assert_ne!(resumed, with_platform);
    let (cover, text) = planned_with(&dir, &resumed);
    let steps = std::fs::read_to_string(&steps_csv).unwrap();
    assert!(steps.starts_with("step,operation,amount,unit,swing_deg,luff_deg,hoist_m,load_yaw_deg,"), "{steps}");
    let first: Vec<&str> = steps.lines().nth(1).unwrap().split(',').collect();
    assert_ne!(first[1], "Hoist up", "{steps}");
    let plan: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("out").join("plan.json")).unwrap()).unwrap();
    let start = &plan["lifts"][0]["moves"][0]["from"];
    assert!((start["swing_rad"].as_f64().unwrap() - at("swing_deg").to_radians()).abs() < 1e-12, "{start}");
    assert!((start["hoist_m"].as_f64().unwrap() - at("hoist_m")).abs() < 1e-12, "{start}");
    let said = format!(
        "RESUMED PART WAY THROUGH THE LIFT, after step {after_step} of plan {crews_plan} (resumes_plan): this plan starts where the load hangs now (resume_from), not at its pick: swing {:.1}°, luff {:.1}°, hoist {:.2} m",
        at("swing_deg"),
        at("luff_deg"),
        at("hoist_m")
    );
    assert!(cover.contains(&said), "{said}\n{cover}");
    // The cover says the pose was checked against the crew's plan, as kept.
    let checked = format!(
        "Checked: resume_from is where plan {crews_plan} (from out/revisions/V-101/{crews_plan}.plan.json) has the load after step {after_step}"
    );
    assert!(cover.contains(&checked), "{checked}\n{cover}");
    assert!(!cover.contains("against the plan it continues (cover)"), "{cover}");
    assert!(cover.contains("CHECK THE CRANE SHOWS THAT before step 1"), "{cover}");
    assert!(cover.contains("CHECK FIRST that the crane shows where the lift resumes"), "{cover}");
    assert!(cover.contains("crane where the lift resumes (the load hanging)"), "{cover}");
    assert!(text.contains("The first step starts where the load hangs when the lift resumes"), "{text}");
    assert!(text.contains("The part of the lift already made, from the pick to there, is not in it"), "{text}");
    assert_eq!(load_comes_near(&steps, platform_xy, platform_half, platform_top), None, "{steps}");
    // Each run checks resume_from against the plan resumes_plan names (the
    // crew's, kept by revision): the pose `liftplan resume` printed agrees;
    // one edited by hand (the load 0.3 m higher) is said, not refused.
    let r = run_json(&dir);
    let check = &r["resume_checks"][0];
    assert_eq!(check["agrees"], true, "{r}");
    let said = check["said"].as_str().unwrap();
    assert!(
        said.contains(&format!("resume_from is where plan {crews_plan} (from "))
            && said.contains(&format!("has the load after step {after_step}")),
        "{said}"
    );
    let hoist = at("hoist_m");
    let edited = resumed.replace(&format!("hoist_m = {hoist:.3}"), &format!("hoist_m = {:.3}", hoist - 0.3));
    assert_ne!(edited, resumed);
    std::fs::write(&toml_path, &edited).unwrap();
    let r = run_json(&dir);
    let check = &r["resume_checks"][0];
    assert_eq!(check["agrees"], false, "{r}");
    let said = check["said"].as_str().unwrap();
    assert!(said.contains(&format!("hoist {:.3} m given, {hoist:.3} m in the plan", hoist - 0.3)), "{said}");
    assert!(said.contains("check that it is where the load hangs"), "{said}");
    // So does the new plan's cover, and it asks for the check first.
    let cover = cover_text(&lopdf::Document::load(&pdf_path).unwrap());
    assert!(
        cover.contains(&format!("NOT CONFIRMED BY THE PLAN IT CONTINUES: resume_from is not where plan {crews_plan}"))
            && cover.contains(&format!("hoist {:.3} m given, {hoist:.3} m in the plan", hoist - 0.3)),
        "{cover}"
    );
    assert!(cover.contains("where the lift resumes, against the plan it continues (cover)"), "{cover}");
    // The crew's plan as kept damaged, then gone (out/ cleaned by hand):
    // the cover says the pose is not checked, and why.
    let kept = dir.join("out").join("revisions").join("V-101").join(format!("{crews_plan}.plan.json"));
    let good = std::fs::read(&kept).unwrap();
    for (damaged, says) in
        [(true, "could not be read from out/revisions/V-101/"), (false, "is not kept in out/revisions/V-101 (")]
    {
        if damaged {
            std::fs::write(&kept, b"{").unwrap();
        } else {
            std::fs::remove_file(&kept).unwrap();
        }
        let r = run_json(&dir);
        assert_eq!(stage(&r, "docs")["status"], "ran", "{r}");
        let cover = cover_text(&lopdf::Document::load(&pdf_path).unwrap());
        let said = format!("NOT CONFIRMED BY THE PLAN IT CONTINUES: plan {crews_plan} {says}");
        assert!(cover.contains(&said) && cover.contains("resume_from is not checked against it"), "{said}\n{cover}");
    }
    std::fs::write(&kept, good).unwrap();
    // The crane set up elsewhere, or another model, in the project since
    // the crew's plan: said too, before the run (which stops at the depth
    // map here: the check does not wait for a plan). By now more runs than
    // the plan stage's cache keeps have been made since the crew's plan:
    // out/revisions/ holds it still.
    let cached_plans = std::fs::read_dir(dir.join(".liftplan").join("cache").join("plan")).unwrap();
    for entry in cached_plans.flatten() {
        let held = std::fs::read_to_string(entry.path().join("plan.json")).unwrap_or_default();
        assert!(!held.contains(&format!("\"revision\": \"{crews_plan}\"")), "{}", entry.path().display());
    }
    // `liftplan revisions` lists it, and asked to remove every plan kept
    // before now, keeps it (the lift resumes it) and every plan a crew may
    // hold or be given, removing only the others, files and all.
    let listed = |args: &[&str]| -> serde_json::Value {
        let o = crate::util::ok(&[&["revisions", d, "--json"], args].concat());
        serde_json::from_slice(&o.stdout).unwrap()
    };
    let before = listed(&[])["kept"].as_array().unwrap().clone();
    // Each lift's newest as many as are kept: nothing to remove, and each
    // listed as held; none newest is not a number of plans to keep.
    let n = before.len().to_string();
    let o = crate::util::ok(&["revisions", d, "--keep-last", &n]);
    let said = String::from_utf8_lossy(&o.stdout);
    assert!(
        said.starts_with(&format!("removed nothing: no plan beyond each lift's {n} newest but those held (below)")),
        "{said}"
    );
    assert_eq!(
        listed(&["--keep-last", &n])["kept"].as_array().unwrap().iter().filter(|k| k["held"].is_string()).count(),
        before.len()
    );
    assert!(!liftplan(&["revisions", d, "--keep-last", "0"]).status.success());
    // Under a size it is under already: nothing removed, said so.
    let o = crate::util::ok(&["revisions", d, "--keep-under", "100000"]);
    let said = String::from_utf8_lossy(&o.stdout);
    assert!(
        said.starts_with("removed nothing: what is kept, ") && said.contains(" MB, is 100000 MB or under already\n"),
        "{said}"
    );
    assert!(!liftplan(&["revisions", d, "--keep-under", "1", "--keep-last", "2"]).status.success());
    let after = listed(&["--remove-older-than", "0"]);
    let (left, removed) = (after["kept"].as_array().unwrap(), after["removed"].as_array().unwrap());
    assert_eq!(left.len() + removed.len(), before.len(), "{after}");
    // Five kept by now: the crew's, the cache's three (one the last) and
    // one before them, which goes.
    assert!(!removed.is_empty(), "{after}");
    let crews = left.iter().find(|k| k["revision"] == crews_plan.as_str()).expect("the crew's plan is kept");
    assert_eq!(crews["held"], "a lift of the project resumes it (resumes_plan)");
    assert!(left.iter().all(|k| k["held"].is_string()), "{after}");
    for gone in before.iter().filter(|k| !left.contains(k)) {
        let revision = gone["revision"].as_str().unwrap();
        assert!(removed.iter().any(|r| r.as_str().unwrap().starts_with(&format!("V-101 plan {revision} "))));
        let files = std::fs::read_dir(dir.join("out").join("revisions").join("V-101")).unwrap();
        assert!(files.flatten().all(|f| !f.file_name().to_string_lossy().starts_with(revision)), "{revision}");
    }
    // A project file that does not read: listed still, saying so; nothing
    // removed (which plans its lifts resume is not known).
    let good_toml = std::fs::read_to_string(dir.join("liftplan.toml")).unwrap();
    std::fs::write(dir.join("liftplan.toml"), format!("{good_toml}\n[[lift]\n")).unwrap();
    let o = crate::util::ok(&["revisions", d]);
    let said = String::from_utf8_lossy(&o.stdout);
    assert!(
        said.starts_with("note: ") && said.contains("the plans the project's lifts resume are not known here"),
        "{said}"
    );
    assert!(said.contains(&format!("V-101 plan {crews_plan}  kept ")), "{said}");
    let o = liftplan(&["revisions", d, "--remove-older-than", "0"]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && stderr.contains("removing plans needs the project file to read"), "{stderr}");
    assert_eq!(listed(&[])["kept"].as_array().map(Vec::len), Some(left.len()));
    std::fs::write(dir.join("liftplan.toml"), good_toml).unwrap();
    for (from, to, says) in [
        ("position_m = [0.0, 0.0]", "position_m = [0.5, 0.0]", ["had the crane at (0.00, 0.00) m", "where it stood"]),
        (
            "model = \"ac-700\"",
            "model = \"ltm-1100\"",
            ["was made for the AC 700", "the crane holding the load is the plan's"],
        ),
    ] {
        let changed = resumed.replace(from, to);
        assert_ne!(changed, resumed);
        std::fs::write(&toml_path, &changed).unwrap();
        let o = crate::util::ok(&["run", d, "--until", "depthmap", "--json", "-q"]);
        let r: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        let check = &r["resume_checks"][0];
        let said = check["said"].as_str().unwrap();
        assert!(check["agrees"] == false && says.iter().all(|s| said.contains(s)), "{r}");
    }

    // An overhead line along the site's north edge: listed with its
    // approach distance, drawn, asked to be checked, and in the run's line.
    // And a fall zone of 3 m round the ground under the load.
    // And the pad the crane is set up on, listed.
    let zoned = t13.replace(
        "shackle_wll_t = 12.0 }",
        "shackle_wll_t = 12.0 }\nfall_zone_m = 3.0\ncrane_stands_in = [{ name = \"crane pad\", corners_m = [[-10.0, -8.0], [15.0, -8.0], [15.0, 8.0], [-10.0, 8.0]] }]",
    );
    assert_ne!(zoned, t13);
    let with_line = format!(
        "{zoned}\n[[power_line]]\nname = \"north feeder\"\npoints_m = [[-40.0, 45.0, 12.0], [10.0, 35.0, 12.25], [60.0, 45.0, 12.5]]\nsag_m = 1.5\nswing_deg = 30.0\nvoltage_kv = 33.0\n"
    );
    let (cover, text) = planned_with(&dir, &with_line);
    // Its middle support stands where the scans show the site but no pole:
    // said, and asked to be checked first; its ends are outside the scans.
    let said = "power line 'north feeder', 33 kV, held at (-40.00, 45.00, 12.00), (10.00, 35.00, 12.25), (60.00, 45.00, 12.50) m, sagging 1.50 m at mid-span, swinging up to 30 degrees either way in the wind: kept 3.05 m off (OSHA 1926.1408 Table A); support 2 at (10.00, 35.00, 12.25) m NOT SEEN, where the scans show the site around (nothing within 1 m of it in plan): CHECK WHERE THE LINE RUNS; outside the scans: supports 1, 3";
    assert!(text.contains(&format!("Power lines {said} ([[power_line]])")), "{text}");
    assert!(cover.contains("power lines in orange"), "{cover}");
    assert!(cover.contains("areas the crane may stand in outlined in blue"), "{cover}");
    assert!(
        cover.contains("where a power line runs: the scans do not show a support it gives (inputs page)"),
        "{cover}"
    );
    assert!(
        text.contains("Crane stands in crane pad (x -10.0 to 15.0 m, y -8.0 to 8.0 m) (crane_stands_in): its carrier and outriggers, with their pads' mats, stand within one of these"),
        "{text}"
    );
    assert!(cover.contains("the power lines: where they run, how low and how high they hang, how far the wind swings them and their voltage"), "{cover}");
    let plan: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("out").join("plan.json")).unwrap()).unwrap();
    assert_eq!(plan["lifts"][0]["summary"]["power_lines"][0], said);
    let coverage = &plan["lifts"][0]["summary"]["coverage"];
    let (under, kept) =
        (coverage["under_load"]["passed_m2"].as_f64().unwrap(), coverage["kept_out"]["area_m2"].as_f64().unwrap());
    assert!(kept > under + 100.0, "{kept} m² kept out round {under} m² under the load");
    assert!(
        cover.contains(&format!("and 3.0 m round it for what may fall (fall_zone_m), in pink ({kept:.0} m²)")),
        "{cover}"
    );
    assert!(cover.contains("from under the load and its fall zone while it moves"), "{cover}");

    // A lift that sets its load back where it picked it (a test lift) has
    // no step but the lift-off and the set-down, and no clearance of its
    // own to report (JSON has no infinity: its plan must still be read by
    // the docs stage); the load rests on the trailer whose top 0.1 m went
    // with the load's cut-out, not 0.10 m above it.
    let set_back = t13.replace(
        "set = { x_m = 30.0, y_m = 2.0, z_m = 1.2, yaw_deg = 0.0 }",
        "set = { x_m = 6.0, y_m = -16.0, z_m = 1.2, yaw_deg = 90.0 }",
    );
    assert_ne!(set_back, t13);
    std::fs::write(&toml_path, set_back).unwrap();
    let r = run_json(&dir);
    assert_eq!(stage(&r, "depthmap")["status"], "fresh", "{r}");
    assert_eq!(stage(&r, "docs")["status"], "ran", "{r}");
    let plan: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("out").join("plan.json")).unwrap()).unwrap();
    assert_eq!(plan["lifts"][0]["steps"].as_array().unwrap().len(), 2, "{plan}");
    assert_eq!(plan["lifts"][0]["summary"]["min_clearance_m"], serde_json::Value::Null);
    let doc = lopdf::Document::load(&pdf_path).unwrap();
    let pages: Vec<u32> = doc.get_pages().keys().copied().collect();
    let text = doc.extract_text(&pages).unwrap().replace('\n', " ");
    assert!(text.contains("no step between the lift-off and the set-down"), "{text}");
    assert!(text.contains("went with the load's cut-out at pick"), "{text}");
    assert!(!text.contains("SET-DOWN ENDS"), "{text}");

    // A second lift takes the vessel from its foundation to the yard: its
    // load was not there when scanned, so its pick is not compared with the
    // scans, and the points its cut-out takes are the foundation's top.
    let second = t13.clone()
        + r#"
[[lift]]
id = "V-101-back"
description = "Vessel V-101 from its foundation to the yard"
load = { name = "vessel V-101", mass_t = 13.0, size_m = [8.0, 3.0, 3.0], cog_m = [0.2, 0.0, -0.1] }
rigging = { mass_t = 0.5, height_m = 4.0 }
crane = { model = "ac-700", position_m = [0.0, 0.0], ground_z_m = 0.0, heading_deg = 0.0, boom_m = 40.0, chart_config = "Main boom 360" }
pick = { x_m = 30.0, y_m = 2.0, z_m = 1.2, yaw_deg = 0.0 }
set = { x_m = -15.0, y_m = 10.0, z_m = 0.0, yaw_deg = 0.0 }
clearance_m = 1.0
liftoff_m = 0.5
"#;
    std::fs::write(&toml_path, second).unwrap();
    let r = run_json(&dir);
    assert_eq!(stage(&r, "plan")["status"], "ran", "{r}");
    let doc = lopdf::Document::load(dir.join("out").join("V-101-back.pdf")).unwrap();
    let pages: Vec<u32> = doc.get_pages().keys().copied().collect();
    let text = doc.extract_text(&pages).unwrap().replace('\n', " ");
    assert!(text.contains("picked up where lift V-101 sets it down, so it was not there when the scans"), "{text}");
    assert!(!text.contains("The load as scanned at its pick position"), "{text}");
    // That lift taken out again: its plan is not left in out/ as if current.
    std::fs::write(&toml_path, &t13).unwrap();
    let r = run_json(&dir);
    let superseded = |name: &str| stage(&r, name)["superseded"].as_array().cloned().unwrap_or_default();
    assert!(superseded("docs").contains(&serde_json::json!("V-101-back.pdf")), "{r}");
    assert!(superseded("plan").contains(&serde_json::json!("V-101-back.steps.csv")), "{r}");
    assert!(!dir.join("out").join("V-101-back.pdf").exists());
    assert!(!dir.join("out").join("V-101-back.steps.csv").exists());
    assert!(dir.join("out").join("superseded").join("V-101-back.pdf").is_file());
    assert!(dir.join("out").join("V-101.pdf").is_file());

    // The vessel declared on the ground under its trailer: refused, and the
    // refusal says what the scans show of the load (its own top, beyond the
    // cut-out, is the "scanned structure" it meets).
    let on_ground = t13.replace("z_m = 1.2, yaw_deg = 90.0", "z_m = 0.0, yaw_deg = 90.0");
    assert_ne!(on_ground, t13);
    let stderr = refused_with(&dir, &on_ground, "planned with the load in its trailer");
    assert!(stderr.contains("the load as scanned at its pick position:"), "{stderr}");
    assert!(stderr.contains("ABOVE ITS BOX'S TOP"), "{stderr}");
    std::fs::write(&toml_path, &t13).unwrap();

    // The plant model placed 2 m off the scans (a wrong translate_m): no
    // plan, and the move that puts it on them is said; planned with it
    // where it is only when asked to, and then said in the PDF.
    let off = t13.replace("translate_m = [-500.0, -300.0, 0.0]", "translate_m = [-498.0, -300.0, 0.0]");
    assert_ne!(off, t13);
    let stderr = refused_with(&dir, &off, "planned with the model 2 m off");
    assert!(stderr.contains("the model lies on the scans when moved by x -2.00 m, y +0.00 m"), "{stderr}");
    let (_, text) = planned_with(&dir, &format!("{off}\n[plan]\nmodel_off_scans = \"warn\"\n"));
    assert!(text.contains("moved by x -2.00 m"), "{text}");
    // The model 0.3 m high (a height datum): its walls still lie on the
    // scans (85 % of the points near it, median 5 mm), but its tops do not,
    // and the move down is said; it read "they agree", and the load met
    // the model's foundation at its set-down ("CHECK set z_m").
    let high = t13.replace("translate_m = [-500.0, -300.0, 0.0]", "translate_m = [-500.0, -300.0, 0.3]");
    let stderr = refused_with(&dir, &high, "planned with the model 0.3 m high");
    assert!(stderr.contains("the model lies on the scans when moved by z -0.30 m"), "{stderr}");
    // The vessel left in the plant model, where it is installed: the load
    // set there meets its own copy, named as such (it read "CHECK set z_m").
    let kept = t13.replace("exclude = [\"/V-101\"]", "");
    assert_ne!(kept, t13);
    let stderr = refused_with(&dir, &kept, "planned with the vessel in the model at its set position");
    assert!(stderr.contains("the plant model's /V-101 fills the load's box there"), "{stderr}");
    assert!(stderr.contains("[plant] exclude = [\"/V-101\"]"), "{stderr}");
    // The vessel set crosswise on its foundation (yaw 90° for 0°): planned
    // (it rests on the foundation), but the plant model's copy of it, left
    // out of the obstacles, has it a quarter turn from that, which the
    // cover asks to check first (nothing said it once the copy was excluded).
    let crosswise = t13.replace(
        "set = { x_m = 30.0, y_m = 2.0, z_m = 1.2, yaw_deg = 0.0 }",
        "set = { x_m = 30.0, y_m = 2.0, z_m = 1.2, yaw_deg = 90.0 }",
    );
    assert_ne!(crosswise, t13);
    let (cover, text) = planned_with(&dir, &crosswise);
    let plan: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("out").join("plan.json")).unwrap()).unwrap();
    let against = &plan["lifts"][0]["summary"]["against_model"][0];
    assert!(against["object"] == "/V-101" && (against["turn_deg"].as_f64().unwrap() - 90.0).abs() < 0.01, "{against}");
    assert!(cover.contains("the set position against the plant model's /V-101"), "{cover}");
    assert!(text.contains("the model has it turned 90° from set yaw_deg: CHECK set yaw_deg"), "{text}");
    // The vessel set 5 m east along its foundation, its centre of gravity
    // 0.7 m beyond the foundation's end: planned, and "set down on
    // /FDN-V101" was all it said; the cover now asks to check it first.
    let overhung = t13.replace(
        "set = { x_m = 30.0, y_m = 2.0, z_m = 1.2, yaw_deg = 0.0 }",
        "set = { x_m = 35.0, y_m = 2.0, z_m = 1.2, yaw_deg = 0.0 }",
    );
    let (cover, text) = planned_with(&dir, &overhung);
    assert!(cover.contains("the load's centre of gravity over what holds it at its set position"), "{cover}");
    assert!(text.contains("BEYOND THE EDGE OF WHAT HOLDS IT"), "{text}");
    // The model 100 m north of the scanned site (a wrong datum): the scans
    // barely meet it, so where it stands is unchecked, which the cover asks
    // to check first.
    let beside = t13.replace("translate_m = [-500.0, -300.0, 0.0]", "translate_m = [-500.0, -200.0, 0.0]");
    let (cover, text) = planned_with(&dir, &beside);
    assert!(cover.contains("where the plant model stands (the scans barely meet it)"), "{cover}");
    assert!(text.contains("THE PLANT MODEL AND THE SCANS BARELY MEET"), "{text}");
    // A drain buried 1.2 m under the rear left pad (the plant model's
    // origin is 500 m east and 300 m north): named on the sign-off page,
    // and the cover asks to check it first.
    let drain = dir.join("plant").join("ug-drain.obj");
    let (x, y) = ([496.5, 497.0], [305.0, 306.5]);
    let (z_lo, z_hi) = (-1.8, -1.2);
    let mut obj = String::from("o UG-DRAIN-1\n");
    for i in 0..8 {
        obj += &format!("v {} {} {}\n", x[i & 1], y[(i >> 1) & 1], if i >> 2 == 0 { z_lo } else { z_hi });
    }
    obj += "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
    std::fs::write(&drain, obj).unwrap();
    let with_obj = t13.replace("[plant]\n", "[plant]\nunit = \"m\"\nup_axis = \"z\"\n");
    assert_ne!(with_obj, t13);
    let (cover, text) = planned_with(&dir, &with_obj);
    assert!(cover.contains("what lies in the ground under the outrigger pads"), "{cover}");
    assert!(
        text.contains(
            "IN THE GROUND UNDER THE OUTRIGGER PADS: UG-DRAIN-1 1.20 m below the set-up level under the rear left pad"
        ),
        "{text}"
    );
    std::fs::remove_file(&drain).unwrap();
    // The chart configuration with the 70 t counterweight: the pads are
    // worked out with the counterweight its name states, and the lift's
    // own counterweight_t that differs from it is to be checked first.
    let cw70 = t13.replace("chart_config = \"Main boom 360\" }", "chart_config = \"Main boom 360 CW 70t\" }");
    assert_ne!(cw70, t13);
    let (cover, _) = planned_with(&dir, &cw70);
    assert!(
        cover.contains("an estimate from the crane file's masses with the 70.0 t counterweight its chart configuration 'Main boom 360 CW 70t' names"),
        "{cover}"
    );
    let most_t = |cover: &str| {
        let at = cover.find("Outrigger pads in step").unwrap();
        let from = at + cover[at..].find("the most: ").unwrap() + "the most: ".len();
        cover[from..from + cover[from..].find(" t (").unwrap()].parse::<f64>().unwrap()
    };
    let with_70 = most_t(&cover);
    let cw140 = cw70.replace("\"Main boom 360 CW 70t\" }", "\"Main boom 360 CW 70t\", counterweight_t = 140.0 }");
    let (cover, text) = planned_with(&dir, &cw140);
    // The rear pads carry 70 t more between them.
    assert!(most_t(&cover) > with_70 + 20.0, "{with_70} t with 70 t of counterweight: {cover}");
    assert!(cover.contains("the counterweight (the lift's is not its chart configuration's)"), "{cover}");
    // The sign-off page, where the cover sends the signer, says why.
    assert!(
        text.contains("(an estimate from the crane file's masses, with the lift's 140.0 t counterweight, NOT THE 70.0 t ITS CHART CONFIGURATION 'Main boom 360 CW 70t' NAMES: CHECK crane counterweight_t against what is rigged)"),
        "{text}"
    );
    // A load too heavy for the chart where the crane stands: the refusal
    // names the nearest crane position, at the height of the ground scanned
    // there, where the lift plans; given it, the lift plans there.
    // (On legs that carry it: the slings are checked first.)
    let heavy = t13
        .replace("mass_t = 13.0", "mass_t = 40.0")
        .replace("leg_wll_t = 10.0, shackle_wll_t = 12.0", "leg_wll_t = 40.0, shackle_wll_t = 40.0");
    let stderr = refused_with(&dir, &heavy, "a 40 t vessel on a 31.4 t chart cell planned");
    let flat = stderr.replace('\n', " ");
    let at = flat.find("; the crane set up at position_m = [").unwrap_or_else(|| panic!("{flat}"));
    let named = &flat[at + "; the crane set up at ".len()..];
    let named = &named[..named.find(" (the ground scanned there; ").unwrap_or_else(|| panic!("{flat}"))];
    assert!(flat.contains("and there the lift plans and passes the validator in "), "{flat}");
    let given = heavy.replace("position_m = [0.0, 0.0], ground_z_m = 0.0, heading_deg = 0.0", named);
    assert_ne!(given, heavy, "{named}");
    // With what its pads put on the ground, nothing found under them: the
    // same pad and load the plan there has at its most.
    assert!(flat.contains("nothing of the plant model or the scans in the ground under them"), "{flat}");
    let pads = &flat[flat.find(", its outrigger pads at their most ").unwrap_or_else(|| panic!("{flat}"))..];
    let pads = &pads[", its outrigger pads at their most ".len()..pads.find(" pad; ").unwrap()];
    let (cover, _) = planned_with(&dir, &given);
    assert!(cover.contains("CRITICAL LIFT"), "{named}: {cover}");
    let (load, pad) = pads.split_once(" t on the ").unwrap();
    assert!(
        cover.contains(&format!("{load} t (")) && cover.contains(&format!("on the {pad} pad (x ")),
        "{pads}: {cover}"
    );
    // A load the chart carries above critical_pct where the crane stands:
    // the cover names where it would not be; given that position, it is not.
    let critical = t13
        .replace("mass_t = 13.0", "mass_t = 26.0")
        .replace("leg_wll_t = 10.0, shackle_wll_t = 12.0", "leg_wll_t = 40.0, shackle_wll_t = 40.0");
    let (cover, _) = planned_with(&dir, &critical);
    let lead = "CRITICAL LIFT (over 75 %); not critical with the crane set up at ";
    let named = &cover[cover.find(lead).unwrap_or_else(|| panic!("{cover}")) + lead.len()..];
    let named = &named[..named.find(" (the ground scanned there; ").unwrap_or_else(|| panic!("{cover}"))];
    assert!(cover.contains("; there the lift plans and passes the validator in "), "{cover}");
    let given = critical.replace("position_m = [0.0, 0.0], ground_z_m = 0.0, heading_deg = 0.0", named);
    assert_ne!(given, critical, "{named}");
    let (cover, _) = planned_with(&dir, &given);
    assert!(cover.contains("not critical (limit 75 %)"), "{named}: {cover}");
    // A load of little area: the chart's speed, nothing to check first; a
    // lift without wind: not worked out, to check first; a lift's chart_ms
    // that is not what the chart's sheet states: said, to check first.
    // (With the shackles' pins given square to the legs' plane: in line as
    // rigged, out of line only as far as the load may turn on its legs with
    // its centre of gravity anywhere within its tolerance.)
    let compact = t13
        .replace("wind = { cw = 1.2 }", "wind = { cw = 1.2, area_m2 = 5.0 }")
        .replace("shackle_wll_t = 12.0 }", "shackle_wll_t = 12.0, pin_axes = [[0.0, 1.0, 0.0], [0.0, 1.0, 0.0]] }");
    assert_eq!(compact.matches("pin_axes").count(), 1);
    let (cover, text) = planned_with(&dir, &compact);
    assert!(
        cover.contains("Wind at most 9.8 m/s, the chart's: ") && !cover.contains("the wind speed the load"),
        "{cover}"
    );
    assert!(text.contains("the wind (at most the chart's 9.8 m/s: cover)"), "{text}");
    let side = &cover[cover
        .find("shackles' 12.00 t, less for side loading: the most used, leg ")
        .unwrap_or_else(|| panic!("{cover}"))..];
    let deg: f64 = side
        [side.find("pulled up to ").unwrap() + "pulled up to ".len()..side.find("° out of line").unwrap()]
        .parse()
        .unwrap();
    assert!(deg > 0.0 && deg < 10.0, "{side}");
    assert!(
        side.contains(&format!(
            "out of line with its pin (rigging pin_axes, {deg:.1}° of it the most the load may turn on its rigging"
        )),
        "{side}"
    );
    // Pins along the load: its legs, 47° from the vertical, pull them 47°
    // out of line, and the shackles cannot carry their pull.
    let along =
        t13.replace("shackle_wll_t = 12.0 }", "shackle_wll_t = 12.0, pin_axes = [[1.0, 0.0, 0.0], [1.0, 0.0, 0.0]] }");
    let stderr = refused_with(&dir, &along, "shackles pulled 47° out of line").replace('\n', " ");
    assert!(
        stderr.contains("the lift points' shackles cannot carry the load")
            && stderr.contains("or lugs turned for their legs to pull square to the pins (rigging pin_axes)"),
        "{stderr}"
    );
    let calm = t13.replace("wind = { cw = 1.2 }", "");
    let (cover, text) = planned_with(&dir, &calm);
    assert!(
        cover.contains("Wind not worked out: the lift gives no wind = { cw }, the load's drag coefficient (its chart's sheet states 9.8 m/s (Main boom 360!A51))"),
        "{cover}"
    );
    assert!(cover.contains("the wind speed the load may be lifted in (not worked out)"), "{cover}");
    assert!(text.contains("the speed this load may be lifted in is not worked out: cover)"), "{text}");
    let other = t13.replace("wind = { cw = 1.2 }", "wind = { chart_ms = 11.0, cw = 1.2 }");
    let (cover, _) = planned_with(&dir, &other);
    assert!(cover.contains("BUT THE CHART'S SHEET STATES 9.8 m/s (Main boom 360!A51): CHECK wind chart_ms"), "{cover}");
    assert!(cover.contains("the chart's wind speed (the lift's chart_ms is not what its sheet states)"), "{cover}");
    // A clearance less than a gust can swing the load: planned for, said
    // so; where the lift turns that off, in capitals in the wind row, and to
    // check first.
    let tight = t13.replace("clearance_m = 1.0", "clearance_m = 0.4");
    assert_ne!(tight, t13);
    let (cover, _) = planned_with(&dir, &tight);
    assert!(
        cover.contains("; the plan keeps its 0.40 m clearance with the load swung so (wind plan_for_swing)"),
        "{cover}"
    );
    assert!(!cover.contains("A GUST CAN SWING") && !cover.contains("the load's swing in the wind"), "{cover}");
    let plumb = tight.replace("wind = { cw = 1.2 }", "wind = { cw = 1.2, plan_for_swing = false }");
    assert_ne!(plumb, tight);
    let (cover, text) = planned_with(&dir, &plumb);
    assert!(
        cover.contains("; A GUST CAN SWING THE LOAD ")
            && cover.contains(
                " m, MORE THAN THE 0.40 m CLEARANCE THE PLAN KEEPS (wind plan_for_swing = false): tag lines, a lower wind limit or more clearance; the crane manufacturer's wind rules govern"
            ),
        "{cover}"
    );
    assert!(
        cover.contains("the load's swing in the wind (a sudden gust at the permissible speed can swing it "),
        "{cover}"
    );
    assert!(!text.contains("measured swung sideways"), "{text}");
    // A lift's counterweight that is not the one the chart's sheet states.
    let cw100 = t13
        .replace("chart_config = \"Main boom 360\" }", "chart_config = \"Main boom 360\", counterweight_t = 100.0 }");
    assert_ne!(cw100, t13);
    let (cover, text) = planned_with(&dir, &cw100);
    assert!(cover.contains("the counterweight (the lift's is not its chart configuration's)"), "{cover}");
    assert!(text.contains("with the lift's 100.0 t counterweight, NOT THE 140.0 t ITS CHART'S SHEET STATES (Main boom 360!A3): CHECK crane counterweight_t"), "{text}");
    // An area the load must never be over: on the inputs page, with the
    // margin the planner keeps (its fall zone and 0.25 m more), and
    // outlined in the site overview.
    let fenced = t13.replace("shackle_wll_t = 12.0 }", "shackle_wll_t = 12.0 }\nfall_zone_m = 3.0").replace(
        "wind = { cw = 1.2 }",
        "wind = { cw = 1.2 }\nnot_over = [{ name = \"CONTROL ROOM\", corners_m = [[-30.0, -10.0], [-20.0, -10.0], [-20.0, 0.0], [-30.0, 0.0]] }, { name = \"NEIGHBOUR\", corners_m = [[60.0, -10.0], [70.0, -10.0], [70.0, 0.0]], crane_too = true }]",
    );
    assert!(fenced.contains("fall_zone_m = 3.0") && fenced.contains("NEIGHBOUR"), "{fenced}");
    let (cover, text) = planned_with(&dir, &fenced);
    // The second, one the crane may not be over either (far off: the same
    // plan), is said so.
    assert!(
        cover.contains(
            "areas the load (and the crane, where the inputs page says so) must never be over outlined in green"
        ),
        "{cover}"
    );
    assert!(
        text.replace('\n', " ").contains("CONTROL ROOM (x -30.0 to -20.0 m, y -10.0 to 0.0 m); NEIGHBOUR (x 60.0 to 70.0 m, y -10.0 to 0.0 m), nor the crane (not_over): the planner keeps the load, its hook block and rope 3.25 m off each in plan (their fall zone, fall_zone_m 3.0 m, and 0.25 m more), and every other part of the crane that swings (boom or jib, counterweight) off those marked 'nor the crane' (crane_too); the validator checks they never come over one nor within 3.0 m of one, nor the crane over those marked so"),
        "{text}"
    );
    // Mats too small for what the ground may bear: the cover asks to check
    // the ground under the pads first.
    let small_mats = t13.replace("mat_m = [2.5, 2.5]", "mat_m = [1.5, 1.5]");
    assert_ne!(small_mats, t13);
    let (cover, text) = planned_with(&dir, &small_mats);
    assert!(cover.contains("the ground under the outrigger pads (more than it may bear)"), "{cover}");
    assert!(
        text.contains("kPa under its 1.50 x 1.50 m mat, MORE THAN THE 200 kPa THE GROUND MAY BEAR: a mat of at least 2.30 x 2.30 m (spreading it as evenly) or a ground check"),
        "{text}"
    );
    std::fs::write(&toml_path, &t13).unwrap();

    // A capacity on the lift's chart configuration typed with a footnote
    // mark ("41.5 (1)", Main boom 360!H28): read with a warning, which the
    // cover's CHECK FIRST and the sign-off page repeat (the mark may
    // restrict the value; it was said on the inputs page only), quoting the
    // note the mark points at (the chart's note 1, under its grid).
    let chart_path = dir.join("charts").join("ac700-illustrative.xlsx");
    liftplan_fixtures::chart::write_demo_chart_with(&chart_path, Some((21, 6, "41.5 (1)"))).unwrap();
    let (cover, text) = planned_with(&dir, &t13);
    assert!(cover.contains("the load chart cells read with a warning"), "{cover}");
    let note_row = 10 + liftplan_fixtures::chart::demo_radii_m().len();
    assert!(
        text.contains(&format!("READING THE LOAD CHART'S CONFIGURATION 'Main boom 360' WARNED: Main boom 360!H28: footnote mark dropped from '41.5 (1)'; its footnote, Main boom 360!A{note_row}, reads: \"Capacities include the hook block and slings; deduct them from the load.\"")),
        "{text}"
    );
    // Which steps read that cell (those at the radius of its row) is said.
    assert!(
        text.contains("(a footnote may restrict the value it marks); THIS PLAN READS Main boom 360!H28 in step"),
        "{text}"
    );
    assert!(
        cover.contains("the load chart cells read with a warning (1 warning; the steps read 1 cell it names)"),
        "{cover}"
    );
    // And the pages of those steps say so, quoting the warning.
    assert!(
        text.contains("Chart warning THIS STEP READS A CELL THE CHART WARNED OF: Main boom 360!H28: footnote mark dropped from '41.5 (1)'"),
        "{text}"
    );
    // A mark on a cell at a radius the lift never works at (11 m): said, and
    // that no step reads it.
    let at_11_m = format!("{}*", liftplan_fixtures::chart::demo_capacity_t(11.0, 41.8, 1.0).unwrap());
    liftplan_fixtures::chart::write_demo_chart_with(&chart_path, Some((10, 6, &at_11_m))).unwrap();
    let (cover, text) = planned_with(&dir, &t13);
    assert!(
        cover.contains("the load chart cells read with a warning (1 warning; no step reads a cell it names)"),
        "{cover}"
    );
    assert!(
        text.contains(&format!("Main boom 360!H17: footnote mark dropped from '{at_11_m}'; no footnote marked '*' was found on sheet Main boom 360: read the chart's notes for it. The capacities this plan checks were read so: CHECK THOSE CELLS against the chart the crane's owner issued (a footnote may restrict the value it marks); no step of this plan reads a cell they name.")),
        "{text}"
    );
    // The same cell typed as text with a decimal comma ("41,5", as a chart
    // typed in a German Excel holds it): read as 41.5, said with the cell.
    liftplan_fixtures::chart::write_demo_chart_with(&chart_path, Some((21, 6, "41,5"))).unwrap();
    let (cover, text) = planned_with(&dir, &t13);
    assert!(
        cover.contains("the load chart cells read with a warning (1 warning; the steps read 1 cell it names)"),
        "{cover}"
    );
    assert!(
        text.contains("WARNED: Main boom 360!H28: '41,5' written as text with a decimal comma, read as 41.5.")
            && text.contains("THIS PLAN READS Main boom 360!H28 in step"),
        "{text}"
    );
    liftplan_fixtures::chart::write_demo_chart(&chart_path).unwrap();

    // Without scans (the plant model alone), the cover asks to check first
    // what only scans would have shown: the ground under the load outside
    // the model, and the level the crane is set up at (it asked nothing).
    let scans = dir.join("scans");
    let scans_aside = tmp.path().join("scans-aside");
    std::fs::rename(&scans, &scans_aside).unwrap();
    std::fs::create_dir(&scans).unwrap();
    let no_stations: String = t13.lines().filter(|l| !l.starts_with("stations =")).collect::<Vec<_>>().join("\n");
    let (cover, _) = planned_with(&dir, &no_stations);
    assert!(cover.contains("ground under the load outside the plant model (there are no scans)"), "{cover}");
    assert!(cover.contains("the crane's set-up level (no ground was scanned under it)"), "{cover}");
    // The pipe rack left out as well, with no scans to show it: the lift
    // goes through where it stands, low and close beside the crane (it was
    // planned through the crane's own carrier, and refused by the
    // validator), and the cover asks to check first what was left out in
    // its way.
    let rack_out = no_stations.replace("exclude = [\"/V-101\"]", "exclude = [\"/V-101\", \"/RACK-1*\"]");
    assert_ne!(rack_out, no_stations);
    let (cover, text) = planned_with(&dir, &rack_out);
    assert!(cover.contains("what [plant] exclude left out of the model, in the lift's way"), "{cover}");
    assert!(
        text.contains("THE LIFT PASSES THROUGH WHAT [plant] EXCLUDE LEFT OUT") && text.contains("/RACK-1"),
        "{text}"
    );
    std::fs::remove_dir(&scans).unwrap();
    std::fs::rename(&scans_aside, &scans).unwrap();
    std::fs::write(&toml_path, &t13).unwrap();

    // Without its load chart the lift is not planned: a plan whose capacity
    // was never checked must not read as validated.
    let charts = dir.join("charts");
    let aside = tmp.path().join("charts-aside");
    std::fs::rename(&charts, &aside).unwrap();
    std::fs::create_dir(&charts).unwrap();
    let stderr = refused_with(&dir, &t13, "planned without a load chart");
    assert!(stderr.contains("lift 'V-101': no load chart was read"), "{stderr}");
    assert!(stderr.contains("put the crane's load chart"), "{stderr}");
}

/// The file `name` in each of `stage`'s cache entries of the project in
/// `dir`, with its bytes as written (to put back after damaging it); at
/// least one.
fn cached_files(dir: &std::path::Path, stage: &str, name: &str) -> Vec<(std::path::PathBuf, Vec<u8>)> {
    let files: Vec<(std::path::PathBuf, Vec<u8>)> = std::fs::read_dir(dir.join(".liftplan").join("cache").join(stage))
        .unwrap()
        .flatten()
        .map(|e| e.path().join(name))
        .filter(|p| p.is_file())
        .map(|p| {
            let good = std::fs::read(&p).unwrap();
            (p, good)
        })
        .collect();
    assert!(!files.is_empty(), "no {name} in the {stage} stage's cache entries");
    files
}

/// Where the demo's load, by the steps file's swings and step ends, comes
/// within its clearance (1 m) of a box standing on the ground, `half_m`
/// either way of `xy` and `top_m` high: the step and the swing there (°),
/// if anywhere. The load's footprint (8 x 3 m, at the step's load yaw,
/// which a swing keeps) is centred under the hook; within the clearance of
/// the box in plan and lower than its top plus the clearance is near.
fn load_comes_near(steps_csv: &str, xy: [f64; 2], half_m: f64, top_m: f64) -> Option<(usize, f64)> {
    let clearance_m = 1.0;
    let near = |swing_deg: f64, radius_m: f64, underside_m: f64, yaw_deg: f64| {
        let (x, y) = (radius_m * swing_deg.to_radians().cos(), radius_m * swing_deg.to_radians().sin());
        let (c, s) = (yaw_deg.to_radians().cos(), yaw_deg.to_radians().sin());
        let load: Vec<[f64; 2]> = [(4.0, 1.5), (-4.0, 1.5), (-4.0, -1.5), (4.0, -1.5)]
            .iter()
            .map(|(u, v)| [x + u * c - v * s, y + u * s + v * c])
            .collect();
        let square: Vec<[f64; 2]> = [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)]
            .iter()
            .map(|(u, v)| [xy[0] + u * half_m, xy[1] + v * half_m])
            .collect();
        liftplan_core::obb::footprint_near_area(&load, &square, clearance_m) && underside_m < top_m + clearance_m
    };
    let rows: Vec<Vec<f64>> =
        steps_csv.lines().skip(1).map(|l| l.split(',').map(|v| v.parse().unwrap_or(f64::NAN)).collect()).collect();
    let (swing, yaw, radius, height) = (4, 7, 8, 9);
    let mut from_deg = rows.first()?[swing];
    for (k, r) in rows.iter().enumerate() {
        // A swing keeps the radius, the height and the load's yaw: its
        // whole arc, 0.5° apart.
        let n = ((r[swing] - from_deg).abs() / 0.5).ceil().max(1.0) as usize;
        let at = |i: usize| from_deg + (r[swing] - from_deg) * i as f64 / n as f64;
        if let Some(i) = (0..=n).find(|i| near(at(*i), r[radius], r[height], r[yaw])) {
            return Some((k + 1, at(i)));
        }
        from_deg = r[swing];
    }
    None
}

/// The hook block's mass (t) of a built-in crane.
fn builtin_hook_block_t(name: &str) -> f64 {
    liftplan_core::crane::builtin(name).unwrap().hook.mass_kg / 1000.0
}

/// Writes `toml` as the demo project's file in `dir` and runs the project
/// to its PDF: the text of the cover and of the whole PDF, each on one line.
fn planned_with(dir: &std::path::Path, toml: &str) -> (String, String) {
    std::fs::write(dir.join("liftplan.toml"), toml).unwrap();
    let r = run_json(dir);
    assert_eq!(stage(&r, "docs")["status"], "ran", "{r}");
    let doc = lopdf::Document::load(dir.join("out").join("V-101.pdf")).unwrap();
    let pages: Vec<u32> = doc.get_pages().keys().copied().collect();
    (cover_text(&doc), doc.extract_text(&pages).unwrap().replace('\n', " "))
}

/// The text of a PDF's cover on one line, with the pages its summary and
/// its site overview ran on to where the cover had no room for them.
fn cover_text(doc: &lopdf::Document) -> String {
    let pages: Vec<u32> = doc.get_pages().keys().copied().collect();
    let one_line = |p: &[u32]| doc.extract_text(p).unwrap().replace('\n', " ");
    let mut cover = one_line(&pages[..1]);
    // The summary's rows and the overview may run on to the next pages.
    for &p in &pages[1..] {
        let next = one_line(&[p]);
        if !(next.contains("Summary (continued from the cover)")
            || next.contains("Site overview (continued from the cover)"))
        {
            break;
        }
        cover = format!("{cover} {next}");
    }
    cover
}

/// Writes `toml` as the demo project's file in `dir` and runs the project,
/// which must fail (`what` says what a success would mean): what it said.
fn refused_with(dir: &std::path::Path, toml: &str, what: &str) -> String {
    std::fs::write(dir.join("liftplan.toml"), toml).unwrap();
    let o = liftplan(&["run", dir.to_str().unwrap(), "-q"]);
    let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(!o.status.success(), "{what}:\n{stderr}");
    stderr
}

/// `line` with every date written as `YYYY-MM-DD` replaced by `DATE`.
fn without_dates(line: &str) -> String {
    let shape = b"dddd-dd-dd";
    let bytes = line.as_bytes();
    let mut out = String::new();
    let mut k = 0;
    while k < bytes.len() {
        let is_date = bytes.len() - k >= shape.len()
            && shape.iter().zip(&bytes[k..]).all(|(s, b)| if *s == b'd' { b.is_ascii_digit() } else { s == b });
        if is_date {
            out.push_str("DATE");
            k += shape.len();
        } else {
            let c = line[k..].chars().next().unwrap_or_default();
            out.push(c);
            k += c.len_utf8().max(1);
        }
    }
    out
}

/// A JSON document with its timings (keys ending `_ms`, `seconds`) taken out.
fn without_timings(v: &serde_json::Value) -> serde_json::Value {
    match v {
        serde_json::Value::Object(m) => m
            .iter()
            .filter(|(k, _)| !(k.ends_with("_ms") || k.as_str() == "seconds"))
            .map(|(k, v)| (k.clone(), without_timings(v)))
            .collect(),
        serde_json::Value::Array(a) => a.iter().map(without_timings).collect(),
        other => other.clone(),
    }
}

#[test]
fn demo_outputs_depend_on_neither_the_thread_count_nor_the_folder_name() {
    // Same inputs and seed give the same outputs, bit for bit, however many
    // threads run them and however the project folder is named; only timings
    // may differ.
    assert_eq!(without_dates("— issued 2026-12-02 — 2026-1-2"), "— issued DATE — 2026-1-2");
    let tmp = tempfile::tempdir().unwrap();
    let run = |threads: &str| {
        // One run names the project folder by a relative path, the other by
        // an absolute one: the outputs name input files relative to it.
        let cwd = tmp.path().join(format!("threads-{threads}"));
        std::fs::create_dir(&cwd).unwrap();
        let dir = cwd.join("demo");
        let given = if threads == "1" { "demo".to_string() } else { dir.display().to_string() };
        let o = std::process::Command::new(crate::util::bin())
            .args(["demo", &given, "-q"])
            .current_dir(&cwd)
            .env("RAYON_NUM_THREADS", threads)
            .output()
            .unwrap();
        assert!(o.status.success(), "demo on {threads} threads failed:\n{}", String::from_utf8_lossy(&o.stderr));
        dir.join("out")
    };
    let (one, three) = (run("1"), run("3"));
    // Every file under out/, the plans kept by revision among them.
    let mut names: Vec<String> = Vec::new();
    let mut folders = vec![one.clone()];
    while let Some(folder) = folders.pop() {
        for e in std::fs::read_dir(&folder).unwrap() {
            let path = e.unwrap().path();
            if path.is_dir() {
                folders.push(path);
            } else {
                names.push(path.strip_prefix(&one).unwrap().to_string_lossy().into_owned());
            }
        }
    }
    names.sort();
    assert!(names.len() >= 15, "{names:?}");
    assert!(names.iter().any(|n| n.starts_with("revisions/V-101/") && n.ends_with(".plan.json")), "{names:?}");
    for name in &names {
        let (a, b) = (std::fs::read(one.join(name)).unwrap(), std::fs::read(three.join(name)).unwrap());
        if name == ".manifest.json" {
            // Hashes of the outputs; those of files with timings differ.
            let parse =
                |bytes: &[u8]| -> std::collections::BTreeMap<String, String> { serde_json::from_slice(bytes).unwrap() };
            let (ma, mb) = (parse(&a), parse(&b));
            assert_eq!(ma.keys().collect::<Vec<_>>(), mb.keys().collect::<Vec<_>>(), "{name}");
            for (file, hash) in &ma {
                if !(file.ends_with(".json") || file.ends_with(".pdf")) {
                    assert_eq!(hash, &mb[file], "{name}: {file}");
                }
            }
        } else if name.ends_with(".json") {
            let parse = |bytes: &[u8]| without_timings(&serde_json::from_slice(bytes).unwrap());
            assert_eq!(parse(&a), parse(&b), "{name} differs beyond its timings");
        } else if name.ends_with(".pdf") {
            // The inputs page gives the depth map's build time ("... (40 ms on
            // cpu)"), and the two runs may fall on either side of midnight.
            let text = |path: &std::path::Path| {
                let doc = lopdf::Document::load(path).unwrap();
                let pages: Vec<u32> = doc.get_pages().keys().copied().collect();
                let text = doc.extract_text(&pages).unwrap();
                text.lines().filter(|l| !l.contains(" ms on ")).map(without_dates).collect::<Vec<_>>()
            };
            assert_eq!(text(&one.join(name)), text(&three.join(name)), "{name}'s text differs beyond its timings");
        } else {
            assert!(a == b, "{name} differs between one and three threads");
        }
    }
}

/// The demo with its site in survey coordinates (a UTM easting and
/// northing, heights 102 m above the datum: the surveyed station, the
/// plant's placement and the lift all given there) runs end to end as the
/// demo does: every scan registers (ICP once lost its rotations 100 km from
/// the origin), the lift plans and validates at the utilisation the set
/// radius gives, and the PDF is written.
#[test]
fn the_demo_in_survey_coordinates_runs_end_to_end() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("utm");
    let out = liftplan(&["demo", dir.to_str().unwrap(), "--survey-coordinates", "-q"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let toml = std::fs::read_to_string(dir.join("liftplan.toml")).unwrap();
    assert!(toml.contains("position_m = [512345.000, 5412345.000], ground_z_m = 102.000"), "{toml}");
    let reg: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("out").join("registration.json")).unwrap()).unwrap();
    let scans = reg["scans"].as_array().unwrap();
    assert!(scans.len() == 4 && scans.iter().all(|s| s["registered"] == true), "{reg}");
    let plan: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("out").join("plan.json")).unwrap()).unwrap();
    let lift = &plan["lifts"][0];
    assert_eq!(lift["validator"]["ok"], true, "{lift}");
    let util = lift["summary"]["max_utilisation_pct"].as_f64().unwrap();
    assert!((util - 53.6).abs() < 0.5, "{util}");
    assert!(dir.join("out").join("V-101.pdf").is_file());
}

/// The demo made with the built-in tower crane: planned, validated, and its
/// PDF speaks of a jib, a trolley and a foundation, never of a boom,
/// outriggers or a carrier it does not have.
#[test]
fn the_tower_crane_demo_runs_and_its_pdf_names_a_tower_cranes_parts() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("tower");
    let out = liftplan(&["demo", dir.to_str().unwrap(), "--tower", "-q"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    // The project file's words on the mobile crane's rope went with it.
    let toml = std::fs::read_to_string(dir.join("liftplan.toml")).unwrap();
    assert!(!toml.contains("longest_rope_m") && !toml.contains("boom head"), "{toml}");
    let plan: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("out").join("plan.json")).unwrap()).unwrap();
    let lift = &plan["lifts"][0];
    assert_eq!(lift["validator"]["ok"], true, "{lift}");
    assert_eq!(lift["crane_model"], "Hammerhead tower crane, 60 m jib (approx.)", "{lift}");
    let doc = lopdf::Document::load(dir.join("out").join("V-101.pdf")).unwrap();
    let pages: Vec<u32> = doc.get_pages().keys().copied().collect();
    let text = doc.extract_text(&pages).unwrap().replace('\n', " ");
    for said in [
        "jib toward grid bearing",
        "trolley",
        "foundation, mast and its ties",
        "one column (any boom or jib)",
        "scanned ground points within 3 m of its mast",
        "crane: 'tower-hh-60', built into liftplan",
    ] {
        assert!(text.contains(said), "{said:?} not in the PDF:\n{text}");
    }
    let text = text.replace("any boom or jib", "");
    for unsaid in ["outrigger", "carrier", "superstructure", "boom", "luff"] {
        assert!(!text.to_lowercase().contains(unsaid), "{unsaid:?} in a tower crane's PDF:\n{text}");
    }
    // The wind is not worked out for a tower crane, and the cover says so,
    // with what its manual's rule needs: the vessel's 8 x 3 m side on its
    // 12 t, 0.5 t of slings and the hook block.
    let cover = cover_text(&doc);
    let hook_t = 12.5 + builtin_hook_block_t("tower-hh-60");
    assert!(
        cover.contains(&format!("Wind NOT WORKED OUT for a tower crane: its manual's in-service wind rules govern, for the crane and for a load that catches much wind for its mass; this load's largest side, 8.00 x 3.00 m (24.0 m²), on {hook_t:.2} t of hook load: CHECK the wind speed it may be lifted in; the plan keeps its clearance with the load hanging plumb")),
        "{cover}"
    );
    assert!(cover.contains("the wind speed the load may be lifted in (the tower crane's manual: Wind)"), "{cover}");

    // The all-terrain crane on the tower crane's chart of one column: the
    // chart does not say which boom it is for, so the cover asks.
    let toml_path = dir.join("liftplan.toml");
    let t = std::fs::read_to_string(&toml_path).unwrap();
    let start = t.find("crane = {").unwrap();
    let end = start + t[start..].find('\n').unwrap();
    let mobile = r#"crane = { model = "ac-700", position_m = [0.0, 0.0], ground_z_m = 0.0, heading_deg = 0.0, boom_m = 40.0, falls = 6, chart_config = "Jib 60 m" }"#;
    std::fs::write(&toml_path, format!("{}{mobile}{}", &t[..start], &t[end..])).unwrap();
    let o = liftplan(&["run", dir.to_str().unwrap(), "-q"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let cover = cover_text(&lopdf::Document::load(dir.join("out").join("V-101.pdf")).unwrap());
    assert!(cover.contains("CHECK FIRST that the chart of one column is the 40.0 m boom's"), "{cover}");
}

/// Scans that do not register and are left out as the project asks are
/// named on the sign-off page: what only they saw is missing from the plan.
/// (The demo's scans taken at a coarse step do not register.)
#[test]
fn scans_left_out_unregistered_are_named_on_the_sign_off_page() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("coarse");
    let d = dir.to_str().unwrap();
    let o = liftplan(&["demo", d, "--scan-step", "0.5", "-q"]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && stderr.contains("does not register"), "{stderr}");
    let toml_path = dir.join("liftplan.toml");
    let t = std::fs::read_to_string(&toml_path).unwrap();
    std::fs::write(&toml_path, t.replace("register = \"auto\"", "register = \"auto\"\non_unregistered = \"exclude\""))
        .unwrap();
    // And the survey's report among the scans: passed by as holding no
    // scan (it failed the run), and named, as it may be a failed export.
    std::fs::write(dir.join("scans").join("readme.txt"), "Survey of the demo site\nScanner: simulated\n").unwrap();
    // And a scan in the scanner's own format, not read: said in the run
    // even when quiet, and on the cover and sign-off page.
    std::fs::write(dir.join("scans").join("scan-5.fls"), b"FARO").unwrap();
    let o = liftplan(&["run", d, "-q"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        stderr.contains(
            "warning: not read: scans/scan-5.fls (FARO Scene's own format, not read: export it as E57, PTX or LAS)"
        ),
        "{stderr}"
    );
    let doc = lopdf::Document::load(dir.join("out").join("V-101.pdf")).unwrap();
    let pages: Vec<u32> = doc.get_pages().keys().copied().collect();
    let text = doc.extract_text(&pages).unwrap().replace('\n', " ");
    assert!(text.contains("3 of the 4 scans DID NOT REGISTER AND WERE LEFT OUT"), "{text}");
    assert!(text.contains("scan-2, scan-3, scan-4"), "{text}");
    assert!(
        text.contains("3 scans left out unregistered; the file among the scans passed by as holding no scan: is it none?; the file in the input folders not read: is it no scan, model or chart of this lift?; ground under the load that no scan saw"),
        "{text}"
    );
    assert!(
        text.contains("FILES AMONG THE SCANS WERE PASSED BY AS HOLDING NO SCAN: scans/readme.txt (holds no scan: no line of numbers x y z, or empty)"),
        "{text}"
    );
    assert!(
        text.contains("FILES IN THE INPUT FOLDERS WERE NOT READ: scans/scan-5.fls (FARO Scene's own format, not read: export it as E57, PTX or LAS). Whatever only a scan or plant model among them shows is not an obstacle in this plan"),
        "{text}"
    );
}

/// A scanner that does not level itself (`leveled = false`) and a reference
/// scan with no walls, columns or tanks in it (the ground alone, as an open
/// yard would give): the reference is levelled by its ground, so the site
/// frame every height rests on is not confirmed level, and the PDF's cover
/// and sign-off page say so. The lift is still planned.
#[test]
fn a_site_frame_levelled_by_the_ground_is_to_be_checked_on_the_cover_and_sign_off_page() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("open-yard");
    let d = dir.to_str().unwrap();
    // The coarse demo's other scans do not register; only its files are wanted.
    let o = liftplan(&["demo", d, "--scan-step", "0.5", "-q"]);
    assert!(dir.join("liftplan.toml").is_file(), "{}", String::from_utf8_lossy(&o.stderr));
    let scans = dir.join("scans");
    for k in 2..=4 {
        std::fs::remove_file(scans.join(format!("scan-{k}.laz"))).unwrap();
    }
    let reference = scans.join("scan-1.laz");
    let info = liftplan_scans::read::list_scans(&reference).unwrap().remove(0);
    let whole = liftplan_scans::read::read_all(&info).unwrap();
    // The scanner stood 1.604 m above the ground (its station file).
    let mut ground = liftplan_core::cloud::PointCloud::default();
    for (p, i) in whole.xyz.iter().zip(&whole.intensity) {
        if p[2] < -1.55 {
            ground.xyz.push(*p);
            ground.intensity.push(*i);
        }
    }
    assert!(ground.len() > 10_000 && ground.len() < whole.len(), "{} of {}", ground.len(), whole.len());
    crate::util::write_scan(&reference, &ground);
    let toml_path = dir.join("liftplan.toml");
    let t = std::fs::read_to_string(&toml_path).unwrap();
    std::fs::write(&toml_path, format!("{t}\n[scans.registration]\nleveled = false\n")).unwrap();
    let o = liftplan(&["run", d, "-q"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let registration = std::fs::read_to_string(dir.join("out").join("registration.json")).unwrap();
    assert!(registration.contains("levelled by its ground"), "{registration}");
    let doc = lopdf::Document::load(dir.join("out").join("V-101.pdf")).unwrap();
    let cover = cover_text(&doc);
    assert!(cover.contains("the site's level (the scanner did not level itself)"), "{cover}");
    let pages: Vec<u32> = doc.get_pages().keys().copied().collect();
    let text = doc.extract_text(&pages).unwrap().replace('\n', " ");
    assert!(text.contains("THE SITE'S LEVEL IS NOT CONFIRMED"), "{text}");
    assert!(text.contains("is levelled by its ground"), "{text}");
    // The same scan from a scanner that levels itself: nothing to check.
    std::fs::write(&toml_path, &t).unwrap();
    let o = liftplan(&["run", d, "-q"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let doc = lopdf::Document::load(dir.join("out").join("V-101.pdf")).unwrap();
    let pages: Vec<u32> = doc.get_pages().keys().copied().collect();
    let text = doc.extract_text(&pages).unwrap().replace('\n', " ");
    assert!(!text.contains("the site's level") && !text.contains("SITE'S LEVEL"), "{text}");
}

/// A wire the scans caught that no `[[power_line]]` gives: strung 14 m up
/// behind the crane, out of the lift's way, 40 m long between poles the
/// scans did not see, its points put in the reference scan (in that
/// scanner's frame). The demo itself names none; with the wire, the plan
/// names it in the run's output, the cover asks what it is first, and the
/// sign-off page says where it runs.
#[test]
fn a_wire_in_the_scans_that_no_power_line_gives_is_asked_about() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("demo");
    let r = crate::util::ok(&["demo", dir.to_str().unwrap()]);
    let said = format!("{}{}", String::from_utf8_lossy(&r.stdout), String::from_utf8_lossy(&r.stderr));
    assert!(said.contains("plan ran"), "{said}");
    assert!(!said.contains("NOT A GIVEN POWER LINE"), "{said}");
    let reg: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("out").join("registration.json")).unwrap()).unwrap();
    let reference = reg["scans"].as_array().unwrap().iter().find(|s| s["name"] == "scan-1").unwrap();
    let pose: Vec<Vec<f64>> = serde_json::from_value(reference["pose"].clone()).unwrap();
    // Site to scanner: the pose's rotation transposed, after its shift.
    let to_scan = |p: [f64; 3]| {
        let d = [0, 1, 2].map(|k| p[k] - pose[k][3]);
        [0, 1, 2].map(|c| (0..3).map(|k| pose[k][c] * d[k]).sum::<f64>())
    };
    let path = dir.join("scans").join("scan-1.laz");
    let info = liftplan_scans::read::list_scans(&path).unwrap().remove(0);
    let mut cloud = liftplan_scans::read::read_all(&info).unwrap();
    let n = cloud.len();
    for k in 0..=800 {
        let y = -20.0 + k as f64 * 0.05;
        let sag = 0.5 * (1.0 - (y / 20.0).powi(2));
        cloud.xyz.push(to_scan([-25.0, y, 14.0 - sag]));
    }
    let added = cloud.len() - n;
    cloud.intensity.resize(cloud.len(), 100);
    if !cloud.rgb.is_empty() {
        cloud.rgb.resize(cloud.len(), [0; 3]);
    }
    if !cloud.class.is_empty() {
        cloud.class.resize(cloud.len(), 1);
    }
    if !cloud.scan.is_empty() {
        cloud.scan.resize(cloud.len(), 0);
    }
    crate::util::write_scan(&path, &cloud);
    let o = crate::util::ok(&["run", dir.to_str().unwrap()]);
    let said = format!("{}{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr));
    assert!(said.contains("lift V-101: NOT A GIVEN POWER LINE: 40 m of line-like scan points ("), "{added}: {said}");
    let plan: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("out").join("plan.json")).unwrap()).unwrap();
    let runs = plan["lifts"][0]["summary"]["line_like"].as_array().unwrap_or_else(|| panic!("{plan}"));
    assert_eq!(runs.len(), 1, "{plan}");
    // Its ends where the wire's are (the last few centimetres of a run may
    // thin out of it).
    let end = |key: &str| -> [f64; 3] { serde_json::from_value(runs[0][key].clone()).unwrap() };
    let (from, to) = (end("from_m"), end("to_m"));
    assert!((from[0] + 25.0).abs() < 0.05 && (to[0] + 25.0).abs() < 0.05, "{from:?} {to:?}");
    assert!((from[1].min(to[1]) + 20.0).abs() < 0.3 && (from[1].max(to[1]) - 20.0).abs() < 0.3, "{from:?} {to:?}");
    let doc = lopdf::Document::load(dir.join("out").join("V-101.pdf")).unwrap();
    let cover = cover_text(&doc);
    assert!(
        cover.contains("what the line-like scan points near the crane are: an overhead line no one gave?"),
        "{cover}"
    );
    // The overview draws it.
    assert!(cover.contains(", line-like scan points no power line given runs along in cyan"), "{cover}");
    let pages: Vec<u32> = doc.get_pages().keys().copied().collect();
    let text = doc.extract_text(&pages).unwrap().replace('\n', " ");
    assert!(text.contains("NOT A GIVEN POWER LINE: 40 m of line-like scan points"), "{text}");
    assert!(text.contains("CHECK WHAT IT IS (an overhead conductor, a guy wire, a cable)"), "{text}");
    assert!(text.contains("or set [plan] found_lines_approach_m to keep off every such run"), "{text}");
    // Kept off as a line of unknown voltage where the project asks: planned
    // and validated round it, and said so.
    let toml_path = dir.join("liftplan.toml");
    let project = std::fs::read_to_string(&toml_path).unwrap();
    assert!(!project.contains("[plan]"), "{project}");
    std::fs::write(&toml_path, format!("{project}\n[plan]\nfound_lines_approach_m = 6.1\n")).unwrap();
    let o = crate::util::ok(&["run", dir.to_str().unwrap()]);
    let said = format!("{}{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr));
    assert!(
        said.contains("the plan keeps every part of the crane, its rope and its load 6.10 m off it, as off a power line of unknown voltage ([plan] found_lines_approach_m)"),
        "{said}"
    );
    let plan: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("out").join("plan.json")).unwrap()).unwrap();
    assert_eq!(plan["lifts"][0]["summary"]["line_like_kept_off_m"], 6.1, "{plan}");
    assert_eq!(plan["lifts"][0]["validator"]["ok"], true, "{plan}");
}

/// Nine scanners over three quarters of the demo site at 0.4 degrees (the
/// registration fixture `a_post_a_far_scanner_stepped_past_does_not_refuse_a_right_alignment`):
/// `s7` is merged with a warning (another scanner's rays passed both sides
/// of the lamp post it sees). The whole run carries that warning from the
/// scans stage's registration.json to the PDF: the cover's CHECK FIRST
/// names `s7`, and the inputs page and the sign-off page give the warning.
/// (As first built, the cover sent the reader to the sign-off page, which
/// said nothing of it.)
#[test]
fn a_scan_merged_with_a_warning_is_named_on_the_cover_and_sign_off_page() {
    use liftplan_fixtures::{demo, scanner, scene};
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("nine");
    let options = demo::DemoOptions { scan_step_deg: 0.5, ..Default::default() };
    demo::write_project(&dir, &options).unwrap();
    let scans = dir.join("scans");
    for k in 1..=4 {
        std::fs::remove_file(scans.join(format!("scan-{k}.laz"))).unwrap();
    }
    let site = scene::demo_site(0);
    let settings = scanner::ScanSettings { az_step_deg: 0.4, el_step_deg: 0.4, ..Default::default() };
    let stations = scanner::ellipse_stations(&site, 9, 0.75);
    for st in &stations {
        liftplan_scans::write::write_las(
            &scans.join(format!("{}.laz", st.name)),
            &scanner::simulate(&site, st, &settings),
        )
        .unwrap();
    }
    let p0 = stations[0].pose();
    std::fs::write(
        scans.join("stations.toml"),
        format!(
            "[[station]]\nscan = \"s0\"\nx_m = {:.4}\ny_m = {:.4}\nz_m = {:.4}\nyaw_deg = {:.6}\n",
            p0.translation.x,
            p0.translation.y,
            p0.translation.z,
            p0.rotation.euler_angles().2.to_degrees()
        ),
    )
    .unwrap();
    let o = liftplan(&["run", dir.to_str().unwrap(), "-q"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let registration: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("out").join("registration.json")).unwrap()).unwrap();
    let warned: Vec<&str> = registration["scans"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|s| s["registered"] == true && s["warning"].is_string())
        .map(|s| s["name"].as_str().unwrap())
        .collect();
    assert_eq!(warned, ["s7"], "{registration}");
    let doc = lopdf::Document::load(dir.join("out").join("V-101.pdf")).unwrap();
    let check = "what registration warned of one scan merged (s7; inputs page)";
    let cover = cover_text(&doc);
    assert!(cover.contains(check), "{cover}");
    let pages: Vec<u32> = doc.get_pages().keys().copied().collect();
    let text = doc.extract_text(&pages).unwrap().replace('\n', " ");
    // The inputs page's line under s7's, then the sign-off page's paragraph.
    assert_eq!(text.matches("scan 's7' was placed though").count(), 2, "{text}");
    let sign_off = &text[text.find("Review and sign-off").unwrap()..];
    assert!(
        sign_off.contains("SCAN 's7' WAS MERGED WITH A WARNING from registration: scan 's7' was placed though")
            && sign_off.contains("CHECK WHAT THE WARNING ASKS before signing"),
        "{sign_off}"
    );
}
