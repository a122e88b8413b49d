//! The planner and the validator on a small synthetic site: a wall between
//! pick and set that the load must be lifted over.

use liftplan_core::crane::{Config, builtin};
use liftplan_core::frame::Point3;
use liftplan_core::lift::{LiftSpec, LiftTask};
use liftplan_core::mesh::TriMesh;
use liftplan_cspace::Joint;
use liftplan_depthmap::mdm::Mdm;
use liftplan_plan::path::Move;
use liftplan_plan::validate::{AGREEMENT_CLOSE_M, Rules, World, validate, validate_lift};
use liftplan_plan::{Settings, Site, plan_lift};

fn spec_of(pick_y: f64) -> LiftSpec {
    let text = format!(
        r#"
id = "T-1"
description = "test lift over a wall"
load = {{ name = "skid", mass_t = 5.0, size_m = [4.0, 2.0, 2.0], cog_m = [0.0, 0.0, 0.0] }}
rigging = {{ mass_t = 0.2, height_m = 3.0 }}
crane = {{ model = "ac-700", position_m = [0.0, 0.0], ground_z_m = 0.0, heading_deg = 0.0, boom_m = 40.0, chart_config = "none" }}
pick = {{ x_m = 22.0, y_m = {pick_y}, z_m = 0.5, yaw_deg = 0.0 }}
set = {{ x_m = 22.0, y_m = 14.0, z_m = 0.5, yaw_deg = 90.0 }}
clearance_m = 1.0
liftoff_m = 0.5
"#
    );
    toml::from_str(&text).unwrap()
}

/// The built-in all-terrain crane with its hoist rope neither weighed nor
/// in the wind: these tests set their gross loads and swings by hand (the
/// skid, its rigging and the block, 8.7 t), and the rope's weight and wind
/// have tests of their own.
fn ac700() -> liftplan_core::crane::CraneModel {
    let mut model = builtin("ac-700").unwrap();
    (model.hook.rope_kg_per_m, model.hook.rope_diameter_mm) = (None, None);
    model
}

fn task(pick_y: f64) -> LiftTask {
    spec_of(pick_y).resolve(ac700()).unwrap()
}

fn box_part(mesh: &mut TriMesh, name: &str, lo: [f64; 3], hi: [f64; 3]) {
    let g = mesh.group_id(name);
    mesh.add_box(g, lo, hi);
}

fn site() -> TriMesh {
    let mut m = TriMesh::default();
    box_part(&mut m, "WALL", [14.0, -1.0, 0.0], [34.0, 1.0, 12.0]);
    box_part(&mut m, "SLAB", [-40.0, -40.0, -0.3], [60.0, 40.0, 0.0]);
    m
}

/// A slab 120 m square and nothing else: the depth map and the
/// validator's world of it.
fn open_slab() -> (Mdm, World) {
    let mut slab = TriMesh::default();
    box_part(&mut slab, "SLAB", [-60.0, -60.0, -0.3], [60.0, 60.0, 0.0]);
    (map(&slab), World::new(&slab, &[], &[]).unwrap())
}

fn map(mesh: &TriMesh) -> Mdm {
    let inp = liftplan_depthmap::Inputs { points: vec![], ground: vec![], mesh: mesh.clone() };
    liftplan_depthmap::build_cpu(&inp, &liftplan_depthmap::Settings::default()).unwrap().0
}

fn quick() -> Settings {
    let mut s = Settings::default();
    s.ga.population = 40;
    s.ga.max_generations = 80;
    s.ga.stall_generations = 30;
    s.cspace.swing_step_deg = 1.0;
    s.cspace.luff_step_deg = 1.0;
    s
}

/// The validator's rules for `task`'s lifts: 1 m clearance, 0.2 m over a
/// landing zone (none here), samples 5 cm of movement apart.
fn rules() -> Rules {
    Rules { clearance_m: 1.0, landing: vec![], landing_clearance_m: 0.2, sample_m: 0.05, support_m: 0.05 }
}

/// The lift over the wall, planned (seed 3): the lift, the validator's view
/// of the site, and the plan.
fn over_the_wall() -> (LiftTask, World, liftplan_plan::LiftPlan) {
    let mesh = site();
    let m = map(&mesh);
    let world = World::new(&mesh, &[], &[]).unwrap();
    let t = task(-14.0);
    let (plan, _) = plan_lift(&t, &Site { map: &m, world: &world, charts: None }, &quick(), 3).unwrap();
    (t, world, plan)
}

#[test]
fn plans_over_the_wall_and_the_validator_agrees() {
    let (t, _, plan) = over_the_wall();
    assert!(plan.validator.ok);
    assert_eq!(plan.moves.first().unwrap().from, t.pick);
    assert!((plan.moves.last().unwrap().to.hoist_m - t.set.hoist_m).abs() < 1e-9);
    // The load had to clear the wall (12 m) by the clearance somewhere.
    let highest = plan.steps.iter().map(|s| s.load_height_m).fold(f64::NEG_INFINITY, f64::max);
    assert!(highest >= 13.0 - 1e-6, "load never went over the wall: {highest}");
    for st in &plan.steps[1..plan.steps.len() - 1] {
        assert!(st.min_clearance_m >= st.required_clearance_m - 1e-3, "step {} too close: {:?}", st.n, st);
    }
    // Its steps are as a document reads them back: one a move, in order;
    // a step lost or numbered otherwise is said.
    assert_eq!(plan.steps_not_as_written(&t), None);
    let (mut short, mut renumbered) = (plan.clone(), plan.clone());
    short.steps.pop();
    let n = plan.moves.len();
    assert_eq!(
        short.steps_not_as_written(&t).as_deref(),
        Some(format!("{} steps for {n} moves (the plan stage writes a step for each move)", n - 1).as_str())
    );
    renumbered.steps[0].n = 0;
    assert_eq!(
        renumbered.steps_not_as_written(&t).as_deref(),
        Some("its step 1 is numbered 0 (the plan stage numbers them from 1 in order)")
    );
    // A step's words edited to say another move, or its amount, or words
    // run on past a page's width (their first 80 characters said).
    let said = |p: &liftplan_plan::LiftPlan| p.steps_not_as_written(&t).unwrap_or_default();
    let written = plan.steps[1].text.clone();
    let mut other_words = plan.clone();
    other_words.steps[1].text = "swing +90.0° (counter-clockwise)".into();
    assert_eq!(
        said(&other_words),
        format!(
            "its step 2 is not in the words its move is said in (\"{written}\", the plan stage's; \"swing +90.0° (counter-clockwise)\" read)"
        )
    );
    let mut other_amount = plan.clone();
    other_amount.steps[1].amount += 1e-9;
    assert!(said(&other_amount).starts_with("its step 2 is not in the words"), "{}", said(&other_amount));
    let mut other_operation = plan.clone();
    other_operation.steps[2].operation = "Swing".into();
    other_operation.steps[2].unit = "m".into();
    assert!(said(&other_operation).starts_with("its step 3 is not in the words"), "{}", said(&other_operation));
    let mut run_on = plan.clone();
    run_on.steps[0].text = "é".repeat(400);
    assert!(said(&run_on).ends_with(&format!("\"{}... (400 characters)\" read)", "é".repeat(80))), "{}", said(&run_on));
    // What a step names, longer than the plan stage writes.
    let mut long_name = plan.clone();
    long_name.steps[1].clearance_to = "/PIPE-".to_string() + &"A".repeat(995);
    assert_eq!(
        said(&long_name),
        format!(
            "its step 2's clearance_to is 1001 characters long, longer than any the plan stage writes (at most 1000): \"/PIPE-{}... (1001 characters)\"",
            "A".repeat(74)
        )
    );
    long_name.steps[1].clearance_to.pop();
    assert_eq!(long_name.steps_not_as_written(&t), None);
    long_name.steps[3].chart_cell = Some("x".repeat(1001));
    assert!(said(&long_name).starts_with("its step 4's chart_cell is 1001 characters long"), "{}", said(&long_name));
    // A luff said of a tower crane (a trolley's move) is not in its words.
    let luff = plan.moves.iter().position(|m| m.joint == liftplan_cspace::Joint::Radial).expect("a luff");
    let mut tower = t.clone();
    tower.crane.model = liftplan_core::crane::builtin("tower-hh-60").unwrap();
    assert!(
        plan.steps_not_as_written(&tower).unwrap_or_default().starts_with(&format!("its step {} is not", luff + 1)),
        "{:?}",
        plan.steps_not_as_written(&tower)
    );
}

#[test]
fn same_plan_on_one_and_two_threads() {
    let mesh = site();
    let m = map(&mesh);
    let world = World::new(&mesh, &[], &[]).unwrap();
    let t = task(-14.0);
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| {
            let (p, _) = plan_lift(&t, &Site { map: &m, world: &world, charts: None }, &quick(), 11).unwrap();
            let bits = p.moves.iter().flat_map(|mv| mv.to.to_array()).map(f64::to_bits).collect::<Vec<u64>>();
            (bits, liftplan_plan::revision(&p, &t))
        })
    };
    assert_eq!(run(1), run(2));
}

/// A lift that gives its sling legs' working load limit has them checked
/// before any path is searched: the 5 t skid on four legs to the corners of
/// its 4 x 2 m top, 3 m below the hook, hangs on two diagonal legs with
/// one slack, each at atan(√5 / 3) from the vertical; legs rated below that
/// refuse the lift saying what to change, legs rated above it plan, and the
/// plan carries the check.
#[test]
fn the_sling_legs_are_checked_before_the_path() {
    let mesh = site();
    let m = map(&mesh);
    let world = World::new(&mesh, &[], &[]).unwrap();
    let site = Site { map: &m, world: &world, charts: None };
    let on_legs = |wll_t: f64| {
        let mut spec = spec_of(-14.0);
        spec.rigging.legs = Some(4);
        spec.rigging.leg_wll_t = Some(wll_t);
        spec.resolve(ac700()).unwrap()
    };
    let cos = 3.0 / (5.0f64 + 9.0).sqrt();
    let most_t = 2.5 / cos;
    let e = plan_lift(&on_legs(most_t - 0.01), &site, &quick(), 3).unwrap_err().to_string();
    assert!(e.contains("the sling legs cannot carry the load: 4 legs at the top's corners"), "{e}");
    assert!(e.contains(&format!("{most_t:.2} t")) && e.contains("rigging leg_wll_t"), "{e}");
    let (plan, _) = plan_lift(&on_legs(most_t + 0.01), &site, &quick(), 3).unwrap();
    let c = plan.summary.slings.clone().expect("the plan carries the legs' check");
    assert!((c.max_leg_kg - most_t * 1000.0).abs() < 1e-6, "{c:?}");
    assert!(plan.summary.slings_line().unwrap().starts_with("lift T-1: sling legs: 4 legs"));
    // The centre of gravity known to 0.2 m either way: the legs that carry
    // the skid with it in the middle are refused, at the worst within it.
    let mut known_so_well = on_legs(most_t + 0.01);
    known_so_well.cog_tolerance_m = 0.2;
    let e = plan_lift(&known_so_well, &site, &quick(), 3).unwrap_err().to_string();
    assert!(
        e.contains("the sling legs cannot carry the load")
            && e.contains("within 0.20 m along x and y (load cog_tolerance_m"),
        "{e}"
    );
    // Without a working load limit they are not checked.
    let (plan, _) = plan_lift(&task(-14.0), &site, &quick(), 3).unwrap();
    assert!(plan.summary.slings.is_none());
    // Two legs plumb from a 4 m spreader beam 1.5 m under the hook: the
    // beam carries the 5 t skid, its top legs the skid and its own 0.15 t
    // (2.575 t each at atan(2 / 1.5) from the vertical: 4.29 t).
    let on_beam = |beam_wll_t: f64| {
        let mut spec = spec_of(-14.0);
        spec.rigging.legs = Some(2);
        spec.rigging.leg_wll_t = Some(3.0);
        spec.rigging.spreader = Some(liftplan_core::lift::SpreaderSpec {
            length_m: 4.0,
            below_hook_m: 1.5,
            wll_t: beam_wll_t,
            mass_t: 0.15,
            top_leg_wll_t: Some(4.5),
            width_m: None,
            top_shackle_wll_t: None,
            top_pin_axes: None,
        });
        spec.resolve(ac700()).unwrap()
    };
    let e = plan_lift(&on_beam(4.9), &site, &quick(), 3).unwrap_err().to_string();
    assert!(e.contains("the spreader beam cannot carry the load: 2 legs at the middles of the top's short edges, hanging plumb from a spreader beam"), "{e}");
    assert!(
        e.contains("carries 5.00 t of its 4.90 t working load limit: 102 %") && e.contains("(spreader wll_t)"),
        "{e}"
    );
    let (plan, _) = plan_lift(&on_beam(6.0), &site, &quick(), 3).unwrap();
    let c = plan.summary.slings.clone().expect("the plan carries the beam's check");
    assert_eq!((c.max_leg_kg, c.max_angle_deg), (2500.0, 0.0));
    let top = c.spreader.as_ref().and_then(|s| s.top.clone()).unwrap();
    assert!((top.max_leg_kg - 2575.0 / 0.6).abs() < 1e-6, "{top:?}");
    assert!(plan.summary.slings_line().unwrap().contains("top legs 2.50 and 2.50 m long from pin to hook"));
    // Four legs plumb from a 4 x 2 m frame over the skid's corners, 1.5 m
    // under the hook: the diagonal legs carry the 5 t skid, half each; the
    // top legs, √5 m across and 1.5 m up, the skid and the frame's 0.15 t.
    let on_frame_shackled = |frame_wll_t: f64, top_shackle_wll_t: Option<f64>| {
        let mut spec = spec_of(-14.0);
        spec.rigging.legs = Some(4);
        spec.rigging.leg_wll_t = Some(3.0);
        spec.rigging.spreader = Some(liftplan_core::lift::SpreaderSpec {
            length_m: 4.0,
            below_hook_m: 1.5,
            wll_t: frame_wll_t,
            mass_t: 0.15,
            top_leg_wll_t: Some(5.0),
            width_m: Some(2.0),
            top_shackle_wll_t,
            top_pin_axes: None,
        });
        spec.resolve(ac700()).unwrap()
    };
    let on_frame = |frame_wll_t: f64| on_frame_shackled(frame_wll_t, None);
    // Top shackles of 2 t at the frame's lugs: refused, named.
    let e = plan_lift(&on_frame_shackled(6.0, Some(2.0)), &site, &quick(), 3).unwrap_err().to_string();
    assert!(
        e.contains("the spreader's top shackles cannot carry the load")
            && e.contains("of the top legs' shackles' 2.00 t at the spreader's lugs (in line)")
            && e.contains("(spreader top_shackle_wll_t)"),
        "{e}"
    );
    let e = plan_lift(&on_frame(4.9), &site, &quick(), 3).unwrap_err().to_string();
    assert!(
        e.contains(
            "the spreader frame cannot carry the load: 4 legs at the top's corners, hanging plumb from a spreader frame"
        ),
        "{e}"
    );
    let (plan, _) = plan_lift(&on_frame(6.0), &site, &quick(), 3).unwrap();
    let c = plan.summary.slings.clone().expect("the plan carries the frame's check");
    assert_eq!((c.max_leg_kg, c.max_angle_deg), (2500.0, 0.0));
    let top = c.spreader.as_ref().and_then(|s| s.top.clone()).unwrap();
    assert!((top.max_leg_kg - 2575.0 * 7.25f64.sqrt() / 1.5).abs() < 1e-6, "{top:?}");
}

/// The hoist rope's falls are checked before the path, like the slings: an
/// 8 t skid with its rigging and the 3.5 t block is 11.7 t, more than one
/// fall of the crane file's 10 t carries; on two it plans, and the plan
/// carries the check.
#[test]
fn the_falls_are_checked_before_the_path() {
    let mesh = site();
    let m = map(&mesh);
    let world = World::new(&mesh, &[], &[]).unwrap();
    let site = Site { map: &m, world: &world, charts: None };
    let reeved = |falls: u32| {
        let mut spec = spec_of(-14.0);
        spec.load.mass_t = 8.0;
        spec.crane.falls = Some(falls);
        spec.resolve(ac700()).unwrap()
    };
    let e = plan_lift(&reeved(1), &site, &quick(), 3).unwrap_err().to_string();
    assert!(
        e.contains("is more than 1 fall of 10.00 t each carries (10.00 t): reeve at least 2 falls (crane falls)"),
        "{e}"
    );
    let (plan, _) = plan_lift(&reeved(2), &site, &quick(), 3).unwrap();
    let r = plan.summary.reeving.clone().expect("the plan carries the reeving");
    assert_eq!((r.falls, r.least_falls()), (Some(2), Some(2)));
    assert!(
        plan.summary
            .reeving_line()
            .unwrap()
            .contains("hook load 11.70 t (load, rigging and hook block); on 2 falls of 10.00 t each: 20.00 t, 58 %")
    );
}

/// An 11 kV line held at `points_m`, sagging `sag_m`, neither its least
/// sag nor its swing given, kept Table A's distance off.
fn feeder(name: &str, points_m: Vec<[f64; 3]>, sag_m: f64) -> liftplan_core::power_line::PowerLine {
    liftplan_core::power_line::PowerLine {
        name: name.into(),
        points_m,
        sag_m,
        least_sag_m: None,
        swing_deg: None,
        voltage_kv: 11.0,
        approach_m: None,
        lifts: vec![],
    }
}

