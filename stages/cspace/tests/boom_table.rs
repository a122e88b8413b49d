//! The boom rows of the hybrid table (marked obstacle by obstacle, see
//! `src/boom.rs`) against direct box queries of the boom on the depth map:
//! never free where the boom grown by the clearance meets an obstacle anywhere
//! in the cell, and blocked only where the boom, grown a little more than the
//! cell's own motion, does meet one.

use liftplan_core::crane::{Config, PartKind, builtin};
use liftplan_core::lift::{LiftSpec, LiftTask};
use liftplan_cspace::{CSpace, Problem, Settings};
use proptest::prelude::*;

#[path = "support/scene.rs"]
mod scene;

fn task(heading_deg: f64) -> LiftTask {
    let text = format!(
        r#"
id = "P"
load = {{ name = "box", mass_t = 3.0, size_m = [4.0, 2.0, 2.0], cog_m = [0.0, 0.0, 0.0] }}
rigging = {{ mass_t = 0.1, height_m = 2.0 }}
crane = {{ model = "ac-700", position_m = [0.0, 0.0], ground_z_m = 0.0, heading_deg = {heading_deg}, boom_m = 40.0, chart_config = "none" }}
pick = {{ x_m = 20.0, y_m = -12.0, z_m = 0.5, yaw_deg = 0.0 }}
set = {{ x_m = 20.0, y_m = 12.0, z_m = 0.5, yaw_deg = 90.0 }}
clearance_m = 0.5
"#
    );
    let spec: LiftSpec = toml::from_str(&text).unwrap();
    spec.resolve(builtin("ac-700").unwrap()).unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(liftplan_core::testing::proptest_cases(8)))]
    #[test]
    fn boom_rows_are_conservative_and_tight(seed in any::<u64>(), heading in 0.0f64..360.0) {
        let t = task(heading);
        let map = scene::depth_map(scene::site(seed), &[]);
        let s = Settings { swing_step_deg: 2.0, luff_step_deg: 2.0, ..Settings::default() };
        let cs = CSpace::build(&Problem { task: &t, chart: None, map: &map }, &s);
        let mut u = liftplan_core::testing::unit_stream(seed);
        let boom_len = t.crane.placement.boom_length_m + 2.0 + 3.0;
        // What a box query must add to cover every configuration of a cell.
        let cell_motion = boom_len * (cs.swing_step + cs.radial_step) / 2.0;
        let (mut free, mut blocked) = (0, 0);
        for k in 0..cs.nr {
            for i in 0..cs.ns {
                let hit = cs.cell_hits[(k * cs.ns + i) as usize];
                if hit.is_none() {
                    free += 1;
                    let (a, b) = cs.row_range(k);
                    for _ in 0..2 {
                        let c = Config {
                            swing_rad: (i as f64 + u()) * cs.swing_step,
                            radial: a + u() * (b - a),
                            hoist_m: 5.0,
                            load_yaw_rad: 0.0,
                        };
                        let boom = t.crane.part(PartKind::Boom, &c, &t.load).unwrap();
                        prop_assert!(
                            map.hit(&boom.expanded(t.clearance_m)).is_none(),
                            "cell ({i}, {k}) is free but the boom meets the map at {c:?}"
                        );
                    }
                } else {
                    blocked += 1;
                    let c = Config { swing_rad: cs.swing_center(i), radial: cs.row_center(k), hoist_m: 5.0, load_yaw_rad: 0.0 };
                    let boom = t.crane.part(PartKind::Boom, &c, &t.load).unwrap();
                    prop_assert!(
                        map.hit(&boom.expanded(t.clearance_m + cell_motion + 0.5)).is_some(),
                        "cell ({i}, {k}) is blocked by {hit:?} but nothing is within reach"
                    );
                }
            }
        }
        prop_assert!(free > 0 && blocked > 0, "a scene should have both: {free} free, {blocked} blocked");
    }
}
