//! The binary's glue for each stage: which project files and settings it reads,
//! and how its crate is called. Stage crates know nothing of the project, the
//! cache or the CLI; everything project-shaped is resolved here.

use crate::pipeline::{Ctx, Produced, StageDef};
use crate::project::Project;
use anyhow::Result;
use liftplan_plan::resumed::Agreement;
use std::path::PathBuf;

pub const SCAN_EXTS: &[&str] = &["las", "laz", "ply", "e57", "ptx", "pts", "xyz", "txt", "asc", "csv"];

/// The most files not read that are named one by one
/// ([`inputs_not_read`]); past it, how many more there are.
const NOT_READ_NAMED: usize = 10;

/// The files in the scans, plant and charts folders that no stage reads,
/// each as "folder/name (why)", sorted, the first [`NOT_READ_NAMED`] named
/// and the rest counted: a scan in a scanner's own format (FARO's `.fls`),
/// a plant model in a CAD tool's (`.dwg`, `.nwd`), a load chart as a PDF or
/// a folder of scans was passed over without a word, and a plan made
/// without what it holds. The run warns of them, and the plan's cover and
/// sign-off page name them.
pub fn inputs_not_read(p: &Project) -> Vec<String> {
    let mut plant_exts: Vec<&str> = liftplan_plant::EXTS.to_vec();
    plant_exts.extend(PLANT_ATTRIBUTE_EXTS);
    let folders = [
        (p.path(&p.raw.paths.scans), SCAN_EXTS),
        (p.path(&p.raw.paths.plant), &plant_exts[..]),
        (p.path(&p.raw.paths.charts), liftplan_charts::EXTS),
    ];
    let read_by_name: Vec<PathBuf> = [Some(crate::project::FILE.into()), p.raw.scans.stations.clone()]
        .into_iter()
        .flatten()
        .map(|f: PathBuf| p.path(&f))
        .collect();
    let mut not_read = std::collections::BTreeMap::new();
    for (folder, _) in &folders {
        // Each folder once, with what every stage reading it takes.
        let read: Vec<&str> =
            folders.iter().filter(|(f, _)| f == folder).flat_map(|(_, exts)| exts.iter().copied()).collect();
        let Ok(entries) = std::fs::read_dir(folder) else { continue };
        for e in entries.flatten() {
            let path = e.path();
            let name = e.file_name().to_string_lossy().into_owned();
            if crate::project::is_hidden_or_office_owner(&name) || read_by_name.contains(&path) {
                continue;
            }
            // A folder's files are not read (a delivery of scans in one
            // folder a day, say), unless it is another input folder, the
            // cranes' or the outputs'.
            if path.is_dir() {
                let known = folders.iter().any(|(f, _)| *f == path)
                    || path == p.out_dir()
                    || path == p.path(&p.raw.paths.cranes);
                if !known {
                    let shown = liftplan_core::location::shown(&path, Some(&p.dir));
                    not_read.insert(
                        shown.clone(),
                        format!("{shown}/ (a folder: the files in it are not read; put them beside it)"),
                    );
                }
                continue;
            }
            if !path.is_file() {
                continue;
            }
            let ext = path.extension().and_then(|x| x.to_str()).unwrap_or("").to_ascii_lowercase();
            if read.contains(&ext.as_str()) {
                continue;
            }
            let shown = liftplan_core::location::shown(&path, Some(&p.dir));
            not_read.insert(shown.clone(), format!("{shown} ({})", why_not_read(&ext, &read)));
        }
    }
    let mut said: Vec<String> = not_read.into_values().collect();
    if said.len() > NOT_READ_NAMED {
        let more = said.len() - NOT_READ_NAMED;
        said.truncate(NOT_READ_NAMED);
        said.push(match more {
            1 => "and 1 more file".to_string(),
            n => format!("and {n} more files"),
        });
    }
    said
}

/// An item of [`inputs_not_read`] as a warning line says it: "not read:
/// scans/a.fls (...)", or "and 2 more files not read".
pub fn not_read_said(item: &str) -> String {
    match item.starts_with("and ") {
        true => format!("{item} not read"),
        false => format!("not read: {item}"),
    }
}