/// An overhead line across the way from the pick to the set, 14 m up
/// beyond the wall: the plan keeps every part of the crane, its rope and its
/// load Table A's 3.05 m off the sagging conductor (measured here at points
/// 5 cm apart along it, at 200 samples of every move), where the plan made
/// without it comes within that.
#[test]
fn the_plan_keeps_the_approach_distance_off_a_power_line() {
    let mesh = site();
    let m = map(&mesh);
    let t = task(-14.0);
    let line = feeder("11 kV feeder", vec![[20.0, 6.0, 14.0], [60.0, 6.0, 14.0]], 0.5);
    let conductor: Vec<Point3> = (0..=800).map(|k| Point3::from(line.at(0, k as f64 / 800.0))).collect();
    let nearest = |plan: &liftplan_plan::LiftPlan| nearest_to(plan, &t, &conductor);
    let world = World::new(&mesh, &[], &[]).unwrap();
    let (plain, _) = plan_lift(&t, &Site { map: &m, world: &world, charts: None }, &quick(), 3).unwrap();
    let mut world = World::new(&mesh, &[], &[]).unwrap();
    world.others = liftplan_plan::power_line_boxes(std::slice::from_ref(&line), &t, &quick(), m.spec.cell).unwrap();
    let with_line = m.with_boxes(&world.others);
    let (plan, _) = plan_lift(&t, &Site { map: &with_line, world: &world, charts: None }, &quick(), 3).unwrap();
    assert!(plan.validator.ok);
    // A step's clearance to the line is to its box: its name says so.
    let named = "power line '11 kV feeder' (beyond its 3.05 m approach distance)";
    assert!(
        plan.steps.iter().any(|s| s.clearance_to == named),
        "{:?}",
        plan.steps.iter().map(|s| &s.clearance_to).collect::<Vec<_>>()
    );
    let (kept, without) = (nearest(&plan), nearest(&plain));
    assert!(kept >= 3.048 - 0.03, "the plan comes {kept:.3} m from the conductor");
    assert!(without < 3.048, "the plan made without the line keeps {without:.3} m off it: the test shows nothing");
}

/// How near any part of the crane, its rope or its load comes to any of
/// `points` along `plan` (at 200 samples of every move).
fn nearest_to(plan: &liftplan_plan::LiftPlan, t: &LiftTask, points: &[Point3]) -> f64 {
    let mut least = f64::INFINITY;
    for mv in &plan.moves {
        let (a, b) = (mv.from.to_array(), mv.to.to_array());
        for s in 0..=200 {
            let f = s as f64 / 200.0;
            let v: Vec<f64> = (0..4).map(|d| a[d] + (b[d] - a[d]) * f).collect();
            let c = Config { swing_rad: v[0], radial: v[1], hoist_m: v[2], load_yaw_rad: v[3] };
            for (_, part) in &t.pose_hanging_swept(&c, false).parts {
                for p in points {
                    least = least.min(part.distance_sq_to_point(p).sqrt());
                }
            }
        }
    }
    least
}

/// Where a power line's conductor is held, against what the scans and the
/// plant model show there: a pole scanned at the first support, a post in
/// the model at the second, nothing at the third where the ground round it
/// is scanned (said, to be checked), the fourth beyond the scans.
#[test]
fn a_power_lines_supports_are_looked_for_in_the_scans_and_the_model() {
    use liftplan_core::power_line::PowerLine;
    let mut mesh = TriMesh::default();
    box_part(&mut mesh, "POLE-B", [29.8, -0.2, 0.0], [30.2, 0.2, 9.0]);
    // Ground scanned from x -10 to 50 m, y -10 to 10 m; a pole at the origin, 9 m tall.
    let mut points: Vec<[f64; 3]> =
        (0..121 * 41).map(|n| [-10.0 + 0.5 * (n / 41) as f64, -10.0 + 0.5 * (n % 41) as f64, 0.0]).collect();
    let mut ground = vec![true; points.len()];
    points.extend((0..=90).map(|k| [0.05, 0.0, 0.1 * k as f64]));
    ground.resize(points.len(), false);
    let world = World::new(&mesh, &points, &ground).unwrap();
    let line = feeder("feeder", vec![[0.0, 0.0, 9.0], [30.0, 0.0, 9.0], [45.0, 5.0, 9.0], [200.0, 0.0, 9.0]], 0.5);
    assert_eq!(
        liftplan_plan::supports_said(&line, &world),
        "; supports seen in the scans or the plant model: 1, 2; support 3 at (45.00, 5.00, 9.00) m NOT SEEN, where the scans show the site around (nothing within 1 m of it in plan): CHECK WHERE THE LINE RUNS; outside the scans: support 4"
    );
    let held = PowerLine { points_m: line.points_m[..2].to_vec(), ..line.clone() };
    assert_eq!(liftplan_plan::supports_said(&held, &world), "; its 2 supports seen in the scans or the plant model");
    // A support given 1.5 m off the pole is not taken for it.
    let off = PowerLine { points_m: vec![[1.5, 0.0, 9.0], [30.0, 0.0, 9.0]], ..line.clone() };
    assert!(
        liftplan_plan::supports_said(&off, &world).starts_with(
            "; supports seen in the scans or the plant model: 2; support 1 at (1.50, 0.00, 9.00) m NOT SEEN"
        )
    );
    let unscanned = World::new(&TriMesh::default(), &[], &[]).unwrap();
    assert_eq!(
        liftplan_plan::supports_said(&line, &unscanned),
        "; its supports outside the scans (where it runs is as given)"
    );
}

/// A load hanging 7 m beside a line that sags 4 m at mid-span, level with
/// its lowest point: clear of it hanging plumb (the approach distance and
/// the clearance, 4.05 m, are less than the gap), within it where the
/// wind swings the conductor 45 degrees towards the load (2.8 m sideways
/// at mid-span). The validator given the line's swing refuses the move,
/// naming the line; given it plumb, it passes it.
#[test]
fn the_validator_keeps_the_approach_distance_off_a_swinging_power_line() {
    use liftplan_core::power_line::PowerLine;
    let t = task(-14.0);
    let (_, mut world) = open_slab();
    let at = Config { swing_rad: 0.0, radial: 0.8, hoist_m: 15.0, load_yaw_rad: 0.0 };
    let hoist = Move { joint: Joint::Hoist, from: at, to: Config { hoist_m: 15.5, ..at } };
    let load = t
        .pose_hanging_swept(&at, false)
        .parts
        .iter()
        .find(|(k, _)| *k == liftplan_core::crane::PartKind::Load)
        .unwrap()
        .1
        .center;
    let out = liftplan_core::frame::Vec3::new(load.x, load.y, 0.0).normalize();
    let beside = liftplan_core::frame::Vec3::new(-out.y, out.x, 0.0) * 7.0;
    let support = |along: f64| {
        let p = load + beside + out * along;
        [p.x, p.y, load.z + 4.0]
    };
    let plumb = feeder("11 kV feeder", vec![support(-15.0), support(15.0)], 4.0);
    let mut check = |line: &PowerLine| {
        world.others = liftplan_plan::power_line_boxes(std::slice::from_ref(line), &t, &quick(), 0.25).unwrap();
        validate(&t, None, &world, &rules(), &[hoist], &[false])
    };
    let v = check(&plumb);
    assert!(v.ok, "{:?}", v.problems);
    let v = check(&PowerLine { swing_deg: Some(45.0), ..plumb.clone() });
    assert!(!v.ok && v.problems.iter().any(|p| p.contains("power line '11 kV feeder'")), "{:?}", v.problems);
}

/// A plan's revision (on every page of its PDF, and what `liftplan
/// resume` is told) names what the plan says and where its crane stands,
/// not how long it took to make.
#[test]
fn a_plans_revision_names_its_moves_and_crane_not_its_timings() {
    let (t, _, plan) = over_the_wall();
    let r = liftplan_plan::revision(&plan, &t);
    assert!(r.len() == 8 && r.bytes().all(|b| b.is_ascii_hexdigit() && !b.is_ascii_uppercase()), "{r}");
    let mut slower = plan.clone();
    slower.planning.plan_ms += 250.0;
    slower.planning.cspace_ms += 40.0;
    slower.validator.seconds += 1.5;
    slower.summary.revision = r.clone();
    assert_eq!(liftplan_plan::revision(&slower, &t), r);
    // Its JSON twin, which keeping by revision compares plans by, leaves
    // out the same times and nothing more.
    let json = |p: &liftplan_plan::LiftPlan| {
        let mut p = p.clone();
        p.summary.revision = r.clone();
        liftplan_plan::but_for_timings(&serde_json::to_value(&p).unwrap())
    };
    assert_eq!(json(&slower), json(&plan));
    let mut other = plan.clone();
    other.moves[1].to.hoist_m += 0.001;
    assert_ne!(liftplan_plan::revision(&other, &t), r, "a move 1 mm longer");
    assert_ne!(json(&other), json(&plan), "a move 1 mm longer");
    let mut other = plan.clone();
    other.steps[2].text.push('.');
    assert_ne!(liftplan_plan::revision(&other, &t), r, "a step's words");
    let mut moved = t.clone();
    moved.crane.placement.x_m += 0.1;
    assert_ne!(liftplan_plan::revision(&plan, &moved), r, "the crane 0.1 m away");
    let mut heavier = t.clone();
    heavier.load_mass_kg += 100.0;
    assert_ne!(liftplan_plan::revision(&plan, &heavier), r, "the load 100 kg heavier");
    let mut weighed = t.clone();
    weighed.crane.model.hook.rope_kg_per_m = Some(3.9);
    assert_ne!(liftplan_plan::revision(&plan, &weighed), r, "the crane file weighing its rope");
    let mut heavier_block = t.clone();
    heavier_block.crane.model.hook.mass_kg += 50.0;
    assert_ne!(liftplan_plan::revision(&plan, &heavier_block), r, "a heavier hook block");
    // A crane file key not given is not in what is hashed, so a key that a
    // later version learns to read leaves the revision of a plan that does
    // not give it as it was.
    let mut bare = t.crane.model.hook;
    (bare.rated_t, bare.line_pull_t, bare.max_falls, bare.rope_m, bare.rope_lead_m) = (None, None, None, None, None);
    let hook = serde_json::to_value(bare).unwrap();
    for key in ["rope_kg_per_m", "rope_m", "rope_lead_m", "rated_t", "line_pull_t", "max_falls"] {
        assert!(hook.get(key).is_none(), "{key}: {hook}");
    }
}

#[test]
fn pick_inside_an_obstacle_is_refused_with_part_and_object() {
    let mut mesh = site();
    // A beam right over the pick position, 1.5 m above the load.
    box_part(&mut mesh, "BEAM-OVER-PICK", [18.0, -16.0, 4.0], [26.0, -12.0, 4.5]);
    let m = map(&mesh);
    let world = World::new(&mesh, &[], &[]).unwrap();
    let err =
        plan_lift(&task(-14.0), &Site { map: &m, world: &world, charts: None }, &quick(), 1).unwrap_err().to_string();
    assert!(err.contains("BEAM-OVER-PICK"), "{err}");
    assert!(err.contains("lifted-off pick"), "{err}");
    // A post 0.1 m beside the load, within the landing zone's clearance but
    // not touching: said as too close, with the clearances, not as a collision.
    let mut mesh = site();
    box_part(&mut mesh, "POST-BESIDE-PICK", [24.1, -14.2, 0.0], [24.5, -13.8, 6.0]);
    let m = map(&mesh);
    let world = World::new(&mesh, &[], &[]).unwrap();
    let err =
        plan_lift(&task(-14.0), &Site { map: &m, world: &world, charts: None }, &quick(), 1).unwrap_err().to_string();
    assert!(
        err.contains(
            "lifted-off pick configuration is not allowed: closer than the clearance allows: load and POST-BESIDE-PICK"
        ),
        "{err}"
    );
    assert!(err.contains("(clearance_m 1.00 m, 0.20 m in a landing zone)"), "{err}");
}

/// A set position declared into the slab it is set on: refused, saying by
/// how much the load's underside lies below the slab's top.
#[test]
fn a_set_position_below_the_top_of_its_support_says_by_how_much() {
    let mesh = site();
    let m = map(&mesh);
    let world = World::new(&mesh, &[], &[]).unwrap();
    let mut spec: LiftSpec = toml::from_str(&format!(
        "{}\n",
        r#"
id = "T-1"
load = { name = "skid", mass_t = 5.0, size_m = [4.0, 2.0, 2.0] }
crane = { model = "ac-700", position_m = [0.0, 0.0], heading_deg = 0.0, boom_m = 40.0, chart_config = "none" }
pick = { x_m = 22.0, y_m = -14.0, z_m = 0.5, yaw_deg = 0.0 }
set = { x_m = 22.0, y_m = 14.0, z_m = -0.2, yaw_deg = 90.0 }
"#
    ))
    .unwrap();
    let t = spec.clone().resolve(ac700()).unwrap();
    let err = plan_lift(&t, &Site { map: &m, world: &world, charts: None }, &quick(), 1).unwrap_err().to_string();
    assert!(err.contains("the set-down is not clear: load touches SLAB"), "{err}");
    assert!(
        err.contains("the load's underside there, z = -0.20 m, is about 0.20 m below the top of what stands under it (about z = 0.00 m"),
        "{err}"
    );
    // The scans have the slab's top there at z = -0.2 m, where the load is
    // set: the model may stand too high, and the refusal says both.
    let scanned: Vec<[f64; 3]> =
        (0..21 * 21).map(|n| [17.0 + (n % 21) as f64 * 0.5, 9.0 + (n / 21) as f64 * 0.5, -0.2]).collect();
    let scanned_world = World::new(&mesh, &scanned, &vec![true; scanned.len()]).unwrap();
    let err =
        plan_lift(&t, &Site { map: &m, world: &scanned_world, charts: None }, &quick(), 1).unwrap_err().to_string();
    assert!(
        err.contains("is about 0.20 m below the top of what stands under it as the plant model has it (SLAB, up to z = 0.00 m), but the scans have that top at z = -0.20 m: CHECK [plant] translate_m's height (the model may stand 0.20 m too high) or set z_m"),
        "{err}"
    );
    // Deeper, the load lifted off above it is already too close.
    spec.set.z_m = Some(-0.6);
    let t = spec.clone().resolve(ac700()).unwrap();
    let err = plan_lift(&t, &Site { map: &m, world: &world, charts: None }, &quick(), 1).unwrap_err().to_string();
    assert!(err.contains("the configuration above the set position is not allowed"), "{err}");
    assert!(err.contains("is about 0.60 m below the top of what stands under it (about z = 0.00 m, as the depth map holds it): CHECK set z_m"), "{err}");
    // Set on the slab, it is not said.
    spec.set.z_m = Some(0.0);
    let t = spec.resolve(ac700()).unwrap();
    if let Err(e) = plan_lift(&t, &Site { map: &m, world: &world, charts: None }, &quick(), 1) {
        assert!(!e.to_string().contains("below the top of what stands under it"), "{e}");
    }
}

/// A lift-off shorter than the landing zone's clearance leaves the load
/// within it of its support: refused naming the key, before the search.
#[test]
fn a_lift_off_within_the_landing_clearance_is_refused_naming_the_key() {
    let mesh = site();
    let m = map(&mesh);
    let world = World::new(&mesh, &[], &[]).unwrap();
    let site = Site { map: &m, world: &world, charts: None };
    let mut t = task(-14.0);
    t.liftoff_m = 0.1;
    let err = plan_lift(&t, &site, &quick(), 1).unwrap_err().to_string();
    assert!(err.contains("liftoff_m 0.10 m is less than the clearance the load keeps"), "{err}");
    assert!(err.contains("set liftoff_m to 0.20 m or more"), "{err}");
    t.liftoff_m = 0.2;
    assert!(plan_lift(&t, &site, &quick(), 1).is_ok());
}

/// What the load meets at its pick where only scan points stand (no name
/// to find it by) is placed: the nearest scan point and the side of the
/// load it is on, and, at the pick, that it may be the load itself standing
/// off its declared position (here: the scans have its east end 0.12 m
/// beyond the box the lift gives it).
#[test]
fn scan_points_the_load_meets_at_its_pick_are_placed() {
    let mesh = site();
    let t = task(-14.0);
    // The load's box at pick: x 20 to 24, y -15 to -13, z 0.5 to 2.5.
    let end: Vec<[f64; 3]> =
        (0..21 * 19).map(|n| [24.12, -15.0 + (n % 21) as f64 * 0.1, 0.6 + (n / 21) as f64 * 0.1]).collect();
    let world = World::new(&mesh, &end, &vec![false; end.len()]).unwrap();
    let inp = liftplan_depthmap::Inputs { points: end.clone(), ground: vec![false; end.len()], mesh: mesh.clone() };
    let m = liftplan_depthmap::build_cpu(&inp, &liftplan_depthmap::Settings::default()).unwrap().0;
    let err = plan_lift(&t, &Site { map: &m, world: &world, charts: None }, &quick(), 1).unwrap_err().to_string();
    assert!(err.contains("the lifted-off pick configuration is not allowed"), "{err}");
    assert!(
        err.contains("the scanned point nearest the load there is at x 24.12, y -15.00, z 1.00 m, 0.12 m beyond an end of the load's box (its size_m[0] side): if that is the load itself"),
        "{err}"
    );
    assert!(err.contains("CHECK pick x_m, y_m, yaw_deg and size_m against the scans"), "{err}");
}

/// A plant model holds what a lift installs where it is installed: the
/// load set there meets its own copy, which the refusal names as such and
/// says how to leave out (it read as the load sunk 2 m into its support:
/// "CHECK set z_m").
#[test]
fn the_load_itself_in_the_plant_model_at_its_set_position_is_named() {
    // The test lift on the site with one more box of the model: the
    // refusal, or none where it plans.
    let with_box = |name: &str, lo: [f64; 3], hi: [f64; 3]| {
        let mut mesh = site();
        box_part(&mut mesh, name, lo, hi);
        let world = World::new(&mesh, &[], &[]).unwrap();
        let m = map(&mesh);
        plan_lift(&task(-14.0), &Site { map: &m, world: &world, charts: None }, &quick(), 1)
            .err()
            .map(|e| e.to_string())
    };
    // The load's box at its set position: x 21 to 23, y 12 to 16, z 0.5 to 2.5.
    let err = with_box("SKID-7", [21.0, 12.0, 0.5], [23.0, 16.0, 2.5]).unwrap();
    assert!(err.contains("the configuration above the set position is not allowed"), "{err}");
    assert!(
        err.contains("the plant model's SKID-7 fills the load's box there (their bounding boxes 100 % alike): if it is this load where it is installed, leave it out of the plant model ([plant] exclude = [\"SKID-7\"])"),
        "{err}"
    );
    assert!(!err.contains("CHECK set z_m") && !err.contains("turned"), "{err}");
    // The copy along x where the set's yaw turns the load along y: the
    // set's yaw is a quarter turn off what the model shows.
    let err = with_box("SKID-7", [20.0, 13.0, 0.5], [24.0, 15.0, 2.5]).unwrap();
    assert!(
        err.contains("the plant model's SKID-7 fills the load's box there turned a quarter turn from the load's set yaw_deg (their bounding boxes 100 % alike)"),
        "{err}"
    );
    assert!(err.contains("and CHECK set yaw_deg: the model has it turned 90° from it"), "{err}");
    // A part of the model beside the set position is not taken for the load.
    if let Some(e) = with_box("PUMP", [21.0, 16.3, 0.0], [23.0, 17.0, 2.5]) {
        assert!(!e.contains("fills the load's box"), "{e}");
    }
}

