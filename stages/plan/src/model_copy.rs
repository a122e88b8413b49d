//! The lift's pick and set positions against the plant model's own copy of
//! the load: a plant model draws the equipment a lift installs where it is
//! installed, and the project leaves it out of the obstacles (`[plant]
//! exclude`). Where such a group stands at the set position (or at the pick,
//! for equipment taken out), it says where the design puts the load, so a
//! set position typed off it, a yaw a quarter turn off or a load box smaller
//! than the model's are named here.
//!
//! Words only: nothing here decides whether a lift is planned; the set-down
//! checks and the validator stand as they are.

use liftplan_core::crane::Config;
use liftplan_core::lift::LiftTask;
use liftplan_core::mesh::ModelBox;
use serde::{Deserialize, Serialize};

/// Farther than this apart (m), in plan or in height, a position differs
/// from the model's copy: what the model against the scans allows.
pub const PLACE_TOLERANCE_M: f64 = 0.1;

/// Past [`PLACE_TOLERANCE_M`] by less than this (m) is within it: a
/// distance said as "0.10 m" is not flagged for the model's single-precision
/// numbers.
const ROUNDING_M: f64 = 0.005;

/// Turned more than this from the model's copy (degrees), a position
/// differs from it (an 8 m load's ends move 0.14 m at 2°).
pub const TURN_TOLERANCE_DEG: f64 = 2.0;

/// A footprint whose sides differ by less than this (m) has no long side
/// to compare the turn by: it is compared a quarter turn at a time.
const SQUARE_WITHIN_M: f64 = 0.1;

/// Each of a group's sizes (long side, short side, height) within this
/// factor of the load's, for the group to be taken as the load's copy.
const ALIKE_FACTOR: f64 = 2.0;

/// One position of a lift against the model's copy of its load.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AgainstModel {
    /// `pick` or `set`.
    pub at: String,
    /// The group left out of the model (`[plant] exclude`).
    pub object: String,
    /// From the load's box to the model's copy: its centre in plan and its
    /// underside (m, site frame).
    pub offset_m: [f64; 3],
    /// The copy's long side against the load's (degrees counter-clockwise,
    /// in (-90, 90]; in (-45, 45] where either footprint is square).
    pub turn_deg: f64,
    /// Long side, short side and height of the copy's box and of the load's (m).
    pub model_size_m: [f64; 3],
    pub load_size_m: [f64; 3],
    /// The keys that set this position: in plan, its height and its yaw.
    pub keys: [String; 3],
}

impl AgainstModel {
    pub fn plan_offset_m(&self) -> f64 {
        self.offset_m[0].hypot(self.offset_m[1])
    }

    pub fn turned(&self) -> bool {
        self.turn_deg.abs() > TURN_TOLERANCE_DEG
    }

    pub fn moved(&self) -> bool {
        self.plan_offset_m() > PLACE_TOLERANCE_M + ROUNDING_M
    }

    pub fn raised(&self) -> bool {
        self.offset_m[2].abs() > PLACE_TOLERANCE_M + ROUNDING_M
    }

    /// The copy is larger than the load's box in some size.
    pub fn larger(&self) -> bool {
        (0..3).any(|i| self.model_size_m[i] > self.load_size_m[i] + PLACE_TOLERANCE_M + ROUNDING_M)
    }

    pub fn agrees(&self) -> bool {
        !(self.turned() || self.moved() || self.raised() || self.larger())
    }

    /// [`AgainstModel::agrees`] said in few words, for the PDF.
    pub fn agrees_clause(&self) -> String {
        format!(
            "the plant model's {} (left out as the load) stands at the {} position to {:.2} m and {:.1}°",
            self.object,
            self.at,
            self.plan_offset_m().max(self.offset_m[2].abs()),
            self.turn_deg.abs()
        )
    }

