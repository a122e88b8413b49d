//! The tables never say "free" where an exact check at a configuration inside
//! the cell finds a collision, and the checker's continuous moves never pass
//! through a configuration that the exact check rejects.

use liftplan_core::crane::{Config, Dependence, builtin};
use liftplan_core::lift::{LiftSpec, LiftTask};
use liftplan_core::mesh::TriMesh;
use liftplan_cspace::{CSpace, Checker, Joint, Problem, Settings, Strategy};
use liftplan_depthmap::mdm::Mdm;
use proptest::prelude::*;

fn task() -> LiftTask {
    let text = r#"
id = "P"
load = { name = "box", mass_t = 3.0, size_m = [5.0, 2.0, 2.0], cog_m = [0.3, 0.0, 0.0] }
rigging = { mass_t = 0.1, height_m = 2.0 }
crane = { model = "ac-700", position_m = [0.0, 0.0], ground_z_m = 0.0, heading_deg = 20.0, boom_m = 40.0, chart_config = "none" }
pick = { x_m = 20.0, y_m = -12.0, z_m = 0.5, yaw_deg = 0.0 }
set = { x_m = 20.0, y_m = 12.0, z_m = 0.5, yaw_deg = 90.0 }
clearance_m = 0.5
"#;
    let spec: LiftSpec = toml::from_str(text).unwrap();
    spec.resolve(builtin("ac-700").unwrap()).unwrap()
}

/// Twelve random boxes, and over all of them, where `roofed`, a slab far
/// above the boom's reach.
fn scene(seed: u64, roofed: bool) -> Mdm {
    let mut mesh = TriMesh::default();
    if roofed {
        let g = mesh.group_id("ROOF");
        mesh.add_box(g, [-60.0, -60.0, 70.0], [60.0, 60.0, 71.0]);
    }
    let mut s = seed;
    let mut next = || {
        s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (s >> 11) as f64 / (1u64 << 53) as f64
    };
    for k in 0..12 {
        let g = mesh.group_id(&format!("B{k}"));
        let (cx, cy) = (next() * 70.0 - 35.0, next() * 70.0 - 35.0);
        if cx.hypot(cy) < 9.0 {
            continue; // not on the crane itself
        }
        let (hx, hy, top) = (0.5 + next() * 4.0, 0.5 + next() * 4.0, 2.0 + next() * 25.0);
        mesh.add_box(g, [cx - hx, cy - hy, 0.0], [cx + hx, cy + hy, top]);
    }
    let inp = liftplan_depthmap::Inputs { points: vec![], ground: vec![], mesh };
    liftplan_depthmap::build_cpu(&inp, &liftplan_depthmap::Settings { cell_m: 0.5, ..Default::default() }).unwrap().0
}

/// A configuration anywhere in the crane's swing and radial range, with up
/// to 30 m of rope more than the shortest, from the unit stream `u`.
fn random_config(t: &LiftTask, u: &mut impl FnMut() -> f64) -> Config {
    let lim = t.crane.limits();
    Config {
        swing_rad: u() * std::f64::consts::TAU,
        radial: lim.radial.0 + u() * (lim.radial.1 - lim.radial.0),
        hoist_m: lim.hoist_m.0 + u() * 30.0,
        load_yaw_rad: u() * 3.0,
    }
}