/// A wall too tall to lift the load over, with the swing held to the short
/// way round: the refusal says how far the load gets and what stops it,
/// how high the load hangs there at most, and what to change (it said
/// only "try a larger population ..., or check the obstacles in the C-space
/// picture", a picture that a failed plan does not write).
#[test]
fn no_path_says_how_far_the_load_gets_and_what_stops_it() {
    let mut mesh = TriMesh::default();
    box_part(&mut mesh, "TALL-WALL", [14.0, -1.0, 0.0], [40.0, 1.0, 30.0]);
    // Closing the way between the wall and the crane, over its body.
    box_part(&mut mesh, "BRIDGE", [-5.0, -1.0, 20.0], [14.0, 1.0, 30.0]);
    box_part(&mut mesh, "SLAB", [-40.0, -40.0, -0.3], [60.0, 40.0, 0.0]);
    let m = map(&mesh);
    let world = World::new(&mesh, &[], &[]).unwrap();
    let mut t = task(-14.0);
    t.swing_range_rad = Some((-60f64.to_radians(), 60f64.to_radians()));
    let Err(e) = plan_lift(&t, &Site { map: &m, world: &world, charts: None }, &quick(), 1) else {
        panic!("planned through a wall 30 m tall");
    };
    let err = e.to_string();
    assert!(err.contains("no collision-free, chart-compliant path found"), "{err}");
    assert!(err.contains("the short way round, the load gets no farther than swing"), "{err}");
    assert!(!err.contains("long way"), "{err}");
    assert!(err.contains("and TALL-WALL at ") || err.contains("and BRIDGE at "), "{err}");
    assert!(err.contains("try another crane position"), "{err}");
    // The pick is at -32.5° from the heading, the wall across 0°.
    let far: f64 = err.split("no farther than swing ").nth(1).unwrap().split('°').next().unwrap().parse().unwrap();
    assert!((-32.5..0.0).contains(&far), "{err}");
}

#[test]
fn validator_rejects_a_swing_through_the_wall() {
    let mesh = site();
    let world = World::new(&mesh, &[], &[]).unwrap();
    let t = task(-14.0);
    let start = t.start();
    let goal = t.goal();
    let mid = Config { swing_rad: goal.swing_rad, ..start };
    let moves = vec![
        Move { joint: Joint::Swing, from: start, to: mid },
        Move { joint: Joint::Rotate, from: mid, to: Config { load_yaw_rad: goal.load_yaw_rad, ..mid } },
    ];
    let rules = rules();
    let v = validate(&t, None, &world, &rules, &moves, &[false, false]);
    assert!(!v.ok);
    assert!(v.problems.iter().any(|p| p.contains("WALL")), "{:?}", v.problems);
}

/// Beside the wall, its side 1.2 m off the wall's face, where the lift keeps
/// 1 m: clear with the load hanging plumb. Planned for the wind, a sudden
/// gust at the permissible speed swings it 0.45 m or so (hanging 30 m and
/// more below the boom head), and the checker, the validator and the
/// planner keep it off the wall by that, saying why.
#[test]
fn the_load_keeps_its_clearance_from_the_wall_swung_by_a_gust() {
    let mesh = site();
    let (m, world) = (map(&mesh), World::new(&mesh, &[], &[]).unwrap());
    // Its underside at `z_m`; 4 m along x, 2 m across: its side at y = -2.2,
    // the wall's face at -1.
    let beside = |z_m: f64, wind: bool| {
        let mut sp = spec_of(-14.0);
        sp.pick = toml::from_str(&format!("x_m = 24.0\ny_m = -3.2\nz_m = {z_m}\nyaw_deg = 0.0")).unwrap();
        if wind {
            sp.wind = toml::from_str("chart_ms = 9.8\ncw = 1.2").unwrap();
        }
        sp.resolve(ac700()).unwrap()
    };
    let s = quick();
    let hoist = |t: &LiftTask| {
        let up = Config { hoist_m: t.pick.hoist_m - 0.5, ..t.pick };
        validate(t, None, &world, &rules(), &[Move { joint: Joint::Hoist, from: t.pick, to: up }], &[false])
    };
    let checked = |t: &LiftTask| {
        let cs = liftplan_cspace::CSpace::build(&liftplan_cspace::Problem { task: t, chart: None, map: &m }, &s.cspace);
        liftplan_cspace::Checker::new(&cs, &m, t, vec![], s.cspace.sample_m).config(&t.pick)
    };
    let plumb = beside(3.0, false);
    assert!(checked(&plumb).is_ok());
    assert!(hoist(&plumb).ok, "{:?}", hoist(&plumb).problems);
    let windy = beside(3.0, true);
    let swing_m = windy.gust_swing_per_m * (windy.crane.sheave(&windy.pick).z - 3.0);
    assert!((0.4..0.6).contains(&swing_m), "{swing_m}");
    let b = checked(&windy).unwrap_err();
    assert_eq!((b.reason.as_str(), b.object.as_deref()), (liftplan_cspace::TOO_CLOSE, Some("WALL")), "{b}");
    let v = hoist(&windy);
    assert!(
        !v.ok && v.problems.iter().any(|p| p.contains("load is 0.7") && p.contains("WALL (needs 1.00 m)")),
        "{:?}",
        v.problems
    );
    // Picked from the slab there and lifted over the wall: the plan made
    // with the load hanging plumb hoists it up beside the wall, which a gust
    // would swing too close; planned for the wind, the lift keeps off it.
    let site = Site { map: &m, world: &world, charts: None };
    let (plumb, windy) = (beside(0.0, false), beside(0.0, true));
    let (plan, _) = plan_lift(&plumb, &site, &s, 3).unwrap();
    assert_eq!(plan.gust_swing_per_m, 0.0);
    let landing: Vec<bool> = (0..plan.moves.len()).map(|i| i == 0 || i + 1 == plan.moves.len()).collect();
    // (These rules draw no landing zones: only what they say of the wall counts.)
    let of_the_wall = |t: &LiftTask| {
        let v = validate(t, None, &world, &rules(), &plan.moves, &landing);
        v.problems.into_iter().filter(|p| p.contains("WALL")).collect::<Vec<_>>()
    };
    assert_eq!(of_the_wall(&plumb), Vec::<String>::new());
    let near = of_the_wall(&windy);
    assert!(!near.is_empty() && near.iter().all(|p| p.contains("move 2 (Hoist)") && p.contains(" is 0.")), "{near:?}");
    let (plan, _) = plan_lift(&windy, &site, &s, 3).unwrap();
    assert!(plan.validator.ok && plan.gust_swing_per_m == windy.gust_swing_per_m);
    // And where it cannot keep off, the refusal says the load was swung.
    let mut tight = windy.clone();
    tight.gust_swing_per_m = 0.1;
    let e = plan_lift(&tight, &site, &s, 3).unwrap_err().to_string();
    assert!(e.contains("closer than the clearance allows: load and WALL"), "{e}");
    assert!(e.contains("what hangs swung 10.0 cm per metre it hangs below the boom head, as far as a sudden gust at the permissible wind can swing it (wind plan_for_swing)"), "{e}");
}

/// Beside the wall as above, its centre of gravity known to 0.5 m either
/// way: the hook hangs over it wherever it lies, so the load may hang 0.5 m
/// nearer the wall, 0.7 m off it. The checker and the validator refuse that
/// (but in a lift-off, held at its support), the planner keeps it off the
/// wall, and where it cannot, says why.
#[test]
fn the_load_keeps_its_clearance_wherever_its_centre_of_gravity_lies() {
    let mesh = site();
    let (m, world) = (map(&mesh), World::new(&mesh, &[], &[]).unwrap());
    let beside = |z_m: f64, cog_tolerance_m: f64| {
        let mut sp = spec_of(-14.0);
        sp.pick = toml::from_str(&format!("x_m = 24.0\ny_m = -3.2\nz_m = {z_m}\nyaw_deg = 0.0")).unwrap();
        sp.load.cog_tolerance_m = cog_tolerance_m;
        sp.resolve(ac700()).unwrap()
    };
    let s = quick();
    let known = beside(3.0, 0.5);
    let cs =
        liftplan_cspace::CSpace::build(&liftplan_cspace::Problem { task: &known, chart: None, map: &m }, &s.cspace);
    let b = liftplan_cspace::Checker::new(&cs, &m, &known, vec![], s.cspace.sample_m).config(&known.pick).unwrap_err();
    assert_eq!((b.reason.as_str(), b.object.as_deref()), (liftplan_cspace::TOO_CLOSE, Some("WALL")), "{b}");
    let up = [Move {
        joint: Joint::Hoist,
        from: known.pick,
        to: Config { hoist_m: known.pick.hoist_m - 0.5, ..known.pick },
    }];
    let v = validate(&known, None, &world, &rules(), &up, &[false]);
    assert!(
        !v.ok && v.problems.iter().any(|p| p.contains("load is 0.70") && p.contains("WALL (needs 1.00 m)")),
        "{:?}",
        v.problems
    );
    assert!(validate(&known, None, &world, &rules(), &up, &[true]).ok);
    assert!(validate(&beside(3.0, 0.0), None, &world, &rules(), &up, &[false]).ok);
    // Picked from the slab there and lifted over the wall: the plan made
    // for the centre of gravity as given hoists the load up beside the
    // wall, too close to it if the centre of gravity lies 0.5 m off; made
    // with the tolerance, it keeps off.
    let site = Site { map: &m, world: &world, charts: None };
    let (plan, _) = plan_lift(&beside(0.0, 0.0), &site, &s, 3).unwrap();
    let landing: Vec<bool> = (0..plan.moves.len()).map(|i| i == 0 || i + 1 == plan.moves.len()).collect();
    let v = validate(&beside(0.0, 0.5), None, &world, &rules(), &plan.moves, &landing);
    assert!(v.problems.iter().any(|p| p.contains("WALL")), "{:?}", v.problems);
    let (plan, _) = plan_lift(&beside(0.0, 0.5), &site, &s, 3).unwrap();
    assert!(plan.validator.ok);
    // Known to a metre, it cannot keep off: the refusal says why.
    let e = plan_lift(&beside(0.0, 1.0), &site, &s, 3).unwrap_err().to_string();
    assert!(e.contains("closer than the clearance allows: load and WALL"), "{e}");
    assert!(e.contains("the load and its rigging 1.00 m off along the load's x and y, as far as its centre of gravity may lie off (load cog_tolerance_m)"), "{e}");
}

/// The falls take rope: with the hoist rope just long enough on 4 falls for
/// the hook to reach the pick and the set (and half a metre more), the lift
/// plans within it, and the checker and the validator refuse the hook
/// lowered a metre past it, as they refuse it past the hook's travel.
#[test]
fn the_hook_hangs_no_lower_than_the_falls_let_it() {
    let mesh = site();
    let (m, world) = (map(&mesh), World::new(&mesh, &[], &[]).unwrap());
    let plain = task(-14.0);
    let reach_m = plain.pick.hoist_m.max(plain.set.hoist_m) + 0.5;
    let mut model = ac700();
    (model.hook.rope_m, model.hook.rope_lead_m) = (Some(20.0 + 40.0 + 4.0 * reach_m), Some(20.0));
    let mut spec = spec_of(-14.0);
    spec.crane.falls = Some(4);
    let t = spec.resolve(model).unwrap();
    assert!((t.crane.limits().hoist_m.1 - reach_m).abs() < 1e-9 && reach_m < plain.crane.limits().hoist_m.1);
    let s = quick();
    let site = Site { map: &m, world: &world, charts: None };
    let (plan, _) = plan_lift(&t, &site, &s, 3).unwrap();
    assert!(plan.validator.ok);
    assert!(plan.moves.iter().all(|mv| mv.from.hoist_m.max(mv.to.hoist_m) <= reach_m + 1e-9));
    hook_refused_past(&t, None, &world, &m, &s, reach_m);
    // The same move on the rope's full travel: within the limits.
    let v = validate(
        &plain,
        None,
        &world,
        &rules(),
        &[Move {
            joint: Joint::Hoist,
            from: Config { hoist_m: reach_m, ..plain.pick },
            to: Config { hoist_m: reach_m + 1.0, ..plain.pick },
        }],
        &[false],
    );
    assert!(!v.problems.iter().any(|p| p.contains("outside the crane's joint limits")), "{:?}", v.problems);
}

/// The hoist rope below the boom head is part of the gross load: on 2 falls
/// over the hook's 110 m travel, 3.9 kg/m is 0.86 t, and a chart that
/// carries the 8.7 t without it (9 t) refuses the pick with it, saying how
/// much is rope and what counts less. Given a longest rope half a metre past
/// what the pick and the set need, the lift plans within it with the rope
/// counted on it, and the validator and the checker refuse the hook a metre
/// below it.
#[test]
fn the_hoist_rope_below_the_head_is_part_of_the_gross_load() {
    let mesh = site();
    let (m, world) = (map(&mesh), World::new(&mesh, &[], &[]).unwrap());
    let table = chart_of(&[(10.0, 9.0), (40.0, 9.0)], "none");
    let site = Site { map: &m, world: &world, charts: Some(&table) };
    let model = builtin("ac-700").unwrap();
    assert_eq!(model.hook.rope_kg_per_m, Some(3.9));
    let weighed = |longest: Option<f64>| {
        let mut spec = spec_of(-14.0);
        (spec.crane.falls, spec.crane.longest_rope_m) = (Some(2), longest);
        spec.resolve(model.clone()).unwrap()
    };
    let plain = task(-14.0);
    assert!(plan_lift(&plain, &site, &quick(), 3).unwrap().0.validator.ok);
    let t = weighed(None);
    assert!((t.gross_kg() - (8700.0 + 2.0 * 110.0 * 3.9)).abs() < 1e-9, "{}", t.gross_kg());
    let e = plan_lift(&t, &site, &quick(), 3).unwrap_err().to_string();
    assert!(e.contains("pick is over capacity: gross 9558 kg"), "{e}");
    assert!(
        e.contains("858 kg of the gross is the hoist rope, counted at 110.00 m on each of 2 falls: a shorter crane.longest_rope_m, if the lift's hook need not hang so low, counts less"),
        "{e}"
    );
    // It names the rope the ends need, and the gross on it.
    let need = (plain.pick.hoist_m.max(plain.set.hoist_m) * 100.0).ceil() / 100.0;
    let on_need = 8700.0 + 2.0 * 3.9 * need;
    assert!(on_need <= 9000.0, "{on_need}");
    assert!(
        e.contains(&format!(
            "; the pick and the set need {need:.2} m of it: with longest_rope_m = {need:.2} (the path may need more) the gross would be {on_need:.0} kg, within the 9000 kg the chart gives at "
        )),
        "{e}"
    );
    // On a chart of 8.8 t even that is too much, and said so.
    let tight = chart_of(&[(10.0, 8.8), (40.0, 8.8)], "none");
    let e = plan_lift(&weighed(None), &Site { charts: Some(&tight), ..site }, &quick(), 3).unwrap_err().to_string();
    assert!(
        on_need > 8800.0 && e.contains(&format!("the gross would be {on_need:.0} kg, still more than the 8800 kg")),
        "{e}"
    );
    let longest = plain.pick.hoist_m.max(plain.set.hoist_m) + 0.5;
    let t = weighed(Some(longest));
    assert!(t.gross_kg() <= 9000.0 && t.crane.limits().hoist_m.1 == longest, "{} {longest}", t.gross_kg());
    let s = quick();
    let (plan, _) = plan_lift(&t, &site, &s, 3).unwrap();
    assert!(plan.validator.ok, "{:?}", plan.validator.problems);
    assert!(plan.moves.iter().all(|mv| mv.from.hoist_m.max(mv.to.hoist_m) <= longest + 1e-9));
    let line = plan.summary.reeving_line().unwrap();
    assert!(
        line.contains(&format!(
            "the {:.2} t of hoist rope: 2 falls of up to {longest:.2} m below the boom head (crane longest_rope_m) at 3.90 kg/m",
            2.0 * longest * 3.9 / 1000.0
        )),
        "{line}"
    );
    hook_refused_past(&t, Some(table.config("none").unwrap()), &world, &m, &s, longest);
}

/// The validator (reading `chart` where given) and the C-space's checker
/// refuse the hook lowered from `longest_m` of rope to a metre past it, at
/// the pick: outside the crane's joint limits.
fn hook_refused_past(
    t: &LiftTask,
    chart: Option<&liftplan_core::capacity::ChartConfig>,
    world: &World,
    m: &Mdm,
    s: &Settings,
    longest_m: f64,
) {
    let low = Config { hoist_m: longest_m + 1.0, ..t.pick };
    let v = validate(
        t,
        chart,
        world,
        &rules(),
        &[Move { joint: Joint::Hoist, from: Config { hoist_m: longest_m, ..t.pick }, to: low }],
        &[false],
    );
    assert!(v.problems.iter().any(|p| p.contains("outside the crane's joint limits")), "{:?}", v.problems);
    let cs = liftplan_cspace::CSpace::build(&liftplan_cspace::Problem { task: t, chart: None, map: m }, &s.cspace);
    assert!(liftplan_cspace::Checker::new(&cs, m, t, vec![], s.cspace.sample_m).config(&low).is_err());
}

/// A chart configuration "none" for the test crane's 40 m boom: its rows
/// (radius m, capacity t), their cells on the chart's `sheet`.
fn chart_of(rows: &[(f64, f64)], sheet: &str) -> liftplan_core::capacity::CapacityTable {
    use liftplan_core::capacity::{CapacityRow, CapacityTable};
    let rows: Vec<CapacityRow> = rows
        .iter()
        .enumerate()
        .map(|(i, &(r, t))| CapacityRow {
            config: "none".into(),
            boom_m: 40.0,
            radius_m: r,
            capacity_kg: t * 1000.0,
            cell: format!("test.xlsx [{sheet}!B{}]", i + 2),
        })
        .collect();
    CapacityTable::from_rows(&rows).unwrap()
}