    /// One sentence without its full stop, for the run's line and the PDF.
    pub fn said(&self) -> String {
        let (at, object) = (&self.at, &self.object);
        let [xy_key, z_key, yaw_key] = &self.keys;
        let left_out = "(left out of the obstacles as the load, [plant] exclude)";
        if self.agrees() {
            return format!(
                "the {at} position agrees with the plant model's {object} {left_out}: {:.2} m apart in plan, {:.2} m in height, turned {:.1}° from it",
                self.plan_offset_m(),
                self.offset_m[2].abs(),
                self.turn_deg.abs()
            );
        }
        let mut differs = Vec::new();
        if self.turned() {
            // A quarter turn is a quarter turn either way.
            let way = match self.turn_deg {
                t if t.abs() >= 89.5 => "",
                t if t > 0.0 => " anticlockwise",
                _ => " clockwise",
            };
            differs.push(format!(
                "the model has it turned {:.0}°{way} from {yaw_key}: CHECK {yaw_key}",
                self.turn_deg.abs()
            ));
        }
        if self.moved() {
            // In the site frame's axes, as the model's move onto the scans is said.
            // No "-0.00" for a rounding below zero.
            let [dx, dy] = [0, 1].map(|a| if self.offset_m[a].abs() < 0.005 { 0.0 } else { self.offset_m[a] });
            differs.push(format!("the model has it x {dx:+.2} m, y {dy:+.2} m from it: CHECK {xy_key}"));
        }
        if self.raised() {
            let dz = self.offset_m[2];
            differs.push(format!(
                "the model has its underside {:.2} m {}: CHECK {z_key}",
                dz.abs(),
                if dz > 0.0 { "higher" } else { "lower" }
            ));
        }
        if self.larger() {
            let [m, l] =
                [self.model_size_m, self.load_size_m].map(|s| format!("{:.2} x {:.2} x {:.2} m", s[0], s[1], s[2]));
            differs.push(format!(
                "the model's copy is {m} (long side, short side, height), larger than the load's box of {l}: CHECK size_m (a box smaller than the load keeps too little clearance)"
            ));
        }
        format!(
            "THE {} POSITION DIFFERS FROM THE PLANT MODEL'S {object} {left_out}: {}",
            at.to_uppercase(),
            differs.join("; ")
        )
    }
}

/// The lift's pick and set against the copies of its load among `boxes`
/// (the groups left out of the plant model), each where one stands there.
pub fn of_lift(task: &LiftTask, boxes: &[ModelBox]) -> Vec<AgainstModel> {
    [(true, &task.pick), (false, &task.set)]
        .into_iter()
        .filter_map(|(at_pick, c)| at(task, boxes, c, at_pick))
        .collect()
}

fn at(task: &LiftTask, boxes: &[ModelBox], c: &Config, at_pick: bool) -> Option<AgainstModel> {
    let load = task.crane.load_obb(c, &task.load);
    let load_long_x = load.half.x >= load.half.y;
    let load_size = sizes(load.half.x, load.half.y, load.half.z);
    let load_yaw = load.axes[(1, 0)].atan2(load.axes[(0, 0)]).to_degrees() + if load_long_x { 0.0 } else { 90.0 };
    let reach = |h: [f64; 3]| h[0].hypot(h[1]);
    let load_reach = reach([load.half.x, load.half.y, 0.0]);
    let alike =
        |m: [f64; 3]| (0..3).all(|i| m[i] <= load_size[i] * ALIKE_FACTOR && m[i] * ALIKE_FACTOR >= load_size[i]);
    let copy = boxes
        .iter()
        .map(|b| {
            let d = [b.center_m[0] - load.center.x, b.center_m[1] - load.center.y];
            (b, d[0].hypot(d[1]))
        })
        .filter(|(b, d)| *d <= load_reach.max(reach(b.half_m)) && alike(sizes(b.half_m[0], b.half_m[1], b.half_m[2])))
        // The nearest, and of equally near the first by name: one answer.
        .min_by(|a, b| a.1.total_cmp(&b.1).then_with(|| a.0.name.cmp(&b.0.name)))?
        .0;
    let model_size = sizes(copy.half_m[0], copy.half_m[1], copy.half_m[2]);
    let square = |s: [f64; 3]| s[0] - s[1] < SQUARE_WITHIN_M;
    let period = if square(model_size) || square(load_size) { 90.0 } else { 180.0 };
    let turn = (copy.yaw_deg - load_yaw).rem_euclid(period);
    let turn = if turn > period / 2.0 { turn - period } else { turn };
    let which = if at_pick { "pick" } else { "set" };
    let xy_key = if task.by_configuration[usize::from(!at_pick)] {
        let radial = if task.crane.model.is_tower() { "trolley_m" } else { "luff_deg" };
        format!("{which} swing_deg and {radial}")
    } else {
        format!("{which} x_m and y_m")
    };
    Some(AgainstModel {
        at: which.to_string(),
        object: copy.name.clone(),
        offset_m: [
            copy.center_m[0] - load.center.x,
            copy.center_m[1] - load.center.y,
            (copy.center_m[2] - copy.half_m[2]) - (load.center.z - load.half.z),
        ],
        turn_deg: turn,
        model_size_m: model_size,
        load_size_m: load_size,
        keys: [xy_key, task.height_key(at_pick).to_string(), format!("{which} yaw_deg")],
    })
}