/// Exact: every part that the tables or online checks cover, grown by the
/// clearance; what hangs as far off as it may hang (swung by a gust where the
/// lift is planned for the wind, off by its centre of gravity's tolerance).
fn exact_free(t: &LiftTask, map: &Mdm, c: &Config) -> bool {
    t.crane.part_kinds().iter().all(|&k| {
        if k.dependence() == Dependence::Fixed {
            return true;
        }
        let Some(b) = t.crane.part(k, c, &t.load) else { return true };
        let b = if k.dependence() == Dependence::Full { t.hanging_swept(k, &b, t.crane.sheave(c).z) } else { b };
        let structure = matches!(k.dependence(), Dependence::Swing | Dependence::SwingRadial);
        map.hit_where(&b.expanded(t.clearance_m), |iv| !(structure && iv.obj == 0)).is_none()
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(liftplan_core::testing::proptest_cases(16)))]
    #[test]
    fn free_answers_are_free(seed in any::<u64>(), strategy in 0usize..3, gusty in any::<bool>(), cog_off in any::<bool>()) {
        let mut t = task();
        if gusty {
            // Twice what the permissible wind gives any load (1.5 cm per
            // metre at 9.8 m/s), so a table that leaves the swing out shows.
            t.gust_swing_per_m = 0.03;
        }
        if cog_off {
            // A centre of gravity known to 0.3 m either way.
            t.cog_tolerance_m = 0.3;
        }
        let map = scene(seed, false);
        let s = Settings {
            swing_step_deg: 2.0,
            luff_step_deg: 2.0,
            strategy: [Strategy::Hybrid, Strategy::Full, Strategy::Online][strategy],
            ..Settings::default()
        };
        let cs = CSpace::build(&Problem { task: &t, chart: None, map: &map }, &s);
        let ck = Checker::new(&cs, &map, &t, vec![], s.sample_m);
        let lim = t.crane.limits();
        let mut u = liftplan_core::testing::unit_stream(seed);
        for _ in 0..150 {
            let c = random_config(&t, &mut u);
            if ck.config(&c).is_ok() {
                prop_assert!(exact_free(&t, &map, &c), "checker says free, exact check collides at {c:?}");
            }
            // Luff, hoist and load-rotation moves the checker passes are exactly free at fine samples.
            let moves = [
                (Joint::Radial, lim.radial.0 + u() * (lim.radial.1 - lim.radial.0)),
                (Joint::Hoist, lim.hoist_m.0 + u() * 30.0),
                (Joint::Rotate, c.load_yaw_rad + (u() - 0.5) * 3.0),
            ];
            for (joint, to) in moves {
                if ck.motion(&c, joint, to).is_ok() {
                    for k in 0..=200 {
                        let mut a = c.to_array();
                        a[joint.index()] += (to - a[joint.index()]) * k as f64 / 200.0;
                        let q = Config::from_array(a);
                        prop_assert!(exact_free(&t, &map, &q), "{joint:?} move passed but collides at {q:?}");
                    }
                }
            }
            // A swing move the checker passes is exactly free at fine samples.
            let to = c.swing_rad + (u() - 0.5) * 1.5;
            if ck.motion(&c, Joint::Swing, to).is_ok() {
                for k in 0..=200 {
                    let x = c.swing_rad + (to - c.swing_rad) * k as f64 / 200.0;
                    let q = Config { swing_rad: x, ..c };
                    prop_assert!(exact_free(&t, &map, &q), "swing move passed but collides at {q:?}");
                }
            }
        }
    }
}

/// A structure over the whole site, above the boom (a roof, a pipe bridge
/// over the crane's reach): the rope below it is as clear as without it.
/// It was "no clear rope" in every cell under it, which sent every
/// hanging-part check there to box queries (the demo under its plant model
/// 100 m up searched for 25 s instead of 1 s).
#[test]
fn a_structure_above_the_boom_leaves_the_rope_below_it_clear() {
    let t = task();
    let s = Settings { swing_step_deg: 2.0, luff_step_deg: 2.0, ..Settings::default() };
    let table = |roofed: bool| {
        let map = scene(7, roofed);
        CSpace::build(&Problem { task: &t, chart: None, map: &map }, &s).max_hoist
    };
    let (open, roofed) = (table(false), table(true));
    // And what the checker then passes under the roof is free.
    let map = scene(7, true);
    let cs = CSpace::build(&Problem { task: &t, chart: None, map: &map }, &s);
    let ck = Checker::new(&cs, &map, &t, vec![], s.sample_m);
    let mut u = liftplan_core::testing::unit_stream(7);
    let mut passed = 0;
    for _ in 0..400 {
        let c = random_config(&t, &mut u);
        if ck.config(&c).is_ok() {
            passed += 1;
            assert!(exact_free(&t, &map, &c), "checker says free, exact check collides at {c:?}");
        }
    }
    assert!(passed > 40, "{passed} of 400 passed");
    let no_rope = |hs: &[f32]| hs.iter().filter(|h| **h == f32::NEG_INFINITY).count();
    assert!(
        no_rope(&roofed) == no_rope(&open) && no_rope(&open) < open.len() / 4,
        "{} {}",
        no_rope(&roofed),
        no_rope(&open)
    );
    for (k, (o, r)) in open.iter().zip(&roofed).enumerate() {
        // Under the roof each cell has the exact query, no more cautious
        // than the dilated tops over the widest envelope.
        assert!(r >= o, "cell {k}: longest clear rope {r} under the roof, {o} without it");
    }
}

