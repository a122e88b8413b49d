//! # liftplan
//!
//! Turns a site capture (laser scans, plant CAD, a crane load chart, a lift
//! request) into a checked crane lift plan. This binary owns the project folder,
//! the stage graph and its cache, watch mode and progress; the stages live in
//! `stages/*` and know nothing of these.
//!
//! Exit codes: 0 ok, 1 a stage failed, 2 usage or project-file error.

mod cache;
mod inspect;
mod pipeline;
mod progress;
use liftplan::{project, revisions};
mod resume;
mod stages;
mod watch;

use anyhow::{Context, Result};
use clap::{Parser, Subcommand};
use pipeline::RunOptions;
use progress::Progress;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

#[derive(Parser)]
#[command(name = "liftplan", version, about = "Crane lift planning from laser scans, plant models and load charts", long_about = None)]
#[command(after_help = "Start with `liftplan demo` to build and run an example project end to end.")]
struct Cli {
    /// More log output (-v info, -vv debug).
    #[arg(short, long, action = clap::ArgAction::Count, global = true)]
    verbose: u8,
    /// No progress output.
    #[arg(short, long, global = true)]
    quiet: bool,
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Create a project folder: a commented liftplan.toml and the input folders.
    #[command(after_help = "Example:\n  liftplan init site-a\n  cp survey/*.laz site-a/scans/\n  liftplan run site-a")]
    Init {
        /// Folder to create (or fill, if it exists without a liftplan.toml).
        dir: PathBuf,
    },
    /// Run the pipeline; stages whose inputs did not change are reused ("fresh").
    #[command(
        after_help = "Examples:\n  liftplan run site-a\n  liftplan run site-a --until scans --json\n  liftplan run site-a --force scans"
    )]
    Run {
        /// Project folder (default: the current folder).
        dir: Option<PathBuf>,
        /// Stop after this stage.
        #[arg(long, value_name = "STAGE")]
        until: Option<String>,
        /// Rerun this stage even if it is fresh (repeatable).
        #[arg(long, value_name = "STAGE")]
        force: Vec<String>,
        /// Print one JSON object with every stage's status, key, time and outputs.
        #[arg(long)]
        json: bool,
    },
    /// Show each stage as fresh or stale, and why; runs nothing.
    #[command(after_help = "Example:\n  liftplan status site-a")]
    Status {
        dir: Option<PathBuf>,
        #[arg(long)]
        json: bool,
    },
    /// Watch the project and rerun affected stages when inputs change.
    #[command(after_help = "Example:\n  liftplan watch site-a     # then drop new scans into site-a/scans/")]
    Watch { dir: Option<PathBuf> },
    /// Write the demo project and run it end to end.
    #[command(after_help = "Example:\n  liftplan demo            # into ./liftplan-demo\n  liftplan demo /tmp/demo")]
    Demo {
        /// Folder for the demo project (default: liftplan-demo).
        dir: Option<PathBuf>,
        /// Angular step of the simulated scanners in degrees (smaller is denser).
        #[arg(long, default_value_t = 0.25)]
        scan_step: f64,
        /// Give the site in survey coordinates (E 512,345, N 5,412,345, heights
        /// + 102 m), as a site surveyed in a projected CRS is.
        #[arg(long)]
        survey_coordinates: bool,
        /// Make the lift with the built-in hammerhead tower crane instead of
        /// the all-terrain crane.
        #[arg(long)]
        tower: bool,
    },
    /// Print the resume_from line (and resumes_plan, naming the plan) for a
    /// lift stopped part way, read off the plan its crew follows: paste them
    /// into the lift's [[lift]] (with any [[obstacle]] that stopped it) and
    /// run again to re-plan from where the load hangs.
    #[command(
        after_help = "Examples:\n  liftplan resume site-a V-101 --plan 3f9a2c1b --after-step 4\n  liftplan resume site-a V-101 --plan 3f9a2c1b --after-step 4 --swing-deg -60"
    )]
    Resume {
        /// Project folder.
        dir: PathBuf,
        /// The lift's id.
        lift: String,
        /// The plan the crew follows: the 8 hex digits after "plan" on the
        /// foot of each page of its PDF.
        #[arg(long)]
        plan: String,
        /// The last step done, as the plan numbers them.
        #[arg(long)]
        after_step: usize,
        /// Where the next step, a swing, stopped (degrees, as the steps give swing).
        #[arg(long, allow_hyphen_values = true)]
        swing_deg: Option<f64>,
    },
    /// Summarise any input file liftplan reads (scans, plant models, charts).
    #[command(after_help = "Examples:\n  liftplan inspect scans/north.laz\n  liftplan inspect scans/site.e57 --json")]
    Inspect {
        file: PathBuf,
        #[arg(long)]
        json: bool,
    },
    /// Remove the cache (.liftplan/) and out/ of a project, but for the plans
    /// kept by revision (out/revisions/).
    #[command(after_help = "Example:\n  liftplan clean site-a")]
    Clean { dir: Option<PathBuf> },
    /// List the plans kept by revision (out/revisions/), each with its PDF;
    /// optionally remove those kept more than some days ago, beyond each
    /// lift's newest few, or the oldest beyond a size, but each lift's
    /// newest, the last plans, those the cache holds and those the
    /// project's lifts resume.
    #[command(
        after_help = "Example:\n  liftplan revisions site-a\n  liftplan revisions site-a --remove-older-than 90\n  liftplan revisions site-a --keep-last 10\n  liftplan revisions site-a --keep-under 2000\n  liftplan revisions site-a --compare 3f9a2c1b 8e2d1a0f\n  liftplan revisions site-a --compare 3f9a2c1b last"
    )]
    Revisions {
        /// Project folder.
        dir: Option<PathBuf>,
        /// Remove the plans (their PDF, steps, inputs and plan files) kept more than
        /// this many days ago, but those a crew may hold or be given.
        #[arg(long, value_name = "DAYS")]
        remove_older_than: Option<u32>,
        /// Remove all but each lift's N newest plans (with
        /// --remove-older-than: only those older than that too), but those
        /// a crew may hold or be given.
        #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
        keep_last: Option<u32>,
        /// Remove the oldest plans, whatever their lift, until what is kept
        /// comes to this many megabytes or under (with --remove-older-than:
        /// only those older than that too), but those a crew may hold or be
        /// given.
        #[arg(long, value_name = "MB", value_parser = clap::value_parser!(u64).range(1..), conflicts_with = "keep_last")]
        keep_under: Option<u64>,
        /// Print the plans kept (and those removed) as JSON.
        #[arg(long)]
        json: bool,
        /// Set two kept plans of a lift side by side: what differs in the
        /// second (NOW; `last`: the lift's last plan) from the first
        /// (WAS), what a signer reads first, then the first step that
        /// differs and every other value.
        #[arg(long, num_args = 2, value_names = ["WAS", "NOW"], conflicts_with_all = ["remove_older_than", "keep_last", "keep_under"])]
        compare: Option<Vec<String>>,
        /// The lift whose plans --compare names, where two lifts keep both.
        #[arg(long, requires = "compare")]
        lift: Option<String>,
    },
    /// List every stage and its settings with their defaults.
    #[command(after_help = "Example:\n  liftplan options scans")]
    Options {
        /// Only this stage.
        stage: Option<String>,
    },
    /// Run the plant stage on loose files: RVM exports and meshes to one PLY.
    #[command(
        after_help = "Example:\n  liftplan plant unit-12.rvm pipe-bridge.glb -o plant.ply --tolerance 0.01 --json"
    )]
    Plant {
        #[arg(required = true)]
        inputs: Vec<PathBuf>,
        /// Output PLY file.
        #[arg(short, long)]
        output: PathBuf,
        /// Chord tolerance in metres.
        #[arg(long)]
        tolerance: Option<f64>,
        /// Length unit of OBJ/PLY/STL files (as `[plant] unit`): m, mm, cm, ft or in.
        #[arg(long)]
        unit: Option<String>,
        /// Up axis of OBJ/PLY/STL files (as `[plant] up_axis`): z or y.
        #[arg(long)]
        up_axis: Option<String>,
        /// Print plant.json.
        #[arg(long)]
        json: bool,
    },
    /// Read a load chart into a capacity table; optionally look up one point.
    #[command(
        after_help = "Examples:\n  liftplan chart ac700.xlsx -o capacity.csv\n  liftplan chart ac700.xlsx -o capacity.csv --config \"Main boom 360\" --lookup boom=40,radius=29"
    )]
    Chart {
        input: PathBuf,
        /// Output CSV (config, boom_m, radius_m, capacity_kg, cell).
        #[arg(short, long)]
        output: PathBuf,
        /// Capacity at a point: boom=B,radius=R (metres).
        #[arg(long, value_name = "boom=B,radius=R")]
        lookup: Option<String>,
        /// Configuration for --lookup (default: the only one).
        #[arg(long)]
        config: Option<String>,
        /// Length unit of grids whose labels name none (as `[charts] length_unit`).
        #[arg(long, value_name = "m|ft", value_parser = ["m", "ft"])]
        length_unit: Option<String>,
        /// Capacity unit of grids whose labels name none (as `[charts] capacity_unit`).
        #[arg(
            long,
            value_name = "t|kg|lb|kips|shortton|kN|daN",
            value_parser = ["t", "kg", "lb", "kips", "shortton", "kN", "daN"]
        )]
        capacity_unit: Option<String>,
        #[arg(long)]
        json: bool,
    },
    /// Reproduce the planner benchmark: Cai 2016 Tables 4.11-4.18 on plants built
    /// like the thesis', then MSPGA against Ali et al.'s GA, RRT-Connect and PRM
    /// and the three C-space strategies on the demo lift. Markdown on stdout.
    #[command(
        after_help = "Examples:\n  liftplan bench > reports/planner.md    # about 40 minutes on 2 cores\n  liftplan bench --runs 2 --grid-runs 0 --t414-runs 1 --demo-seeds 1\n  liftplan bench --runs 0 --grid-runs 0 --t414-runs 0 --demo-seeds 0 --validator-runs 10 > reports/validator.md\n  liftplan bench --runs 0 --grid-runs 0 --t414-runs 0 --demo-seeds 0 --replan-seeds 10 > reports/replan.md"
    )]
    Bench {
        /// Seeds per row of Tables 4.11/4.12 (the thesis: 50).
        #[arg(long, default_value_t = 50)]
        runs: u64,
        /// Seeds per cell of the rate grids, Tables 4.15-4.18 (the thesis: 50; 0 skips them).
        #[arg(long, default_value_t = 50)]
        grid_runs: u64,
        /// Runs per C-space strategy for Table 4.14 (0 skips it).
        #[arg(long, default_value_t = 3)]
        t414_runs: u64,
        /// Seeds per planner on the demo lift (0 skips it).
        #[arg(long, default_value_t = 3)]
        demo_seeds: u64,
        /// Seeds per plant for the validator's table (reports/validator.md; 0 skips it).
        #[arg(long, default_value_t = 0)]
        validator_runs: u64,
        /// Seeds for re-planning part way through the demo lift round a new
        /// obstacle (reports/replan.md; 0 skips it).
        #[arg(long, default_value_t = 0)]
        replan_seeds: u64,
    },
    /// Run the scans stage on loose files.
    #[command(after_help = "Example:\n  liftplan scans a.laz b.e57 -o site.laz --voxel 0.05 --ground-cell 0.5 --json")]
    Scans {
        #[arg(required = true)]
        inputs: Vec<PathBuf>,
        /// Output LAS/LAZ file.
        #[arg(short, long)]
        output: PathBuf,
        /// Voxel edge in metres.
        #[arg(long)]
        voxel: Option<f64>,
        /// auto | none | poses
        #[arg(long)]
        register: Option<String>,
        /// Cell of the ground classification's grid in metres (default 1).
        #[arg(long, conflicts_with = "no_ground")]
        ground_cell: Option<f64>,
        /// Leave ground classification out (every point unclassified).
        #[arg(long)]
        no_ground: bool,
        /// Print the registration report as JSON.
        #[arg(long)]
        json: bool,
    },
}