/// A group the plant stage left out that the lift passes through (or within
/// its clearance of), where the scans show nothing of it: no obstacle to
/// the plan, and nothing else stands there to keep clear of.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PassesLeftOut {
    pub object: String,
    /// The first step that meets it, and the crane's part that does.
    pub step: usize,
    pub part: String,
    /// The scans show other parts of the group, none near where the lift
    /// passes through its box.
    #[serde(default)]
    pub partly_scanned: bool,
}

impl PassesLeftOut {
    pub fn said(passes: &[PassesLeftOut], clearance_m: f64) -> Option<String> {
        let first = passes.first()?;
        let listed: Vec<String> = passes
            .iter()
            .take(MAX_PASSES_SAID)
            .map(|p| {
                let partly = if p.partly_scanned {
                    format!(
                        " (the scans show other parts of it, none within {:.0} m of where the {} passes beyond the clearance: a part in their shadow, or where the box holds none of it)",
                        crate::coverage::SEEN_WITHIN_M,
                        p.part
                    )
                } else {
                    String::new()
                };
                format!("the {} at {} in step {}{partly}", p.part, p.object, p.step)
            })
            .collect();
        let more = passes.len().saturating_sub(MAX_PASSES_SAID);
        Some(format!(
            "THE LIFT PASSES THROUGH WHAT [plant] EXCLUDE LEFT OUT OF THE PLANT MODEL (the box around it, or around each of its parts, grown by clearance_m {clearance_m:.2} m), WHERE THE SCANS SHOW NOTHING OF IT: {}{}; it is no obstacle to this plan: if it stands on site, CHECK [plant] exclude (is {} meant to be left out?)",
            listed.join(", "),
            if more > 0 { format!(" and {more} more") } else { String::new() },
            first.object
        ))
    }
}

/// How many [`PassesLeftOut`] a line names.
const MAX_PASSES_SAID: usize = 5;

/// How far apart the configurations [`passes_left_out`] tries lie, as the
/// farthest part moves (m).
const PASS_SAMPLE_M: f64 = 0.5;