/// Why a file of extension `ext` in a folder whose stages read `read` is
/// not read, and what to do: the formats' owners, where known.
fn why_not_read(ext: &str, read: &[&str]) -> String {
    let export = |whose: &str, to: &str| format!("{whose} own format, not read: export it as {to}");
    let scan = "E57, PTX or LAS";
    let model = "RVM, glTF (.glb), OBJ, PLY or STL";
    match ext {
        "fls" | "lsproj" | "fws" => export("FARO Scene's", scan),
        "zfs" | "zfprj" => export("Z+F's", scan),
        "rxp" | "rdbx" | "rdb" | "rsp" => export("RIEGL's", scan),
        "tzf" | "tdx" | "rwcx" | "rwp" => export("Trimble's", scan),
        "bk2" | "blk" | "imp" | "lgs" => export("Leica's", scan),
        "rcp" | "rcs" => export("Autodesk ReCap's", scan),
        "pod" => export("Bentley Pointools'", scan),
        "dwg" | "dxf" => export("AutoCAD's", model),
        "nwd" | "nwc" | "nwf" => export("Navisworks'", model),
        "dgn" => export("MicroStation's", model),
        "rvt" | "rfa" => export("Revit's", model),
        "rev" => export("AVEVA Review's", model),
        "skp" => export("SketchUp's", model),
        "step" | "stp" | "iges" | "igs" | "fbx" | "3ds" | "dae" | "ifczip" | "ifcxml" => {
            format!("not read: export the model as {model}")
        }
        "pdf" | "png" | "jpg" | "jpeg" | "tif" | "tiff" if read.contains(&"xlsx") => {
            "a load chart as a document or picture is not read: type or paste it into a workbook (.xlsx) and check it \
             cell by cell against the chart"
                .to_string()
        }
        "csv" | "txt" if read.contains(&"xlsx") => {
            "a load chart as text is not read: open it in Excel or LibreOffice and save it as .xlsx".to_string()
        }
        "numbers" => "Apple Numbers' own format, not read: export it as .xlsx".to_string(),
        "zip" | "7z" | "rar" | "tar" | "gz" | "tgz" => {
            "an archive, not read: unpack its files into this folder".to_string()
        }
        "toml" if read.contains(&"e57") => "a stations file is read only where [scans] stations names it".to_string(),
        "" => format!("a file without an extension is not read; this folder's files read are .{}", read.join(", .")),
        _ => format!("no .{ext} file is read; this folder's files read are .{}", read.join(", .")),
    }
}

pub fn scans() -> StageDef {
    StageDef {
        name: liftplan_scans::NAME,
        version: liftplan_scans::VERSION,
        code: env!("LIFTPLAN_CODE_SCANS"),
        about: "read, register, thin and ground-classify the survey scans",
        inputs: |p: &Project| {
            let mut files = p.files(&p.raw.paths.scans, SCAN_EXTS)?;
            if let Some(st) = &p.raw.scans.stations {
                files.push(p.path(st));
            }
            Ok(files)
        },
        settings: |p: &Project| serde_json::json!({ "scans": p.raw.scans, "seed": p.raw.project.seed }),
        reads: &[],
        applicable: |p, files, _| files.iter().any(|f| !p.raw.scans.stations.as_ref().is_some_and(|s| p.path(s) == *f)),
        run: run_scans,
    }
}

fn run_scans(ctx: &Ctx) -> Result<Produced> {
    let p = ctx.project;
    let mut s = p.raw.scans.clone();
    let station_file = s.stations.as_ref().map(|st| p.path(st));
    s.stations = station_file.clone();
    let scan_files: Vec<PathBuf> = ctx.inputs.iter().filter(|f| Some(*f) != station_file.as_ref()).cloned().collect();
    let report = ctx.report("scans");
    let memo = ctx.memo.join("registration.memo");
    let summary = liftplan_scans::run(
        &scan_files,
        &s,
        &liftplan_scans::RunOptions {
            seed: p.raw.project.seed,
            progress: &report,
            root: Some(&p.dir),
            memo: Some(liftplan_scans::MemoFile { path: &memo, build: ctx.code, reuse: !ctx.forced }),
        },
        ctx.out,
    )?;
    let mut outputs = vec!["site.laz".to_string(), "registration.json".into(), "scans.png".into()];
    if ctx.out.join("ground.asc").exists() {
        outputs.push("ground.asc".into());
    }
    let mut lines = summary.lines();
    lines.push(format!(
        "site cloud: {} points ({}), {} ground",
        summary.points_out, summary.subsample, summary.ground_points
    ));
    Ok(Produced { outputs, summary: serde_json::to_value(&summary)?, lines })
}