/// A chart for the test crane's 40 m boom: ample capacity up to 28 m radius,
/// less than the test load's gross weight beyond.
fn chart(far_capacity_t: f64) -> liftplan_core::capacity::CapacityTable {
    chart_of(&[(10.0, 50.0), (20.0, 50.0), (28.0, 50.0), (34.0, far_capacity_t), (40.0, far_capacity_t)], "main")
}

/// A pick over capacity says what would carry it, as the charts read tell:
/// how far out the lift's boom and configuration carry it, and which other
/// boom length and which configuration of the same chart file carry it at
/// that radius (a configuration of another crane's chart file is not one).
#[test]
fn a_pick_over_capacity_says_what_would_carry_it() {
    use liftplan_core::capacity::{CapacityRow, CapacityTable};
    let row = |config: &str, file: &str, boom_m: f64, radius_m: f64, t: f64| CapacityRow {
        config: config.into(),
        boom_m,
        radius_m,
        capacity_kg: t * 1000.0,
        cell: format!("{file} [{config}!R{radius_m}B{boom_m}]"),
    };
    let mut rows = Vec::new();
    for (r, at40, at30, heavy) in
        [(10.0, 50.0, 50.0, 60.0), (20.0, 50.0, 50.0, 60.0), (28.0, 3.0, 10.0, 20.0), (40.0, 3.0, 5.0, 20.0)]
    {
        rows.push(row("none", "test.xlsx", 40.0, r, at40));
        rows.push(row("none", "test.xlsx", 30.0, r, at30));
        rows.push(row("heavy", "test.xlsx", 40.0, r, heavy));
        rows.push(row("other crane", "other.xlsx", 40.0, r, heavy));
        // Booms the chart lists that could not hang the load at the pick
        // (26.08 m from the slewing axis, its underside at 0.5 m): too short
        // to reach it, too short to lift it high enough there, and longer
        // than the crane model's longest (62.4 m).
        for b in [20.0, 29.0, 70.0] {
            rows.push(row("none", "test.xlsx", b, r, heavy));
        }
    }
    let table = CapacityTable::from_rows(&rows).unwrap();
    let mesh = site();
    let m = map(&mesh);
    let world = World::new(&mesh, &[], &[]).unwrap();
    let t = task(-14.0);
    let e = plan_lift(&t, &Site { map: &m, world: &world, charts: Some(&table) }, &quick(), 3).unwrap_err().to_string();
    assert!(e.contains("pick is over capacity") && e.contains("gives 3000 kg"), "{e}");
    assert!(
        e.contains("'none' on its 40.00 m boom carries 8700 kg out to a radius of 20.00 m (test.xlsx [none!R20B40]): the crane set up with its slewing axis that near the pick position could lift it"),
        "{e}"
    );
    assert!(
        e.contains("it is carried by the 30.00 m boom (10000 kg, test.xlsx [none!R28B30]; boom_m), 'heavy' (20000 kg, test.xlsx [heavy!R28B40]; chart_config); the chart's 20.00 m boom carries it at 26.08 m (20000 kg, test.xlsx [none!R28B20]), BUT with it the crane reaches "),
        "{e}"
    );
    assert!(e.contains(" m from its slewing axis, not the pick position's 26.08 m; the chart's 29.00 m boom carries it at 26.08 m (20000 kg, test.xlsx [none!R28B29]), BUT its head stands too low there: it hangs the load's underside at z = "), "{e}");
    assert!(e.contains(" m at the highest, under the pick position's z = 0.50 m; the chart's 70.00 m boom carries it at 26.08 m (20000 kg, test.xlsx [none!R28B70]), BUT the crane model AC 700 (approx.) has no 70.00 m boom"), "{e}");
    assert!(!e.contains("other crane"), "{e}");
    // Only a boom that cannot reach the pick carries it there.
    let short: Vec<CapacityRow> =
        rows.iter().filter(|r| r.config == "none" && [40.0, 20.0].contains(&r.boom_m)).cloned().collect();
    let table = CapacityTable::from_rows(&short).unwrap();
    let e = plan_lift(&t, &Site { map: &m, world: &world, charts: Some(&table) }, &quick(), 3).unwrap_err().to_string();
    assert!(
        e.contains("at 26.08 m no other boom length and no other configuration of its chart file carries it where the crane could hang it; the chart's 20.00 m boom carries it at 26.08 m"),
        "{e}"
    );
}

#[test]
fn validator_rejects_a_step_over_capacity() {
    let mesh = site();
    let world = World::new(&mesh, &[], &[]).unwrap();
    let t = task(-14.0);
    let start = t.start();
    // Hoist 10 m clear of everything, then luff down to a 32 m radius, away
    // from the wall: geometrically free, but the chart allows only 3 t there.
    let up = Config { hoist_m: start.hoist_m - 10.0, ..start };
    let out = Config { radial: (34.5f64 / 40.0).acos(), ..up };
    assert!((t.crane.radius_m(out.radial) - 32.0).abs() < 1e-9);
    let moves =
        vec![Move { joint: Joint::Hoist, from: start, to: up }, Move { joint: Joint::Radial, from: up, to: out }];
    let rules = rules();
    let tight = chart(3.0);
    let v = validate(&t, Some(tight.config("none").unwrap()), &world, &rules, &moves, &[false, false]);
    assert!(!v.ok, "a luff to 32 m with {:.1} t gross on a 3 t row passed", t.gross_kg() / 1000.0);
    assert!(v.problems.iter().any(|p| p.contains("over capacity")), "{:?}", v.problems);
    assert!(v.moves[0].problems.is_empty(), "the hoist stays within 28 m: {:?}", v.moves[0].problems);
    // The same moves with capacity to spare everywhere pass: the refusal above
    // was the chart's, not a collision.
    let ample = chart(50.0);
    let v = validate(&t, Some(ample.config("none").unwrap()), &world, &rules, &moves, &[false, false]);
    assert!(v.ok, "{:?}", v.problems);
}

/// The tower crane's lift over the wall ([`tower_task`]).
const TOWER_LIFT: &str = r#"
id = "T-2"
description = "tower crane lift over a wall"
load = { name = "skid", mass_t = 5.0, size_m = [4.0, 2.0, 2.0], cog_m = [0.0, 0.0, 0.0] }
rigging = { mass_t = 0.2, height_m = 3.0 }
crane = { model = "tower-hh-60", position_m = [0.0, 0.0], ground_z_m = 0.0, heading_deg = 0.0, chart_config = "none" }
pick = { x_m = 22.0, y_m = -14.0, z_m = 0.5, yaw_deg = 0.0 }
set = { x_m = 30.0, y_m = 20.0, z_m = 0.5, yaw_deg = 90.0 }
clearance_m = 1.0
liftoff_m = 0.5
"#;

fn tower_task() -> LiftTask {
    let spec: LiftSpec = toml::from_str(TOWER_LIFT).unwrap();
    spec.resolve(builtin("tower-hh-60").unwrap()).unwrap()
}

#[test]
fn tower_crane_plans_over_the_wall_with_the_trolley() {
    let mesh = site();
    let m = map(&mesh);
    let world = World::new(&mesh, &[], &[]).unwrap();
    let t = tower_task();
    let mut s = quick();
    s.cspace.trolley_step_m = 0.5;
    let (plan, _) = plan_lift(&t, &Site { map: &m, world: &world, charts: None }, &s, 5).unwrap();
    assert!(plan.validator.ok, "{:?}", plan.validator.problems);
    // Over the wall or round its inner end (it starts 14 m out): either way
    // every step keeps the clearance.
    for st in &plan.steps[1..plan.steps.len() - 1] {
        assert!(st.min_clearance_m >= st.required_clearance_m - 1e-3, "step {} too close: {:?}", st.n, st);
    }
    // The radius changes (26.1 m at the pick, 36.1 m at the set) with the
    // trolley, and the steps say so in metres.
    assert!(plan.moves.iter().any(|mv| mv.joint == Joint::Radial));
    assert!(plan.steps.iter().any(|st| st.operation.to_lowercase().contains("trolley")), "{:?}", plan.steps);
    let last = plan.moves.last().unwrap().to;
    assert!((t.crane.radius_m(last.radial) - 30f64.hypot(20.0)).abs() < 1e-6);
}

/// A tower crane's falls take rope along its jib: with the hoist rope just
/// long enough on 2 falls for the hook to reach the pick and the set below
/// the trolley (and half a metre more), the lift plans within it, every
/// hoist kept to that rope, and validates.
#[test]
fn a_tower_cranes_hook_hangs_no_lower_than_its_falls_let_it() {
    let mesh = site();
    let (m, world) = (map(&mesh), World::new(&mesh, &[], &[]).unwrap());
    let plain = tower_task();
    let reach_m = plain.pick.hoist_m.max(plain.set.hoist_m) + 0.5;
    assert!(reach_m < plain.crane.limits().hoist_m.1, "{reach_m}");
    let mut model = builtin("tower-hh-60").unwrap();
    (model.hook.rope_m, model.hook.rope_lead_m) = (Some(10.0 + 60.0 + 2.0 * reach_m), Some(10.0));
    let mut spec: LiftSpec = toml::from_str(TOWER_LIFT).unwrap();
    spec.crane.falls = Some(2);
    let t = spec.resolve(model).unwrap();
    assert!((t.crane.limits().hoist_m.1 - reach_m).abs() < 1e-9);
    assert!(t.rope_reach.as_ref().unwrap().said(None).contains("m jib) on 2 falls lets the hook hang"));
    let mut s = quick();
    s.cspace.trolley_step_m = 0.5;
    let (plan, _) = plan_lift(&t, &Site { map: &m, world: &world, charts: None }, &s, 5).unwrap();
    assert!(plan.validator.ok, "{:?}", plan.validator.problems);
    assert!(plan.moves.iter().all(|mv| mv.from.hoist_m.max(mv.to.hoist_m) <= reach_m + 1e-9));
}

/// A tower crane's base is not checked against the ground as a mobile
/// crane's is (its foundation may stand proud of it), but the scanned ground
/// around its mast is measured for the PDF: a base on a plinth 2 m above
/// the ground around the mast is said, not refused; no ground beyond 3 m of
/// the mast is counted.
#[test]
fn the_ground_around_a_tower_cranes_mast_is_measured_not_refused() {
    let t = tower_task();
    let mesh = site();
    let c = Config { swing_rad: 0.3, radial: 20.0, hoist_m: 20.0, load_yaw_rad: 0.0 };
    let swing = Move { joint: Joint::Swing, from: c, to: Config { swing_rad: 0.31, ..c } };
    // Ground at -2 m within 3 m of the mast (2 m wide), and at 9 m beyond.
    let pts: Vec<[f64; 3]> = (0..81 * 81)
        .map(|n| {
            let (x, y) = ((n % 81) as f64 * 0.25 - 10.0, (n / 81) as f64 * 0.25 - 10.0);
            [x, y, if x.abs().max(y.abs()) <= 4.1 { -2.0 } else { 9.0 }]
        })
        .collect();
    let world = World::new(&mesh, &pts, &vec![true; pts.len()]).unwrap();
    let v = validate(&t, None, &world, &rules(), &[swing], &[false]);
    assert!(!v.problems.iter().any(|p| p.contains("crane set-up")), "{:?}", v.problems);
    let g = v.set_up_ground.expect("the ground around the mast is measured");
    assert!(g.points > 100 && g.median_m == -2.0 && g.highest_m == -2.0, "{g:?}");
}

/// A load turning 0.1 rad on its rope after the lift-off: where it starts,
/// where it ends, its box at mid-turn and one corner of that box (from its
/// centre).
fn turn_by_a_tenth(t: &LiftTask) -> (Config, Config, liftplan_core::obb::Obb, liftplan_core::frame::Vec3) {
    let start = t.start();
    let turned = Config { load_yaw_rad: start.load_yaw_rad + 0.1, ..start };
    let mid = Config { load_yaw_rad: start.load_yaw_rad + 0.05, ..start };
    let b = t.crane.load_obb(&mid, &t.load);
    let corner = b.axis(0) * b.half.x + b.axis(1) * b.half.y;
    (start, turned, b, corner)
}

/// A load turning on its rope past a scanned point: its corner passes the
/// point at 5 cm between two samples that each see it more than 9 cm away.
/// Samples alone (0.5 m of corner movement apart, the coarsest setting) pass
/// the move at an 8 cm clearance; the validator must look between them.
#[test]
fn validator_finds_a_closer_approach_between_its_samples() {
    let t = task(-14.0);
    let (start, turned, b, corner) = turn_by_a_tenth(&t);
    // The point 5 cm out from that corner at the load's mid-height, straight
    // out from the rope.
    let out = liftplan_core::frame::Vec3::new(corner.x, corner.y, 0.0).normalize();
    let p = b.center + corner + out * 0.05;
    let world = World::new(&TriMesh::default(), &[[p.x, p.y, p.z]], &[false]).unwrap();
    let rules = Rules { clearance_m: 0.08, landing_clearance_m: 0.08, sample_m: 0.5, ..rules() };
    let turn = |from: Config, to: Config| Move { joint: Joint::Rotate, from, to };
    // Either end alone keeps the clearance, and the move is one gap between them.
    for end in [start, turned] {
        let v = validate(&t, None, &world, &rules, &[turn(end, end)], &[false]);
        assert!(v.ok, "{:?}", v.problems);
        assert!(v.moves[0].tightest.nearest.distance_m > 0.09, "{:?}", v.moves[0].tightest);
    }
    let v = validate(&t, None, &world, &rules, &[turn(start, turned)], &[false]);
    assert!(v.refined_samples > 0 && v.samples == 2 + v.refined_samples, "{} {}", v.samples, v.refined_samples);
    assert!(!v.ok, "the turn passed: {:?}", v.moves[0].tightest);
    assert!(
        v.problems.iter().any(|p| p.contains("load is 0.05") && p.contains("scanned structure")),
        "{:?}",
        v.problems
    );
    // The same turn with the point 1 m farther out passes without a sample
    // added: the ends' distances leave no room for a closer approach.
    let far = p + out * 1.0;
    let world = World::new(&TriMesh::default(), &[[far.x, far.y, far.z]], &[false]).unwrap();
    let v = validate(&t, None, &world, &rules, &[turn(start, turned)], &[false]);
    assert!(v.ok && v.refined_samples == 0, "{:?} {}", v.problems, v.refined_samples);
}

/// The validator checks that the moves make one path from the pick pose to
/// the set pose, not only each move: a planner that dropped or bent a move
/// would have the crane jump where nothing was checked.
#[test]
fn validator_rejects_a_broken_path() {
    let (t, world, plan) = over_the_wall();
    let rules = rules();
    let check = |moves: &[Move]| {
        let landing: Vec<bool> = (0..moves.len()).map(|i| i == 0 || i + 1 == moves.len()).collect();
        validate_lift(&t, None, &world, &rules, moves, &landing)
    };
    let whole = check(&plan.moves);
    assert!(whole.ok, "{:?}", whole.problems);
    let n = plan.moves.len();
    assert!(n >= 4, "{n} moves");
    // A move left out.
    let mut gap = plan.moves.clone();
    gap.remove(2);
    let v = check(&gap);
    assert!(v.problems.iter().any(|p| p.contains("does not start where move 2 ends")), "{:?}", v.problems);
    // A move that also turns the load.
    let mut bent = plan.moves.clone();
    let k = bent.iter().position(|mv| mv.joint != Joint::Rotate).unwrap();
    bent[k].to.load_yaw_rad += 0.2;
    let v = check(&bent);
    assert!(
        v.problems.iter().any(|p| p.contains(&format!("move {} ", k + 1)) && p.contains("more than its own joint")),
        "{:?}",
        v.problems
    );
    // Stopped short of the set-down, and started after the lift-off.
    let v = check(&plan.moves[1..n - 1]);
    assert!(v.problems.iter().any(|p| p.starts_with("the path starts") && p.contains("pick pose")), "{:?}", v.problems);
    assert!(v.problems.iter().any(|p| p.starts_with("the path ends") && p.contains("set pose")), "{:?}", v.problems);
    assert!(!check(&[]).ok);
    // A whole turn of swing more is the same place.
    let mut turned = plan.moves.clone();
    turned[n - 1].to.swing_rad += std::f64::consts::TAU;
    turned[n - 1].from.swing_rad += std::f64::consts::TAU;
    let v = check(&turned);
    assert!(!v.problems.iter().any(|p| p.contains("set pose")), "{:?}", v.problems);
}

/// A lift's permitted slewing range (`swing_range_deg`, e.g. to keep the
/// load off a road) binds the validator as it binds the planner.
#[test]
fn validator_rejects_a_swing_outside_the_permitted_range() {
    let mut t = task(-14.0);
    let start = t.start();
    let (a, b) = (start.swing_rad - 0.5, start.swing_rad + 0.5);
    t.swing_range_rad = Some((a, b));
    let world = World::new(&TriMesh::default(), &[], &[]).unwrap();
    let rules = rules();
    let swing = |from: f64, to: f64| {
        let mv = Move {
            joint: Joint::Swing,
            from: Config { swing_rad: from, ..start },
            to: Config { swing_rad: to, ..start },
        };
        validate(&t, None, &world, &rules, &[mv], &[false])
    };
    let outside = |v: &liftplan_plan::validate::Verdict| v.problems.iter().any(|p| p.contains("permitted swing range"));
    let tau = std::f64::consts::TAU;
    assert!(!outside(&swing(start.swing_rad, b)), "to the range's end");
    assert!(!outside(&swing(a + tau, b + tau)), "the same range a turn on");
    assert!(outside(&swing(start.swing_rad, b + 0.05)), "past the range's end");
    assert!(outside(&swing(start.swing_rad, a - tau + 0.1)), "the long way round to a permitted swing");
}