fn project_dir(dir: Option<PathBuf>) -> PathBuf {
    dir.unwrap_or_else(|| PathBuf::from("."))
}

/// Says so, and the exit code, where `dir` holds no project file.
fn not_a_project(dir: &Path) -> Option<ExitCode> {
    (!dir.join(project::FILE).exists()).then(|| {
        eprintln!("error: {} is not a liftplan project (no {})", dir.display(), project::FILE);
        ExitCode::from(2)
    })
}

fn load(dir: &Path) -> Result<project::Project, ExitCode> {
    project::Project::load(dir).map_err(|e| {
        eprintln!("error: {}", progress::for_terminal(&e.to_string()));
        ExitCode::from(2)
    })
}

fn print_report(rep: &pipeline::RunReport, json: bool, progress: &Progress) {
    if json {
        println!("{}", serde_json::to_string(rep).unwrap_or_default());
        return;
    }
    for s in &rep.stages {
        let status = format!("{:?}", s.status).to_lowercase();
        let extra = match (&s.error, &s.reason) {
            (Some(e), _) => format!(": {e}"),
            (None, Some(r)) => format!(" ({r})"),
            _ => String::new(),
        };
        progress.line(&format!("{:>9} {:<6} {:6.2}s{}", s.name, status, s.seconds, extra));
        // `-q` quiets progress, not failures: a run that fails says why.
        if let (true, Some(e)) = (progress.is_quiet(), &s.error) {
            eprintln!("error: stage {} failed: {}", s.name, progress::for_terminal(e));
        }
        for l in &s.lines {
            progress.line(&format!("          {l}"));
        }
    }
    // Said even when quiet: what only such a file holds is in no plan.
    for f in &rep.inputs_not_read {
        eprintln!("warning: {}", progress::for_terminal(&stages::not_read_said(f)));
    }
    // A resumed lift's pose that is not its plan's is said even when quiet.
    for c in &rep.resume_checks {
        if c.agrees {
            progress.line(&c.said);
        } else {
            eprintln!("warning: {}", progress::for_terminal(&c.said));
        }
    }
}