/// The extensions of the files the plant stage takes as an RVM file's
/// attributes, not as models.
const PLANT_ATTRIBUTE_EXTS: [&str; 2] = ["att", "txt"];

fn is_plant_attributes(f: &std::path::Path) -> bool {
    f.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| PLANT_ATTRIBUTE_EXTS.iter().any(|a| e.eq_ignore_ascii_case(a)))
}

pub fn plant() -> StageDef {
    StageDef {
        name: liftplan_plant::NAME,
        version: liftplan_plant::VERSION,
        code: env!("LIFTPLAN_CODE_PLANT"),
        about: "tessellate PDMS/E3D RVM exports and read BIM meshes into one plant mesh",
        inputs: |p: &Project| {
            // Attribute files are read beside their RVM files (.att, or a
            // .txt opening as one), and are inputs so that a change reruns.
            let mut exts: Vec<&str> = liftplan_plant::EXTS.to_vec();
            exts.extend(PLANT_ATTRIBUTE_EXTS);
            p.files(&p.raw.paths.plant, &exts)
        },
        settings: |p: &Project| serde_json::json!({ "plant": p.raw.plant }),
        reads: &[],
        applicable: |_, files, _| files.iter().any(|f| !is_plant_attributes(f)),
        run: run_plant,
    }
}

fn run_plant(ctx: &Ctx) -> Result<Produced> {
    let files: Vec<PathBuf> = ctx.inputs.iter().filter(|f| !is_plant_attributes(f)).cloned().collect();
    let report = ctx.report("plant");
    let summary = liftplan_plant::run(&files, &ctx.project.raw.plant, ctx.out, Some(&ctx.project.dir), &report)?;
    Ok(Produced {
        outputs: vec!["plant.mesh".into(), "plant.ply".into(), "plant.json".into()],
        summary: serde_json::to_value(&summary)?,
        lines: summary.lines(),
    })
}

pub fn charts() -> StageDef {
    StageDef {
        name: liftplan_charts::NAME,
        version: liftplan_charts::VERSION,
        code: env!("LIFTPLAN_CODE_CHARTS"),
        about: "read load charts into a capacity table and check each lift against it",
        inputs: |p: &Project| {
            let mut files = p.files(&p.raw.paths.charts, liftplan_charts::EXTS)?;
            files.extend(p.crane_files());
            Ok(files)
        },
        // Lifts are part of the settings: lifts.json depends on their loads.
        settings: |p: &Project| serde_json::json!({ "charts": p.raw.charts, "lifts": p.raw.lift }),
        reads: &[],
        applicable: |p, files, _| files.iter().any(|f| !f.starts_with(p.path(&p.raw.paths.cranes))),
        run: run_charts,
    }
}

fn run_charts(ctx: &Ctx) -> Result<Produced> {
    let p = ctx.project;
    let cranes = p.path(&p.raw.paths.cranes);
    let files: Vec<PathBuf> = ctx.inputs.iter().filter(|f| !f.starts_with(&cranes)).cloned().collect();
    let lifts = p.lifts()?;
    let summary = liftplan_charts::run(&files, &p.raw.charts, &lifts, ctx.out, Some(&p.dir))?;
    Ok(Produced {
        outputs: vec!["capacity.csv".into(), "chart.json".into(), "lifts.json".into()],
        summary: serde_json::to_value(&summary)?,
        lines: summary.lines(),
    })
}

/// The lifts' load boxes at pick, cut out of the site cloud (the scanned load
/// must not block its own lift); see `liftplan_plan::load_exclusions`.
fn exclusions(p: &Project) -> Vec<liftplan_core::obb::Obb> {
    p.lifts().map(|l| liftplan_plan::load_exclusions(&l, p.raw.plan.load_cutout_m)).unwrap_or_default()
}