/// Over a landing zone the hanging parts need less clearance. A load whose
/// corner dips out of the zone between two samples, both inside it, needs the
/// full clearance there: the validator must not carry the zone's smaller
/// requirement across the gap.
#[test]
fn validator_applies_the_full_clearance_where_the_load_leaves_a_landing_zone_between_samples() {
    let t = task(-14.0);
    let (start, turned, b, corner) = turn_by_a_tenth(&t);
    let mid = Config { load_yaw_rad: start.load_yaw_rad + 0.05, ..start };
    // The zone: a 20 m square round the load with a slot 10 cm wide from just
    // inside that corner out to the square's edge.
    let c = [b.center.x, b.center.y];
    let r = corner.x.hypot(corner.y);
    let (u, n) = ([corner.x / r, corner.y / r], [-corner.y / r, corner.x / r]);
    let at = |s: f64, q: f64| [c[0] + s * u[0] + q * n[0], c[1] + s * u[1] + q * n[1]];
    let w = 0.05;
    let zone = vec![
        at(-10.0, -10.0),
        at(10.0, -10.0),
        at(10.0, -w),
        at(r - 0.3, -w),
        at(r - 0.3, w),
        at(10.0, w),
        at(10.0, 10.0),
        at(-10.0, 10.0),
    ];
    // One scanned point 0.5 m under the load's centre: as far at every yaw.
    let p = [b.center.x, b.center.y, b.center.z - b.half.z - 0.5];
    let world = World::new(&TriMesh::default(), &[p], &[false]).unwrap();
    let rules = Rules { landing: vec![zone], sample_m: 0.5, ..rules() };
    let turn = |from: Config, to: Config| Move { joint: Joint::Rotate, from, to };
    let load_check = |c: Config| {
        let v = validate(&t, None, &world, &rules, &[turn(c, c)], &[false]);
        let load = v.moves[0].tightest.clone();
        (v.ok, load.part, load.required_m)
    };
    // The ends are over the zone (0.2 m needed, 0.5 m kept); mid-turn is not.
    for end in [start, turned] {
        assert_eq!(load_check(end), (true, liftplan_core::crane::PartKind::Load, 0.2));
    }
    assert!(!load_check(mid).0);
    let v = validate(&t, None, &world, &rules, &[turn(start, turned)], &[false]);
    assert!(v.problems.iter().any(|p| p.contains("load is 0.500") && p.contains("needs 1.00")), "{:?}", v.problems);
}

/// The load and its rigging must not touch the crane itself: hoisting the
/// load up under a steep boom runs it into the boom, with no obstacle on site.
#[test]
fn validator_rejects_the_load_hoisted_into_the_boom() {
    let t = task(-14.0);
    let world = World::new(&TriMesh::default(), &[], &[]).unwrap();
    let rules = rules();
    let steep = Config { swing_rad: 0.0, radial: 80f64.to_radians(), hoist_m: 20.0, load_yaw_rad: 0.0 };
    let up = |to: f64| Move { joint: Joint::Hoist, from: steep, to: Config { hoist_m: to, ..steep } };
    let v = validate(&t, None, &world, &rules, &[up(15.0)], &[false]);
    assert!(v.ok, "{:?}", v.problems);
    let v = validate(&t, None, &world, &rules, &[up(5.0)], &[false]);
    assert!(v.problems.iter().any(|p| p.contains("from the crane's boom")), "{:?}", v.problems);
}

/// The scanned ground counts for the boom, as it does in the planner: a boom
/// luffed low over a mound of scanned ground is too close to it. (Only the
/// superstructure and what turns with it, standing just above the ground
/// the crane is set up on, leave the ground out.)
#[test]
fn validator_keeps_the_boom_clear_of_scanned_ground() {
    let t = task(-14.0);
    let low = Config { swing_rad: 0.0, radial: 5f64.to_radians(), hoist_m: 5.0, load_yaw_rad: 0.0 };
    let boom = t.crane.part(liftplan_core::crane::PartKind::Boom, &low, &t.load).unwrap();
    // A scanned ground point 0.3 m under the boom, halfway along it.
    let p = boom.center - boom.axis(2) * (boom.half.z + 0.3);
    let rules = rules();
    let swing =
        Move { joint: Joint::Swing, from: Config { swing_rad: -0.05, ..low }, to: Config { swing_rad: 0.05, ..low } };
    for (ground, as_what) in [(true, "ground (scan)"), (false, "scanned structure")] {
        let world = World::new(&TriMesh::default(), &[[p.x, p.y, p.z]], &[ground]).unwrap();
        let v = validate(&t, None, &world, &rules, &[swing], &[false]);
        assert!(v.problems.iter().any(|q| q.contains("boom is 0.300") && q.contains(as_what)), "{:?}", v.problems);
    }
}

#[test]
fn validator_refuses_a_move_it_cannot_sample() {
    let t = task(-14.0);
    let start = t.start();
    let world = World::new(&TriMesh::default(), &[], &[]).unwrap();
    let rules = rules();
    for swing in [f64::NAN, f64::INFINITY, 1e6] {
        let to = Config { swing_rad: swing, ..start };
        let v = validate(&t, None, &world, &rules, &[Move { joint: Joint::Swing, from: start, to }], &[false]);
        assert!(!v.ok && v.problems.iter().any(|p| p.contains("more than the validator checks")), "{:?}", v.problems);
    }
}

/// A short move of one joint of either built-in crane from a random place,
/// with three scanned points just off corners of random parts part-way along
/// it, so that its closest approach usually lies between two coarse samples.
fn points_off_corners(
    seed: u64,
    tower: bool,
    joint: usize,
    at: [f64; 4],
    step: f64,
    past: f64,
) -> (LiftTask, World, Move) {
    let t = if tower { tower_task() } else { task(-14.0) };
    let mut u = {
        use rand::{RngExt, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        move || rng.random::<f64>()
    };
    let lim = t.crane.limits();
    let joint = [Joint::Swing, Joint::Radial, Joint::Hoist, Joint::Rotate][joint];
    let j = joint.index();
    // About 2 m of movement at most, `past` of it before the points.
    let span = step * [0.04, if tower { 2.0 } else { 0.04 }, 2.0, 0.5][j];
    let (lo, hi) = match joint {
        Joint::Radial => lim.radial,
        Joint::Hoist => (lim.hoist_m.0, lim.hoist_m.0 + (lim.hoist_m.1 - lim.hoist_m.0).min(40.0)),
        _ => (-10.0, 10.0),
    };
    let mut mid = [
        at[0] * std::f64::consts::TAU,
        lim.radial.0 + at[1] * (lim.radial.1 - lim.radial.0),
        lim.hoist_m.0 + at[2] * (lim.hoist_m.1 - lim.hoist_m.0).min(40.0),
        at[3] * std::f64::consts::TAU,
    ];
    mid[j] = mid[j].clamp(lo + span * past, hi - span * (1.0 - past));
    let (mut from, mut to) = (mid, mid);
    from[j] -= span * past;
    to[j] += span * (1.0 - past);
    let mid = Config::from_array(mid);
    let pose = t.crane.pose(&mid, &t.load);
    let points: Vec<[f64; 3]> = (0..3)
        .map(|_| {
            let (_, b) = &pose.parts[(u() * pose.parts.len() as f64) as usize % pose.parts.len()];
            let signs = [0, 1, 2].map(|_| if u() < 0.5 { -1.0 } else { 1.0 });
            let corner = b.axis(0) * (signs[0] * b.half.x)
                + b.axis(1) * (signs[1] * b.half.y)
                + b.axis(2) * (signs[2] * b.half.z);
            let p = b.center + corner + corner.normalize() * (0.02 + u() * 0.5);
            [p.x, p.y, p.z]
        })
        .collect();
    let world = World::new(&TriMesh::default(), &points, &[false; 3]).unwrap();
    (t, world, Move { joint, from: Config::from_array(from), to: Config::from_array(to) })
}

proptest::prop_compose! {
    /// Random arguments for [`points_off_corners`].
    fn corner_moves()(
        seed in proptest::prelude::any::<u64>(),
        tower in proptest::prelude::any::<bool>(),
        joint in 0usize..4,
        at in proptest::array::uniform4(0.0f64..1.0),
        step in 0.2f64..1.0,
        past in 0.2f64..0.8,
    ) -> (u64, bool, usize, [f64; 4], f64, f64) {
        (seed, tower, joint, at, step, past)
    }
}

/// The validator's rules at one clearance everywhere and one sample spacing.
fn spaced(clearance_m: f64, sample_m: f64) -> Rules {
    Rules { clearance_m, landing_clearance_m: clearance_m, sample_m, ..rules() }
}

proptest::proptest! {
    #![proptest_config({
        let cases = liftplan_core::testing::proptest_cases(24);
        proptest::prelude::ProptestConfig {
            max_global_rejects: liftplan_core::testing::proptest_rejects(cases),
            ..proptest::prelude::ProptestConfig::with_cases(cases)
        }
    })]
    /// A move whose closest approach, found by samples 1 mm apart, falls
    /// short of the clearance by 3 mm or more is rejected at the validator's
    /// coarsest spacing (0.5 m of movement between samples): it may pass a
    /// part within 2 mm of its requirement, never farther. Scanned points
    /// stand just off corners of the crane's parts part-way along the move,
    /// so the closest approach usually lies between two coarse samples, and
    /// the clearance is set just above it.
    #[test]
    fn a_move_that_comes_too_close_between_samples_is_rejected(
        (seed, tower, joint, at, step, past) in corner_moves(),
        short in 0.003f64..0.1,
    ) {
        let (t, world, mv) = points_off_corners(seed, tower, joint, at, step, past);
        let fine = validate(&t, None, &world, &spaced(0.0, 0.001), &[mv], &[false]);
        let closest = fine.moves[0].tightest.nearest.distance_m;
        proptest::prop_assume!(closest.is_finite());
        let coarse = validate(&t, None, &world, &spaced(closest + short, 0.5), &[mv], &[false]);
        proptest::prop_assert!(
            !coarse.ok,
            "passed with {} samples ({} added), but {:?} comes {:.4} m from {} at {:?} (needs {:.4})",
            coarse.samples, coarse.refined_samples, fine.moves[0].tightest.part, closest,
            fine.moves[0].tightest.nearest.object, fine.moves[0].tightest.config, closest + short
        );
    }

    /// The clearance a step reports is a bound the whole move keeps: never
    /// more than the closest approach (found with samples 1 mm apart), and
    /// at most half the sample spacing less, at the default spacing and the
    /// coarsest. The same scanned points off the parts' corners as above.
    #[test]
    fn the_clearance_a_step_reports_is_never_more_than_the_closest_approach(
        (seed, tower, joint, at, step, past) in corner_moves(),
    ) {
        let (t, world, mv) = points_off_corners(seed, tower, joint, at, step, past);
        let fine = validate(&t, None, &world, &spaced(0.0, 0.001), &[mv], &[false]);
        let closest = fine.moves[0].tightest.nearest.distance_m;
        proptest::prop_assume!(closest.is_finite());
        // The closest approach is at most `closest` (samples 1 mm apart may
        // miss it by half a millimetre, never the other way).
        for sample_m in [0.05, 0.5] {
            let coarse = validate(&t, None, &world, &spaced(0.0, sample_m), &[mv], &[false]);
            // A rejected move's clearance is not shown (a sample with a
            // problem, here the joint limits or the crane's own structure,
            // is not refined around).
            proptest::prop_assume!(coarse.ok);
            let shown = coarse.moves[0].clearance_m;
            proptest::prop_assert!(
                shown <= closest + 1e-9 && shown >= closest - sample_m / 2.0 - 0.0005,
                "samples {} m apart show {:.4} m; the closest approach is {:.4} m ({:?} to {})",
                sample_m, shown, closest, fine.moves[0].tightest.part, fine.moves[0].tightest.nearest.object
            );
        }
    }
}

/// During the lift-off and the set-down the hanging parts may touch nothing
/// but the load's support: a beam through the load where it rests, or across
/// the rigging above it, is refused; the bare pad it rests on is not.
#[test]
fn validator_rejects_a_set_down_through_an_obstacle() {
    let t = task(-14.0);
    let rules = rules();
    let load = t.crane.load_obb(&t.set, &t.load);
    let (c, under) = (load.center, load.center.z - load.half.z);
    let top = load.center.z + load.half.z;
    let pad = ("PAD", [c.x - 3.0, c.y - 3.0, under - 0.5], [c.x + 3.0, c.y + 3.0, under]);
    let set_down = Move { joint: Joint::Hoist, from: t.goal(), to: t.set };
    let check = |extra: Option<(&str, [f64; 3], [f64; 3])>| {
        let mut mesh = TriMesh::default();
        for (name, lo, hi) in std::iter::once(pad).chain(extra) {
            box_part(&mut mesh, name, lo, hi);
        }
        let world = World::new(&mesh, &[], &[]).unwrap();
        validate(&t, None, &world, &rules, &[set_down], &[true])
    };
    let v = check(None);
    assert!(v.ok, "{:?}", v.problems);
    for (name, z) in [("BEAM-THROUGH-LOAD", under + 0.3), ("BEAM-ACROSS-RIGGING", top + 1.0)] {
        let v = check(Some((name, [c.x - 3.0, c.y - 0.1, z], [c.x + 3.0, c.y + 0.1, z + 0.1])));
        assert!(
            v.problems.iter().any(|p| p.contains(name) && p.contains("during the lift-off or set-down")),
            "{name}: {:?}",
            v.problems
        );
    }
}

/// The scan points taken for the load at pick: its box and 0.1 m round it
/// (0.3 m above, where slings lie), no more: something standing 0.2 m beside
/// the load, closer than the landing clearance asks, stays in the checks.
#[test]
fn only_the_load_and_its_slings_are_cut_out_of_the_scan() {
    let t = task(-14.0);
    let cut =
        liftplan_plan::load_exclusions(std::slice::from_ref(&t), liftplan_plan::Settings::default().load_cutout_m);
    let load = t.crane.load_obb(&t.pick, &t.load);
    let c = load.center;
    let (side, top, under) = (load.axis(0) * load.half.x, c.z + load.half.z, c.z - load.half.z);
    let at = |p: liftplan_core::frame::Point3| cut[0].contains(&p);
    assert!(at(c) && at(c + side * 1.01));
    assert!(at(c + side + load.axis(0) * 0.09), "scan noise beside the load");
    assert!(!at(c + side + load.axis(0) * 0.2), "an obstacle 0.2 m beside the load");
    assert!(at(liftplan_core::frame::Point3::new(c.x, c.y, top + 0.29)), "slings on top");
    assert!(!at(liftplan_core::frame::Point3::new(c.x, c.y, top + 0.35)));
    assert!(!at(liftplan_core::frame::Point3::new(c.x, c.y, under - 0.2)), "what it stands on, 0.2 m down");
}

/// The planner refuses a lift whose set-down is blocked before it searches,
/// naming what blocks it, rather than having every plan rejected at the end.
#[test]
fn a_blocked_set_down_is_refused_before_planning() {
    let t = task(-14.0);
    let load = t.crane.load_obb(&t.set, &t.load);
    let (c, under) = (load.center, load.center.z - load.half.z);
    let mut mesh = site();
    // A bar through the load where it comes to rest, 0.1 m above its
    // underside: 0.3 m under it at the configuration above the set position,
    // more than the landing clearance.
    box_part(&mut mesh, "BAR-THROUGH-SET", [c.x - 3.0, c.y - 0.05, under + 0.1], [c.x + 3.0, c.y + 0.05, under + 0.2]);
    let m = map(&mesh);
    let world = World::new(&mesh, &[], &[]).unwrap();
    let err = plan_lift(&t, &Site { map: &m, world: &world, charts: None }, &quick(), 3).unwrap_err().to_string();
    assert!(err.contains("the set-down is not clear") && err.contains("BAR-THROUGH-SET"), "{err}");
}

/// The counterweight swings over the ground the crane stands on, but not
/// through a bank: scanned ground more than half a metre above the crane's
/// set-up level counts for it (it was left out for every part that turns
/// with the superstructure).
#[test]
fn validator_keeps_the_counterweight_off_a_scanned_bank() {
    let t = task(-14.0);
    let c = Config { swing_rad: 0.0, radial: 40f64.to_radians(), hoist_m: 20.0, load_yaw_rad: 0.0 };
    let cw = t.crane.part(liftplan_core::crane::PartKind::Counterweight, &c, &t.load).unwrap();
    let swing = Move { joint: Joint::Swing, from: c, to: Config { swing_rad: 0.01, ..c } };
    let check = |p: liftplan_core::frame::Point3, clearance_m: f64| {
        let world = World::new(&TriMesh::default(), &[[p.x, p.y, p.z]], &[true]).unwrap();
        let rules = Rules { clearance_m, ..rules() };
        validate(&t, None, &world, &rules, &[swing], &[false])
    };
    // A bank's top 0.3 m behind the counterweight, at its mid-height.
    let out = cw.axis(0) * (if cw.center.x < 0.0 { -1.0 } else { 1.0 });
    let bank = cw.center + out * (cw.half.x + 0.3);
    let v = check(bank, 1.0);
    assert!(
        v.problems.iter().any(|p| p.contains("counterweight is 0.3") && p.contains("ground (scan)")),
        "{:?}",
        v.problems
    );
    // The ground it stands on, under it, does not count even for a clearance
    // larger than the counterweight's height; ground 0.6 m up does.
    let under = liftplan_core::frame::Point3::new(cw.center.x, cw.center.y, 0.3);
    assert!(check(under, 3.5).ok, "{:?}", check(under, 3.5).problems);
    let raised = liftplan_core::frame::Point3::new(cw.center.x, cw.center.y, 0.6);
    assert!(!check(raised, 3.5).ok);
}

