//! The sling legs between the hook and the load: how steep each hangs and
//! the most any one carries, against the legs' working load limit.
//!
//! The legs meet at the hook block's underside, `rigging.height_m` above
//! the load's top and plumb over its centre of gravity (where a hanging
//! load settles), and take the load at its lift points: by default the
//! top's corners for four legs, the middles of the top's two short edges
//! for two, its centre for one; or the points `rigging.lift_points_m` gives.
//! Each leg's share follows from the forces meeting at the hook:
//!
//! - one leg carries the whole load;
//! - two legs share it as their angles to the vertical have it (the load
//!   hangs with its centre of gravity under the hook, in the legs' plane);
//! - three legs: the three forces at the hook are determinate;
//! - four legs are not (they share by how their lengths happen to match): a
//!   leg a little long goes slack and three carry the load, so the most
//!   each leg carries is the most over the four ways of one leg slack. For a
//!   rigid load with its centre of gravity at the middle of four corners,
//!   that is two diagonal legs carrying it all, as the lifting codes of
//!   practice warn; it is more than EN 13414-1's uniform load method rates
//!   a four-leg sling for (three legs' worth), which assumes the legs share.
//!
//! Legs more than [`MAX_LEG_ANGLE_DEG`] from the vertical are refused: no
//! sling is rated for them.
//!
//! What this module must not do: plan (the check does not depend on the
//! path), or say more than the statics of the legs: the lift points' own
//! strength, the shackles, a spreader beam and the load's strength under
//! the legs' pull are the engineer's.

use serde::{Deserialize, Serialize};

/// The steepest a sling leg may hang from the vertical (degrees): EN
/// 13414-1 and the codes of practice rate multi-leg slings up to 60°.
pub const MAX_LEG_ANGLE_DEG: f64 = 60.0;

/// Standard gravity (m/s²), for the legs' forces in kN.
const G: f64 = 9.806_65;

/// The sling legs of a lift, as its `rigging` gives them.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Slings {
    /// Where each leg takes the load, in the load's frame from the centre
    /// of its box (m); one to four.
    pub lift_points_m: Vec<[f64; 3]>,
    /// Whether the lift gave the points (`rigging.lift_points_m`) or they
    /// are the default for the number of legs.
    pub points_given: bool,
    /// Each leg's working load limit (kg), straight pull.
    pub leg_wll_kg: f64,
}

/// What the legs carry ([`check`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SlingCheck {
    pub legs: usize,
    /// The steepest leg's angle from the vertical (degrees).
    pub max_angle_deg: f64,
    /// The most one leg carries (kg), in the worst way the load may hang
    /// on them (for four legs, any one slack).
    pub max_leg_kg: f64,
    /// Which leg (1-based, in the order of the lift points) carries it.
    pub max_leg: usize,
    pub leg_wll_kg: f64,
    pub points_given: bool,
    /// Each leg's length from its lift point to the hook block's underside
    /// (m), in the order of the lift points: what the legs must be for the
    /// load to hang level, as it is planned.
    #[serde(default)]
    pub leg_lengths_m: Vec<f64>,
}

impl SlingCheck {
    /// The most one leg carries over its working load limit (%).
    pub fn utilisation_pct(&self) -> f64 {
        100.0 * self.max_leg_kg / self.leg_wll_kg
    }

    /// In words, for the run's line and the PDF.
    pub fn said(&self) -> String {
        let where_ = match (self.points_given, self.legs) {
            (true, _) => "at the lift points given (rigging lift_points_m)",
            (false, 1) => "at the top's centre",
            (false, 2) => "at the middles of the top's short edges",
            (false, _) => "at the top's corners",
        };
        let how = if self.legs == 4 { ", any one leg slack" } else { "" };
        let lengths: Vec<String> = self.leg_lengths_m.iter().map(|l| format!("{l:.2}")).collect();
        format!(
            "{} leg{} {where_}, up to {:.1}° from the vertical; the most on one leg (leg {}{how}) {:.2} t ({:.0} kN) of its {:.2} t working load limit: {:.0} %; {} from lift point to hook, for the load to hang level",
            self.legs,
            if self.legs == 1 { "" } else { "s" },
            self.max_angle_deg,
            self.max_leg,
            self.max_leg_kg / 1000.0,
            self.max_leg_kg * G / 1000.0,
            self.leg_wll_kg / 1000.0,
            self.utilisation_pct(),
            match &lengths[..] {
                [one] => format!("the leg {one} m long"),
                [first @ .., last] => format!("legs {} and {last} m long", first.join(", ")),
                [] => String::new(),
            }
        )
    }
}