/// The groups among `boxes` (left out of the plant model) that some part of
/// the crane or what hangs from it meets along `moves`, each box (or each of
/// its parts' boxes, [`ModelBox::boxes`]: an L-shaped group is not met in
/// its empty corner) grown by
/// the lift's clearance and half a sample's motion (so that nothing passes
/// between two samples unseen), where no scan point but ground lies in the
/// group's box, or, where some do, none lies in it within the clearance and
/// [`crate::coverage::SEEN_WITHIN_M`] of the part that meets it there (the
/// scans saw part of the group, not that: a part in their shadow); not the
/// `loads`, the groups that are copies of a lift's load
/// ([`of_lift`] of every lift): this lift's meets it by design, and another
/// lift's stands there, as an obstacle, only while that lift has set it
/// (the planner keeps clear of it then, [`crate::other_loads`]).
pub fn passes_left_out(
    task: &LiftTask,
    moves: &[crate::path::Move],
    boxes: &[ModelBox],
    loads: &[String],
    world: &crate::validate::World,
) -> Vec<PassesLeftOut> {
    // Each group's boxes (its parts' where it has them) grown, with their
    // bounds, and whether the scans saw anything of it.
    type Grown = (liftplan_core::obb::Obb, liftplan_core::frame::Aabb);
    let grown: Vec<(&ModelBox, Grown, Vec<Grown>, bool)> = boxes
        .iter()
        .filter(|b| !loads.contains(&b.name))
        .map(|b| {
            let grown = b
                .boxes()
                .iter()
                .map(|p| {
                    let g = p.obb().expanded(task.clearance_m + PASS_SAMPLE_M / 2.0);
                    (g, g.aabb())
                })
                .collect();
            let whole = b.obb().expanded(task.clearance_m + PASS_SAMPLE_M / 2.0);
            (b, (whole, whole.aabb()), grown, crate::validate::scanned_structure_in(world, &b.obb()))
        })
        .collect();
    let seen_within_m = task.clearance_m + PASS_SAMPLE_M / 2.0 + crate::coverage::SEEN_WITHIN_M;
    // Each group is said once, at the first step that meets it.
    let mut met = vec![false; grown.len()];
    let mut found: Vec<PassesLeftOut> = Vec::new();
    if grown.is_empty() {
        return found;
    }
    // What hangs swung by a gust where the lift is planned for the wind, as
    // the planner and the validator swing it (not in a lift-off or set-down).
    let landing = crate::landing_moves(task, moves.len());
    for (i, m) in moves.iter().enumerate() {
        for c in crate::validate::configs_along(task, m, PASS_SAMPLE_M) {
            let pose = task.pose_hanging_swept(&c, !landing[i]);
            for (kind, part) in &pose.parts {
                let reach = part.aabb();
                for (g, (group, (whole, whole_near), boxes, scanned)) in grown.iter().enumerate() {
                    if met[g] {
                        continue;
                    }
                    let apart = |near: &liftplan_core::frame::Aabb| {
                        (0..3).any(|k| reach.max[k] < near.min[k] || reach.min[k] > near.max[k])
                    };
                    // The group's own box first: most parts of the crane are
                    // far from most groups.
                    if apart(whole_near)
                        || !part.intersects(whole)
                        || !boxes.iter().any(|(b, near)| !apart(near) && part.intersects(b))
                    {
                        continue;
                    }
                    if *scanned && crate::validate::scanned_structure_near(world, part, seen_within_m, &group.obb()) {
                        continue;
                    }
                    met[g] = true;
                    found.push(PassesLeftOut {
                        object: group.name.clone(),
                        step: i + 1,
                        part: kind.name().to_string(),
                        partly_scanned: *scanned,
                    });
                }
            }
        }
    }
    found
}