pub fn depthmap() -> StageDef {
    StageDef {
        name: liftplan_depthmap::NAME,
        version: liftplan_depthmap::VERSION,
        code: env!("LIFTPLAN_CODE_DEPTHMAP"),
        about: "rasterise the site cloud and the plant mesh into a multi-level depth map",
        inputs: |_| Ok(vec![]),
        // The load boxes cut out of the cloud depend on the lifts' geometry (not their mass).
        settings: |p: &Project| {
            let cut: Vec<_> = exclusions(p)
                .iter()
                .map(|b| (b.center.coords.as_slice().to_vec(), b.half.as_slice().to_vec(), b.axes.as_slice().to_vec()))
                .collect();
            serde_json::json!({ "depthmap": p.raw.depthmap, "exclude": cut })
        },
        reads: &[("scans", "site.laz"), ("plant", "plant.mesh")],
        applicable: |_, _, up| up.contains_key("scans") || up.contains_key("plant"),
        run: run_depthmap,
    }
}

fn run_depthmap(ctx: &Ctx) -> Result<Produced> {
    let cloud = ctx.upstream_file("scans", "site.laz");
    let mesh = ctx.upstream_file("plant", "plant.mesh");
    let summary = liftplan_depthmap::run(
        cloud.as_deref(),
        mesh.as_deref(),
        &exclusions(ctx.project),
        &ctx.project.raw.depthmap,
        ctx.project.raw.gpu.use_,
        ctx.out,
    )?;
    Ok(Produced {
        outputs: vec!["site.mdm".into(), "depthmap.png".into(), "depthmap.json".into()],
        summary: serde_json::to_value(&summary)?,
        lines: summary.lines(),
    })
}

pub fn plan() -> StageDef {
    StageDef {
        name: liftplan_plan::NAME,
        version: liftplan_plan::VERSION,
        code: env!("LIFTPLAN_CODE_PLAN"),
        about: "plan each lift (MSPGA on the hybrid C-space) and validate it independently",
        inputs: |p: &Project| Ok(p.crane_files()),
        settings: |p: &Project| serde_json::json!({ "plan": p.raw.plan, "lifts": p.raw.lift, "seed": p.raw.project.seed, "obstacles": p.raw.obstacle, "power_lines": p.raw.power_line }),
        reads: &[
            ("depthmap", "site.mdm"),
            ("scans", "site.laz"),
            ("plant", "plant.mesh"),
            // The groups left out of the model, against the lifts' positions.
            ("plant", "plant.json"),
            ("charts", "capacity.csv"),
            // The counterweight each configuration's sheet states, for the
            // outrigger loads.
            ("charts", "chart.json"),
        ],
        applicable: |p, _, up| !p.raw.lift.is_empty() && up.contains_key("depthmap"),
        run: run_plan,
    }
}

/// The charts stage's chart.json, read and checked
/// ([`liftplan_core::chart_json`]); `None` where it wrote none.
fn chart_configs(ctx: &Ctx) -> Result<Option<Vec<liftplan_core::chart_json::ConfigStated>>> {
    ctx.upstream_file("charts", "chart.json")
        .map(|f| liftplan_core::chart_json::read(&f).map_err(anyhow::Error::msg))
        .transpose()
}

fn run_plan(ctx: &Ctx) -> Result<Produced> {
    let p = ctx.project;
    let mut tasks = p.lifts()?;
    // The counterweight each lift's chart configuration's sheet states,
    // where it states one.
    if let Some(configs) = chart_configs(ctx)? {
        for (name, stated) in liftplan_core::chart_json::stated(&configs, |c| &c.counterweight_kg) {
            if let [one] = &stated[..] {
                for t in tasks.iter_mut().filter(|t| t.chart_config == name) {
                    t.chart_sheet_counterweight = Some(one.clone());
                }
            }
        }
        // The wind speed it states, for the load's swing in the wind.
        // (Without a chart no lift is planned, which the plan says first.)
        let chart_wind = liftplan_core::chart_json::stated(&configs, |c| &c.wind_ms);
        for t in &mut tasks {
            let stated = chart_wind.iter().find(|(name, _)| *name == t.chart_config).map_or(&[][..], |(_, s)| &s[..]);
            t.plan_for_wind(stated).map_err(|e| anyhow::anyhow!(e))?;
        }
    }
    let map = ctx.upstream_file("depthmap", "site.mdm").ok_or_else(|| anyhow::anyhow!("no depth map"))?;
    let summary = liftplan_plan::run(
        &tasks,
        &map,
        ctx.upstream_file("plant", "plant.mesh").as_deref(),
        ctx.upstream_file("plant", "plant.json").as_deref(),
        ctx.upstream_file("scans", "site.laz").as_deref(),
        ctx.upstream_file("charts", "capacity.csv").as_deref(),
        &p.raw.obstacle,
        &p.raw.power_line,
        &p.raw.plan,
        p.raw.project.seed,
        ctx.out,
    )?;
    let mut outputs = vec!["plan.json".to_string()];
    for t in &tasks {
        outputs.push(format!("{}.steps.csv", t.id));
        outputs.push(format!("{}.cspace.png", t.id));
    }
    Ok(Produced { outputs, summary: serde_json::to_value(&summary)?, lines: summary.lines() })
}

