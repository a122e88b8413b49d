//! Outrigger loads of a mobile crane: what each of its four pads carries at
//! a configuration, and the pressure under a pad's mat.
//!
//! The crane file's masses ([`crate::crane::Masses`]) each act at their
//! part's centre, the hanging load (load, rigging, hook block and the
//! chart's deductions) under the rope sheave. Their centre of gravity is
//! shared among the pads as by a rigid frame on four supports (the usual
//! approximation: each pad carries a quarter of the weight, plus the share
//! of the moment about the pads' centre its lever gives, and nothing from a
//! twist of the frame); where that leaves a pad pulling, the pad lifts and
//! the other three carry it all, and where the centre of gravity lies
//! outside those three as well the crane tips.
//!
//! What this must not do: stand in for the manufacturer's outrigger load
//! figures, which know the frame's stiffness and the true masses; the lift
//! plan says its figures are from the crane file's masses and asks for the
//! manufacturer's to be checked. Wind, the load swinging and dynamic factors
//! are not in it.

use crate::crane::{CraneKind, CraneSetup};
use crate::frame::{Vec3, rot_z};
use serde::{Deserialize, Serialize};

pub use crate::units::G_M_S2;

/// A pad, named in the carrier's frame: front is the carrier's heading,
/// left is to the left looking along it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Pad {
    FrontLeft,
    FrontRight,
    RearLeft,
    RearRight,
}

impl Pad {
    pub const ALL: [Pad; 4] = [Pad::FrontLeft, Pad::FrontRight, Pad::RearLeft, Pad::RearRight];

    pub fn name(self) -> &'static str {
        match self {
            Pad::FrontLeft => "front left",
            Pad::FrontRight => "front right",
            Pad::RearLeft => "rear left",
            Pad::RearRight => "rear right",
        }
    }

    /// +1 front, -1 rear; +1 left, -1 right.
    fn signs(self) -> [f64; 2] {
        match self {
            Pad::FrontLeft => [1.0, 1.0],
            Pad::FrontRight => [1.0, -1.0],
            Pad::RearLeft => [-1.0, 1.0],
            Pad::RearRight => [-1.0, -1.0],
        }
    }
}

/// The pads' loads at one configuration.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PadLoads {
    /// Each pad's load (kg), in [`Pad::ALL`]'s order; 0 for a pad that lifts.
    pub loads_kg: [f64; 4],
    /// Crane and hanging load together (kg).
    pub total_kg: f64,
    /// Their centre of gravity from the pads' centre, along and across the
    /// carrier (m).
    pub cog_m: [f64; 2],
    /// Whether the centre of gravity lies outside the pads: the crane tips.
    pub tips: bool,
}

impl PadLoads {
    /// The pad that carries the most, and its load (kg).
    pub fn highest(&self) -> (Pad, f64) {
        let mut best = (Pad::ALL[0], self.loads_kg[0]);
        for (p, &l) in Pad::ALL.iter().zip(&self.loads_kg).skip(1) {
            if l > best.1 {
                best = (*p, l);
            }
        }
        best
    }
}

/// A pad's centre in the site frame (m).
pub fn pad_at(setup: &CraneSetup, pad: Pad) -> Option<[f64; 2]> {
    let CraneKind::Luffing(l) = &setup.model.kind else { return None };
    let [sx, sy] = pad.signs();
    let local = Vec3::new(
        l.carrier.center_x_m + sx * l.outriggers.spread_length_m / 2.0,
        sy * l.outriggers.spread_width_m / 2.0,
        0.0,
    );
    // Placed as the carrier and outriggers are (`CraneSetup::part`).
    let at = setup.slew_center() + rot_z(setup.placement.heading_rad) * local;
    Some([at.x, at.y])
}