/// The planner, too, keeps the counterweight off a scanned bank: the short
/// swing from pick to set would take the counterweight through a bank
/// behind the crane, so the plan swings the long way round, and the
/// validator agrees. (The planner used to leave all scanned ground out for
/// the parts that turn with the superstructure: it planned the short swing
/// and the validator refused every plan.)
#[test]
fn the_planner_swings_the_counterweight_round_a_scanned_bank() {
    // The carrier along the site's y axis, so that nothing but the bank
    // stands behind the crane; no wall: the short swing is the quick one.
    let text = r#"
id = "T-BANK"
description = "test lift beside a bank"
load = { name = "skid", mass_t = 5.0, size_m = [4.0, 2.0, 2.0], cog_m = [0.0, 0.0, 0.0] }
rigging = { mass_t = 0.2, height_m = 3.0 }
crane = { model = "ac-700", position_m = [0.0, 0.0], ground_z_m = 0.0, heading_deg = 90.0, boom_m = 40.0, chart_config = "none" }
pick = { x_m = 22.0, y_m = -14.0, z_m = 0.5, yaw_deg = 0.0 }
set = { x_m = 22.0, y_m = 14.0, z_m = 0.5, yaw_deg = 90.0 }
clearance_m = 1.0
liftoff_m = 0.5
"#;
    let t = toml::from_str::<LiftSpec>(text).unwrap().resolve(ac700()).unwrap();
    // A bank's face 0.7 m behind the counterweight where it swings past
    // the site's -x axis (its rear is 6.3 m from the slewing axis), rising
    // from the crane's level to 4.5 m, beside its 3.1 to 5.5 m.
    let mut bank = Vec::new();
    for i in 0..9 {
        for j in 0..11 {
            for k in 0..46 {
                bank.push([-7.0 - 0.1 * i as f64, -0.5 + 0.1 * j as f64, 0.1 * k as f64]);
            }
        }
    }
    let ground = vec![true; bank.len()];
    let mut mesh = TriMesh::default();
    box_part(&mut mesh, "SLAB", [-40.0, -40.0, -0.3], [60.0, 40.0, 0.0]);
    let inp = liftplan_depthmap::Inputs { points: bank.clone(), ground: ground.clone(), mesh: mesh.clone() };
    let m = liftplan_depthmap::build_cpu(&inp, &liftplan_depthmap::Settings::default()).unwrap().0;
    let world = World::new(&mesh, &bank, &ground).unwrap();
    let (plan, _) = plan_lift(&t, &Site { map: &m, world: &world, charts: None }, &quick(), 3).unwrap();
    assert!(plan.validator.ok);
    // The long way round: 295 degrees, not the 65 between pick and set.
    let swung: f64 = plan.moves.iter().map(|m| m.to.swing_rad - m.from.swing_rad).sum();
    assert!(swung.abs() > std::f64::consts::PI, "swung {:.1} degrees", swung.to_degrees());
}

/// A lift whose crane stands at another height than the scanned ground
/// under it (a site in survey heights with `ground_z_m = 0`) is refused by
/// the planner before it plans and by the validator, naming both heights;
/// ground within half a metre of it (mats, uneven ground) is its ground.
#[test]
fn a_crane_set_up_off_the_scanned_ground_is_refused() {
    let t = task(-14.0);
    let mesh = site();
    let m = map(&mesh);
    // Ground points every 0.5 m over the crane's outrigger square and beyond.
    let ground_at = |z: f64| -> Vec<[f64; 3]> {
        (0..41 * 41).map(|n| [(n % 41) as f64 * 0.5 - 10.0, (n / 41) as f64 * 0.5 - 10.0, z]).collect()
    };
    let c = Config { swing_rad: 0.3, radial: 40f64.to_radians(), hoist_m: 20.0, load_yaw_rad: 0.0 };
    let swing = Move { joint: Joint::Swing, from: c, to: Config { swing_rad: 0.31, ..c } };
    for (z, ok) in [(0.3, true), (-0.4, true), (1.8, false), (-0.7, false)] {
        let pts = ground_at(z);
        let world = World::new(&mesh, &pts, &vec![true; pts.len()]).unwrap();
        let v = validate(&t, None, &world, &rules(), &[swing], &[false]);
        let said = v.problems.iter().any(|p| p.contains("set ground_z_m") && p.contains(&format!("at {z:.2} m")));
        assert_eq!(said, !ok, "ground at {z} m: {:?}", v.problems);
        if !ok {
            let err =
                plan_lift(&t, &Site { map: &m, world: &world, charts: None }, &quick(), 3).unwrap_err().to_string();
            assert!(err.contains("z = 0.00 m (ground_z_m)") && err.contains("median of"), "{err}");
        }
    }
}

/// What the load rests on at its set position, and a set-down that ends
/// above it, are said: the test lift's set position is 0.5 m over the slab.
#[test]
fn the_set_down_says_what_the_load_rests_on() {
    let (t, world, plan) = over_the_wall();
    let on = plan.summary.set_on.clone().unwrap();
    assert_eq!(on.object, "SLAB");
    assert!((on.gap_m - 0.5).abs() <= 2e-3, "{on:?}");
    assert!(plan.summary.line().contains("SET-DOWN ENDS 0.50 m ABOVE SLAB"), "{}", plan.summary.line());
    // Set down on the slab, and over nothing.
    let on_slab = Config { hoist_m: t.set.hoist_m + 0.5, ..t.set };
    let s = liftplan_plan::validate::set_support(&t, &world, &on_slab, 0.05).unwrap();
    assert!(s.gap_m <= 2e-3 && s.object == "SLAB", "{s:?}");
    // Set 3 cm into the slab (a model's top a rounding or a little above the
    // set level): it rests on the slab, not 0.27 m above the slab's bottom.
    let into_slab = Config { hoist_m: t.set.hoist_m + 0.53, ..t.set };
    let s = liftplan_plan::validate::set_support(&t, &world, &into_slab, 0.05).unwrap();
    assert!(s.gap_m <= 2e-3 && s.object == "SLAB", "{s:?}");
    let bare = World::new(&TriMesh::default(), &[], &[]).unwrap();
    assert_eq!(liftplan_plan::validate::set_support(&t, &bare, &t.set, 0.05), None);
}

/// Where the load comes to rest, what holds it must be under its centre of
/// gravity: the test lift's load (4 x 2 m, its long side along +y) set at
/// (22, 14) with its underside at 0.5 m, on plinths and rails whose tops
/// lie there (or scan points), is measured from its centre of gravity to
/// the edge of what holds it, never more than that (a lower bound).
#[test]
fn the_load_tips_where_its_centre_of_gravity_is_beyond_what_holds_it() {
    use liftplan_plan::validate::cog_over_support_m;
    let t = task(-14.0);
    let on = |boxes: &[([f64; 3], [f64; 3])], cog_along_m: f64| {
        let mut mesh = TriMesh::default();
        for (k, (lo, hi)) in boxes.iter().enumerate() {
            box_part(&mut mesh, &format!("PLINTH-{k}"), *lo, *hi);
        }
        let world = World::new(&mesh, &[], &[]).unwrap();
        let mut t = t.clone();
        t.load.cog_m[0] = cog_along_m;
        cog_over_support_m(&t, &world, &t.set, 0.0, 0.05, 0.05)
    };
    let within = |m: f64, truth: f64| m <= truth && m >= truth - 0.35;
    // A plinth under all of it: 1 m from its centre of gravity to its sides.
    let m = on(&[([20.0, 11.0, 0.0], [24.0, 17.0, 0.5])], 0.0);
    assert!(within(m, 1.0), "{m}");
    // Its centre of gravity 1.5 m along it: 0.5 m from its end.
    let m = on(&[([20.0, 11.0, 0.0], [24.0, 17.0, 0.5])], 1.5);
    assert!(within(m, 0.5), "{m}");
    // Known to 0.3 m either way: it may lie 1.8 m along, 0.2 m from its end.
    let mut known_so_well = t.clone();
    known_so_well.cog_tolerance_m = 0.3;
    known_so_well.load.cog_m[0] = 1.5;
    let mut mesh = TriMesh::default();
    box_part(&mut mesh, "PLINTH", [20.0, 11.0, 0.0], [24.0, 17.0, 0.5]);
    let world = World::new(&mesh, &[], &[]).unwrap();
    let m = cog_over_support_m(&known_so_well, &world, &known_so_well.set, 0.0, 0.05, 0.05);
    assert!(within(m, 0.2), "{m}");
    // A plinth under its south end only, to 0.5 m short of its centre of
    // gravity; one 0.3 m lower under the rest holds nothing at that level.
    let m = on(&[([20.0, 11.0, 0.0], [24.0, 13.5, 0.5]), ([20.0, 13.5, 0.0], [24.0, 17.0, 0.2])], 0.0);
    assert!(within(m, -0.5), "{m}");
    // Two rails (saddles) under its ends hold it between them; one does not.
    let rails = [([20.0, 12.0, 0.0], [24.0, 12.6, 0.5]), ([20.0, 15.4, 0.0], [24.0, 16.0, 0.5])];
    let m = on(&rails, 0.0);
    assert!(within(m, 1.0), "{m}");
    let m = on(&rails[..1], 0.0);
    assert!(within(m, -1.4), "{m}");
    assert_eq!(on(&[], 0.0), f64::NEG_INFINITY);
    // Scan points on a plinth's top, as a survey shows it.
    let top: Vec<[f64; 3]> =
        (0..41 * 61).map(|n| [20.0 + (n % 41) as f64 * 0.1, 11.0 + (n / 41) as f64 * 0.1, 0.5]).collect();
    let world = World::new(&TriMesh::default(), &top, &vec![false; top.len()]).unwrap();
    let m = cog_over_support_m(&t, &world, &t.set, 0.0, 0.05, 0.05);
    assert!(within(m, 1.0), "{m}");
    // Said on the run's line where it tips, and on the PDF's page as it is.
    let (_, _, mut plan) = over_the_wall();
    let support = |m: f64| liftplan_plan::validate::SetSupport {
        gap_m: 0.0,
        object: "PLINTH".into(),
        cog_inside_m: Some(m),
        cog_tolerance_m: 0.0,
    };
    plan.summary.set_on = Some(support(-0.64));
    let line = plan.summary.line();
    assert!(
        line.contains("set down on PLINTH, BUT ITS CENTRE OF GRAVITY LIES 0.64 m BEYOND THE EDGE OF WHAT HOLDS IT"),
        "{line}"
    );
    plan.summary.set_on = Some(support(0.05));
    assert!(plan.summary.line().contains("ONLY 0.05 m INSIDE THE EDGE"), "{}", plan.summary.line());
    plan.summary.set_on = Some(support(0.76));
    assert!(plan.summary.line().ends_with("set down on PLINTH"), "{}", plan.summary.line());
    assert!(support(0.76).cog_said().unwrap().starts_with("its centre of gravity lies 0.76 m inside"));
    let within_tolerance = |m: f64| liftplan_plan::validate::SetSupport { cog_tolerance_m: 0.15, ..support(m) };
    let said = within_tolerance(-0.64).cog_said().unwrap();
    assert!(
        said.starts_with(
            "ITS CENTRE OF GRAVITY WITHIN ITS 0.15 m TOLERANCE (load cog_tolerance_m) MAY LIE 0.64 m BEYOND THE EDGE"
        ),
        "{said}"
    );
    let said = within_tolerance(0.76).cog_said().unwrap();
    assert!(said.starts_with("its centre of gravity, anywhere within 0.15 m of where the lift gives it (load cog_tolerance_m), lies at least 0.76 m inside"), "{said}");
}

/// The carrier and outriggers stand on the ground, but not in a bank: a
/// patch of scanned ground more than half a metre above the set-up level
/// under the carrier is refused by the validator and the planner; a kerb
/// lower than that is ground they stand on.
#[test]
fn a_carrier_parked_in_a_bank_is_refused() {
    let t = task(-14.0);
    let mesh = site();
    let c = Config { swing_rad: 0.3, radial: 40f64.to_radians(), hoist_m: 20.0, load_yaw_rad: 0.0 };
    let swing = Move { joint: Joint::Swing, from: c, to: Config { swing_rad: 0.31, ..c } };
    // Level ground over the outrigger square, and a 2 m patch under the
    // carrier's rear (the carrier runs along x, its rear near x = -7.75).
    let with_patch = |z: f64| -> Vec<[f64; 3]> {
        let mut pts: Vec<[f64; 3]> =
            (0..41 * 41).map(|n| [(n % 41) as f64 * 0.5 - 10.0, (n / 41) as f64 * 0.5 - 10.0, 0.0]).collect();
        pts.extend((0..25).map(|n| [-7.0 + (n % 5) as f64 * 0.4, -0.8 + (n / 5) as f64 * 0.4, z]));
        pts
    };
    for (z, ok) in [(0.3, true), (1.2, false)] {
        let pts = with_patch(z);
        let world = World::new(&mesh, &pts, &vec![true; pts.len()]).unwrap();
        let v = validate(&t, None, &world, &rules(), &[swing], &[false]);
        let said = v.problems.iter().any(|p| p.contains("crane set-up: carrier intersects ground (scan)"));
        assert_eq!(said, !ok, "patch at {z} m: {:?}", v.problems);
        if !ok {
            let inp =
                liftplan_depthmap::Inputs { points: pts.clone(), ground: vec![true; pts.len()], mesh: mesh.clone() };
            let m = liftplan_depthmap::build_cpu(&inp, &liftplan_depthmap::Settings::default()).unwrap().0;
            let err =
                plan_lift(&t, &Site { map: &m, world: &world, charts: None }, &quick(), 3).unwrap_err().to_string();
            assert!(err.contains("crane set-up: the carrier meets ground (scan) in the cell at x -7.25 to -7.00 m, y -1.00 to -0.75 m"), "{err}");
            assert!(err.contains("where it reaches from z = 1.1"), "{err}");
        }
    }
}

/// The plant model is checked against the scans where both see the site:
/// scanned points on the wall's face agree with the model; the same points
/// half a metre off it (a model placed wrong) are said to disagree.
/// Points every 0.5 m on the wall's south face and west end, as scanned
/// with the wall `dx`, `dy` off where the model has it.
fn wall_faces(dx: f64, dy: f64) -> Vec<[f64; 3]> {
    let mut pts: Vec<[f64; 3]> =
        (0..41 * 24).map(|n| [14.0 + dx + (n % 41) as f64 * 0.5, -1.0 + dy, 0.5 + (n / 41) as f64 * 0.5]).collect();
    pts.extend((0..9 * 24).map(|n| [14.0 + dx, -1.0 + dy + (n % 9) as f64 * 0.25, 0.5 + (n / 9) as f64 * 0.5]));
    pts
}

#[test]
fn the_plant_model_is_checked_against_the_scans() {
    let mesh = site();
    let face = |off: f64| -> Vec<[f64; 3]> {
        (0..41 * 25).map(|n| [14.0 + (n % 41) as f64 * 0.5, -1.0 - off, (n / 41) as f64 * 0.5]).collect()
    };
    let agree = |pts: Vec<[f64; 3]>| {
        let world = World::new(&mesh, &pts, &vec![false; pts.len()]).unwrap();
        liftplan_plan::validate::model_scan_agreement(&world)
    };
    let a = agree(face(0.0)).unwrap();
    assert!(!a.disagrees() && a.close_pct == 100.0 && a.median_m < 1e-9, "{a:?}");
    assert!(a.line().contains("they agree"), "{}", a.line());
    let off = agree(face(0.5)).unwrap();
    assert!(off.disagrees() && (off.median_m - 0.5).abs() < 1e-9, "{off:?}");
    assert!(off.line().contains("CHECK [plant] translate_m"), "{}", off.line());
    // One face alone does not say how far along it the model is off.
    assert_eq!(off.fits_moved_by, None, "{off:?}");
    // Two faces of the wall, scanned 0.3 m west and 0.5 m south of where
    // the model has them: the move that puts the model on them is found.
    let (dx, dy) = (-0.3, -0.5);
    let moved = agree(wall_faces(dx, dy)).unwrap();
    let m = moved.fits_moved_by.unwrap_or_else(|| panic!("no move found: {moved:?}"));
    assert!((m.by_m[0] - dx).abs() < 0.02 && (m.by_m[1] - dy).abs() < 0.02 && m.close_pct > 90.0, "{moved:?}");
    assert!(m.turn_deg.abs() < 0.01, "{m:?}");
    assert!(
        moved.line().contains("the model lies on the scans when moved by x -0.30 m, y -0.50 m"),
        "{}",
        moved.line()
    );
    // The same faces scanned turned by 2° about (20, 0) (a wrong
    // rotate_z_deg): the turn is found, and the move it makes where the
    // points are.
    let turn = 2f64.to_radians();
    let turned: Vec<[f64; 3]> = wall_faces(0.0, 0.0)
        .iter()
        .map(|p| {
            let (x, y) = (p[0] - 20.0, p[1]);
            [20.0 + x * turn.cos() - y * turn.sin(), x * turn.sin() + y * turn.cos(), p[2]]
        })
        .collect();
    let a = agree(turned).unwrap();
    let m = a.fits_moved_by.unwrap_or_else(|| panic!("no turn found: {a:?}"));
    assert!((m.turn_deg - 2.0).abs() < 0.05 && m.close_pct > 90.0, "{m:?}");
    // Turned about another point, the same move: it takes the wall's far
    // corner where the 2° turn about (20, 0) does.
    let (w, o) = (m.turn_deg.to_radians(), m.about_m);
    let corner = [34.0 - o[0], -1.0 - o[1]];
    let moved_to = [
        o[0] + corner[0] * w.cos() - corner[1] * w.sin() + m.by_m[0],
        o[1] + corner[0] * w.sin() + corner[1] * w.cos() + m.by_m[1],
    ];
    let want = [20.0 + 14.0 * turn.cos() + turn.sin(), 14.0 * turn.sin() - turn.cos()];
    assert!((moved_to[0] - want[0]).abs() < 0.03 && (moved_to[1] - want[1]).abs() < 0.03, "{m:?} {moved_to:?}");
    // Said as the one turn it is, about the point it leaves where it is.
    assert!(m.by_m == [0.0, 0.0] && (m.about_m[0] - 20.0).abs() < 0.5 && m.about_m[1].abs() < 0.5, "{m:?}");
    assert!(a.line().contains("the model lies on the scans when turned by +2.0"), "{}", a.line());
    // The wall's faces and its top scanned 0.4 m higher than the model has
    // them (a height datum): most points still lie on the model's faces,
    // so the points' median is small, but the move up is found.
    let with_top = |dx: f64, dy: f64, dz: f64| -> Vec<[f64; 3]> {
        let mut pts: Vec<[f64; 3]> = wall_faces(dx, dy).iter().map(|p| [p[0], p[1], p[2] + dz]).collect();
        pts.extend(
            (0..41 * 5).map(|n| [14.0 + dx + (n % 41) as f64 * 0.5, -1.0 + dy + (n / 41) as f64 * 0.5, 12.0 + dz]),
        );
        pts
    };
    let high = agree(with_top(0.0, 0.0, 0.4)).unwrap();
    let m = high.fits_moved_by.unwrap_or_else(|| panic!("no move found: {high:?}"));
    assert!(high.median_m < AGREEMENT_CLOSE_M && high.disagrees(), "{high:?}");
    assert!((m.z_m - 0.4).abs() < 0.02 && m.by_m[0].abs() < 0.02 && m.by_m[1].abs() < 0.02, "{m:?}");
    assert!(high.line().contains("the model lies on the scans when moved by z +0.40 m"), "{}", high.line());
    // And 0.3 m west, 0.2 m north and 0.4 m up at once.
    let all = agree(with_top(-0.3, 0.2, 0.4)).unwrap();
    assert!(all.line().contains("moved by x -0.30 m, y +0.20 m, z +0.40 m"), "{}", all.line());
    // Walls alone (below their top) do not say the height: none is sought.
    let walls: Vec<[f64; 3]> =
        wall_faces(-0.3, -0.5).iter().filter(|p| p[2] < 11.0).map(|p| [p[0], p[1], p[2] - 0.3]).collect();
    let walls = agree(walls).unwrap();
    assert!(walls.fits_moved_by.is_some_and(|m| m.z_m == 0.0), "{walls:?}");
    // Too little overlap to say.
    assert_eq!(agree(face(0.0)[..40].to_vec()), None);
}