pub fn docs() -> StageDef {
    StageDef {
        name: liftplan_docs::NAME,
        version: liftplan_docs::VERSION,
        code: env!("LIFTPLAN_CODE_DOCS"),
        about: "render the pictures and the step-by-step lift plan PDF",
        // The plans resumed lifts continue, kept by revision (written once,
        // never changed): the cover says whether resume_from is where each
        // has the load.
        inputs: |p: &Project| Ok(p.crane_files().into_iter().chain(resumed_plan_files(p)).collect()),
        // The GPU setting is part of the key: the GPU twin's pictures agree with the
        // CPU's within a tolerance, not bit for bit.
        // The files in the input folders not read are named on the cover.
        settings: |p: &Project| serde_json::json!({ "docs": p.raw.docs, "lifts": p.raw.lift, "project": p.raw.project.name, "gpu": p.raw.gpu.use_, "obstacles": p.raw.obstacle, "power_lines": p.raw.power_line, "inputs_not_read": inputs_not_read(p) }),
        reads: &[
            ("plan", "*"),
            ("scans", "site.laz"),
            ("scans", "registration.json"),
            ("plant", "plant.mesh"),
            ("charts", "capacity.csv"),
            ("charts", "lifts.json"),
            // The warnings reading each configuration gave, which the
            // sign-off page repeats for the lift's.
            ("charts", "chart.json"),
        ],
        applicable: |_, _, up| up.contains_key("plan"),
        run: run_docs,
    }
}

/// The kept plans (out/revisions/) that the project's resumed lifts name,
/// where kept.
fn resumed_plan_files(p: &Project) -> Vec<std::path::PathBuf> {
    p.raw
        .lift
        .iter()
        .filter_map(|l| {
            let named = l.resumes_plan.as_ref()?;
            liftplan::revisions::kept_plan_file(&p.out_dir(), &l.id, &named.revision)
        })
        .collect()
}

/// For each lift that resumes a plan it names: whether resume_from is where
/// that plan, as kept by revision, has the load (for the cover). Read only
/// from the stage's own inputs ([`resumed_plan_files`]), so that the
/// document depends on nothing its key does not.
fn resume_agreements(ctx: &Ctx, tasks: &[liftplan_core::lift::LiftTask]) -> Vec<(String, Agreement)> {
    let p = ctx.project;
    tasks
        .iter()
        .filter_map(|t| {
            let named = t.resume_from.as_ref().and(t.resumes_plan.as_ref())?;
            let file = liftplan::revisions::plan_file(&p.out_dir(), &t.id, &named.revision);
            // Project-relative: the document must not depend on the folder's name.
            let shown = liftplan_core::location::shown(&file, Some(&p.dir));
            let unchecked = |why: String| Agreement {
                agrees: false,
                said: format!("plan {} {why}: resume_from is not checked against it", named.revision),
            };
            let agreement = if !ctx.inputs.contains(&file) {
                unchecked(format!(
                    "is not kept in {} (made by a liftplan that kept no plans by revision, or out/ cleaned since)",
                    liftplan_core::location::shown(file.parent().unwrap_or(&file), Some(&p.dir))
                ))
            } else {
                match crate::resume::plan_in(&file, &t.id) {
                    Ok(Some(plan)) if plan.summary.revision == named.revision => {
                        liftplan_plan::resumed::compare(t, &plan, &shown)?
                    }
                    Ok(_) => unchecked(format!("is not what {shown} holds (edited by hand?)")),
                    Err(_) => unchecked(format!("could not be read from {shown} (damaged?)")),
                }
            };
            Some((t.id.clone(), agreement))
        })
        .collect()
}