/// The default lift points for `legs` legs on a box of `size_m` (m, from
/// the box's centre): its top's corners, the middles of its short edges or
/// its centre; `None` for another number of legs.
pub fn default_points(legs: usize, size_m: [f64; 3]) -> Option<Vec<[f64; 3]>> {
    let [hx, hy, hz] = size_m.map(|s| s / 2.0);
    match legs {
        1 => Some(vec![[0.0, 0.0, hz]]),
        // Along the box's longer side.
        2 if hx >= hy => Some(vec![[-hx, 0.0, hz], [hx, 0.0, hz]]),
        2 => Some(vec![[0.0, -hy, hz], [0.0, hy, hz]]),
        4 => Some(vec![[-hx, -hy, hz], [hx, -hy, hz], [hx, hy, hz], [-hx, hy, hz]]),
        _ => None,
    }
}

/// The legs' angles and the most one carries, for a load of `load_kg` with
/// its centre of gravity `cog_m` from its box's centre (load frame) and a
/// box `size_m`, hanging `rigging_height_m` below the hook block's
/// underside; or why the legs cannot carry it.
pub fn check(
    slings: &Slings,
    load_kg: f64,
    size_m: [f64; 3],
    cog_m: [f64; 3],
    rigging_height_m: f64,
) -> Result<SlingCheck, String> {
    let hook = [cog_m[0], cog_m[1], size_m[2] / 2.0 + rigging_height_m];
    let pts = &slings.lift_points_m;
    // Unit vectors from each lift point up its leg to the hook.
    let mut up = Vec::with_capacity(pts.len());
    let mut leg_lengths_m = Vec::with_capacity(pts.len());
    let mut max_angle_deg: f64 = 0.0;
    for (k, p) in pts.iter().enumerate() {
        let d = [hook[0] - p[0], hook[1] - p[1], hook[2] - p[2]];
        let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        if !(d[2] > 1e-6) {
            return Err(format!(
                "sling leg {} takes the load at z {:.2} m from its box's centre, not below the hook block ({:.2} m: the load's top plus rigging height_m)",
                k + 1,
                p[2],
                hook[2]
            ));
        }
        // One leg hangs plumb: the load tilts until its centre of gravity
        // is under the point.
        let angle = if pts.len() == 1 { 0.0 } else { d[0].hypot(d[1]).atan2(d[2]).to_degrees() };
        max_angle_deg = max_angle_deg.max(angle);
        up.push(d.map(|v| v / len));
        leg_lengths_m.push(len);
    }
    if max_angle_deg > MAX_LEG_ANGLE_DEG + 1e-9 {
        return Err(format!(
            "the sling legs hang up to {max_angle_deg:.1}° from the vertical, more than the {MAX_LEG_ANGLE_DEG:.0}° slings are rated for: give a taller rigging (rigging height_m {rigging_height_m:.2} m) or lift points nearer the centre of gravity"
        ));
    }
    // Each way the load may hang: the legs that carry, and their shares.
    let shares: Vec<(Vec<usize>, Vec<f64>)> = match pts.len() {
        1 => vec![(vec![0], vec![load_kg])],
        2 => vec![(vec![0, 1], two_legs(pts, &up, load_kg)?)],
        3 => vec![(vec![0, 1, 2], three_legs(&up, [0, 1, 2], load_kg).ok_or_else(outside)?)],
        4 => {
            let ways: Vec<(Vec<usize>, Vec<f64>)> = [[1, 2, 3], [0, 2, 3], [0, 1, 3], [0, 1, 2]]
                .into_iter()
                .filter_map(|legs| three_legs(&up, legs, load_kg).map(|t| (legs.to_vec(), t)))
                .collect();
            if ways.is_empty() {
                return Err(outside());
            }
            ways
        }
        n => return Err(format!("{n} sling legs: liftplan checks one to four")),
    };
    let (mut max_leg_kg, mut max_leg) = (0.0, 0);
    for (legs, t) in &shares {
        for (&leg, &kg) in legs.iter().zip(t) {
            if kg > max_leg_kg {
                (max_leg_kg, max_leg) = (kg, leg);
            }
        }
    }
    Ok(SlingCheck {
        legs: pts.len(),
        max_angle_deg,
        max_leg_kg,
        max_leg: max_leg + 1,
        leg_lengths_m,
        leg_wll_kg: slings.leg_wll_kg,
        points_given: slings.points_given,
    })
}

fn outside() -> String {
    "the load's centre of gravity (cog_m) lies outside the sling legs' lift points in plan: it would tip in them; give lift points round it (rigging lift_points_m)".to_string()
}