/// The load and its rigging clear of the crane's own parts that stand or
/// swing (carrier, outriggers, superstructure, counterweight), as the
/// validator asks (1 cm); swung as far as a gust can swing them, where the
/// lift is planned for the wind.
fn off_the_crane(t: &LiftTask, c: &Config) -> bool {
    let own: Vec<_> = t
        .crane
        .part_kinds()
        .iter()
        .filter(|k| matches!(k.dependence(), Dependence::Fixed | Dependence::Swing))
        .filter_map(|&k| t.crane.part(k, c, &t.load))
        .collect();
    let sheave_z = t.crane.sheave(c).z;
    t.crane.hanging_parts(c, &t.load)[..2]
        .iter()
        .all(|(k, b)| own.iter().all(|o| !t.hanging_swept(*k, b, sheave_z).expanded(0.01).intersects(o)))
}

/// Near the crane, with rope enough to reach the ground, the checker passes
/// no configuration and no hoist or swing move where the load or its
/// rigging meets the crane's own carrier, outriggers or superstructure (the
/// depth map holds none of them): with a trailer parked beside the crane
/// and nothing else in the way, a plan went through the carrier, which the
/// validator refused ("load is 0.000 m from the crane's carrier"). Also
/// with what hangs swung by a gust (3 cm per metre it hangs), and off by a
/// centre of gravity known to 0.3 m.
#[test]
fn the_load_keeps_off_the_crane_it_hangs_from() {
    for (gust, cog_tolerance_m) in [(0.0, 0.0), (0.03, 0.0), (0.0, 0.3)] {
        let mut t = task();
        (t.gust_swing_per_m, t.cog_tolerance_m) = (gust, cog_tolerance_m);
        keeps_off_the_crane(&t);
    }
}