/// The pads' loads of a mobile crane at swing `swing_rad` and luff
/// `luff_rad`, with `hanging_kg` on the hook and `counterweight_kg` rigged
/// (which one is the lift's to say: [`crate::lift::LiftTask::counterweight_used_kg`]).
/// `None` for a tower crane or a crane file without masses.
pub fn pad_loads(
    setup: &CraneSetup,
    swing_rad: f64,
    luff_rad: f64,
    hanging_kg: f64,
    counterweight_kg: f64,
) -> Option<PadLoads> {
    let CraneKind::Luffing(l) = &setup.model.kind else { return None };
    let m = l.masses?;
    let t = crate::units::KG_PER_TONNE;
    let (sin, cos) = swing_rad.sin_cos();
    let turned = |x: f64, y: f64| [x * cos - y * sin, x * sin + y * cos];
    let boom_len = setup.placement.boom_length_m + l.boom.head_length_m;
    let (_, radius) = setup.sheave_height_and_radius(luff_rad);
    // (kg, position in the carrier's frame about the slewing axis).
    let parts = [
        (m.carrier_t * t, [l.carrier.center_x_m, l.carrier.center_y_m]),
        (m.superstructure_t * t, turned(l.superstructure.center_x_m, l.superstructure.center_y_m)),
        (counterweight_kg, turned(l.counterweight.center_x_m, l.counterweight.center_y_m)),
        (m.boom_t * t, turned(l.boom.pivot_x_m + m.boom_cog_frac * boom_len * luff_rad.cos(), 0.0)),
        (hanging_kg, turned(radius, 0.0)),
    ];
    let total_kg: f64 = parts.iter().map(|p| p.0).sum();
    if !(total_kg > 0.0) {
        return None;
    }
    let centre = [l.carrier.center_x_m, 0.0];
    let mut cog = [0.0; 2];
    for (kg, at) in &parts {
        cog[0] += kg * (at[0] - centre[0]) / total_kg;
        cog[1] += kg * (at[1] - centre[1]) / total_kg;
    }
    let (a, b) = (l.outriggers.spread_length_m, l.outriggers.spread_width_m);
    let four = Pad::ALL.map(|p| {
        let [sx, sy] = p.signs();
        total_kg / 4.0 + total_kg * cog[0] / a * sx / 2.0 + total_kg * cog[1] / b * sy / 2.0
    });
    let (lifted, least) =
        four.iter().enumerate().fold((0, f64::INFINITY), |m, (i, &x)| if x < m.1 { (i, x) } else { m });
    if least >= 0.0 {
        return Some(PadLoads { loads_kg: four, total_kg, cog_m: cog, tips: false });
    }
    // One pad lifts: the other three carry it all, each the share the
    // centre of gravity's barycentric coordinate in their triangle gives.
    let corner = |p: Pad| {
        let [sx, sy] = p.signs();
        [sx * a / 2.0, sy * b / 2.0]
    };
    let three: Vec<usize> = (0..4).filter(|&i| i != lifted).collect();
    let [p, q, r] = [corner(Pad::ALL[three[0]]), corner(Pad::ALL[three[1]]), corner(Pad::ALL[three[2]])];
    let det = (q[0] - p[0]) * (r[1] - p[1]) - (r[0] - p[0]) * (q[1] - p[1]);
    let lq = ((cog[0] - p[0]) * (r[1] - p[1]) - (r[0] - p[0]) * (cog[1] - p[1])) / det;
    let lr = ((q[0] - p[0]) * (cog[1] - p[1]) - (cog[0] - p[0]) * (q[1] - p[1])) / det;
    let shares = [1.0 - lq - lr, lq, lr];
    let mut loads_kg = [0.0; 4];
    for (k, &i) in three.iter().enumerate() {
        loads_kg[i] = total_kg * shares[k];
    }
    let tips = shares.iter().any(|&s| s < 0.0);
    Some(PadLoads { loads_kg, total_kg, cog_m: cog, tips })
}

/// The pressure under a mat of `mat_m` (m by m) carrying `load_kg` (kPa).
pub fn pressure_kpa(load_kg: f64, mat_m: [f64; 2]) -> f64 {
    load_kg * G_M_S2 / 1000.0 / (mat_m[0] * mat_m[1])
}

/// The mat to look for (m), where one of `mat_m` puts more than
/// `allowable_kpa` on the ground under `load_kg`: of the same proportions,
/// each side rounded up to [`MAT_STEP_M`], large enough that the same even
/// spread under it stays within it. Whether a mat that size spreads the load
/// evenly (its stiffness) is not known here.
pub fn mat_bearing_m(load_kg: f64, mat_m: [f64; 2], allowable_kpa: f64) -> [f64; 2] {
    let grow = (pressure_kpa(load_kg, mat_m) / allowable_kpa).sqrt().max(1.0);
    let up = |side: f64| {
        let steps = (side * grow / MAT_STEP_M - 1e-9).ceil();
        // Rounding of the step itself: the side a whole number of steps.
        (steps * MAT_STEP_M * 100.0).round() / 100.0
    };
    mat_m.map(up)
}