/// Another lift's load where it stands during this lift (here: on top of
/// the wall, where the lift over the wall takes its load) is an obstacle
/// to the validator, which refuses the plan made without it and names it,
/// and to the planner, whose map holds it too: the lift planned with it
/// goes round it and validates.
#[test]
fn another_lifts_load_is_an_obstacle_to_the_planner_and_the_validator() {
    let (t, _, plan) = over_the_wall();
    // The load at the top of its way over the wall.
    let over = plan
        .moves
        .iter()
        .map(|m| m.to)
        .max_by(|a, b| t.crane.load_obb(a, &t.load).center.z.total_cmp(&t.crane.load_obb(b, &t.load).center.z))
        .unwrap();
    let other = (t.crane.load_obb(&over, &t.load), "load of lift T-0 at its set position".to_string());
    let mesh = site();
    let mut world = World::new(&mesh, &[], &[]).unwrap();
    world.others = vec![other.clone()];
    let landing: Vec<bool> = (0..plan.moves.len()).map(|i| i == 0 || i == plan.moves.len() - 1).collect();
    let v = validate_lift(&t, None, &world, &rules(), &plan.moves, &landing);
    assert!(!v.ok && v.problems.iter().any(|p| p.contains("load of lift T-0 at its set position")), "{:?}", v.problems);

    let m = map(&mesh).with_boxes(std::slice::from_ref(&other));
    let (round, _) = plan_lift(&t, &Site { map: &m, world: &world, charts: None }, &quick(), 3).unwrap();
    assert!(round.validator.ok && round.moves != plan.moves);
    let (pb, cb) = liftplan_plan::validate::parry_box(&other.0);
    for mv in &round.moves[1..round.moves.len() - 1] {
        let (ph, ch) = liftplan_plan::validate::parry_box(&t.crane.load_obb(&mv.to, &t.load));
        let d = parry3d_f64::query::distance(&ph, &ch, &pb, &cb).unwrap().distance;
        assert!(d >= 1.0 - 2e-3, "the load comes {d} m from the other load at {:?}", mv.to);
    }
}

/// A chart for the test crane's 40 m boom carrying 50 t out to `reach_m`
/// and 3 t beyond.
fn chart_reaching(reach_m: f64) -> liftplan_core::capacity::CapacityTable {
    chart_of(&[(10.0, 50.0), (reach_m, 50.0), (reach_m + 2.0, 3.0), (40.0, 3.0)], "none")
}

/// An area the load must never be over, across the short way from the pick
/// to the set: the plan made without it takes the load over it, and the
/// validator given the area refuses that plan naming it; the plan made
/// with it goes round, keeps the load's footprint off it at every sample
/// of every move, and passes the validator.
#[test]
fn the_load_is_never_over_an_area_it_must_not_be_over() {
    use liftplan_core::lift::{NOT_OVER_MARGIN_M, NotOver};
    use liftplan_core::obb::footprint_near_area;
    let (m, world) = open_slab();
    let site = Site { map: &m, world: &world, charts: None };
    let free = task(-14.0);
    let (direct, _) = plan_lift(&free, &site, &quick(), 3).unwrap();
    let road = NotOver {
        name: "ROAD".into(),
        corners_m: vec![[15.0, -3.0], [40.0, -3.0], [40.0, 3.0], [15.0, 3.0]],
        crane_too: false,
    };
    let mut spec = spec_of(-14.0);
    spec.not_over = vec![road.clone()];
    let kept = spec.resolve(ac700()).unwrap();
    // The footprint along a plan's moves, every 2 cm of the load's travel.
    let comes_over = |moves: &[liftplan_plan::path::Move], within_m: f64| {
        moves.iter().any(|mv| {
            let (a, b) = (mv.from.to_array(), mv.to.to_array());
            let j = mv.joint.index();
            let travel = (b[j] - a[j]).abs() * if j == 0 { 30.0 } else { 40.0 };
            let n = (travel / 0.02).ceil().max(1.0) as usize;
            (0..=n).any(|i| {
                let mut v = a;
                v[j] = a[j] + (b[j] - a[j]) * i as f64 / n as f64;
                let c = liftplan_core::crane::Config::from_array(v);
                footprint_near_area(&kept.crane.load_obb(&c, &kept.load).footprint(), &road.corners_m, within_m)
            })
        })
    };
    assert!(comes_over(&direct.moves, 0.0), "the direct plan does not cross the road: the test shows nothing");
    let landing: Vec<bool> = (0..direct.moves.len()).map(|i| i == 0 || i == direct.moves.len() - 1).collect();
    let v = validate_lift(&kept, None, &world, &rules(), &direct.moves, &landing);
    assert!(!v.ok && v.problems.iter().any(|p| p.contains("the load comes over not_over 'ROAD'")), "{:?}", v.problems);
    let (round, _) = plan_lift(&kept, &site, &quick(), 3).unwrap();
    assert!(round.validator.ok, "{:?}", round.validator.problems);
    assert!(!comes_over(&round.moves, NOT_OVER_MARGIN_M - 0.02), "{:?}", round.moves);

    // With a fall zone of 3 m round the load, the road is kept out of it
    // too: the plan made without the fall zone comes within it and the
    // validator given it refuses that plan; the plan made with it keeps
    // the footprint its fall zone and the margin off, and passes.
    const FALL_ZONE_M: f64 = 3.0;
    assert!(comes_over(&round.moves, FALL_ZONE_M), "the plan keeps 3 m off the road already: the test shows nothing");
    spec.fall_zone_m = FALL_ZONE_M;
    let zoned = spec.resolve(ac700()).unwrap();
    let landing: Vec<bool> = (0..round.moves.len()).map(|i| i == 0 || i == round.moves.len() - 1).collect();
    let v = validate_lift(&zoned, None, &world, &rules(), &round.moves, &landing);
    assert!(
        !v.ok
            && v.problems
                .iter()
                .any(|p| p
                    .contains("the load comes over not_over 'ROAD' or within its fall zone of it (fall_zone_m = 3 m)")),
        "{:?}",
        v.problems
    );
    let (wide, _) = plan_lift(&zoned, &site, &quick(), 3).unwrap();
    assert!(wide.validator.ok, "{:?}", wide.validator.problems);
    assert!(!comes_over(&wide.moves, FALL_ZONE_M + NOT_OVER_MARGIN_M - 0.02), "{:?}", wide.moves);
    // A lift resumed with the load hanging 2 m off the road (its footprint
    // from y -7 to -5 m): within its fall zone, so no path is planned from
    // there, and the refusal says why.
    let mut hanging = zoned.clone();
    let pose = liftplan_core::crane::LoadPose { x_m: 22.0, y_m: -6.0, z_m: 5.0, yaw_rad: 0.0 };
    hanging.resume_from = Some((hanging.crane.inverse(&pose, &hanging.load).unwrap(), pose));
    let why = plan_lift(&hanging, &site, &quick(), 3).map(|_| "planned").unwrap_err().to_string();
    assert!(
        why.contains("where the load hangs now (resume_from) is not clear")
            && why.contains("ROAD")
            && why.contains("its fall zone, fall_zone_m 3 m, kept off it"),
        "{why}"
    );
}

/// An area the crane may not be over either (`crane_too`: a railway in
/// front of it, between it and the swing from the pick to the set): the
/// plan made where only the load keeps off it swings the boom over it, and
/// the validator given it refuses that plan naming the boom; the plan made
/// with it swings the other way round, passes the validator, and no part
/// that turns with the swing comes within the margin of it, at samples
/// 2 cm apart.
#[test]
fn the_crane_is_never_over_an_area_it_may_not_be_over() {
    use liftplan_core::crane::{Config, Dependence};
    use liftplan_core::lift::{NOT_OVER_MARGIN_M, NotOver};
    use liftplan_core::obb::footprint_near_area;
    let (m, world) = open_slab();
    let site = Site { map: &m, world: &world, charts: None };
    let railway = NotOver {
        name: "RAILWAY".into(),
        corners_m: vec![[9.0, -2.0], [12.0, -2.0], [12.0, 2.0], [9.0, 2.0]],
        crane_too: true,
    };
    let with = |area: NotOver| {
        let mut spec = spec_of(-14.0);
        spec.not_over = vec![area];
        spec.resolve(ac700()).unwrap()
    };
    let load_only = with(NotOver { crane_too: false, ..railway.clone() });
    let (direct, _) = plan_lift(&load_only, &site, &quick(), 3).unwrap();
    assert!(direct.validator.ok, "{:?}", direct.validator.problems);
    let kept = with(railway.clone());
    // Every swinging part's footprint along a plan's moves, every 2 cm of
    // the farthest travel.
    let comes_over = |moves: &[liftplan_plan::path::Move], within_m: f64| {
        moves.iter().any(|mv| {
            let (a, b) = (mv.from.to_array(), mv.to.to_array());
            let j = mv.joint.index();
            let travel = (b[j] - a[j]).abs() * 50.0;
            let n = (travel / 0.02).ceil().max(1.0) as usize;
            (0..=n).any(|i| {
                let mut v = a;
                v[j] = a[j] + (b[j] - a[j]) * i as f64 / n as f64;
                let pose = kept.crane.pose(&Config::from_array(v), &kept.load);
                pose.parts
                    .iter()
                    .filter(|(k, _)| k.dependence() != Dependence::Fixed)
                    .any(|(_, part)| footprint_near_area(&part.footprint(), &railway.corners_m, within_m))
            })
        })
    };
    assert!(comes_over(&direct.moves, 0.0), "the direct plan does not swing over it: the test shows nothing");
    let landing: Vec<bool> = (0..direct.moves.len()).map(|i| i == 0 || i == direct.moves.len() - 1).collect();
    let v = validate_lift(&kept, None, &world, &rules(), &direct.moves, &landing);
    assert!(
        !v.ok && v.problems.iter().any(|p| p.contains("the crane's boom comes over not_over 'RAILWAY'")),
        "{:?}",
        v.problems
    );
    let (round, _) = plan_lift(&kept, &site, &quick(), 3).unwrap();
    assert!(round.validator.ok, "{:?}", round.validator.problems);
    assert!(!comes_over(&round.moves, NOT_OVER_MARGIN_M - 0.02), "{:?}", round.moves);
}

/// A lift that plans above its critical_pct: the search for where it would
/// not be names the nearest position from which the chart carries it within
/// critical_pct at the pick and the set and the whole lift plans within it;
/// given that position, the lift plans there, not critical. Where the chart
/// carries it within critical_pct from nowhere, that is said.
#[test]
fn a_critical_lift_names_a_crane_position_where_it_is_not() {
    use liftplan_plan::positions::{self, Found, Sought};
    let mesh = site();
    let (m, world) = (map(&mesh), World::new(&mesh, &[], &[]).unwrap());
    let table = chart_of(&[(10.0, 50.0), (24.0, 50.0), (26.0, 10.5), (40.0, 10.5)], "none");
    let chart = table.config("none").unwrap();
    let site = Site { map: &m, world: &world, charts: Some(&table) };
    let t = task(-14.0);
    let (plan, _) = plan_lift(&t, &site, &quick(), 3).unwrap();
    assert!(plan.summary.critical, "{:?}", plan.summary);
    let found = positions::search(&t, &site, chart, &quick(), 3, Sought::NotCritical);
    let (Found::Tried(tried), Some(k)) = (&found, found.chosen()) else { panic!("{found:?}") };
    let at = &tried[k];
    assert!(!at.critical && at.pick.0.max(at.set.0) <= t.critical_pct && at.moved_m > 0.0, "{at:?}");
    let said = found.not_critical_said(t.critical_pct).unwrap();
    assert!(
        said.starts_with(&format!(
            "not critical with the crane set up at position_m = [{:.1}, {:.1}], heading_deg = {:.0}, ground_z_m = 0.00 (the lift's: no ground is scanned there; {:.1} m from the lift's position): pick ",
            at.x_m, at.y_m, at.heading_deg, at.moved_m
        )) && said.contains("; there the lift plans and passes the validator in "),
        "{said}"
    );
    // Given that position, the lift plans there, the same, not critical.
    let mut spec = spec_of(-14.0);
    (spec.crane.position_m, spec.crane.heading_deg) = ([at.x_m, at.y_m], at.heading_deg);
    let there = spec.resolve(ac700()).unwrap();
    let (plan, _) = plan_lift(&there, &site, &quick(), 3).unwrap();
    assert!(!plan.summary.critical && Some(plan.steps.len()) == at.planned_steps(), "{:?}", plan.summary);
    // A chart that carries it within critical_pct nowhere.
    let low = chart_of(&[(10.0, 10.5), (40.0, 10.5)], "none");
    let site = Site { map: &m, world: &world, charts: Some(&low) };
    let (plan, _) = plan_lift(&t, &site, &quick(), 3).unwrap();
    assert!(plan.summary.critical);
    let found = positions::search(&t, &site, low.config("none").unwrap(), &quick(), 3, Sought::NotCritical);
    assert_eq!(
        found.not_critical_said(t.critical_pct).unwrap(),
        "its chart carries the load within 75 % at both the pick and the set from no crane position"
    );
}

/// A lift that gives the areas its crane may stand in: set up outside
/// them it is refused, saying so; the validator refuses a set-up outside
/// them too; and a crane position named for it (here, where it would not
/// be critical) stands within one, where the one named without them stands
/// outside them (turned, its carrier off the pad the crane stands on).
#[test]
fn the_crane_stands_only_in_the_areas_the_lift_gives() {
    use liftplan_core::lift::CraneArea;
    use liftplan_plan::positions::{self, Found, Sought};
    let square = |name: &str, lo: [f64; 2], hi: [f64; 2]| CraneArea {
        name: name.into(),
        corners_m: vec![lo, [hi[0], lo[1]], hi, [lo[0], hi[1]]],
    };
    // The AC 700's carrier runs from x -7.75 to 12.75 m, its outriggers 12.3 m square.
    let own = square("pad", [-8.5, -7.0], [13.5, 7.0]);
    // Set up outside every area given: refused, naming them.
    let mut spec = spec_of(-14.0);
    spec.crane_stands_in = vec![square("road", [30.0, -40.0], [40.0, 40.0])];
    let e = spec.resolve(ac700()).unwrap_err();
    assert!(
        e.contains("the crane set up at position_m = [0.00, 0.00], heading_deg = 0: its carrier and outriggers are not within an area it may stand in (crane_stands_in: 'road')"),
        "{e}"
    );
    // A tower crane's mast, likewise: within its foundation's area, or refused.
    let tower = |areas: Vec<CraneArea>| {
        let mut spec = spec_of(-14.0);
        spec.crane.model = "tower-hh-60".into();
        spec.crane.chart_config = "none".into();
        spec.crane.boom_m = None;
        spec.crane_stands_in = areas;
        spec.resolve(builtin("tower-hh-60").unwrap())
    };
    assert!(tower(vec![square("foundation", [-4.0, -4.0], [4.0, 4.0])]).is_ok());
    let e = tower(vec![square("road", [30.0, -40.0], [40.0, 40.0])]).unwrap_err();
    assert!(e.contains("its mast is not within an area it may stand in (crane_stands_in: 'road')"), "{e}");
    // Half in the pad: refused too.
    spec.crane_stands_in = vec![square("half", [-2.0, -7.0], [13.5, 7.0])];
    assert!(spec.resolve(ac700()).is_err());
    spec.crane_stands_in = vec![own.clone()];
    let t = spec.resolve(ac700()).unwrap();
    let mesh = site();
    let (m, world) = (map(&mesh), World::new(&mesh, &[], &[]).unwrap());
    let table = chart_of(&[(10.0, 50.0), (24.0, 50.0), (26.0, 10.5), (40.0, 10.5)], "none");
    let chart = table.config("none").unwrap();
    let site = Site { map: &m, world: &world, charts: Some(&table) };
    // The validator, given the set-up outside the areas, refuses it.
    let (plan, _) = plan_lift(&t, &site, &quick(), 3).unwrap();
    let mut elsewhere = t.clone();
    elsewhere.crane_stands_in = vec![square("road", [30.0, -40.0], [40.0, 40.0])];
    let v = validate(&elsewhere, None, &world, &rules(), &plan.moves, &[false; 64][..plan.moves.len()]);
    assert!(
        v.problems.iter().any(|p| p.starts_with("crane set-up: the crane set up at position_m")),
        "{:?}",
        v.problems
    );
    // Where it would not be critical: without the areas, and with the pad
    // and the half of the site away from that position.
    let found = positions::search(&task(-14.0), &site, chart, &quick(), 3, Sought::NotCritical);
    let (Found::Tried(tried), Some(k)) = (&found, found.chosen()) else { panic!("{found:?}") };
    let free = tried[k].clone();
    let away = if free.y_m >= 0.0 {
        square("south", [-40.0, -40.0], [60.0, -1.0])
    } else {
        square("north", [-40.0, 1.0], [60.0, 40.0])
    };
    let mut t = t.clone();
    t.crane_stands_in = vec![own, away];
    let found = positions::search(&t, &site, chart, &quick(), 3, Sought::NotCritical);
    match (&found, found.chosen()) {
        (Found::Tried(tried), Some(k)) => {
            let at = &tried[k];
            // The lift file given either position, with the areas: the one
            // found without them stands outside, the one found with them
            // within.
            let mut spec = spec_of(-14.0);
            spec.crane_stands_in = t.crane_stands_in.clone();
            let at_place = |spec: &mut LiftSpec, at: &positions::Tried| {
                (spec.crane.position_m, spec.crane.heading_deg) = ([at.x_m, at.y_m], at.heading_deg);
                spec.resolve(ac700())
            };
            assert!(at_place(&mut spec, &free).is_err(), "{free:?}");
            assert!(at_place(&mut spec, at).is_ok(), "{at:?}");
        }
        _ => panic!("{found:?}"),
    }
}

