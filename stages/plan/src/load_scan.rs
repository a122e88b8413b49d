//! The load as the scans show it at its pick position, against the box the
//! project gives it.
//!
//! The planner carries the load as its declared box (`size_m`, placed by the
//! pick position), and the scan points inside that box (grown by the
//! cut-out) are taken for the load and left out of every check. So the scans
//! never contradict the box: a load taller than declared (nozzles, lugs, a
//! wrong `size_m` or pick `z_m`) has its top cut out as "slings" and keeps
//! less clearance than the plan shows, and a pick position a few metres off
//! leaves the box over a fragment of the load. This module says what the
//! taken points show: how far they span the box along its length, width and
//! height, and whether they stand above its top.
//!
//! What this module must not do: refuse a plan or change what the planner
//! sees. The load may not have been on site when the site was scanned, and
//! slings lying on it stand above its box too; only the engineer can tell.

use liftplan_core::frame::Point3;
use liftplan_core::lift::LiftTask;
use serde::{Deserialize, Serialize};

/// Scan noise (m): a point this close above the box's top, or this close
/// above its underside (the top of what it rests on), is read as on it.
pub const NOISE_M: f64 = 0.05;

/// A load seen over less than this share of its box's length, width or
/// height (above the support) is said to be seen over too little of it.
pub const SPAN_SHARE_MIN: f64 = 0.5;

/// A load whose highest scanned point lies more than this below its box's
/// top is said to stand lower (or be shorter) than its box (m): a load
/// standing lower than pick `z_m` says is carried through the whole lift
/// that much lower than the plan shows, the cut-out having taken its lower
/// part for the box's.
pub const TOP_BELOW_M: f64 = 0.25;

/// What the scan points taken for a load at its pick position show.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LoadAsScanned {
    /// The load's box: length, width, height (m, its own x, y, z).
    pub box_m: [f64; 3],
    /// Taken points above the support's top band (on the load, its slings,
    /// or whatever else stood within the cut-out).
    pub points: usize,
    /// How far those points spread along the box's x, y and z (m); 0 where
    /// there are none.
    pub span_m: [f64; 3],
    /// The key that sets the pick's height, as the lift gives it (`pick
    /// z_m`, or `pick hoist_m` for a pick given as a crane configuration).
    #[serde(default = "pick_z_m")]
    pub height_key: String,
    /// How many of them stand more than [`NOISE_M`] above the box's top.
    pub above_top: usize,
    /// How far the highest of them stands above the box's top (m; 0 where
    /// none does).
    pub above_top_max_m: f64,
    /// How far above the box the cut-out reaches (m): anything higher was
    /// not taken and stays an obstacle.
    pub cutout_above_m: f64,
    /// How far the highest of them lies below the box's top (m; 0 where one
    /// reaches it, or there are none).
    #[serde(default)]
    pub top_below_m: f64,
}

/// What `taken` (the scan points the cut-out took for `task`'s load, site
/// frame) shows of the load at its pick position.
pub fn of_pick(task: &LiftTask, taken: &[[f64; 3]], cutout_above_m: f64) -> LoadAsScanned {
    let b = task.crane.load_obb(&task.pick, &task.load);
    let (hx, hy, hz) = (b.half.x, b.half.y, b.half.z);
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    let (mut points, mut above_top, mut above_top_max_m) = (0, 0, 0.0f64);
    for p in taken {
        let l = b.to_local(&Point3::new(p[0], p[1], p[2]));
        // The support's top lies at the box's underside; the cut-out took
        // its top centimetres with the load.
        if l.z <= -hz + NOISE_M {
            continue;
        }
        points += 1;
        // Within the box's sides: the cut-out's grown band beside the load
        // would stretch the spans by its width.
        let l = [l.x.clamp(-hx, hx), l.y.clamp(-hy, hy), l.z];
        for a in 0..3 {
            lo[a] = lo[a].min(l[a]);
            hi[a] = hi[a].max(l[a]);
        }
        if l[2] > hz + NOISE_M {
            above_top += 1;
            above_top_max_m = above_top_max_m.max(l[2] - hz);
        }
    }
    let span_m = std::array::from_fn(|a| if points > 0 { hi[a] - lo[a] } else { 0.0 });
    let top_below_m = if points > 0 { (hz - hi[2]).max(0.0) } else { 0.0 };
    LoadAsScanned {
        box_m: task.load.size_m,
        points,
        span_m,
        height_key: task.height_key(true).to_string(),
        above_top,
        above_top_max_m,
        cutout_above_m,
        top_below_m,
    }
}

fn pick_z_m() -> String {
    "pick z_m".to_string()
}