fn real_main() -> Result<ExitCode> {
    // A third-party reader's panic on a damaged file is caught and reported
    // as that file's error; do not print it as if the program had crashed.
    liftplan_core::guard::quiet_caught_panics();
    let cli = Cli::parse();
    let level = match (cli.quiet, cli.verbose) {
        (true, _) => tracing::Level::ERROR,
        (false, 0) => tracing::Level::WARN,
        (false, 1) => tracing::Level::INFO,
        _ => tracing::Level::DEBUG,
    };
    // Without colours: an event is printed as [`progress::log_event`] makes it,
    // which shows each escape as U+FFFD, the colours' too.
    tracing_subscriber::fmt()
        .with_max_level(level)
        .with_writer(progress::TerminalLog)
        .with_ansi(false)
        .with_target(false)
        .init();
    let progress = Progress::new(cli.quiet);
    match cli.command {
        Command::Init { dir } => {
            project::init(&dir)?;
            println!(
                "created {}: put scans in scans/, plant models in plant/, load charts in charts/, then `liftplan run {}`",
                dir.display(),
                dir.display()
            );
            Ok(ExitCode::SUCCESS)
        }
        Command::Run { dir, until, force, json } => {
            let dir = project_dir(dir);
            let p = match load(&dir) {
                Ok(p) => p,
                Err(c) => return Ok(c),
            };
            // Before the run, which writes the plans the check reads.
            let resume_checks = resume::check_resumed(&p);
            let mut rep = match pipeline::run(&p, &RunOptions { until, force }, &progress) {
                Ok(r) => r,
                Err(e) => {
                    eprintln!("error: {}", progress::for_terminal(&format!("{e:#}")));
                    return Ok(ExitCode::from(2));
                }
            };
            rep.resume_checks = resume_checks;
            print_report(&rep, json, &progress);
            Ok(if rep.ok { ExitCode::SUCCESS } else { ExitCode::from(1) })
        }
        Command::Status { dir, json } => {
            let dir = project_dir(dir);
            let p = match load(&dir) {
                Ok(p) => p,
                Err(c) => return Ok(c),
            };
            let st = pipeline::status(&p)?;
            if json {
                println!("{}", serde_json::to_string(&st)?);
            } else {
                for s in &st {
                    println!("{:>9} {:<7} {}", s.name, s.state, progress::for_terminal(&s.why.join("; ")));
                }
            }
            Ok(ExitCode::SUCCESS)
        }
        Command::Watch { dir } => {
            let dir = project_dir(dir);
            if let Err(c) = load(&dir) {
                return Ok(c);
            }
            let stop = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
            let s2 = stop.clone();
            ctrlc::set_handler(move || s2.store(true, std::sync::atomic::Ordering::SeqCst))
                .context("installing the Ctrl-C handler")?;
            watch::watch(&dir, &progress, stop)?;
            Ok(ExitCode::SUCCESS)
        }
        Command::Demo { dir, scan_step, survey_coordinates, tower } => {
            let dir = dir.unwrap_or_else(|| PathBuf::from("liftplan-demo"));
            if dir.join(project::FILE).exists() {
                progress.line(&format!("{} already holds a project: running it again", dir.display()));
            } else {
                progress.line(&format!("writing the demo project into {}", dir.display()));
                liftplan_fixtures::demo::write_project(
                    &dir,
                    &liftplan_fixtures::demo::DemoOptions {
                        scan_step_deg: scan_step,
                        site_offset_m: if survey_coordinates {
                            liftplan_fixtures::demo::SURVEY_OFFSET_M
                        } else {
                            [0.0; 3]
                        },
                        tower_crane: tower,
                    },
                )
                .map_err(anyhow::Error::msg)?;
            }
            let p = match load(&dir) {
                Ok(p) => p,
                Err(c) => return Ok(c),
            };
            let rep = pipeline::run(&p, &RunOptions { until: None, force: vec![] }, &progress)?;
            print_report(&rep, false, &progress);
            if rep.ok {
                println!("demo finished: outputs in {}", p.out_dir().display());
                for l in &p.raw.lift {
                    let pdf = p.out_dir().join(format!("{}.pdf", l.id));
                    if pdf.is_file() {
                        println!("lift plan: {}", pdf.display());
                    }
                }
            }
            Ok(if rep.ok { ExitCode::SUCCESS } else { ExitCode::from(1) })
        }
        Command::Bench { runs, grid_runs, t414_runs, demo_seeds, validator_runs, replan_seeds } => {
            use liftplan_plan::bench;
            if runs > 0 || grid_runs > 0 {
                bench::thesis_tables(runs, grid_runs);
                println!();
            }
            if t414_runs > 0 {
                bench::table_414(t414_runs);
                println!();
            }
            if demo_seeds > 0 || replan_seeds > 0 {
                let dir = std::env::temp_dir().join(format!("liftplan-bench-{}", std::process::id()));
                let run_demo = || -> anyhow::Result<()> {
                    liftplan_fixtures::demo::write_project(&dir, &liftplan_fixtures::demo::DemoOptions::default())
                        .map_err(anyhow::Error::msg)?;
                    let p = project::Project::load(&dir)?;
                    let rep = pipeline::run(&p, &RunOptions { until: None, force: vec![] }, &progress)?;
                    anyhow::ensure!(rep.ok, "the demo project did not run; see `liftplan demo`");
                    if demo_seeds > 0 {
                        bench::demo_lift(&dir, demo_seeds).map_err(anyhow::Error::msg)?;
                    }
                    if replan_seeds > 0 {
                        println!();
                        bench::replanning(&dir, replan_seeds).map_err(anyhow::Error::msg)?;
                    }
                    Ok(())
                };
                let done = run_demo();
                // The temporary project is removed whatever happened.
                let _ = std::fs::remove_dir_all(&dir);
                done?;
            }
            if validator_runs > 0 {
                println!();
                bench::validator_table(validator_runs);
            }
            Ok(ExitCode::SUCCESS)
        }
        Command::Inspect { file, json } => {
            let v = match inspect::inspect(&file) {
                Ok(v) => v,
                Err(e) => {
                    eprintln!("error: {}", progress::for_terminal(&format!("{e:#}")));
                    return Ok(ExitCode::from(1));
                }
            };
            if json {
                println!("{}", serde_json::to_string(&v)?);
            } else {
                print!("{}", inspect::human(&v));
            }
            Ok(ExitCode::SUCCESS)
        }
        Command::Clean { dir } => {
            let dir = project_dir(dir);
            if let Some(code) = not_a_project(&dir) {
                return Ok(code);
            }
            let state = project::state_dir_of(&dir);
            if state.exists() {
                std::fs::remove_dir_all(&state).with_context(|| format!("removing {}", state.display()))?;
            }
            // The plans kept by revision are the record of what crews were
            // given (and what `resume` reads): a clean to rebuild must not
            // take them.
            let out = project::out_dir_of(&dir);
            let mut kept_revisions = false;
            if out.exists() {
                for entry in std::fs::read_dir(&out).with_context(|| format!("reading {}", out.display()))? {
                    let path = entry.with_context(|| format!("reading {}", out.display()))?.path();
                    if path.file_name().is_some_and(|n| n == revisions::DIR) && path.is_dir() {
                        kept_revisions = true;
                        continue;
                    }
                    let removed =
                        if path.is_dir() { std::fs::remove_dir_all(&path) } else { std::fs::remove_file(&path) };
                    removed.with_context(|| format!("removing {}", path.display()))?;
                }
                if !kept_revisions {
                    std::fs::remove_dir(&out).with_context(|| format!("removing {}", out.display()))?;
                }
            }
            println!(
                "removed the cache and outputs of {}{}",
                dir.display(),
                if kept_revisions {
                    "; the plans kept by revision stay in out/revisions/ (`liftplan revisions --remove-older-than DAYS` removes old ones)"
                } else {
                    ""
                }
            );
            Ok(ExitCode::SUCCESS)
        }
        Command::Revisions { dir, remove_older_than, keep_last, keep_under, json, compare, lift } => {
            let removing = remove_older_than.is_some() || keep_last.is_some() || keep_under.is_some();
            let dir = project_dir(dir);
            if let Some(code) = not_a_project(&dir) {
                return Ok(code);
            }
            if let Some([was, now]) = compare.as_deref() {
                let c = match revisions::compare(&project::out_dir_of(&dir), lift.as_deref(), was, now) {
                    Ok(c) => c,
                    Err(e) => {
                        eprintln!("error: {}", progress::for_terminal(&format!("{e:#}")));
                        return Ok(ExitCode::from(2));
                    }
                };
                if json {
                    println!("{}", serde_json::to_string_pretty(&c)?);
                } else {
                    println!("{}", progress::for_terminal(&c.said()));
                }
                return Ok(ExitCode::SUCCESS);
            }
            // Its lifts say which plans they resume: removing needs the
            // project file to read; a listing says where it does not.
            let (resumed, unread): (Vec<(String, String)>, Option<String>) = match project::Project::load(&dir) {
                Ok(p) => (
                    p.raw
                        .lift
                        .iter()
                        .filter_map(|l| Some((l.id.clone(), l.resumes_plan.as_ref()?.revision.clone())))
                        .collect(),
                    None,
                ),
                Err(e) if removing => {
                    eprintln!(
                        "error: {e} (removing plans needs the project file to read: its lifts say which plans they resume)"
                    );
                    return Ok(ExitCode::from(2));
                }
                Err(e) => (Vec::new(), Some(e.to_string())),
            };
            let out = project::out_dir_of(&dir);
            let kept = revisions::list(&out)?;
            let mut plan_dirs = cache::Cache::new(&project::state_dir_of(&dir)).entries(liftplan_plan::NAME);
            plan_dirs.push(out.clone());
            let held = revisions::held(&kept, &plan_dirs, &resumed, keep_last.map_or(1, |n| n as usize));
            let removed = if removing {
                let now = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.as_secs());
                let before = remove_older_than.map_or(u64::MAX, |days| now.saturating_sub(u64::from(days) * 86_400));
                match keep_under {
                    Some(mb) => {
                        revisions::remove(&out, &revisions::to_fit(&kept, &held, before, mb.saturating_mul(1_000_000)))?
                    }
                    None => revisions::remove_older_than(&out, &kept, &held, before)?,
                }
            } else {
                Vec::new()
            };
            // What is left, read again only where files went.
            let left = if removed.is_empty() { kept } else { revisions::list(&out)? };
            if json {
                let listed: Vec<serde_json::Value> = left
                    .iter()
                    .map(|k| {
                        let mut v = serde_json::to_value(k).unwrap_or_default();
                        v["held"] = held
                            .get(&(k.lift.clone(), k.revision.clone()))
                            .map_or(serde_json::Value::Null, |h| (*h).into());
                        v
                    })
                    .collect();
                let all = serde_json::json!({ "kept": listed, "removed": removed, "project_unread": unread });
                println!("{}", serde_json::to_string_pretty(&all)?);
                return Ok(ExitCode::SUCCESS);
            }
            if let Some(e) = &unread {
                let note = format!("note: {e}: the plans the project's lifts resume are not known here");
                println!("{}", progress::for_terminal(&note));
            }
            for r in &removed {
                println!("removed {}", progress::for_terminal(r));
            }
            let total: u64 = left.iter().map(|k| k.bytes).sum();
            let under = keep_under.map(|mb| (mb, total <= mb.saturating_mul(1_000_000)));
            if removing && removed.is_empty() {
                if let Some((mb, true)) = under {
                    println!(
                        "removed nothing: what is kept, {:.1} MB, is {mb} MB or under already",
                        total as f64 / 1e6
                    );
                } else {
                    let which = [
                        remove_older_than.map(|days| format!("kept more than {days} days ago")),
                        keep_last.map(|n| format!("beyond each lift's {n} newest")),
                    ];
                    let which: Vec<String> = which.into_iter().flatten().collect();
                    let which = if which.is_empty() { String::new() } else { format!(" {}", which.join(" and ")) };
                    println!("removed nothing: no plan{which} but those held (below)");
                }
            }
            if let Some((mb, false)) = under {
                println!(
                    "still {:.1} MB kept, over {mb} MB: the rest is held (below){}",
                    total as f64 / 1e6,
                    if remove_older_than.is_some() { " or not kept long enough ago" } else { "" }
                );
            }
            println!(
                "{}: {} plan{} kept by revision, {:.1} MB",
                out.join(revisions::DIR).display(),
                left.len(),
                if left.len() == 1 { "" } else { "s" },
                total as f64 / 1e6
            );
            for k in &left {
                let why =
                    held.get(&(k.lift.clone(), k.revision.clone())).map_or(String::new(), |h| format!(" (held: {h})"));
                println!("  {}", progress::for_terminal(&format!("{}{why}", k.said())));
            }
            Ok(ExitCode::SUCCESS)
        }
        Command::Resume { dir, lift, plan, after_step, swing_deg } => {
            println!("{}", progress::for_terminal(&resume::line(&dir, &lift, &plan, after_step, swing_deg)?));
            Ok(ExitCode::SUCCESS)
        }
        Command::Options { stage } => {
            let defs = pipeline::stages();
            fn section<T: serde::Serialize>(name: &str, value: T) -> Result<String> {
                Ok(toml::to_string_pretty(&std::collections::BTreeMap::from([(name, value)]))?)
            }
            // Each stage's own section of liftplan.toml, with its defaults.
            let settings = |name: &str| -> Result<String> {
                match name {
                    liftplan_scans::NAME => section("scans", liftplan_scans::Settings::default()),
                    liftplan_plant::NAME => section("plant", liftplan_plant::Settings::default()),
                    liftplan_charts::NAME => section("charts", liftplan_charts::Settings::default()),
                    liftplan_depthmap::NAME => section("depthmap", liftplan_depthmap::Settings::default()),
                    liftplan_plan::NAME => section("plan", liftplan_plan::Settings::default()),
                    liftplan_docs::NAME => section("docs", liftplan_docs::Settings::default()),
                    _ => Ok(String::new()),
                }
            };
            if let Some(s) = &stage
                && !defs.iter().any(|d| d.name == s)
            {
                eprintln!("error: no stage '{s}' (stages: {})", pipeline::stage_names().join(", "));
                return Ok(ExitCode::from(2));
            }
            for d in defs.iter().filter(|d| stage.as_deref().is_none_or(|s| s == d.name)) {
                println!("# stage {} (version {}): {}\n{}", d.name, d.version, d.about, settings(d.name)?);
            }
            if stage.is_none() {
                let p = project::RawProject::default();
                println!(
                    "# every stage: where the inputs are, the GPU, watching and the cache\n{}\n{}\n{}\n{}",
                    section("paths", p.paths)?,
                    section("gpu", p.gpu)?,
                    section("watch", p.watch)?,
                    section("cache", p.cache)?
                );
            }
            Ok(ExitCode::SUCCESS)
        }
        Command::Chart { input, output, lookup, config, length_unit, capacity_unit, json } => {
            // The parsers above admit only the units' own names.
            fn unit<T: serde::de::DeserializeOwned>(u: Option<String>) -> serde_json::Result<Option<T>> {
                u.map(|u| serde_json::from_value(serde_json::Value::String(u))).transpose()
            }
            let settings = liftplan_charts::Settings {
                length_unit: unit(length_unit)?,
                capacity_unit: unit(capacity_unit)?,
                ..Default::default()
            };
            let (configs, reports) = match liftplan_charts::read_chart(&input, &settings) {
                Ok(x) => x,
                Err(e) => {
                    eprintln!("error: {}", progress::for_terminal(&e.to_string()));
                    if e.to_string().contains("unit found around the chart grid") {
                        eprintln!("(here: --length-unit and --capacity-unit)");
                    }
                    return Ok(ExitCode::from(1));
                }
            };
            let table = liftplan_core::capacity::CapacityTable { configs };
            if let Err(e) = table.check_grid_cells() {
                eprintln!("error: {}", progress::for_terminal(&format!("{}: {e}", input.display())));
                return Ok(ExitCode::from(1));
            }
            table.write_csv(&output).with_context(|| format!("writing {}", output.display()))?;
            let mut result = serde_json::json!({ "configs": reports, "rows": table.rows().len(), "output": output.display().to_string() });
            if let Some(q) = lookup {
                let mut boom = None;
                let mut radius = None;
                for kv in q.split(',') {
                    match kv.split_once('=') {
                        // "NaN" and "inf" parse as numbers: not lengths.
                        Some(("boom", v)) => boom = v.trim().parse::<f64>().ok().filter(|v| v.is_finite()),
                        Some(("radius", v)) => radius = v.trim().parse::<f64>().ok().filter(|v| v.is_finite()),
                        _ => {}
                    }
                }
                let cfg = match &config {
                    Some(name) => table.config(name).map_err(|e| anyhow::anyhow!("{e}"))?,
                    None if table.configs.len() == 1 => &table.configs[0],
                    None => {
                        eprintln!(
                            "error: the chart has {} configurations; name one with --config ({})",
                            table.configs.len(),
                            table.configs.iter().map(|c| format!("'{}'", c.name)).collect::<Vec<_>>().join(", ")
                        );
                        return Ok(ExitCode::from(2));
                    }
                };
                // A chart of one column for any boom (a tower crane's jib)
                // needs no boom length.
                let any_boom = cfg.boom_independent();
                let (Some(b), Some(r)) = (boom.or(any_boom.then_some(0.0)), radius) else {
                    eprintln!(
                        "error: --lookup expects boom=B,radius=R in metres (radius=R alone for a chart of one column for any boom), got '{q}'"
                    );
                    return Ok(ExitCode::from(2));
                };
                match cfg.lookup(b, r) {
                    Ok(c) => {
                        if !json {
                            let column = if any_boom {
                                "one column for any boom or jib".to_string()
                            } else {
                                format!("column {} m", c.boom_m)
                            };
                            let at = if any_boom { String::new() } else { format!("boom {b} m, ") };
                            println!(
                                "{:.3} t at {at}radius {r} m (chart row {} m, {column}, cell {})",
                                c.capacity_kg / 1000.0,
                                c.radius_m,
                                c.cell
                            );
                        }
                        result["lookup"] = serde_json::to_value(&c)?;
                    }
                    Err(e) => {
                        if !json {
                            println!("not permitted: {e}");
                        }
                        result["lookup"] = serde_json::json!({ "error": e.to_string() });
                    }
                }
            } else if !json {
                for r in &reports {
                    // With the units read, as a run's line says them: what
                    // the engineer checks first.
                    let said = format!(
                        "'{}': {} x {} radii [{}!{}] ({}){}",
                        r.name,
                        r.columns_said(),
                        r.radii,
                        r.sheet,
                        r.range,
                        r.units.found.join(", "),
                        r.stated_said()
                    );
                    println!("{}", progress::for_terminal(&said));
                }
                println!("wrote {} ({} rows)", output.display(), table.rows().len());
            }
            // What the reading found worth checking (a decimal comma, a
            // footnote dropped, a broken column): on stderr, as a run
            // shows it; in the JSON with each configuration.
            if !json {
                for r in &reports {
                    for w in &r.warnings {
                        eprintln!("warning: {}", progress::for_terminal(&format!("'{}': {w}", r.name)));
                    }
                }
            }
            if json {
                println!("{}", serde_json::to_string(&result)?);
            }
            Ok(ExitCode::SUCCESS)
        }
        Command::Plant { inputs, output, tolerance, unit, up_axis, json } => {
            let mut s = liftplan_plant::Settings::default();
            if let Some(t) = tolerance {
                s.tolerance = t;
            }
            // The settings' own parsers admit only their names.
            let named = |v: Option<String>| v.map(serde_json::Value::String);
            s.unit =
                named(unit).map(serde_json::from_value).transpose().context("--unit: expected m, mm, cm, ft or in")?;
            s.up_axis = named(up_axis).map(serde_json::from_value).transpose().context("--up-axis: expected z or y")?;
            let tmp = tempdir_near(&output)?;
            let report = |what: &str, d: u64, t: u64| progress.report("plant", what, d, t);
            let res = liftplan_plant::run(&inputs, &s, &tmp, None, &report);
            let code = match res {
                Ok(sum) => {
                    std::fs::rename(tmp.join("plant.ply"), &output)
                        .or_else(|_| std::fs::copy(tmp.join("plant.ply"), &output).map(|_| ()))?;
                    if json {
                        println!("{}", std::fs::read_to_string(tmp.join("plant.json"))?);
                    } else {
                        for l in sum.lines() {
                            println!("{}", progress::for_terminal(&l));
                        }
                        println!("wrote {}", output.display());
                    }
                    ExitCode::SUCCESS
                }
                Err(e) => {
                    eprintln!("error: {}", progress::for_terminal(&e.to_string()));
                    ExitCode::from(1)
                }
            };
            let _ = std::fs::remove_dir_all(&tmp);
            Ok(code)
        }
        Command::Scans { inputs, output, voxel, register, ground_cell, no_ground, json } => {
            let mut s = liftplan_scans::Settings::default();
            if let Some(v) = voxel {
                s.voxel = v;
            }
            if let Some(c) = ground_cell {
                s.ground.cell_m = c;
            }
            s.ground.enabled = !no_ground;
            if let Some(r) = register {
                s.register = serde_json::from_value(serde_json::Value::String(r.clone()))
                    .map_err(|_| anyhow::anyhow!("--register {r}: expected auto, none or poses"))?;
            }
            let tmp = tempdir_near(&output)?;
            let report = |what: &str, d: u64, t: u64| progress.report("scans", what, d, t);
            let res = liftplan_scans::run(
                &inputs,
                &s,
                &liftplan_scans::RunOptions { seed: 0, progress: &report, root: None, memo: None },
                &tmp,
            );
            let out = match res {
                Ok(sum) => {
                    std::fs::rename(tmp.join("site.laz"), &output)
                        .or_else(|_| std::fs::copy(tmp.join("site.laz"), &output).map(|_| ()))?;
                    if json {
                        println!("{}", std::fs::read_to_string(tmp.join("registration.json"))?);
                    } else {
                        for l in sum.lines() {
                            println!("{}", progress::for_terminal(&l));
                        }
                        println!("wrote {} ({} points)", output.display(), sum.points_out);
                    }
                    ExitCode::SUCCESS
                }
                Err(e) => {
                    eprintln!("error: {}", progress::for_terminal(&e.to_string()));
                    ExitCode::from(1)
                }
            };
            let _ = std::fs::remove_dir_all(&tmp);
            Ok(out)
        }
    }
}