/// What the outrigger pads bear on is looked at, at a crane position named
/// for a lift, as at the lift's own: a duct buried under a pad of the
/// position named passes it over for another, where nothing lies under the
/// pads, and which plans there; where the ground may bear less than the
/// mats put on it wherever the crane stands, the first position where the
/// lift plans is named with it, to be checked.
#[test]
fn a_crane_position_with_a_duct_under_its_pads_is_passed_over() {
    use liftplan_core::outriggers::{Pad, pad_at};
    use liftplan_plan::positions::{self, Found};
    let table = chart_reaching(24.0);
    let chart = table.config("none").unwrap();
    let searched = |mesh: &TriMesh, t: &LiftTask| {
        let (m, world) = (map(mesh), World::new(mesh, &[], &[]).unwrap());
        let site = Site { map: &m, world: &world, charts: Some(&table) };
        let found = positions::search(t, &site, chart, &quick(), 3, positions::Sought::Plans);
        let (Found::Tried(tried), Some(k)) = (&found, found.chosen()) else { panic!("{found:?}") };
        let e = plan_lift(t, &site, &quick(), 3).unwrap_err().to_string();
        (tried[k].clone(), found.said("none"), e)
    };
    let t = task(-14.0);
    let (first, said, _) = searched(&site(), &t);
    assert!(
        first.under_pads.is_empty()
            && said.contains("nothing of the plant model or the scans in the ground under them"),
        "{said}"
    );
    // A duct 0.4 m under the slab, under that position's front left pad.
    let given = |x_m: f64, y_m: f64, heading_deg: f64| {
        let mut spec = spec_of(-14.0);
        (spec.crane.position_m, spec.crane.heading_deg) = ([x_m, y_m], heading_deg);
        spec.resolve(ac700()).unwrap()
    };
    let pad = pad_at(&given(first.x_m, first.y_m, first.heading_deg).crane, Pad::FrontLeft).unwrap();
    let mut ducted = site();
    box_part(&mut ducted, "DUCT", [pad[0] - 0.3, pad[1] - 0.3, -0.7], [pad[0] + 0.3, pad[1] + 0.3, -0.4]);
    let (other, said, e) = searched(&ducted, &t);
    assert!(other.under_pads.is_empty() && other.planned_steps().is_some(), "{other:?}");
    assert!((other.x_m, other.y_m, other.heading_deg) != (first.x_m, first.y_m, first.heading_deg), "{said}");
    assert!(
        e.ends_with(&said) && said.contains("nothing of the plant model or the scans in the ground under them"),
        "{said}"
    );
    // Given that position, the lift plans there with nothing under its pads.
    let (m, world) = (map(&ducted), World::new(&ducted, &[], &[]).unwrap());
    let there = given(other.x_m, other.y_m, other.heading_deg);
    plan_lift(&there, &Site { map: &m, world: &world, charts: Some(&table) }, &quick(), 3).unwrap();
    assert!(liftplan_plan::validate::under_pads(&there, &world).is_empty());
    assert!(!liftplan_plan::validate::under_pads(&given(first.x_m, first.y_m, first.heading_deg), &world).is_empty());
    // A culvert under the pads at every heading there: another position,
    // farther, with the one passed over named, and its culvert.
    let mut culverted = site();
    box_part(
        &mut culverted,
        "CULVERT",
        [first.x_m - 9.0, first.y_m - 9.0, -0.7],
        [first.x_m + 9.0, first.y_m + 9.0, -0.4],
    );
    let (farther, said, _) = searched(&culverted, &t);
    assert!(farther.under_pads.is_empty() && farther.moved_m > first.moved_m, "{farther:?}");
    assert!(
        said.contains(&format!(
            " (tried before it: passed over at position_m = [{:.1}, {:.1}], heading_deg = {:.0}",
            first.x_m, first.y_m, first.heading_deg
        )) && said
            .contains("IN THE GROUND UNDER ITS PADS: CULVERT 0.40 m below the set-up level under the front left pad"),
        "{said}"
    );
    // Mats the ground bears nowhere: the first position that plans, with
    // what its mats put on the ground.
    let mut soft = spec_of(-14.0);
    soft.ground = Some(liftplan_core::lift::GroundSpec { mat_m: [1.0, 1.0], allowable_kpa: Some(50.0) });
    let soft = soft.resolve(ac700()).unwrap();
    let (named, said, _) = searched(&site(), &soft);
    assert!(named.planned_steps().is_some() && named.pads_to_check(), "{named:?}");
    assert!(
        said.contains(" of the chart's capacity), BUT ") && said.contains("MORE THAN THE 50 kPa THE GROUND MAY BEAR"),
        "{said}"
    );
}

/// A lift over capacity where the crane stands names the nearest position
/// from which the chart carries the load at both the pick and the set, the
/// crane stands clear, and the lift plans; given that position, the lift
/// file plans the same there. So does a lift whose crane stands on the wall,
/// or whose boom meets a mast at the pick (not one whose load meets
/// something there). Where the chart's reach cannot span the pick and the
/// set, or every such position stands on the wall, it says so.
#[test]
fn a_lift_over_capacity_names_a_crane_position_where_it_plans() {
    use liftplan_plan::positions::{self, Found};
    let mesh = site();
    let m = map(&mesh);
    let world = World::new(&mesh, &[], &[]).unwrap();
    let t = task(-14.0);
    let table = chart_reaching(24.0);
    let chart = table.config("none").unwrap();
    let site = Site { map: &m, world: &world, charts: Some(&table) };
    let e = plan_lift(&t, &site, &quick(), 3).unwrap_err().to_string();
    assert!(e.contains("pick is over capacity"), "{e}");
    let found = positions::search(&t, &site, chart, &quick(), 3, positions::Sought::Plans);
    let (Found::Tried(tried), Some(k)) = (&found, found.chosen()) else { panic!("{e}: {found:?}") };
    let at = &tried[k];
    let steps = at.planned_steps().unwrap();
    assert!(
        e.contains(&format!(
            "; the crane set up at position_m = [{:.1}, {:.1}], heading_deg = {:.0}, ground_z_m = 0.00 (the lift's: no ground is scanned there; ",
            at.x_m, at.y_m, at.heading_deg
        )) && e.contains(&format!("and there the lift plans and passes the validator in {steps} steps")),
        "{e}"
    );
    // Within the chart's reach of both, clear of the wall, nearer than any
    // position said to be refused before it.
    for (hook, r) in [([22.0, -14.0], at.pick.1), ([22.0, 14.0], at.set.1)] {
        assert!(((at.x_m - hook[0]).hypot(at.y_m - hook[1]) - r).abs() < 1e-6 && r <= 24.0, "{at:?}");
    }
    assert!(at.x_m < 14.0 - 3.0 || at.x_m > 34.0 + 3.0 || at.y_m.abs() > 4.0, "{at:?}");
    assert!(tried.windows(2).all(|w| w[0].moved_m <= w[1].moved_m), "{tried:?}");
    // The lift file given that position plans there, the same.
    let mut spec = spec_of(-14.0);
    spec.crane.position_m = [at.x_m, at.y_m];
    spec.crane.heading_deg = at.heading_deg;
    let there = spec.resolve(ac700()).unwrap();
    let (plan, _) = plan_lift(&there, &site, &quick(), 3).unwrap();
    assert_eq!(plan.steps.len(), steps);
    assert!(plan.summary.max_utilisation_pct <= 100.0);
    // A planner's map without the wall, a validator's world with it: every
    // plan passes through the wall and is rejected, at each position tried
    // once (a refusal there searches no further).
    let mut slab = TriMesh::default();
    box_part(&mut slab, "SLAB", [-40.0, -40.0, -0.3], [60.0, 40.0, 0.0]);
    let blind = map(&slab);
    let unseen = Site { map: &blind, world: &world, charts: Some(&table) };
    let Found::Tried(tried) = positions::search(&t, &unseen, chart, &quick(), 3, positions::Sought::Plans) else {
        panic!("no position tried")
    };
    assert!(
        tried.len() == positions::MOST_PLANNED
            && tried.iter().all(|t| matches!(t.outcome, positions::Outcome::Refused(_))),
        "{tried:?}"
    );
    let e = plan_lift(&t, &unseen, &quick(), 3).unwrap_err().to_string();
    assert!(e.contains(&format!("; at the {} crane position(s) nearest the lift's where it carries the load at both and stands clear, the lift is refused too: at position_m = [", positions::MOST_PLANNED)), "{e}");
    assert_eq!(e.matches("the validator rejected the plan").count(), positions::MOST_PLANNED, "{e}");
    // A lift with a permitted swing range keeps its heading: the range
    // turns with the carrier. At heading 0 the carrier meets the wall
    // wherever the chart reaches both (the position found above is turned).
    assert_ne!(at.heading_deg, 0.0);
    let mut ranged = spec_of(-14.0);
    ranged.swing_range_deg = Some([-180.0, 180.0]);
    let ranged = ranged.resolve(ac700()).unwrap();
    match positions::search(&ranged, &site, chart, &quick(), 3, positions::Sought::Plans) {
        Found::Tried(tried) => assert!(tried.iter().all(|t| t.heading_deg == 0.0), "{tried:?}"),
        found => assert!(matches!(found, Found::NoClearSetUp { .. }), "{found:?}"),
    }
    // A crane set up on the wall: where else it could stand, too.
    let mut on_wall = spec_of(-14.0);
    on_wall.crane.position_m = [20.0, 0.0];
    let on_wall = on_wall.resolve(ac700()).unwrap();
    let e = plan_lift(&on_wall, &site, &quick(), 3).unwrap_err().to_string();
    assert!(e.contains("crane set-up: the carrier meets WALL"), "{e}");
    let found = positions::search(&on_wall, &site, chart, &quick(), 3, positions::Sought::Plans);
    let (Found::Tried(tried), Some(k)) = (&found, found.chosen()) else { panic!("{e}: {found:?}") };
    let at = &tried[k];
    assert!(at.planned_steps().is_some() && at.moved_m < 15.0, "{tried:?}");
    assert!(
        e.contains(&format!(
            "; move the crane or clear its footprint; the crane set up at position_m = [{:.1}, {:.1}]",
            at.x_m, at.y_m
        )),
        "{e}"
    );
    // A mast between the crane and the pick that the boom meets there: the
    // crane's own structure, which another position clears.
    let mut masted = self::site();
    box_part(&mut masted, "MAST", [11.3, -8.0, 0.0], [12.3, -7.0, 40.0]);
    let masted_map = map(&masted);
    let masted_world = World::new(&masted, &[], &[]).unwrap();
    let ample = chart_reaching(30.0);
    let at_mast = Site { map: &masted_map, world: &masted_world, charts: Some(&ample) };
    let e = plan_lift(&t, &at_mast, &quick(), 3).unwrap_err().to_string();
    assert!(e.contains("the lifted-off pick configuration is not allowed") && e.contains("boom and MAST"), "{e}");
    assert!(e.contains("; the crane set up at position_m = [") && e.contains("and there the lift plans"), "{e}");
    // A load that meets something at its pick moves with the crane: no
    // position is searched.
    let mut crate_at_pick = self::site();
    box_part(&mut crate_at_pick, "CRATE", [23.5, -14.5, 0.0], [24.5, -13.5, 4.0]);
    let crate_map = map(&crate_at_pick);
    let crate_world = World::new(&crate_at_pick, &[], &[]).unwrap();
    let e = plan_lift(&t, &Site { map: &crate_map, world: &crate_world, charts: Some(&ample) }, &quick(), 3)
        .unwrap_err()
        .to_string();
    assert!(e.contains("load and CRATE") && !e.contains("position_m") && !e.contains("crane positions"), "{e}");
    // A reach of 16 m spans the two only over the wall.
    let table = chart_reaching(16.0);
    let site = Site { map: &m, world: &world, charts: Some(&table) };
    let found = positions::search(&t, &site, table.config("none").unwrap(), &quick(), 3, positions::Sought::Plans);
    assert!(matches!(found, Found::NoClearSetUp { looked_at, in_areas: false } if looked_at > 10), "{found:?}");
    let e = plan_lift(&t, &site, &quick(), 3).unwrap_err().to_string();
    assert!(e.contains("crane positions nearest the lift's within the reach of 'none' of both the pick and the set, none stands clear (its carrier and outriggers on ground level within 0.50 m, the boom and the load clear at the lift-off and the set-down)"), "{e}");
    // A reach of 12 m does not span them.
    let table = chart_reaching(12.0);
    let site = Site { map: &m, world: &world, charts: Some(&table) };
    let e = plan_lift(&t, &site, &quick(), 3).unwrap_err().to_string();
    assert!(
        e.contains("; no crane position carries it at both: the pick and the set lie more than twice 12.00 m apart"),
        "{e}"
    );
}

/// A lift resumed part way (the load hanging above the wall's far side,
/// where the lift over the wall took it): the plan starts there, with no
/// lift-off, and passes the validator, which refuses the plan from the pick
/// for it (it does not start where the load hangs). Where the load hangs
/// within its clearance of the wall, no path is planned and the refusal
/// says so.
#[test]
fn a_lift_resumed_part_way_plans_from_where_the_load_hangs() {
    let (t, world, plan) = over_the_wall();
    let mesh = site();
    let m = map(&mesh);
    let site = Site { map: &m, world: &world, charts: None };
    // Where the first plan has the load at its highest, part way over.
    let over = plan
        .moves
        .iter()
        .map(|mv| mv.to)
        .max_by(|a, b| t.crane.load_obb(a, &t.load).center.z.total_cmp(&t.crane.load_obb(b, &t.load).center.z))
        .unwrap();
    let resumed_at = |c: &Config| {
        let mut spec = spec_of(-14.0);
        spec.resume_from = Some(
            toml::from_str(&format!(
                "swing_deg = {}\nluff_deg = {}\nhoist_m = {}\nyaw_deg = {}",
                c.swing_rad.to_degrees(),
                c.radial.to_degrees(),
                c.hoist_m,
                c.load_yaw_rad.to_degrees()
            ))
            .unwrap(),
        );
        spec.resolve(ac700()).unwrap()
    };
    let r = resumed_at(&over);
    let (from_there, _) = plan_lift(&r, &site, &quick(), 3).unwrap();
    assert!(from_there.validator.ok, "{:?}", from_there.validator.problems);
    let first = from_there.moves[0];
    let apart =
        |a: &Config, b: &Config| a.to_array().iter().zip(b.to_array()).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max);
    assert!(apart(&first.from, &over) < 1e-9, "{:?} is not {over:?}", first.from);
    assert!(from_there.moves.iter().all(|mv| apart(&mv.from, &t.pick) > 1.0), "a resumed lift has no lift-off");
    assert!((from_there.moves.last().unwrap().to.hoist_m - t.set.hoist_m).abs() < 1e-9);
    // Fewer steps than from the pick: the part done is not done again.
    assert!(
        from_there.steps.len() < plan.steps.len(),
        "{} steps, {} from the pick",
        from_there.steps.len(),
        plan.steps.len()
    );
    // The plan from the pick does not start where the load hangs.
    let landing: Vec<bool> = (0..plan.moves.len()).map(|i| i == plan.moves.len() - 1).collect();
    let v = validate_lift(&r, None, &world, &rules(), &plan.moves, &landing);
    assert!(v.problems.iter().any(|p| p.contains("not at its resume_from pose")), "{:?}", v.problems);

    // The load hanging 0.5 m off the wall's face, below its top.
    let mut beside = resumed_at(&over);
    let pose = liftplan_core::crane::LoadPose { x_m: 22.0, y_m: -2.5, z_m: 5.0, yaw_rad: 0.0 };
    let c = beside.crane.inverse(&pose, &beside.load).unwrap();
    beside.resume_from = Some((c, pose));
    let why = plan_lift(&beside, &site, &quick(), 3).map(|_| "planned").unwrap_err().to_string();
    assert!(why.contains("where the load hangs now (resume_from) is not clear") && why.contains("WALL"), "{why}");
    // Hanging 0.3 m above where it was picked, 0.8 m over the slab: a lift
    // off the pick may be that close over its landing zone, a lift resumed
    // part way is not lifted off there and keeps its full clearance.
    let low = Config { hoist_m: t.pick.hoist_m - 0.3, ..t.pick };
    let mut just_up = resumed_at(&over);
    just_up.resume_from = Some((low, t.crane.load_pose(&low, &t.load)));
    let why = plan_lift(&just_up, &site, &quick(), 3).map(|_| "planned").unwrap_err().to_string();
    assert!(why.contains("where the load hangs now (resume_from) is not clear") && why.contains("SLAB"), "{why}");

    // A pick the chart does not carry the load at (29.7 m out; 50 t to
    // 28 m, 3 t beyond) refuses the lift from it, not the lift resumed 8 m
    // over its set position (26.1 m out): that was lifted off already.
    let table = chart(3.0);
    let charted = Site { map: &m, world: &world, charts: Some(&table) };
    let far = task(-20.0);
    let e = plan_lift(&far, &charted, &quick(), 3).map(|_| "planned").unwrap_err().to_string();
    assert!(e.contains("pick is over capacity"), "{e}");
    let mut over_set = far.clone();
    let hangs = Config { hoist_m: far.set.hoist_m - 8.0, ..far.set };
    over_set.resume_from = Some((hangs, far.crane.load_pose(&hangs, &far.load)));
    let (down, _) = plan_lift(&over_set, &charted, &quick(), 3).unwrap();
    assert!(down.validator.ok && down.summary.max_utilisation_pct < 100.0, "{:?}", down.validator.problems);
}