/// Two legs' shares: their pulls across balance, their lifts add to the
/// load. The hook hangs over the centre of gravity, which must lie between
/// the two points (in plan, along the line through them).
fn two_legs(pts: &[[f64; 3]], up: &[[f64; 3]], load_kg: f64) -> Result<Vec<f64>, String> {
    // Sideways, along the line from the first point to the second in plan.
    let along = [pts[1][0] - pts[0][0], pts[1][1] - pts[0][1]];
    let n = along[0].hypot(along[1]);
    let sin = |u: &[f64; 3]| if n > 0.0 { (u[0] * along[0] + u[1] * along[1]) / n } else { 0.0 };
    // Leg 0 pulls towards +along (toward the hook), leg 1 towards -along.
    let (a0, a1) = (sin(&up[0]), -sin(&up[1]));
    let (c0, c1) = (up[0][2], up[1][2]);
    if a0 < -1e-9 || a1 < -1e-9 {
        return Err(outside());
    }
    let den = a1 * c0 + a0 * c1;
    if den <= 1e-12 {
        // Both hang plumb under the hook: one point in plan; they share it.
        return Ok(vec![load_kg / 2.0 / c0.max(1e-12), load_kg / 2.0 / c1.max(1e-12)]);
    }
    Ok(vec![load_kg * a1 / den, load_kg * a0 / den])
}