impl LoadAsScanned {
    /// The axes ("length", "width", "height") along which the taken points
    /// span less than [`SPAN_SHARE_MIN`] of the box, with span and size.
    pub fn short_axes(&self) -> Vec<(&'static str, f64, f64)> {
        // Height is measured from the support's top band up.
        let size = [self.box_m[0], self.box_m[1], self.box_m[2] - NOISE_M];
        ["length", "width", "height"]
            .into_iter()
            .enumerate()
            .filter(|&(a, _)| self.span_m[a].min(size[a]) < SPAN_SHARE_MIN * size[a])
            .map(|(a, name)| (name, self.span_m[a], self.box_m[a]))
            .collect()
    }

    /// Whether the engineer has something to check.
    pub fn needs_checking(&self) -> bool {
        self.points == 0 || self.above_top > 0 || self.top_below() || !self.short_axes().is_empty()
    }

    /// Whether its highest point lies more than [`TOP_BELOW_M`] below the
    /// box's top.
    pub fn top_below(&self) -> bool {
        self.points > 0 && self.top_below_m > TOP_BELOW_M
    }

    /// One sentence, for the run's output and the sign-off page.
    pub fn said(&self) -> String {
        let [l, w, h] = self.box_m;
        if self.points == 0 {
            return format!(
                "the load as scanned at its pick position: no scan point on its {l:.1} x {w:.1} x {h:.1} m box: if the load was on site when the scans were taken, CHECK ITS PICK POSITION"
            );
        }
        let [sl, sw, sh] = self.span_m;
        let mut s = format!(
            "the load as scanned at its pick position: {} scan points spanning {sl:.1} x {sw:.1} x {sh:.1} m of its {l:.1} x {w:.1} x {h:.1} m box",
            self.points
        );
        let short = self.short_axes();
        if !short.is_empty() {
            let parts: Vec<String> =
                short.iter().map(|(name, span, size)| format!("{span:.1} m of its {size:.1} m {name}")).collect();
            s += &format!(
                ", only {}: if the load was on site when the scans were taken, CHECK ITS PICK POSITION AND size_m",
                parts.join(" and ")
            );
        }
        if self.above_top > 0 {
            s += &format!(
                "; {} of them up to {:.2} m ABOVE ITS BOX'S TOP: slings lying on it, or a load taller than size_m says or standing higher than {} says, which keeps less clearance than the plan shows: CHECK THE LOAD'S HEIGHT (the cut-out takes points up to {:.2} m above the box; anything higher stays an obstacle)",
                self.above_top, self.above_top_max_m, self.height_key, self.cutout_above_m
            );
        } else if self.top_below() {
            s += &format!(
                "; the highest of them {:.2} m BELOW ITS BOX'S TOP: a load standing lower than {} says, carried that much lower through the whole lift than the plan shows (less clearance under it), or shorter than size_m says, or a top the scans did not see: CHECK ITS {}",
                self.top_below_m,
                self.height_key,
                self.height_key.replacen("pick", "PICK", 1)
            );
        } else {
            s += ", none above its top";
        }
        if !self.needs_checking() {
            s += ": its size and pick position agree with the scans";
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use liftplan_core::frame::Vec3;

    /// Points every 0.1 m over the sides and top of a box `grown_top_m`
    /// taller than the test lift's load box at pick (its underside where the
    /// load's is), as a scanner sees a load, and over the top of what it
    /// rests on (the cut-out takes that too), along a share `along` of the
    /// box's length.
    fn scanned(task: &LiftTask, grown_top_m: f64, along: f64) -> Vec<[f64; 3]> {
        let b = task.crane.load_obb(&task.pick, &task.load);
        let (hx, hy, hz) = (b.half.x, b.half.y, b.half.z);
        let mut local = Vec::new();
        let steps = |lo: f64, hi: f64| {
            let n = ((hi - lo) / 0.1).round() as usize;
            (0..=n).map(move |k| lo + (hi - lo) * k as f64 / n as f64)
        };
        let x_hi = -hx + 2.0 * hx * along;
        let top = hz + grown_top_m;
        for x in steps(-hx, x_hi) {
            for z in steps(-hz + 0.1, top) {
                local.push([x, -hy, z]);
                local.push([x, hy, z]);
            }
            for y in steps(-hy, hy) {
                local.push([x, y, top]);
                // The support's top, 5 cm under the load's underside.
                local.push([x, y, -hz - 0.05]);
            }
        }
        local
            .into_iter()
            .map(|[x, y, z]| {
                let p = b.center + b.axes * Vec3::new(x, y, z);
                [p.x, p.y, p.z]
            })
            .collect()
    }

    #[test]
    fn a_load_scanned_as_its_box_says_agrees() {
        let t = crate::test_lift("ltm-1100");
        let mut pts = scanned(&t, 0.0, 1.0);
        // A trailer's stake 8 cm beside the load, inside the cut-out: it
        // does not widen the load.
        let b = t.crane.load_obb(&t.pick, &t.load);
        let stake = b.center + b.axes * Vec3::new(0.0, b.half.y + 0.08, 0.0);
        pts.push([stake.x, stake.y, stake.z]);
        let s = of_pick(&t, &pts, 0.3);
        assert_eq!(s.above_top, 0, "{s:?}");
        assert!((s.span_m[0] - 6.0).abs() < 1e-6 && (s.span_m[1] - 3.0).abs() < 1e-6, "{s:?}");
        assert!((s.span_m[2] - 2.4).abs() < 1e-6, "{s:?}");
        assert!(!s.needs_checking(), "{}", s.said());
        assert!(
            s.said().ends_with("none above its top: its size and pick position agree with the scans"),
            "{}",
            s.said()
        );
    }

    /// A load 0.2 m taller than its box: the cut-out took its top, and
    /// that is said with how far it stands above.
    #[test]
    fn a_load_taller_than_its_box_is_said() {
        let t = crate::test_lift("ltm-1100");
        let s = of_pick(&t, &scanned(&t, 0.2, 1.0), 0.3);
        assert!(s.above_top > 0 && (s.above_top_max_m - 0.2).abs() < 1e-6, "{s:?}");
        assert!(s.needs_checking());
        assert!(s.said().contains("up to 0.20 m ABOVE ITS BOX'S TOP"), "{}", s.said());
        assert!(s.said().contains("CHECK THE LOAD'S HEIGHT"), "{}", s.said());
        // Within scan noise of the top is on it.
        assert_eq!(of_pick(&t, &scanned(&t, 0.04, 1.0), 0.3).above_top, 0);
    }

    /// A load standing 0.5 m lower than its box (its pick z_m 0.5 m too
    /// high): the cut-out takes its lower part for the box's, and its top
    /// lies 0.5 m under the box's, which is said; a top 0.1 m under it is
    /// scan noise and the load's own shape.
    #[test]
    fn a_load_standing_lower_than_its_box_is_said() {
        let t = crate::test_lift("ltm-1100");
        let s = of_pick(&t, &scanned(&t, -0.5, 1.0), 0.3);
        assert!((s.top_below_m - 0.5).abs() < 1e-6, "{s:?}");
        assert!(s.short_axes().is_empty() && s.above_top == 0, "{s:?}");
        assert!(s.needs_checking());
        assert!(s.said().contains("the highest of them 0.50 m BELOW ITS BOX'S TOP"), "{}", s.said());
        assert!(s.said().contains("CHECK ITS PICK z_m"), "{}", s.said());
        let s = of_pick(&t, &scanned(&t, -0.1, 1.0), 0.3);
        assert!(!s.needs_checking(), "{}", s.said());
        // A pick given as a crane configuration: its rope sets the height.
        let mut t = t;
        t.by_configuration = [true, false];
        let s = of_pick(&t, &scanned(&t, -0.5, 1.0), 0.3);
        assert!(
            s.said().contains("lower than pick hoist_m says") && s.said().contains("CHECK ITS PICK hoist_m"),
            "{}",
            s.said()
        );
    }

    /// A box placed over a third of the load (its pick position 4 m off
    /// along the load) is seen over a third of its length; a load not
    /// scanned at all, only what it rests on, is said as such.
    #[test]
    fn a_box_over_part_of_the_load_or_none_is_said() {
        let t = crate::test_lift("ltm-1100");
        let s = of_pick(&t, &scanned(&t, 0.0, 1.0 / 3.0), 0.3);
        assert_eq!(s.short_axes().iter().map(|a| a.0).collect::<Vec<_>>(), ["length"], "{s:?}");
        assert!(s.said().contains("only 2.0 m of its 6.0 m length"), "{}", s.said());
        assert!(s.said().contains("CHECK ITS PICK POSITION AND size_m"), "{}", s.said());
        let support_only: Vec<[f64; 3]> = scanned(&t, 0.0, 1.0)
            .into_iter()
            .filter(|p| p[2] < t.crane.load_obb(&t.pick, &t.load).center.z - 1.2)
            .collect();
        assert!(!support_only.is_empty());
        let s = of_pick(&t, &support_only, 0.3);
        assert_eq!(s.points, 0);
        assert!(s.needs_checking() && s.said().contains("no scan point on its 6.0 x 3.0 x 2.5 m box"), "{}", s.said());
    }
}