fn keeps_off_the_crane(t: &LiftTask) {
    // Nothing near the crane: one post far off, for the map to have an extent.
    let mut mesh = TriMesh::default();
    let g = mesh.group_id("FAR");
    mesh.add_box(g, [-45.0, -45.0, 0.0], [-44.0, -44.0, 1.0]);
    let inp = liftplan_depthmap::Inputs { points: vec![], ground: vec![], mesh };
    let map = liftplan_depthmap::build_cpu(&inp, &liftplan_depthmap::Settings { cell_m: 0.5, ..Default::default() })
        .unwrap()
        .0;
    let lim = t.crane.limits();
    let mut u = liftplan_core::testing::unit_stream(11);
    for strategy in [Strategy::Hybrid, Strategy::Full, Strategy::Online] {
        let s = Settings { swing_step_deg: 2.0, luff_step_deg: 2.0, strategy, ..Settings::default() };
        let cs = CSpace::build(&Problem { task: t, chart: None, map: &map }, &s);
        let ck = Checker::new(&cs, &map, t, vec![], s.sample_m);
        let (mut passed, mut kept_off) = (0, 0);
        for _ in 0..300 {
            // The steepest fifth of the boom's range (the hook within about
            // 12 m of the crane), the load's underside 1 m below the ground
            // to 5 m above it (the carrier's height).
            let mut c = Config {
                swing_rad: u() * std::f64::consts::TAU,
                radial: lim.radial.1 - u() * 0.2 * (lim.radial.1 - lim.radial.0),
                hoist_m: 0.0,
                load_yaw_rad: u() * 3.0,
            };
            let hang = t.crane.model.hook.height_m + t.load.rigging_height_m + t.load.size_m[2];
            c.hoist_m = (t.crane.sheave(&c).z - hang - (6.0 * u() - 1.0)).clamp(lim.hoist_m.0, lim.hoist_m.1);
            match ck.config(&c) {
                Ok(()) => {
                    passed += 1;
                    assert!(off_the_crane(t, &c), "{strategy:?}: passed with the load on the crane at {c:?}");
                }
                Err(b) if b.object.as_deref().is_some_and(|o| o.starts_with("the crane's")) => kept_off += 1,
                Err(_) => {}
            }
            for (joint, to) in [
                (Joint::Hoist, lim.hoist_m.0 + u() * (lim.hoist_m.1 - lim.hoist_m.0)),
                (Joint::Swing, c.swing_rad + (u() - 0.5) * 2.0),
            ] {
                if ck.motion(&c, joint, to).is_ok() {
                    for k in 0..=200 {
                        let mut a = c.to_array();
                        a[joint.index()] += (to - a[joint.index()]) * k as f64 / 200.0;
                        let q = Config::from_array(a);
                        assert!(off_the_crane(t, &q), "{strategy:?}: {joint:?} move passed through the crane at {q:?}");
                    }
                }
            }
        }
        assert!(passed > 30 && kept_off > 30, "{strategy:?}: {passed} passed, {kept_off} kept off the crane");
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(liftplan_core::testing::proptest_cases(64)))]
    /// The highest top below a height over a rectangle is never lower than
    /// the cell-by-cell walk's: the pyramid's blocks where they answer
    /// (they may reach past the rectangle), else down the pyramid exactly
    /// the walk's. Stopped at `enough`, it is that, or a top at or above
    /// `enough` and no higher than it.
    #[test]
    fn the_highest_top_below_a_height_is_the_walks(
        seed in any::<u64>(), roofed in any::<bool>(),
        x in -50.0..50.0f64, y in -50.0..50.0f64, w in 0.0..30.0f64, h in 0.0..30.0f64,
        z_max in -1.0..80.0f32, enough in -1.0..80.0f32,
    ) {
        let map = scene(seed, roofed);
        let walk = liftplan_cspace::highest_interval_below(&map, x, x + w, y, y + h, z_max)
            .map_or(f32::NEG_INFINITY, |iv| iv.zhi);
        let below = liftplan_cspace::highest_below(&map, x, x + w, y, y + h, z_max);
        prop_assert!(below >= walk, "{} under the walk's {}", below, walk);
        if map.max_top_in(x, x + w, y, y + h) >= z_max {
            prop_assert_eq!(below.to_bits(), walk.to_bits());
        }
        let until = liftplan_cspace::highest_below_until(&map, (x, x + w, y, y + h), z_max, enough);
        prop_assert!(until.to_bits() == below.to_bits() || (until >= enough && until <= below), "{} of {}", until, below);
    }
}

/// What hangs swung further than any wind swings it (the C-space is built
/// only from a lift whose numbers passed their checks, but its window must
/// not depend on that): the C-space is built (the dilation's window, worked
/// out from the reach, overflowed at 1e300 per metre and panicked) and
/// passes no configuration with the load clear of the ground.
#[test]
fn a_swing_past_any_wind_passes_nothing() {
    let map = scene(5, false);
    for gust in [1e12, 1e300, f64::INFINITY] {
        let mut t = task();
        t.gust_swing_per_m = gust;
        let s = Settings { swing_step_deg: 4.0, luff_step_deg: 4.0, ..Settings::default() };
        let cs = CSpace::build(&Problem { task: &t, chart: None, map: &map }, &s);
        let ck = Checker::new(&cs, &map, &t, vec![], s.sample_m);
        let lim = t.crane.limits();
        let mut u = liftplan_core::testing::unit_stream(3);
        for _ in 0..50 {
            let c = Config {
                swing_rad: u() * std::f64::consts::TAU,
                radial: lim.radial.0 + u() * (lim.radial.1 - lim.radial.0),
                hoist_m: lim.hoist_m.0 + u() * 0.5 * (lim.hoist_m.1 - lim.hoist_m.0),
                load_yaw_rad: u() * 3.0,
            };
            assert!(ck.config(&c).is_err(), "gust {gust} per m: passed {c:?}");
        }
    }
}