fn tempdir_near(output: &Path) -> Result<PathBuf> {
    let parent = output.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    let d = parent.join(format!(".liftplan-scans-{}", std::process::id()));
    std::fs::create_dir_all(&d)?;
    Ok(d)
}

/// Mesa's Vulkan driver asks libwayland for a display while wgpu lists the
/// adapters; where `XDG_RUNTIME_DIR` is unset (a terminal without a desktop
/// session, CI, a container) libwayland prints "error: XDG_RUNTIME_DIR is
/// invalid or not set in the environment." for every probe, which reads like
/// one of liftplan's own errors though nothing is wrong. liftplan opens no
/// window, so there the variable is pointed at the temporary directory:
/// libwayland looks for a display socket in it, finds none and says nothing.
fn quiet_the_wayland_probe() {
    if cfg!(target_os = "linux") && std::env::var_os("XDG_RUNTIME_DIR").is_none() {
        // SAFETY: the first thing `main` does, before any thread is started.
        unsafe { std::env::set_var("XDG_RUNTIME_DIR", std::env::temp_dir()) };
    }
}

fn main() -> ExitCode {
    quiet_the_wayland_probe();
    match real_main() {
        Ok(c) => c,
        Err(e) => {
            eprintln!("error: {}", progress::for_terminal(&format!("{e:#}")));
            ExitCode::from(1)
        }
    }
}