/// Long side, short side and height from half sizes.
fn sizes(hx: f64, hy: f64, hz: f64) -> [f64; 3] {
    [2.0 * hx.max(hy), 2.0 * hx.min(hy), 2.0 * hz]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The test lift's skid (6 x 3 x 2.5 m) set at (22, 14) with its
    /// underside at 0.5 m, its long side along +y (yaw 90°); a model copy of
    /// it there, moved, turned or sized as asked.
    fn copy_at(dx: f64, dz: f64, yaw_deg: f64, half: [f64; 3]) -> ModelBox {
        ModelBox {
            name: "/SKID-1".into(),
            center_m: [22.0 + dx, 14.0, 0.5 + dz + half[2]],
            half_m: half,
            yaw_deg,
            parts: Vec::new(),
        }
    }

    const SKID: [f64; 3] = [3.0, 1.5, 1.25];

    fn set_against(b: ModelBox) -> Option<AgainstModel> {
        let task = crate::test_lift("ac-700");
        let found = of_lift(&task, &[b]);
        assert!(found.len() <= 1 && found.iter().all(|a| a.at == "set"), "{found:?}");
        found.into_iter().next()
    }

    /// A set position is compared with the model's copy of its load, and
    /// each way it is off it is named with the key that sets it.
    #[test]
    fn a_set_position_off_the_models_copy_of_its_load_is_named() {
        let a = set_against(copy_at(0.0, 0.0, 90.0, SKID)).unwrap();
        assert!(a.agrees(), "{a:?}");
        assert!(a.said().starts_with("the set position agrees with the plant model's /SKID-1"), "{}", a.said());
        // Its long side the other way (-90° is the same box as 90°).
        assert!(set_against(copy_at(0.0, 0.0, -90.0, SKID)).unwrap().agrees());
        let turned = set_against(copy_at(0.0, 0.0, 0.0, SKID)).unwrap();
        assert!(turned.turned() && !turned.moved() && !turned.raised() && !turned.larger(), "{turned:?}");
        assert!(
            turned.said().starts_with("THE SET POSITION DIFFERS FROM THE PLANT MODEL'S /SKID-1")
                && turned.said().ends_with("the model has it turned 90° from set yaw_deg: CHECK set yaw_deg"),
            "{}",
            turned.said()
        );
        let a = set_against(copy_at(0.0, 0.0, 85.0, SKID)).unwrap();
        assert!(a.said().contains("turned 5° clockwise from set yaw_deg"), "{}", a.said());
        assert!(set_against(copy_at(0.0, 0.0, 88.5, SKID)).unwrap().agrees());
        let a = set_against(copy_at(0.3, 0.0, 90.0, SKID)).unwrap();
        assert!(
            a.said().contains("the model has it x +0.30 m, y +0.00 m from it: CHECK set x_m and y_m"),
            "{}",
            a.said()
        );
        let a = set_against(copy_at(0.0, 0.2, 90.0, SKID)).unwrap();
        assert!(a.said().contains("the model has its underside 0.20 m higher: CHECK set z_m"), "{}", a.said());
        let a = set_against(copy_at(0.0, 0.0, 90.0, [3.5, 1.5, 1.25])).unwrap();
        assert!(
            a.said().contains("the model's copy is 7.00 x 3.00 x 2.50 m (long side, short side, height), larger than the load's box of 6.00 x 3.00 x 2.50 m: CHECK size_m"),
            "{}",
            a.said()
        );
        // Within the tolerance (0.10 m, as said) in each way at once.
        assert!(set_against(copy_at(0.1, 0.1, 90.0, [3.05, 1.5, 1.25])).unwrap().agrees());
        // Smaller than the load's box: the box holds it.
        assert!(set_against(copy_at(0.0, 0.0, 90.0, [2.8, 1.4, 1.2])).unwrap().agrees());
        // Not a copy of the load: beyond its footprint, or unlike it in size
        // (a scaffold 30 m long over the set position).
        assert!(set_against(copy_at(6.0, 0.0, 90.0, SKID)).is_none());
        assert!(set_against(copy_at(0.0, 0.0, 90.0, [15.0, 1.5, 1.25])).is_none());
    }

    /// A position given as a crane configuration is named by its keys; a
    /// copy at the pick (equipment taken out) is compared there.
    #[test]
    fn positions_are_named_by_the_keys_that_set_them() {
        let mut task = crate::test_lift("ac-700");
        task.by_configuration = [true, true];
        let at_set = of_lift(&task, &[copy_at(0.3, 0.2, 0.0, SKID)]);
        let said = at_set[0].said();
        for key in ["CHECK set yaw_deg", "CHECK set swing_deg and luff_deg", "CHECK set hoist_m"] {
            assert!(said.contains(key), "{key}: {said}");
        }
        let at_pick = ModelBox { center_m: [22.0, -14.0, 0.5 + 1.25], yaw_deg: 0.0, ..copy_at(0.0, 0.0, 0.0, SKID) };
        let found = of_lift(&crate::test_lift("ac-700"), &[at_pick]);
        assert!(found.len() == 1 && found[0].at == "pick" && found[0].agrees(), "{found:?}");
    }

    /// Planned for the wind, a group left out that what hangs passes within
    /// a gust's swing of is named; not with it hanging plumb, nor in a
    /// lift-off or set-down (a lift's first and last moves).
    #[test]
    fn what_a_gust_may_swing_the_load_into_that_was_left_out_is_named() {
        use crate::path::Move;
        let mut task = crate::test_lift("ac-700");
        let (from, to) = (task.pick.swing_rad, task.set.swing_rad);
        let at = |f: f64| Config { swing_rad: from + f * (to - from), ..task.pick };
        let swing = |a: f64, b: f64| Move { joint: liftplan_cspace::Joint::Swing, from: at(a), to: at(b) };
        let thirds = [swing(0.0, 1.0 / 3.0), swing(1.0 / 3.0, 2.0 / 3.0), swing(2.0 / 3.0, 1.0)];
        let one = [swing(0.0, 1.0)];
        // Beyond the load at the middle of its swing, out from the crane:
        // 0.3 m more than the clearance (and half a sample) off its side.
        let load = task.crane.load_obb(&at(0.5), &task.load);
        let o = task.crane.slew_center();
        let out = (load.center - o).xy().normalize();
        let side = load.corners().iter().map(|p| (p - load.center).xy().dot(&out)).fold(f64::MIN, f64::max);
        let off = side + task.clearance_m + PASS_SAMPLE_M / 2.0 + 0.3 + 1.0;
        let beside = ModelBox {
            name: "/SCAFFOLD-4".into(),
            center_m: [load.center.x + off * out.x, load.center.y + off * out.y, load.center.z],
            half_m: [1.0, 1.0, 1.0],
            yaw_deg: out.y.atan2(out.x).to_degrees(),
            parts: Vec::new(),
        };
        let bare = crate::validate::World::new(&liftplan_core::mesh::TriMesh::default(), &[], &[]).unwrap();
        let met = |t: &LiftTask, moves: &[Move]| {
            passes_left_out(t, moves, std::slice::from_ref(&beside), &[], &bare)
                .into_iter()
                .map(|p| p.step)
                .collect::<Vec<_>>()
        };
        assert!(met(&task, &thirds).is_empty() && met(&task, &one).is_empty());
        // Hanging some 30 m below the boom head, 3 cm a metre swings it 0.9 m.
        task.gust_swing_per_m = 0.03;
        assert_eq!(met(&task, &thirds), [2]);
        assert!(met(&task, &one).is_empty());
    }

    /// What the lift passes through among the groups left out of the model
    /// is said where the scans show nothing of it; not where they do (it was
    /// kept clear of as scanned), and not the load's own copy.
    #[test]
    fn what_the_lift_passes_through_that_was_left_out_is_named() {
        use crate::path::Move;
        use crate::validate::World;
        let task = crate::test_lift("ac-700");
        let swing = Move {
            joint: liftplan_cspace::Joint::Swing,
            from: task.pick,
            to: Config { swing_rad: task.set.swing_rad, ..task.pick },
        };
        let mid = Config { swing_rad: 0.5 * (task.pick.swing_rad + task.set.swing_rad), ..task.pick };
        let on_the_way = task.crane.load_obb(&mid, &task.load);
        let in_the_way = ModelBox {
            name: "/SCAFFOLD-3".into(),
            center_m: [on_the_way.center.x, on_the_way.center.y, on_the_way.center.z],
            half_m: [1.0, 1.0, 1.0],
            yaw_deg: 0.0,
            parts: Vec::new(),
        };
        let copy = copy_at(0.0, 0.0, 90.0, SKID);
        let boxes = [in_the_way.clone(), copy];
        let copies: Vec<String> = of_lift(&task, &boxes).into_iter().map(|a| a.object).collect();
        assert_eq!(copies, ["/SKID-1"]);
        let bare = World::new(&liftplan_core::mesh::TriMesh::default(), &[], &[]).unwrap();
        let found = passes_left_out(&task, std::slice::from_ref(&swing), &boxes, &copies, &bare);
        assert!(found.len() == 1 && found[0].object == "/SCAFFOLD-3" && found[0].step == 1, "{found:?}");
        // What hangs meets it first (the load or its slings, as sampled).
        assert!(["load", "rigging"].contains(&found[0].part.as_str()), "{found:?}");
        let said = PassesLeftOut::said(&found, task.clearance_m).unwrap();
        assert!(
            said.contains("WHERE THE SCANS SHOW NOTHING OF IT: the ") && said.contains(" at /SCAFFOLD-3 in step 1"),
            "{said}"
        );
        // Another lift's load (a vessel this skid is set on): where it
        // stands during this lift it is an obstacle as that lift's load.
        let loads = ["/SCAFFOLD-3".to_string(), "/SKID-1".to_string()];
        assert!(passes_left_out(&task, std::slice::from_ref(&swing), &boxes, &loads, &bare).is_empty());
        // Scanned: kept clear of as the scans show it; ground in the box's
        // foot is not it.
        let c = in_the_way.center_m;
        let scanned = World::new(&liftplan_core::mesh::TriMesh::default(), &[c], &[false]).unwrap();
        assert!(passes_left_out(&task, std::slice::from_ref(&swing), &boxes, &copies, &scanned).is_empty());
        let ground = World::new(&liftplan_core::mesh::TriMesh::default(), &[c], &[true]).unwrap();
        assert_eq!(passes_left_out(&task, std::slice::from_ref(&swing), &boxes, &copies, &ground).len(), 1);
        // A group 16 m long across the way, scanned at its far end only (the
        // rest in the scans' shadow): where the lift passes through it, 7.5 m
        // from what the scans show of it, it is named as partly scanned; a
        // point of it near where the lift passes (1 m along) vouches for it.
        let o = task.crane.slew_center();
        let out = (c[1] - o.y).atan2(c[0] - o.x);
        let across = ModelBox { half_m: [8.0, 1.0, 1.0], yaw_deg: out.to_degrees(), ..in_the_way.clone() };
        let along = |d: f64| [c[0] + d * out.cos(), c[1] + d * out.sin(), c[2]];
        let far_end = World::new(&liftplan_core::mesh::TriMesh::default(), &[along(7.5)], &[false]).unwrap();
        let found = passes_left_out(&task, std::slice::from_ref(&swing), std::slice::from_ref(&across), &[], &far_end);
        assert!(found.len() == 1 && found[0].partly_scanned, "{found:?}");
        let said = PassesLeftOut::said(&found, task.clearance_m).unwrap();
        assert!(
            said.contains(" at /SCAFFOLD-3 in step 1 (the scans show other parts of it, none within 2 m of where the "),
            "{said}"
        );
        let near =
            World::new(&liftplan_core::mesh::TriMesh::default(), &[along(7.5), along(1.0)], &[false, false]).unwrap();
        assert!(
            passes_left_out(&task, std::slice::from_ref(&swing), std::slice::from_ref(&across), &[], &near).is_empty()
        );
        // Ground there is not it.
        let near_ground =
            World::new(&liftplan_core::mesh::TriMesh::default(), &[along(7.5), along(1.0)], &[false, true]).unwrap();
        assert_eq!(
            passes_left_out(&task, std::slice::from_ref(&swing), std::slice::from_ref(&across), &[], &near_ground)
                .len(),
            1
        );
        // A group whose box the lift passes through, but none of its parts
        // (an L whose empty corner it passes): nothing met; through a part
        // of it: met.
        let wide = ModelBox { half_m: [10.0, 10.0, 1.0], ..in_the_way.clone() };
        let aside_part =
            ModelBox { center_m: [c[0] + 8.0 * out.cos(), c[1] + 8.0 * out.sin(), c[2]], ..in_the_way.clone() };
        let l_shaped = ModelBox {
            parts: vec![
                aside_part.clone(),
                ModelBox { center_m: [c[0] - 8.0 * out.cos(), c[1] - 8.0 * out.sin(), c[2]], ..aside_part.clone() },
            ],
            ..wide.clone()
        };
        assert_eq!(
            passes_left_out(&task, std::slice::from_ref(&swing), std::slice::from_ref(&wide), &[], &bare).len(),
            1
        );
        assert!(
            passes_left_out(&task, std::slice::from_ref(&swing), std::slice::from_ref(&l_shaped), &[], &bare)
                .is_empty()
        );
        let through_a_part = ModelBox { parts: vec![aside_part, in_the_way.clone()], ..wide };
        assert_eq!(passes_left_out(&task, std::slice::from_ref(&swing), &[through_a_part], &[], &bare).len(), 1);
        // Off the way (20 m over the load the rope passes it), beyond the
        // crane's reach: nothing to say.
        let over = ModelBox { center_m: [c[0], c[1], c[2] + 20.0], ..in_the_way.clone() };
        let found = passes_left_out(&task, std::slice::from_ref(&swing), &[over], &[], &bare);
        assert!(found.len() == 1 && found[0].part == "hoist rope", "{found:?}");
        let aside = ModelBox { center_m: [c[0] + 60.0, c[1], c[2]], ..in_the_way };
        assert!(passes_left_out(&task, std::slice::from_ref(&swing), &[aside], &[], &bare).is_empty());
    }
}