/// The step mats' sides are said in (m).
pub const MAT_STEP_M: f64 = 0.1;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::crane::{CraneModel, Placement};

    /// The mat said bears it, each side a whole step, and no step smaller
    /// would; a mat that bears it already is kept.
    #[test]
    fn the_mat_that_bears_a_pad_is_the_smallest_of_its_proportions() {
        let load_kg = 104_200.0;
        for (mat, allowed) in [([1.5, 1.5], 200.0), ([2.0, 1.2], 150.0), ([1.0, 1.0], 455.0)] {
            let m = mat_bearing_m(load_kg, mat, allowed);
            assert!(pressure_kpa(load_kg, m) <= allowed, "{mat:?} {m:?}");
            assert!(m.iter().all(|s| ((s / MAT_STEP_M) - (s / MAT_STEP_M).round()).abs() < 1e-9), "{m:?}");
            let smaller = m.map(|s| s - MAT_STEP_M);
            assert!(pressure_kpa(load_kg, smaller) > allowed, "{mat:?} {m:?}");
        }
        assert_eq!(mat_bearing_m(load_kg, [3.0, 3.0], 200.0), [3.0, 3.0]);
        assert_eq!(mat_bearing_m(load_kg, [1.5, 1.5], 200.0), [2.3, 2.3]);
    }

    /// The hand-sum crane's counterweight, as its file gives it.
    const FILE_COUNTERWEIGHT_KG: f64 = 20_000.0;

    /// A crane whose masses stand where a hand sum is easy: the slewing
    /// axis over the pads' centre, a 10 by 8 m spread.
    fn crane(heading_deg: f64) -> CraneSetup {
        let text = r#"
name = "hand sum"
kind = "luffing"
[carrier]
length_m = 12.0
width_m = 3.0
height_m = 2.5
[outriggers]
spread_length_m = 10.0
spread_width_m = 8.0
[superstructure]
length_m = 6.0
width_m = 3.0
height_m = 2.0
base_z_m = 2.5
[cockpit]
length_m = 2.0
width_m = 1.0
height_m = 2.0
center_x_m = 1.5
center_y_m = -1.0
base_z_m = 2.5
[counterweight]
length_m = 2.0
width_m = 3.0
height_m = 2.0
center_x_m = -4.0
base_z_m = 2.5
[boom]
pivot_x_m = 0.0
pivot_z_m = 4.0
width_m = 1.5
depth_m = 1.5
min_length_m = 10.0
max_length_m = 40.0
luff_min_deg = 0.0
luff_max_deg = 80.0
head_length_m = 0.0
[masses]
carrier_t = 40.0
superstructure_t = 10.0
counterweight_t = 20.0
boom_t = 10.0
boom_cog_frac = 0.5
[hook]
height_m = 2.0
width_m = 1.0
mass_kg = 1000.0
min_rope_m = 1.0
max_rope_m = 60.0
[speeds]
swing_deg_s = 5.0
luff_deg_s = 1.0
hoist_m_s = 0.2
"#;
        let model = CraneModel::from_toml(std::path::Path::new("hand.toml"), text).unwrap();
        let placement =
            Placement { x_m: 100.0, y_m: 50.0, z_m: 0.0, heading_rad: heading_deg.to_radians(), boom_length_m: 20.0 };
        CraneSetup::new(model, placement).unwrap()
    }

    /// Against sums done by hand: the boom level over the front (its
    /// centre 10 m out), 10 t on the hook at 20 m, the counterweight 4 m
    /// behind. Moment about the pads' centre along the carrier: 10 x 10 +
    /// 10 x 20 - 20 x 4 = 220 t m of 90 t, so the centre of gravity lies
    /// 2.444 m forward; each front pad carries 90/4 + 220/(2 x 10) = 33.5 t,
    /// each rear pad 11.5 t. Swung over the left side, the same moment
    /// across an 8 m spread: 22.5 ± 220/16 = 36.25 and 8.75 t.
    #[test]
    fn pad_loads_match_a_hand_sum() {
        let c = crane(0.0);
        let l = pad_loads(&c, 0.0, 0.0, 10_000.0, FILE_COUNTERWEIGHT_KG).unwrap();
        assert!((l.total_kg - 90_000.0).abs() < 1e-6);
        assert!((l.cog_m[0] - 220.0 / 90.0).abs() < 1e-9 && l.cog_m[1].abs() < 1e-9, "{l:?}");
        for (got, want) in l.loads_kg.iter().zip([33_500.0, 33_500.0, 11_500.0, 11_500.0]) {
            assert!((got - want).abs() < 1e-6, "{l:?}");
        }
        assert!(!l.tips);
        let side = pad_loads(&c, 90f64.to_radians(), 0.0, 10_000.0, FILE_COUNTERWEIGHT_KG).unwrap();
        for (got, want) in side.loads_kg.iter().zip([36_250.0, 8_750.0, 36_250.0, 8_750.0]) {
            assert!((got - want).abs() < 1e-6, "{side:?}");
        }
        assert_eq!(side.highest().0, Pad::FrontLeft);
        // Luffed up to 60°, the boom's centre comes in to 5 m and the hook
        // to 10 m: 50 + 100 - 80 = 70 t m.
        let up = pad_loads(&c, 0.0, 60f64.to_radians(), 10_000.0, FILE_COUNTERWEIGHT_KG).unwrap();
        assert!((up.loads_kg[0] - (22_500.0 + 70_000.0 / 20.0)).abs() < 1e-6, "{up:?}");
        // A heavier counterweight than the file's.
        let heavy = pad_loads(&c, 0.0, 0.0, 10_000.0, 60_000.0).unwrap();
        assert!((heavy.total_kg - 130_000.0).abs() < 1e-6);
        // The pads' weights always sum to the whole.
        for l in [l, side, up, heavy] {
            assert!((l.loads_kg.iter().sum::<f64>() - l.total_kg).abs() < 1e-6);
        }
    }

    /// A load far over the corner lifts the opposite pad, and the three
    /// others carry it all; a load beyond any pad's reach tips the crane.
    #[test]
    fn a_pad_lifts_and_then_the_crane_tips() {
        let c = crane(0.0);
        let corner = 38.66f64.to_radians(); // towards the front-left pad, (5, 4)
        let l = pad_loads(&c, corner, 0.0, 20_000.0, FILE_COUNTERWEIGHT_KG).unwrap();
        assert_eq!(l.loads_kg[3], 0.0, "the rear right pad lifts: {l:?}");
        assert!(l.loads_kg.iter().all(|&x| x >= 0.0) && !l.tips, "{l:?}");
        assert!((l.loads_kg.iter().sum::<f64>() - l.total_kg).abs() < 1e-6);
        // Moment balance about both axes with three pads.
        let mx: f64 = Pad::ALL.iter().zip(&l.loads_kg).map(|(p, k)| k * p.signs()[0] * 5.0).sum();
        let my: f64 = Pad::ALL.iter().zip(&l.loads_kg).map(|(p, k)| k * p.signs()[1] * 4.0).sum();
        assert!((mx - l.total_kg * l.cog_m[0]).abs() < 1e-3 && (my - l.total_kg * l.cog_m[1]).abs() < 1e-3);
        let over = pad_loads(&c, corner, 0.0, 400_000.0, FILE_COUNTERWEIGHT_KG).unwrap();
        assert!(over.tips, "{over:?}");
    }

    #[test]
    fn pads_stand_where_the_carrier_heads() {
        let c = crane(90.0);
        let at = pad_at(&c, Pad::FrontLeft).unwrap();
        // Front is +y, left is -x once the carrier heads 90°.
        assert!((at[0] - 96.0).abs() < 1e-9 && (at[1] - 55.0).abs() < 1e-9, "{at:?}");
        assert!((pressure_kpa(10_000.0, [2.0, 2.5]) - 10_000.0 * G_M_S2 / 5000.0).abs() < 1e-9);
    }
}