/// Three legs' shares: the forces at the hook balance the load, which is
/// determinate; `None` where they cannot (the centre of gravity outside
/// the three points in plan, or the points in a line).
fn three_legs(up: &[[f64; 3]], legs: [usize; 3], load_kg: f64) -> Option<Vec<f64>> {
    let [a, b, c] = legs.map(|k| up[k]);
    // Solve [a b c] t = (0, 0, load) by Cramer's rule.
    let det = |x: [f64; 3], y: [f64; 3], z: [f64; 3]| {
        x[0] * (y[1] * z[2] - y[2] * z[1]) - y[0] * (x[1] * z[2] - x[2] * z[1]) + z[0] * (x[1] * y[2] - x[2] * y[1])
    };
    let d = det(a, b, c);
    if d.abs() < 1e-9 {
        return None;
    }
    let w = [0.0, 0.0, load_kg];
    let t = vec![det(w, b, c) / d, det(a, w, c) / d, det(a, b, w) / d];
    // A share just below zero is a leg on the line through the centre of
    // gravity: it carries nothing.
    if t.iter().any(|&x| x < -1e-9 * load_kg) {
        return None;
    }
    Some(t.into_iter().map(|x| x.max(0.0)).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn slings(legs: usize, size_m: [f64; 3]) -> Slings {
        Slings { lift_points_m: default_points(legs, size_m).unwrap(), points_given: false, leg_wll_kg: 8000.0 }
    }

    /// Two legs to the ends of an 8 m box, 3 m below the hook: each at
    /// atan(4 / 3) from the vertical, each carrying half over its cosine.
    #[test]
    fn two_legs_share_a_centred_load_by_their_angle() {
        let c = check(&slings(2, [8.0, 3.0, 2.0]), 12_000.0, [8.0, 3.0, 2.0], [0.0; 3], 3.0).unwrap();
        let angle = (4.0f64 / 3.0).atan();
        assert!((c.max_angle_deg - angle.to_degrees()).abs() < 1e-9, "{c:?}");
        assert!((c.max_leg_kg - 6000.0 / angle.cos()).abs() < 1e-6, "{c:?}");
        assert!((c.utilisation_pct() - 100.0 * 10_000.0 / 8000.0).abs() < 1e-6, "{c:?}");
        // 4 m across and 3 m down: 5 m each.
        assert_eq!(c.leg_lengths_m, [5.0, 5.0]);
        assert!(
            c.said().ends_with("; legs 5.00 and 5.00 m long from lift point to hook, for the load to hang level"),
            "{}",
            c.said()
        );
    }

    /// With the centre of gravity 1 m off the middle towards leg 2, leg 2
    /// carries more: statics by hand (sideways balance, vertical sum).
    #[test]
    fn two_legs_carry_an_off_centre_load_unequally() {
        let c = check(&slings(2, [8.0, 3.0, 2.0]), 12_000.0, [8.0, 3.0, 2.0], [1.0, 0.0, 0.0], 3.0).unwrap();
        // Leg 1 at 5 m across, leg 2 at 3 m, both 3 m down.
        let (l1, l2) = ((25.0f64 + 9.0).sqrt(), (9.0f64 + 9.0).sqrt());
        let (s1, c1, s2, c2) = (5.0 / l1, 3.0 / l1, 3.0 / l2, 3.0 / l2);
        let t1 = 12_000.0 * s2 / (s2 * c1 + s1 * c2);
        let t2 = 12_000.0 * s1 / (s2 * c1 + s1 * c2);
        assert!(t2 > t1 && (t1 * s1 - t2 * s2).abs() < 1e-6 && (t1 * c1 + t2 * c2 - 12_000.0).abs() < 1e-6);
        assert_eq!(c.max_leg, 2);
        assert!((c.max_leg_kg - t2).abs() < 1e-6, "{c:?} {t2}");
    }

    /// Four legs to the corners with the centre of gravity in the middle:
    /// one leg slack leaves the two diagonal legs carrying it all.
    #[test]
    fn four_legs_hang_on_two_with_one_slack() {
        let size = [6.0, 4.0, 2.0];
        let c = check(&slings(4, size), 10_000.0, size, [0.0; 3], 3.0).unwrap();
        let corner = (3.0f64).hypot(2.0);
        let cos = 3.0 / corner.hypot(3.0);
        assert!((c.max_leg_kg - 5000.0 / cos).abs() < 1e-6, "{c:?}");
        assert!((c.max_angle_deg - corner.atan2(3.0).to_degrees()).abs() < 1e-9);
        // Each leg's share, whatever the way it hangs, is at least a quarter.
        assert!(c.max_leg_kg >= 2500.0 / cos);
        // Off centre: the nearest corner's leg carries the most.
        let off = check(&slings(4, size), 10_000.0, size, [1.0, 0.5, 0.0], 3.0).unwrap();
        assert_eq!(off.max_leg, 3, "{off:?}");
        assert!(off.max_leg_kg > c.max_leg_kg);
    }

    /// Three legs: the shares are the statics' and add up to the load.
    #[test]
    fn three_legs_are_determinate() {
        let s = Slings {
            lift_points_m: vec![[-2.0, -1.0, 1.0], [2.0, -1.0, 1.0], [0.0, 2.0, 1.0]],
            points_given: true,
            leg_wll_kg: 9000.0,
        };
        let up: Vec<[f64; 3]> = s
            .lift_points_m
            .iter()
            .map(|p| {
                let d = [0.0 - p[0], 0.0 - p[1], 4.0 - p[2]];
                let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                d.map(|v| v / n)
            })
            .collect();
        let t = three_legs(&up, [0, 1, 2], 9000.0).unwrap();
        for axis in 0..3 {
            let sum: f64 = (0..3).map(|k| t[k] * up[k][axis]).sum();
            assert!((sum - if axis == 2 { 9000.0 } else { 0.0 }).abs() < 1e-6, "{axis}: {sum}");
        }
        let c = check(&s, 9000.0, [4.0, 4.0, 2.0], [0.0; 3], 3.0).unwrap();
        assert!((c.max_leg_kg - t.iter().cloned().fold(0.0, f64::max)).abs() < 1e-9);
        assert!(c.said().starts_with("3 legs at the lift points given (rigging lift_points_m), up to"), "{}", c.said());
    }

    /// Legs too flat, a centre of gravity outside the legs and a lift point
    /// above the hook are refused, each saying what to change.
    #[test]
    fn what_the_legs_cannot_carry_is_refused() {
        let size = [8.0, 3.0, 2.0];
        let flat = check(&slings(2, size), 12_000.0, size, [0.0; 3], 2.0).unwrap_err();
        assert!(flat.contains("up to 63.4° from the vertical, more than the 60°"), "{flat}");
        let outside = check(&slings(2, size), 12_000.0, size, [4.5, 0.0, 0.0], 20.0).unwrap_err();
        assert!(outside.contains("outside the sling legs' lift points"), "{outside}");
        let four = check(&slings(4, size), 12_000.0, size, [4.5, 0.0, 0.0], 20.0).unwrap_err();
        assert!(four.contains("outside the sling legs' lift points"), "{four}");
        let high = Slings { lift_points_m: vec![[0.0, 0.0, 9.0]], points_given: true, leg_wll_kg: 1.0 };
        assert!(check(&high, 1.0, size, [0.0; 3], 3.0).unwrap_err().contains("not below the hook block"));
        // One leg: the whole load, whatever its angle.
        let one = check(&slings(1, size), 12_000.0, size, [0.3, 0.0, 0.0], 3.0).unwrap();
        assert_eq!((one.max_leg_kg, one.max_angle_deg), (12_000.0, 0.0));
        assert!(one.said().starts_with("1 leg at the top's centre"), "{}", one.said());
    }
}