fn run_docs(ctx: &Ctx) -> Result<Produced> {
    let p = ctx.project;
    let tasks = p.lifts()?;
    let (plan_dir, _) = ctx.upstream.get("plan").ok_or_else(|| anyhow::anyhow!("no plan"))?;
    let resume_checks = resume_agreements(ctx, &tasks);
    let mut input_lines = Vec::new();
    let mut input_hashes = Vec::new();
    for stage in ["scans", "plant", "charts", "depthmap"] {
        if let Some((_, m)) = ctx.upstream.get(stage) {
            for l in &m.lines {
                input_lines.push(format!("{stage}: {}", l.trim()));
            }
            for (name, hash) in &m.inputs {
                let shown = match name.as_str() {
                    "code" => format!("code of the {stage} stage"),
                    "settings" => format!("settings of the {stage} stage"),
                    _ if name.starts_with("setting:") || name.starts_with("upstream:") => continue,
                    // A file's name as words ("file:scans/...").
                    _ => liftplan_core::names::without_controls(name).into_owned(),
                };
                input_hashes.push((shown, hash.chars().take(16).collect::<String>()));
            }
        }
    }
    // Every clearance rests on the crane model's boxes: say whose they are.
    let mut models: Vec<&str> = p.raw.lift.iter().map(|l| l.crane.model.as_str()).collect();
    models.sort();
    models.dedup();
    for name in models {
        let file = p.path(&p.raw.paths.cranes).join(format!("{name}.toml"));
        let m = p.crane_model(name)?;
        let whence = if file.is_file() {
            format!("in {}", file.strip_prefix(&p.dir).unwrap_or(&file).display())
        } else {
            format!("built into liftplan {}", env!("CARGO_PKG_VERSION"))
        };
        input_lines.push(format!(
            "crane: '{name}', {whence}, from {}: every clearance is measured from its boxes; check them on site",
            m.source
        ));
    }
    // The plan's and this document's own code, so the PDF names every build
    // that had a hand in it.
    for (stage, code) in [("plan", env!("LIFTPLAN_CODE_PLAN")), ("docs", env!("LIFTPLAN_CODE_DOCS"))] {
        input_hashes.push((format!("code of the {stage} stage"), code.to_string()));
    }
    input_hashes.sort();
    input_hashes.dedup();
    // Scans left out unregistered: what only they saw is missing.
    let registration =
        ctx.upstream_read("scans", "registration.json", liftplan_scans::recorded::Registration::from_json)?;
    let scans_left_out = registration.as_ref().map(|r| r.left_out()).unwrap_or_default();
    let site_level_unconfirmed = registration.as_ref().and_then(|r| r.site_level_unconfirmed());
    let scans_warned = registration.as_ref().map(|r| r.warned()).unwrap_or_default();
    let scans_passed_by = registration.as_ref().map(|r| r.passed_by()).unwrap_or_default();
    // Lifts on a chart of one column: which boom it is for, the chart does not say.
    let one_column_charts = ctx
        .upstream_read("charts", "lifts.json", |bytes| {
            liftplan_charts::recorded::LiftsCharted::from_json(bytes)?.one_column_booms(&tasks)
        })?
        .unwrap_or_default();
    // What reading each chart configuration warned of, for the lifts on it.
    let mut chart_warnings = Vec::new();
    let mut chart_wind = Vec::new();
    if let Some(configs) = chart_configs(ctx)? {
        chart_wind = liftplan_core::chart_json::stated(&configs, |c| &c.wind_ms);
        chart_warnings = configs.into_iter().filter(|c| !c.warnings.is_empty()).map(|c| (c.name, c.warnings)).collect();
    }
    let inputs = liftplan_docs::Inputs {
        project: p.raw.project.name.clone(),
        date: liftplan_docs::today(),
        tasks: tasks.clone(),
        plan_json: plan_dir.join("plan.json"),
        mesh: ctx.upstream_file("plant", "plant.mesh"),
        cloud: ctx.upstream_file("scans", "site.laz"),
        capacity_csv: ctx.upstream_file("charts", "capacity.csv"),
        plan_dir: plan_dir.clone(),
        input_lines,
        input_hashes,
        scans_left_out,
        scans_warned,
        scans_passed_by,
        inputs_not_read: inputs_not_read(p),
        site_level_unconfirmed,
        one_column_charts,
        chart_warnings,
        chart_wind,
        obstacles: p.raw.obstacle.clone(),
        power_lines: p.raw.power_line.clone(),
        resume_checks,
    };
    let summary = liftplan_docs::run(&inputs, &p.raw.docs, p.raw.gpu.use_, ctx.out)?;
    let mut outputs = Vec::new();
    for t in &tasks {
        outputs.push(format!("{}.pdf", t.id));
        outputs.push(format!("{}.overview.png", t.id));
        if ctx.out.join(format!("{}.chart.png", t.id)).exists() {
            outputs.push(format!("{}.chart.png", t.id));
        }
    }
    Ok(Produced { outputs, summary: serde_json::to_value(&summary)?, lines: summary.lines() })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A scan, a model and a chart in formats not read, and other files,
    /// are named with why; the files read, the project file, a stations
    /// file the project names and hidden files are not; past ten, counted.
    #[test]
    fn files_in_the_input_folders_not_read_are_named() {
        let t = tempfile::tempdir().unwrap();
        crate::project::init(t.path()).unwrap();
        let put = |name: &str| std::fs::write(t.path().join(name), b"x").unwrap();
        for name in [
            "scans/a.laz",
            "scans/site.fls",
            "scans/.DS_Store",
            "scans/Thumbs.db",
            "charts/desktop.ini",
            "scans/~$notes.xlsx",
            "plant/model.rvm",
            "plant/model.att",
            "plant/model.nwd",
            "charts/chart.xlsx",
            "charts/chart.pdf",
            "charts/chart.csv",
            "plant/delivery.zip",
        ] {
            put(name);
        }
        let project = Project::load(t.path()).unwrap();
        assert_eq!(
            inputs_not_read(&project),
            [
                "charts/chart.csv (a load chart as text is not read: open it in Excel or LibreOffice and save it as .xlsx)",
                "charts/chart.pdf (a load chart as a document or picture is not read: type or paste it into a workbook (.xlsx) and check it cell by cell against the chart)",
                "plant/delivery.zip (an archive, not read: unpack its files into this folder)",
                "plant/model.nwd (Navisworks' own format, not read: export it as RVM, glTF (.glb), OBJ, PLY or STL)",
                "scans/site.fls (FARO Scene's own format, not read: export it as E57, PTX or LAS)",
            ]
        );
        // A stations file is read where the project names it, else said.
        put("scans/stations.toml");
        assert!(
            inputs_not_read(&project)
                .iter()
                .any(|f| f.starts_with("scans/stations.toml (a stations file is read only where"))
        );
        let toml = t.path().join(crate::project::FILE);
        let text = std::fs::read_to_string(&toml).unwrap();
        std::fs::write(&toml, text.replace("[scans]", "[scans]\nstations = \"scans/stations.toml\"")).unwrap();
        let project = Project::load(t.path()).unwrap();
        assert!(!inputs_not_read(&project).iter().any(|f| f.contains("stations")));
        // A folder's files are not read: said of the folder.
        std::fs::create_dir(t.path().join("scans").join("day-2")).unwrap();
        put("scans/day-2/b.laz");
        assert!(
            inputs_not_read(&project)
                .contains(&"scans/day-2/ (a folder: the files in it are not read; put them beside it)".to_string())
        );
        for k in 0..7 {
            put(&format!("scans/photo-{k}.jpg"));
        }
        let said = inputs_not_read(&project);
        assert_eq!(said.len(), NOT_READ_NAMED + 1);
        assert_eq!(said.last().unwrap(), "and 3 more files");
        assert_eq!(not_read_said(said.last().unwrap()), "and 3 more files not read");
        assert!(not_read_said(&said[0]).starts_with("not read: charts/chart.csv ("));
        assert!(said.iter().any(|f| f == "scans/photo-0.jpg (no .jpg file is read; this folder's files read are .las, .laz, .ply, .e57, .ptx, .pts, .xyz, .txt, .asc, .csv)"), "{said:?}");
    }
}
