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
//! sling is rated for them. Legs choked round the load (`rigging.hitch =
//! "choked"`) are rated at [`CHOKE_FACTOR`] of their straight pull; where the
//! lift gives its shackles' working load limit (`rigging.shackle_wll_t`), the
//! shackle at each lift point is checked against its leg's pull, in line, and
//! so is each lift point itself (a lug, a trunnion: `lift_point_wll_t`), at
//! its rating for the leg's direction, which the engineer gives.
//!
//! **Side loading.** A shackle's pin runs through its lug's hole, and the
//! shackle turns on it: a leg pulling square to the pin pulls it in line,
//! one pulling at an angle to that plane side-loads it, and the makers rate
//! it for less ([`SIDE_LOADING_CHART`]). Where the lift gives each pin's
//! direction (`rigging.pin_axes`), [`side_loading`] works out how far each
//! leg pulls out of line, as rigged and as the load may turn on its legs
//! with its centre of gravity anywhere within its tolerance, and each
//! shackle is checked at the rating left at its leg's angle against the
//! most its leg carries ([`SlingCheck::shackle_most_used`]); the lugs' own
//! rating must then be for that angle out of their plane, which the words
//! say. The shackles at a spreader's top lugs are checked alike where the
//! lift gives them ([`TopShackles`], [`TopLegs::shackle_most_used`]), each
//! top leg at its angle out of line as rigged.
//!
//! Two legs may hang plumb from a beam instead (`rigging.spreader`, [`Spreader`]):
//! its pins stand over the two lift points, `below_hook_m` under the hook
//! block, and it hangs level with the hook over the centre of gravity of
//! the load and the beam together. The legs share the load by the lever
//! rule along the beam; the beam carries the load against its working load
//! limit; a spreader beam hangs from the hook by two top legs, checked as
//! two legs are above (their shares, angles and what they press the beam
//! with), a lifting beam by its lug, which must then be over that centre of
//! gravity (where it is, is said). The beam is centred on its pins and must
//! lie within the load's footprint, where the planner keeps the rigging
//! (`crane::rigging_above`); one reaching beyond it is refused, not planned.
//!
//! What this module must not do: plan (the check does not depend on the
//! path), or say more than the statics of the legs and the beam: the lift
//! points' own strength, the shackles, the beam's rating at its span and
//! top-leg angle, and the load's strength under the legs' pull are the
//! engineer's.

use crate::frame::Vec3;
use serde::{Deserialize, Serialize};

/// The steepest a sling leg may hang from the vertical (degrees): EN
/// 13414-1 and the codes of practice rate multi-leg slings up to 60°.
pub const MAX_LEG_ANGLE_DEG: f64 = 60.0;

/// What a leg choked round the load may carry, as a share of its working
/// load limit in a straight pull: EN 13414-1's (wire rope), EN 818-4's
/// (chain) and EN 1492-1's (textile) mode factor for a choke hitch.
pub const CHOKE_FACTOR: f64 = 0.8;

/// The most a load may hang off level on one or two legs with its centre
/// of gravity where the lift gives it (degrees): there it hangs with its
/// centre of gravity under its lift point, or under the line through its
/// two, whatever the legs' lengths, and liftplan plans a load level
/// ([`hanging_tilt`]).
pub const MAX_HANGING_TILT_DEG: f64 = 1.0;

/// Standard gravity (m/s²), for the legs' forces in kN.
const G: f64 = 9.806_65;

/// The shackle makers' side-loading chart for screw pin and bolt type
/// shackles (Crosby's and Green Pin's alike): the share of a shackle's
/// working load limit left where its leg pulls at an angle (degrees) out of
/// line, that is out of the plane square to its pin; between the chart's
/// angles, straight between them ([`side_loading_factor`]).
pub const SIDE_LOADING_CHART: [(f64, f64); 3] = [(0.0, 1.0), (45.0, 0.7), (90.0, 0.5)];

/// The share of a shackle's working load limit left at `out_of_line_deg`
/// ([`SIDE_LOADING_CHART`]); the chart's last share beyond it, and for an
/// angle that is not a number.
pub fn side_loading_factor(out_of_line_deg: f64) -> f64 {
    let (last_deg, last_share) = SIDE_LOADING_CHART[SIDE_LOADING_CHART.len() - 1];
    if !(out_of_line_deg < last_deg) {
        return last_share;
    }
    let deg = out_of_line_deg.max(0.0);
    for pair in SIDE_LOADING_CHART.windows(2) {
        let ((a, share_a), (b, share_b)) = (pair[0], pair[1]);
        if deg <= b {
            return share_a + (share_b - share_a) * (deg - a) / (b - a);
        }
    }
    last_share
}

/// The sling legs of a lift, as its `rigging` gives them.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Slings {
    /// Where each leg takes the load, in the load's frame from the centre
    /// of its box (m); one to four.
    pub lift_points_m: Vec<[f64; 3]>,
    /// Whether the lift gave the points (`rigging.lift_points_m`) or they
    /// are the default for the number of legs.
    pub points_given: bool,
    /// What the legs, their shackles and the lift points are rated for.
    #[serde(flatten)]
    pub ratings: Ratings,
    /// The beam the legs hang plumb from, where the lift gives one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spreader: Option<Spreader>,
    /// The direction of the shackle's pin at each lift point, in the
    /// order of the points (the axis of its lug's hole; unit vectors in the
    /// load's frame), where the lift gives them (`rigging.pin_axes`): the
    /// shackles are then checked for side loading ([`side_loading`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pin_axes: Option<Vec<[f64; 3]>>,
}

/// What the rigging between the legs and the load is rated for, as the
/// lift gives it: carried from the lift ([`Slings`]) into its check
/// ([`SlingCheck`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Ratings {
    /// Each leg's working load limit (kg), straight pull.
    pub leg_wll_kg: f64,
    /// Whether the legs are choked round the load: each may carry
    /// [`CHOKE_FACTOR`] of `leg_wll_kg`.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub choked: bool,
    /// The working load limit of the shackle at each lift point (kg, in
    /// line), which carries its leg's pull, where the lift gives it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shackle_wll_kg: Option<f64>,
    /// What each lift point (a lug, a trunnion) may carry in its leg's
    /// direction (kg), where the lift gives it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lift_point_wll_kg: Option<f64>,
}

impl Ratings {
    /// Legs of `leg_wll_kg` in a straight pull, nothing else rated.
    pub fn legs(leg_wll_kg: f64) -> Ratings {
        Ratings { leg_wll_kg, choked: false, shackle_wll_kg: None, lift_point_wll_kg: None }
    }
}

/// A spreader or lifting beam between the hook and two sling legs hanging
/// plumb from its pins (`rigging.spreader`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Spreader {
    /// The beam's length, end to end (m); it is taken centred on its pins.
    pub length_m: f64,
    /// From the hook block's underside down to the beam's pins (m).
    pub below_hook_m: f64,
    /// What the beam may carry below it (kg).
    pub wll_kg: f64,
    /// The beam's own mass (kg), which the top legs carry with the load.
    pub mass_kg: f64,
    /// Each top leg's working load limit (kg, straight pull) of a spreader
    /// beam hung from the hook by two legs; `None`: a lifting beam hung from
    /// the hook by its lug.
    pub top_leg_wll_kg: Option<f64>,
    /// A frame's width (m, along the load's y; `length_m` along its x): a
    /// spreader frame over four lift points, four legs hanging plumb from
    /// its pins and, where `top_leg_wll_kg` gives them, four top legs up to
    /// the hook ([`check_frame`]). `None`: a beam.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub width_m: Option<f64>,
    /// The shackles joining the top legs to the spreader's lugs, where the
    /// lift gives them (`spreader.top_shackle_wll_t`, `top_pin_axes`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub top_shackles: Option<TopShackles>,
}

/// The shackles at a spreader's top lugs, one per top leg: what each may
/// carry in line and, where the lift gives them, the directions of their
/// pins (the axes of the lugs' holes, unit vectors in the load's frame, one
/// per top leg in the order of the lift points), for the side loading.
///
/// A top leg's direction from its lug does not change where the load's
/// centre of gravity lies within its tolerance: the top legs, made for the
/// centre of gravity as given, and the spreader hang as one rigid piece
/// (four top legs, or three with one slack, hold the hook where it is over
/// the frame; two hold it in the beam's plane, and the load and the beam
/// turn in that plane, the load hanging under its lift points' line
/// whatever its centre of gravity across it). So each is taken as rigged.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TopShackles {
    pub wll_kg: f64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pin_axes: Option<Vec<[f64; 3]>>,
}

/// What a beam carries ([`check`] with a [`Spreader`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SpreaderCheck {
    pub length_m: f64,
    /// Between its pins, over the two lift points (m).
    pub span_m: f64,
    pub below_hook_m: f64,
    /// What hangs below it (kg): the load.
    pub carries_kg: f64,
    pub wll_kg: f64,
    /// Where the hook hangs over the beam (where its top legs meet, or its
    /// lug must be), from the middle of its pins towards the second (m):
    /// over the centre of gravity of the load and the beam.
    pub hook_from_middle_m: f64,
    /// The top legs of a spreader beam; `None` for a lifting beam.
    pub top: Option<TopLegs>,
    /// A frame's width (m); `None`: a beam.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub width_m: Option<f64>,
    /// Where the hook hangs over a frame (where its top legs meet, or its
    /// lug must be), from the frame's centre along the load's x and y (m).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub hook_from_centre_m: Option<[f64; 2]>,
}

/// The two legs from a spreader beam's pins up to the hook.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TopLegs {
    /// The steeper's angle from the vertical (degrees).
    pub max_angle_deg: f64,
    /// The most one carries (kg): the load and the beam share them.
    pub max_leg_kg: f64,
    /// Which (1: over the first pin, 2: over the second).
    pub max_leg: usize,
    pub leg_wll_kg: f64,
    /// Each one's length, pin to hook (m), for the beam to hang level.
    pub leg_lengths_m: Vec<f64>,
    /// What they press the beam with along its length (kg-force).
    pub compression_kg: f64,
    /// The most each carries (kg), in the order of the pins, as
    /// [`SlingCheck::leg_most_kg`] is for the legs below; empty in a plan
    /// written before liftplan kept it.
    #[serde(default)]
    pub leg_most_kg: Vec<f64>,
    /// What the shackle at each one's lug may carry in line (kg), where the
    /// lift gives them.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shackle_wll_kg: Option<f64>,
    /// Each one's angle out of the plane square to its shackle's pin as
    /// rigged (degrees, at most 90), in the order of the lift points, where
    /// the lift gives the pins' directions ([`TopShackles`]); empty where not.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub out_of_line_deg: Vec<f64>,
}

impl TopLegs {
    /// The top leg whose shackle is most used for what it may carry: which
    /// (from 0), what the leg carries at most (kg) and what its shackle may
    /// carry (kg): its working load limit, less for side loading at its
    /// leg's angle out of line ([`side_loading_factor`]). `None` where the
    /// lift gives no top shackles.
    pub fn shackle_most_used(&self) -> Option<(usize, f64, f64)> {
        let out_of_line = |k: usize| self.out_of_line_deg.get(k).copied();
        most_used_shackle(
            self.shackle_wll_kg?,
            self.leg_most_kg.len().max(1),
            &self.leg_most_kg,
            self.max_leg_kg,
            out_of_line,
        )
    }

    /// Their shackles at the spreader's lugs, in words (starting "; "):
    /// the most used against what it may carry; nothing where the lift
    /// gives none.
    fn shackles_said(&self) -> String {
        let (Some(wll_kg), Some((leg, carries_kg, limit_kg))) = (self.shackle_wll_kg, self.shackle_most_used()) else {
            return String::new();
        };
        match self.out_of_line_deg.get(leg) {
            Some(deg) => format!(
                "; of the top legs' shackles' {:.2} t at the spreader's lugs, less for side loading: the most used, top leg {}'s, pulls {deg:.1}° out of line with its pin as rigged (spreader top_pin_axes), {}",
                wll_kg / 1000.0,
                leg + 1,
                shackle_use_said(wll_kg, limit_kg, carries_kg, "the makers' chart, as for the lift points' shackles")
            ),
            None => format!(
                "; of the top legs' shackles' {:.2} t at the spreader's lugs (in line): {:.0} %",
                wll_kg / 1000.0,
                100.0 * carries_kg / limit_kg
            ),
        }
    }
}

/// The shackle most used for what it may carry among `legs`: which (from
/// 0), what its leg carries at most (kg: `leg_most_kg`'s, else
/// `max_leg_kg`) and what it may carry (kg): `wll_kg`, less for side
/// loading where `out_of_line` gives its leg's angle out of line
/// ([`side_loading_factor`]); the first of the most used where several are.
fn most_used_shackle(
    wll_kg: f64,
    legs: usize,
    leg_most_kg: &[f64],
    max_leg_kg: f64,
    out_of_line: impl Fn(usize) -> Option<f64>,
) -> Option<(usize, f64, f64)> {
    (0..legs)
        .map(|k| {
            let share = out_of_line(k).map_or(1.0, side_loading_factor);
            (k, leg_most_kg.get(k).copied().unwrap_or(max_leg_kg), wll_kg * share)
        })
        .fold(None, |most: Option<(usize, f64, f64)>, leg| match most {
            Some(m) if !(leg.1 / leg.2 > m.1 / m.2) => Some(m),
            _ => Some(leg),
        })
}

/// What a side-loaded shackle of `wll_kg` may carry (`limit_kg`, by
/// `chart`) and what it carries (`carries_kg`), in words.
fn shackle_use_said(wll_kg: f64, limit_kg: f64, carries_kg: f64, chart: &str) -> String {
    format!(
        "may carry {:.0} % of it, {:.2} t ({chart}), and carries up to {:.2} t: {:.0} %",
        100.0 * limit_kg / wll_kg,
        limit_kg / 1000.0,
        carries_kg / 1000.0,
        100.0 * carries_kg / limit_kg
    )
}

/// Each of `up` (unit vectors from the spreader's lugs to the hook) out of
/// the plane square to its shackle's pin (degrees), where `shackles` gives
/// the pins' directions; empty where not.
fn top_out_of_line_deg(shackles: Option<&TopShackles>, up: &[[f64; 3]]) -> Vec<f64> {
    let Some(axes) = shackles.and_then(|s| s.pin_axes.as_ref()) else { return Vec::new() };
    up.iter()
        .zip(axes)
        .map(|(u, a)| (u[0] * a[0] + u[1] * a[1] + u[2] * a[2]).abs().min(1.0).asin().to_degrees())
        .collect()
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
    /// The most each leg carries (kg), in the order of the lift points, in
    /// the worst way the load may hang on them (and, with a centre of
    /// gravity's tolerance, the worst place for that leg); empty in a plan
    /// written before liftplan kept it.
    #[serde(default)]
    pub leg_most_kg: Vec<f64>,
    /// What the legs, their shackles and the lift points are rated for.
    #[serde(flatten)]
    pub ratings: Ratings,
    pub points_given: bool,
    /// Each leg's length from its lift point to the hook block's underside
    /// (m), in the order of the lift points: what the legs must be for the
    /// load to hang level, as it is planned.
    #[serde(default)]
    pub leg_lengths_m: Vec<f64>,
    /// The beam the legs hang from, where the lift gives one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spreader: Option<SpreaderCheck>,
    /// How far the centre of gravity may lie from where the lift gives it,
    /// along each of the load's axes in plan (m, `load.cog_tolerance_m`):
    /// the most on a leg, the steepest angle and the top legs' figures are
    /// then the worst over that square ([`check_within`]); the legs'
    /// lengths and where the hook or the lug hangs are for the centre of
    /// gravity as given, which the rigging is made for.
    #[serde(default, skip_serializing_if = "crate::is_zero")]
    pub cog_tolerance_m: f64,
    /// Where the centre of gravity puts the most on one leg, within that
    /// tolerance (m from the box's centre, load frame), where it is not the
    /// centre of gravity as given.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub worst_cog_m: Option<[f64; 2]>,
    /// How far off level the load may hang on legs made for the centre of
    /// gravity as given, where it lies elsewhere within the tolerance
    /// (degrees, an upper bound: [`tilt_bound_deg`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tilt_deg: Option<f64>,
    /// How far above where the lift gives it the centre of gravity may lie
    /// (m, `load.cog_tolerance_z_m`): the turn-over check and the tilt's
    /// bound are then made with it that much higher, the worst for both
    /// (`LiftTask::check_slings`).
    #[serde(default, skip_serializing_if = "crate::is_zero")]
    pub cog_tolerance_z_m: f64,
    /// How far each leg pulls out of line with its shackle, where the lift
    /// gives the pins' directions ([`side_loading`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub side_loading: Option<SideLoading>,
}

/// How far each leg pulls out of line with the shackle at its lift point
/// ([`side_loading`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SideLoading {
    /// Each leg's angle out of the plane square to its shackle's pin
    /// (degrees, at most 90), in the order of the lift points: as the legs
    /// are rigged, plus `turn_deg`.
    pub out_of_line_deg: Vec<f64>,
    /// How far the legs may turn in the load's frame where its centre of
    /// gravity lies anywhere within its tolerance, or off the line it hangs
    /// from (degrees, an upper bound; 0 on three or four legs meeting at
    /// the hook, which hold the load as rigged).
    pub turn_deg: f64,
}

impl SideLoading {
    /// How far the leg pulled farthest out of line pulls (degrees).
    pub fn most_deg(&self) -> f64 {
        self.out_of_line_deg.iter().copied().fold(0.0, f64::max)
    }
}

impl SlingCheck {
    /// What one leg may carry (kg): its working load limit, less for a
    /// choke hitch.
    pub fn leg_limit_kg(&self) -> f64 {
        if self.ratings.choked { self.ratings.leg_wll_kg * CHOKE_FACTOR } else { self.ratings.leg_wll_kg }
    }

    /// The most one leg carries over what it may carry (%).
    pub fn utilisation_pct(&self) -> f64 {
        100.0 * self.max_leg_kg / self.leg_limit_kg()
    }

    /// The shackle most used for what it may carry: its leg (from 0), what
    /// that leg carries at most (kg) and what the shackle may carry (kg):
    /// its working load limit, less for side loading at its leg's angle out
    /// of line where the pins' directions are given
    /// ([`side_loading_factor`]); the first of the most used where several
    /// are. `None` where the lift gives no shackles.
    pub fn shackle_most_used(&self) -> Option<(usize, f64, f64)> {
        let out_of_line = |k: usize| self.side_loading.as_ref().and_then(|s| s.out_of_line_deg.get(k)).copied();
        most_used_shackle(self.ratings.shackle_wll_kg?, self.legs, &self.leg_most_kg, self.max_leg_kg, out_of_line)
    }

    /// The most one leg carries, against its limit and its lift point's
    /// shackle's, in words.
    fn most_on_a_leg_said(&self, how: &str) -> String {
        let limit = if self.ratings.choked {
            format!(
                "{:.2} t working load limit choked ({:.2} t in a straight pull, x {CHOKE_FACTOR})",
                self.leg_limit_kg() / 1000.0,
                self.ratings.leg_wll_kg / 1000.0
            )
        } else {
            format!("{:.2} t working load limit", self.ratings.leg_wll_kg / 1000.0)
        };
        let shackle = match (self.ratings.shackle_wll_kg, self.shackle_most_used(), &self.side_loading) {
            (Some(wll_kg), Some((leg, carries_kg, limit_kg)), Some(side)) => {
                let deg = side.out_of_line_deg.get(leg).copied().unwrap_or(0.0);
                let turn = if side.turn_deg > 0.0 {
                    format!(
                        ", {:.1}° of it the most the load may turn on its rigging as its centre of gravity has it, load cog_m and its tolerance",
                        side.turn_deg.min(deg)
                    )
                } else {
                    String::new()
                };
                format!(
                    ", and of the lift points' shackles' {:.2} t, less for side loading: the most used, leg {}'s, pulled up to {deg:.1}° out of line with its pin (rigging pin_axes{turn}), {}",
                    wll_kg / 1000.0,
                    leg + 1,
                    shackle_use_said(
                        wll_kg,
                        limit_kg,
                        carries_kg,
                        "the makers' chart for screw pin and bolt type shackles: 100 % in line, 70 % at 45°, 50 % at 90°, straight between; a round pin shackle must not be side loaded"
                    )
                )
            }
            (Some(wll_kg), _, _) => format!(
                ", and of its lift point's shackle's {:.2} t (in line): {:.0} %",
                wll_kg / 1000.0,
                100.0 * self.max_leg_kg / wll_kg
            ),
            (None, _, _) => String::new(),
        };
        let lug = match (self.ratings.lift_point_wll_kg, &self.side_loading) {
            (Some(p), Some(side)) => format!(
                ", and of the lift point's own {:.2} t, which must be its rating for a pull up to {:.1}° out of its lug's plane: {:.0} %",
                p / 1000.0,
                side.most_deg(),
                100.0 * self.max_leg_kg / p
            ),
            (Some(p), None) => {
                format!(", and of the lift point's own {:.2} t: {:.0} %", p / 1000.0, 100.0 * self.max_leg_kg / p)
            }
            (None, _) => String::new(),
        };
        format!(
            "the most on one leg (leg {}{how}) {:.2} t ({:.0} kN) of its {limit}: {:.0} %{shackle}{lug}",
            self.max_leg,
            self.max_leg_kg / 1000.0,
            self.max_leg_kg * G / 1000.0,
            self.utilisation_pct()
        )
    }

    /// The refusal where something carries more than its working load
    /// limit: what, the check, and what to give instead; `None` where
    /// nothing does.
    pub fn over_limit(&self) -> Option<String> {
        let over = |kg: f64, wll_kg: f64| kg > wll_kg * (1.0 + 1e-12);
        let mut what = Vec::new();
        let mut give = Vec::new();
        if over(self.max_leg_kg, self.leg_limit_kg()) {
            what.push("the sling legs");
            give.push(if self.spreader.is_some() {
                "give legs of a higher working load limit (rigging leg_wll_t)"
            } else {
                "give legs of a higher working load limit (rigging leg_wll_t), more legs or a taller rigging (height_m)"
            });
        }
        if self.shackle_most_used().is_some_and(|(_, carries_kg, limit_kg)| over(carries_kg, limit_kg)) {
            what.push("the lift points' shackles");
            give.push(if self.side_loading.is_some() {
                "give shackles of a higher working load limit (rigging shackle_wll_t) or lugs turned for their legs to pull square to the pins (rigging pin_axes)"
            } else {
                "give shackles of a higher working load limit (rigging shackle_wll_t)"
            });
        }
        if self.ratings.lift_point_wll_kg.is_some_and(|p| over(self.max_leg_kg, p)) {
            what.push("the lift points");
            give.push("give lift points of a higher working load limit (rigging lift_point_wll_t) or more legs");
        }
        if let Some(s) = &self.spreader {
            let frame = s.width_m.is_some();
            if over(s.carries_kg, s.wll_kg) {
                what.push(if frame { "the spreader frame" } else { "the spreader beam" });
                give.push(if frame {
                    "give a frame of a higher working load limit (spreader wll_t)"
                } else {
                    "give a beam of a higher working load limit (spreader wll_t)"
                });
            }
            if let Some(t) = &s.top
                && t.shackle_most_used().is_some_and(|(_, carries_kg, limit_kg)| over(carries_kg, limit_kg))
            {
                what.push("the spreader's top shackles");
                give.push(if t.out_of_line_deg.is_empty() {
                    "give top shackles of a higher working load limit (spreader top_shackle_wll_t)"
                } else {
                    "give top shackles of a higher working load limit (spreader top_shackle_wll_t) or lugs turned for the top legs to pull square to their pins (spreader top_pin_axes)"
                });
            }
            if s.top.as_ref().is_some_and(|t| over(t.max_leg_kg, t.leg_wll_kg)) {
                what.push("the spreader's top legs");
                give.push(if frame {
                    "give top legs of a higher working load limit (spreader top_leg_wll_t) or hang the frame lower (below_hook_m)"
                } else {
                    "give top legs of a higher working load limit (spreader top_leg_wll_t) or hang the beam lower (below_hook_m)"
                });
            }
        }
        (!what.is_empty())
            .then(|| format!("{} cannot carry the load: {}; {}", what.join(" and "), self.said(), give.join("; ")))
    }

    /// Where the legs take the load, in words.
    fn where_said(&self) -> &'static str {
        match (self.points_given, self.legs) {
            (true, _) => "at the lift points given (rigging lift_points_m)",
            (false, 1) => "at the top's centre",
            (false, 2) => "at the middles of the top's short edges",
            (false, _) => "at the top's corners",
        }
    }

    /// In words, for the run's line and the PDF.
    pub fn said(&self) -> String {
        let check = match &self.spreader {
            Some(s) => self.said_with(s),
            None => self.said_on_legs(),
        };
        let tz = self.cog_tolerance_z_m;
        let tilt = if self.tilt_deg.is_some() { ", the tilt's bound taken there" } else { "" };
        let higher = match (tz > 0.0, self.legs <= 2) {
            (false, _) => String::new(),
            (true, true) => format!(
                "; its lift points above the centre of gravity even up to {tz:.2} m higher than given (load cog_tolerance_z_m){tilt}"
            ),
            (true, false) if self.tilt_deg.is_some() => format!(
                "; the tilt's bound taken with the centre of gravity up to {tz:.2} m higher than given (load cog_tolerance_z_m)"
            ),
            (true, false) => format!(
                "; the centre of gravity's height, known to {tz:.2} m (load cog_tolerance_z_m), changes nothing of this on {} legs",
                self.legs
            ),
        };
        format!("{check}{}{higher}", self.cog_tolerance_said())
    }

    /// What a centre of gravity's tolerance ([`check_within`]) made of
    /// the figures, in words; nothing where there is none.
    fn cog_tolerance_said(&self) -> String {
        if self.cog_tolerance_m == 0.0 {
            return String::new();
        }
        let worst = match self.worst_cog_m {
            Some([x, y]) => format!("the most on a leg with it at ({x:.2}, {y:.2}) m"),
            None => "the most on a leg with it as given".to_string(),
        };
        // On one or two legs (a spreader beam's too) the load hangs turned
        // under its lift point or their line, which no leg's length sets
        // level ([`hanging_tilt`]); three or four legs' lengths can.
        let frame = self.spreader.as_ref().is_some_and(|s| s.width_m.is_some());
        let tilt = match (self.tilt_deg, self.legs) {
            (Some(deg), 1) => format!(
                ": on one leg a load whose centre of gravity lies off hangs up to {deg:.1}° off level, with its centre of gravity under its lift point, which no leg's length changes: at the trial lift, CHECK that it hangs level, as the plan takes it, and where it does not, find its centre of gravity"
            ),
            (Some(deg), 2) if !frame => format!(
                ": on two legs a load whose centre of gravity lies off hangs up to {deg:.1}° off level; along the line through its lift points the legs' lengths set it level, across it no length does (it hangs with its centre of gravity under that line): at the trial lift, set the legs for it to hang level along the line and CHECK that it hangs level across it, as the plan takes it, and where it does not, find its centre of gravity"
            ),
            (Some(deg), _) => format!(
                ": on legs of those lengths a load whose centre of gravity lies off hangs up to {deg:.1}° off level: at the trial lift, set the legs for it to hang level, as the plan takes it"
            ),
            (None, _) => String::new(),
        };
        format!(
            "; the worst with the centre of gravity within {:.2} m along x and y (load cog_tolerance_m, the worst over that square worked out; {worst}), the lengths for it as given{tilt}",
            self.cog_tolerance_m
        )
    }

    fn said_on_legs(&self) -> String {
        let where_ = self.where_said();
        let how = if self.legs == 4 { ", any one leg slack" } else { "" };
        let lengths: Vec<String> = self.leg_lengths_m.iter().map(|l| format!("{l:.2}")).collect();
        format!(
            "{} leg{} {where_}{}, up to {:.1}° from the vertical; {}; {} from lift point to hook, for the load to hang level",
            self.legs,
            if self.legs == 1 { "" } else { "s" },
            if self.ratings.choked { " choked round the load" } else { "" },
            self.max_angle_deg,
            self.most_on_a_leg_said(how),
            match &lengths[..] {
                [one] => format!("the leg {one} m long"),
                [first @ .., last] => format!("legs {} and {last} m long", first.join(", ")),
                [] => String::new(),
            }
        )
    }

    fn said_with(&self, s: &SpreaderCheck) -> String {
        if let Some(width_m) = s.width_m {
            return self.said_with_frame(s, width_m);
        }
        let where_ = self.where_said();
        let lengths: Vec<String> = self.leg_lengths_m.iter().map(|l| format!("{l:.2}")).collect();
        let hung = match &s.top {
            Some(t) => format!(
                "hung from the hook by 2 top legs up to {:.1}° from the vertical: the most on one (top leg {}) {:.2} t ({:.0} kN) of its {:.2} t working load limit: {:.0} %{}; top legs {} and {} m long from pin to hook, for the beam to hang level, meeting over the centre of gravity {:.2} m from the pins' middle, pressing the beam with {:.2} t ({:.0} kN)",
                t.max_angle_deg,
                t.max_leg,
                t.max_leg_kg / 1000.0,
                t.max_leg_kg * G / 1000.0,
                t.leg_wll_kg / 1000.0,
                100.0 * t.max_leg_kg / t.leg_wll_kg,
                t.shackles_said(),
                t.leg_lengths_m.first().map(|l| format!("{l:.2}")).unwrap_or_default(),
                t.leg_lengths_m.get(1).map(|l| format!("{l:.2}")).unwrap_or_default(),
                s.hook_from_middle_m.abs(),
                t.compression_kg / 1000.0,
                t.compression_kg * G / 1000.0,
            ),
            None => format!(
                "hung from the hook by its lug, which must be over the centre of gravity, {:.2} m from the pins' middle{} (a lug elsewhere tilts the beam)",
                s.hook_from_middle_m.abs(),
                if s.hook_from_middle_m.abs() < 0.005 {
                    ""
                } else if s.hook_from_middle_m > 0.0 {
                    " towards leg 2"
                } else {
                    " towards leg 1"
                }
            ),
        };
        format!(
            "2 legs {where_}{}, hanging plumb from a spreader beam: {}; legs {} m long from lift point to pin; the beam {:.2} m long, its pins {:.2} m apart and {:.2} m below the hook block, carries {:.2} t of its {:.2} t working load limit: {:.0} %, {hung}",
            if self.ratings.choked { " choked round the load" } else { "" },
            self.most_on_a_leg_said(""),
            lengths.join(" and "),
            s.length_m,
            s.span_m,
            s.below_hook_m,
            s.carries_kg / 1000.0,
            s.wll_kg / 1000.0,
            100.0 * s.carries_kg / s.wll_kg,
        )
    }
}

impl SlingCheck {
    /// [`Self::said`] for four legs hanging plumb from a spreader frame.
    fn said_with_frame(&self, s: &SpreaderCheck, width_m: f64) -> String {
        let lengths: Vec<String> = self.leg_lengths_m.iter().map(|l| format!("{l:.2}")).collect();
        let [dx, dy] = s.hook_from_centre_m.unwrap_or([0.0; 2]);
        let hung = match &s.top {
            Some(t) => {
                let top: Vec<String> = t.leg_lengths_m.iter().map(|l| format!("{l:.2}")).collect();
                format!(
                    "hung from the hook by 4 top legs up to {:.1}° from the vertical: the most on one (top leg {}, any one slack) {:.2} t ({:.0} kN) of its {:.2} t working load limit: {:.0} %{}; top legs {} m long from pin to hook, for the frame to hang level, meeting over the centre of gravity ({dx:.2}, {dy:.2}) m from the frame's centre, each pulling its corner in with up to {:.2} t ({:.0} kN)",
                    t.max_angle_deg,
                    t.max_leg,
                    t.max_leg_kg / 1000.0,
                    t.max_leg_kg * G / 1000.0,
                    t.leg_wll_kg / 1000.0,
                    100.0 * t.max_leg_kg / t.leg_wll_kg,
                    t.shackles_said(),
                    top.join(", "),
                    t.compression_kg / 1000.0,
                    t.compression_kg * G / 1000.0,
                )
            }
            None => format!(
                "hung from the hook by its lug, which must be over the centre of gravity, ({dx:.2}, {dy:.2}) m from the frame's centre along the load's x and y (a lug elsewhere tilts the frame)"
            ),
        };
        format!(
            "4 legs {}{}, hanging plumb from a spreader frame: {}; legs {} m long from lift point to pin; the frame {:.2} x {width_m:.2} m, its pins {:.2} m below the hook block, carries {:.2} t of its {:.2} t working load limit: {:.0} %, {hung}",
            self.where_said(),
            if self.ratings.choked { " choked round the load" } else { "" },
            self.most_on_a_leg_said(", any one leg slack"),
            lengths.join(", "),
            s.length_m,
            s.below_hook_m,
            s.carries_kg / 1000.0,
            s.wll_kg / 1000.0,
            100.0 * s.carries_kg / s.wll_kg,
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
    // On one or two legs (a spreader's too) the load turns about its lift
    // points' line: below its centre of gravity, it turns over.
    let lowest = slings.lift_points_m.iter().map(|p| p[2]).fold(f64::INFINITY, f64::min);
    if slings.lift_points_m.len() <= 2 && !(lowest > cog_m[2] + 1e-9) {
        return Err(format!(
            "the load hangs on {} leg{} from lift points as low as z {lowest:.2} m from its box's centre, not above its centre of gravity (z {:.2} m): it would turn over in the slings; give lift points above it (rigging lift_points_m) or more legs",
            slings.lift_points_m.len(),
            if slings.lift_points_m.len() == 1 { "" } else { "s" },
            cog_m[2]
        ));
    }
    match &slings.spreader {
        Some(frame) if frame.width_m.is_some() => {
            return check_frame(slings, frame, load_kg, size_m, cog_m, rigging_height_m);
        }
        Some(beam) => return check_spreader(slings, beam, load_kg, size_m, cog_m, rigging_height_m),
        None => {}
    }
    let hook = [cog_m[0], cog_m[1], size_m[2] / 2.0 + rigging_height_m];
    let pts = &slings.lift_points_m;
    let Legs { up, lengths_m: leg_lengths_m, max_angle_deg } = legs_to(hook, pts).map_err(|k| {
        format!(
            "sling leg {} takes the load at z {:.2} m from its box's centre, not below the hook block ({:.2} m: the load's top plus rigging height_m)",
            k + 1,
            pts[k][2],
            hook[2]
        )
    })?;
    // One leg hangs plumb: the load tilts until its centre of gravity is
    // under the point.
    let max_angle_deg = if pts.len() == 1 { 0.0 } else { max_angle_deg };
    if max_angle_deg > MAX_LEG_ANGLE_DEG + 1e-9 {
        return Err(format!(
            "the sling legs hang up to {max_angle_deg:.1}° from the vertical, more than the {MAX_LEG_ANGLE_DEG:.0}° slings are rated for: give a taller rigging (rigging height_m {rigging_height_m:.2} m) or lift points nearer the centre of gravity"
        ));
    }
    // Each way the load may hang: each carrying leg and its pull.
    let pulls: Vec<(usize, f64)> = match pts.len() {
        1 => vec![(0, load_kg)],
        2 => two_legs(pts, &up, load_kg)?.into_iter().enumerate().collect(),
        3 => three_legs(&up, [0, 1, 2], load_kg).ok_or_else(outside)?.into_iter().enumerate().collect(),
        4 => one_slack(|legs| three_legs(&up, legs, load_kg)).ok_or_else(outside)?,
        n => return Err(format!("{n} sling legs: liftplan checks one to four")),
    };
    let (max_leg, max_leg_kg) = most_on_one(&pulls);
    Ok(SlingCheck {
        legs: pts.len(),
        max_angle_deg,
        max_leg_kg,
        max_leg: max_leg + 1,
        leg_most_kg: most_on_each(&pulls, pts.len()),
        leg_lengths_m,
        ratings: slings.ratings,
        points_given: slings.points_given,
        spreader: None,
        cog_tolerance_m: 0.0,
        cog_tolerance_z_m: 0.0,
        worst_cog_m: None,
        tilt_deg: None,
        side_loading: None,
    })
}

/// The places a centre of gravity within its tolerance is first checked at,
/// along each of the load's axes: [`COG_SAMPLES`] across, the square's
/// corners and edges among them.
pub const COG_SAMPLES: usize = 9;

/// [`check`] with the centre of gravity anywhere within `cog_tolerance_m`
/// of `cog_m` along the load's x and y (a square in plan): the check at
/// `cog_m` (the legs' lengths, where the hook or the lug hangs: what the
/// rigging is made for), with the most on a leg, the steepest leg and the
/// spreader's top legs the worst over the square, each place worked out as
/// [`check`] does, with the hook over it (the legs' pulls follow the centre
/// of gravity; the small tilt of a load rigged for another is not
/// modelled). Refused where the legs cannot carry the load at one of the
/// places, saying where.
///
/// The worst is worked out, not searched for: it lies at one of the places
/// [`worst_places`] lists, where the check is made, besides
/// [`COG_SAMPLES`] x [`COG_SAMPLES`] places across the square (its corners
/// among them). Why those places hold it:
///
/// - A leg's pull, where a set of legs meets at one hook `H` high over
///   `h` in plan (over the centre of gravity; over a spreader's and the
///   load's together, on a beam's line: affine in the centre of gravity's
///   place either way) and carries `W`: the pulls balance the load, so the legs'
///   pulls over their lengths, `t_k = T_k / L_k`, weigh their lift points'
///   places in plan to `h` (barycentric weights `μ_k`, affine in `h`, along
///   the line for two legs) and `t_k = W μ_k / D` with `D = H - Σ μ_k z_k`
///   (affine, above zero where they carry it), so `T_k = W μ_k L_k / D`,
///   and `L_k`, the leg's length, is convex in `h`. Along a line on which
///   `μ_k` stays the same, `L_k / D` is quasi-convex (its sublevel sets,
///   `L_k ≤ c D`, are convex), so the pull is most at the line's ends: over
///   a convex region, on its edge.
/// - The regions: the whole square, where all legs carry (one leg, two,
///   three, a beam's top legs; where they cannot all carry at some place of
///   the square, they cannot at one of its corners, the grid's, since the
///   places where they can are convex); four legs, one slack: each three
///   carry within their triangle, whose edges are lines through two lift
///   points, so a leg's most over the square lies on the square's edges or
///   on those lines within it.
/// - On each such segment the pull is `μ(s) √q(s) / D(s)` (μ, D affine, q
///   quadratic in `s`): most at the segment's ends (the square's corners,
///   where a line crosses its edges, a lift point within it) or where its
///   derivative is zero, a root of a cubic. The pull across a spreader's
///   top leg (what presses the spreader) is alike, `q` without the height.
/// - Plumb legs from a frame's pins share the load by their triangle's
///   barycentric weights, affine: most at a corner of the region, the
///   square's, where a line through two lift points crosses its edges, a
///   lift point within it. A beam's two plumb legs by the lever rule,
///   affine: at a corner.
/// - A leg's angle from the vertical grows with its run in plan, convex in
///   the hook's place, affine in the centre of gravity's: most at a corner.
///
/// So the worst is found to the rounding of the roots and of the check
/// itself; the test `no_place_finds_more_than_the_worst_worked_out` checks
/// it against 101 x 101 places over the square and 2001 along each edge, on
/// random riggings.
pub fn check_within(
    slings: &Slings,
    load_kg: f64,
    size_m: [f64; 3],
    cog_m: [f64; 3],
    cog_tolerance_m: f64,
    rigging_height_m: f64,
) -> Result<SlingCheck, String> {
    let mut worst = check(slings, load_kg, size_m, cog_m, rigging_height_m)?;
    if let Some(why) = hanging_tilt(slings, cog_m).filter(|t| t.0 > MAX_HANGING_TILT_DEG).map(|t| t.1) {
        return Err(why);
    }
    if !(cog_tolerance_m > 0.0) {
        return Ok(worst);
    }
    worst.cog_tolerance_m = cog_tolerance_m;
    worst.tilt_deg = Some(tilt_bound_deg(slings, size_m, cog_m, cog_tolerance_m, rigging_height_m));
    let tol = cog_tolerance_m;
    let at = |[x, y]: [f64; 2]| -> Result<SlingCheck, String> {
        check(slings, load_kg, size_m, [x, y, cog_m[2]], rigging_height_m).map_err(|e| {
            format!(
                "with the load's centre of gravity at ({x:.2}, {y:.2}) m from its box's centre, within load cog_tolerance_m ({tol:.2} m) of the given one: {e}"
            )
        })
    };
    // The grid first: its corners show where the legs cannot carry it.
    let across = |k: usize| -tol + 2.0 * tol * k as f64 / (COG_SAMPLES - 1) as f64;
    let grid = (0..COG_SAMPLES * COG_SAMPLES)
        .map(|k| [cog_m[0] + across(k % COG_SAMPLES), cog_m[1] + across(k / COG_SAMPLES)]);
    for p in grid.chain(worst_places(slings, load_kg, size_m, cog_m, tol, rigging_height_m)) {
        worst_of(&mut worst, &at(p)?, p);
    }
    Ok(worst)
}

/// Legs meeting at one hook, for [`worst_places`]: the load's own legs, or
/// a spreader's top legs.
struct LegsToOneHook {
    /// Where they take hold, in the load's frame (m).
    points: Vec<[f64; 3]>,
    /// The hook's height in that frame (m).
    hook_z: f64,
    /// The load's share of what the legs carry (1 without a spreader) and
    /// the spreader's centre of gravity in plan: the hook hangs over their
    /// joint centre of gravity,
    load_share: f64,
    own_centre: [f64; 2],
    /// and a beam's over its line (a point on it, its unit direction).
    onto_line: Option<([f64; 2], [f64; 2])>,
    /// Whether the pull across (what a spreader's top legs press it with)
    /// is worked out too.
    across: bool,
}

impl LegsToOneHook {
    /// The hook's place in plan for the centre of gravity at `cog`.
    fn hook(&self, cog: [f64; 2]) -> [f64; 2] {
        let joint = [0, 1].map(|a| self.load_share * cog[a] + (1.0 - self.load_share) * self.own_centre[a]);
        match self.onto_line {
            Some((a, dir)) => {
                let along = (joint[0] - a[0]) * dir[0] + (joint[1] - a[1]) * dir[1];
                [a[0] + dir[0] * along, a[1] + dir[1] * along]
            }
            None => joint,
        }
    }

    /// The centre of gravity's place for which the hook hangs at `hook`
    /// (not for a beam, whose hook keeps to its line).
    fn cog_for(&self, hook: [f64; 2]) -> [f64; 2] {
        [0, 1].map(|a| (hook[a] - (1.0 - self.load_share) * self.own_centre[a]) / self.load_share)
    }
}

/// The places of the centre of gravity within `tol` of `cog_m` (plan) at
/// which the most on each leg of `slings`, on each of a spreader's top legs
/// and across them, may lie, besides the square's corners
/// ([`check_within`] says why): on the square's edges and on the lines
/// through two lift points where four legs meet (or hang plumb from a
/// frame), their ends and where the pull's derivative along them is zero;
/// and the lift points within the square.
fn worst_places(
    slings: &Slings,
    load_kg: f64,
    size_m: [f64; 3],
    cog_m: [f64; 3],
    tol: f64,
    rigging_height_m: f64,
) -> Vec<[f64; 2]> {
    let pts = &slings.lift_points_m;
    let hook_z = size_m[2] / 2.0 + rigging_height_m;
    let plan = |p: &[f64; 3]| [p[0], p[1]];
    let mut sets = Vec::new();
    let mut places: Vec<[f64; 2]> = Vec::new();
    match &slings.spreader {
        None if pts.len() >= 2 => sets.push(LegsToOneHook {
            points: pts.clone(),
            hook_z,
            load_share: 1.0,
            own_centre: [0.0; 2],
            onto_line: None,
            across: false,
        }),
        None => {}
        Some(s) => {
            let pins_z = hook_z - s.below_hook_m;
            let load_share = load_kg / (load_kg + s.mass_kg);
            let pins: Vec<[f64; 3]> = pts.iter().map(|p| [p[0], p[1], pins_z]).collect();
            let n = pts.len() as f64;
            let centre = [pts.iter().map(|p| p[0]).sum::<f64>() / n, pts.iter().map(|p| p[1]).sum::<f64>() / n];
            // A frame's plumb legs share by their triangles: the lift
            // points within the square are corners of them.
            places.extend(pts.iter().map(plan));
            if s.top_leg_wll_kg.is_some() && pts.len() >= 2 {
                let onto_line = (s.width_m.is_none()).then(|| {
                    let along = [pts[1][0] - pts[0][0], pts[1][1] - pts[0][1]];
                    let n = along[0].hypot(along[1]).max(1e-12);
                    (plan(&pts[0]), [along[0] / n, along[1] / n])
                });
                sets.push(LegsToOneHook {
                    points: pins,
                    hook_z,
                    load_share,
                    own_centre: centre,
                    onto_line,
                    across: true,
                });
            }
        }
    }
    let [cx, cy] = [cog_m[0], cog_m[1]];
    // Where the square's edges cross a line through two lift points: a
    // corner of the region where three of four legs carry, or three of a
    // frame's plumb legs.
    for (i, a) in pts.iter().enumerate() {
        for b in &pts[i + 1..] {
            places.extend(edge_crossings(plan(a), plan(b), [cx, cy], tol));
        }
    }
    let corners = [[cx - tol, cy - tol], [cx + tol, cy - tol], [cx + tol, cy + tol], [cx - tol, cy + tol]];
    for set in &sets {
        let mut segments: Vec<[[f64; 2]; 2]> = (0..4).map(|k| [corners[k], corners[(k + 1) % 4]]).collect();
        if set.points.len() == 4 && set.onto_line.is_none() && set.load_share > 0.0 {
            for (i, a) in set.points.iter().enumerate() {
                places.push(set.cog_for(plan(a)));
                for b in &set.points[i + 1..] {
                    let ends = edge_crossings(set.cog_for(plan(a)), set.cog_for(plan(b)), [cx, cy], tol);
                    if let (Some(first), Some(last)) = (ends.first(), ends.last()) {
                        // The crossings lie on one line: its farthest two.
                        let far = ends.iter().fold(*last, |far, p| {
                            let d = |q: &[f64; 2]| (q[0] - first[0]).hypot(q[1] - first[1]);
                            if d(p) > d(&far) { *p } else { far }
                        });
                        places.extend([*first, far]);
                        segments.push([*first, far]);
                    }
                }
            }
        }
        for [h0, h1] in segments {
            for s in pull_turning_points(set, set.hook(h0), set.hook(h1)) {
                places.push([h0[0] + s * (h1[0] - h0[0]), h0[1] + s * (h1[1] - h0[1])]);
            }
        }
    }
    // Those on the square's edges kept there, not lost to the rounding;
    // lift points and the like outside it dropped.
    let slack = 1e-9 * tol.max(1.0);
    places.retain(|p| (p[0] - cx).abs() <= tol + slack && (p[1] - cy).abs() <= tol + slack);
    for p in &mut places {
        *p = [p[0].clamp(cx - tol, cx + tol), p[1].clamp(cy - tol, cy + tol)];
    }
    places
}

/// Where between 0 and 1 along the hook's path from `hook0` to `hook1`
/// (plan) the pull on one of `set`'s legs, or across it, has a zero
/// derivative, for each way its legs may carry (two, three, or any three of
/// four) ([`check_within`]: the roots of a cubic).
fn pull_turning_points(set: &LegsToOneHook, hook0: [f64; 2], hook1: [f64; 2]) -> Vec<f64> {
    let pts = &set.points;
    let ways: Vec<Vec<usize>> = match pts.len() {
        2 => vec![vec![0, 1]],
        3 => vec![vec![0, 1, 2]],
        4 => vec![vec![1, 2, 3], vec![0, 2, 3], vec![0, 1, 3], vec![0, 1, 2]],
        _ => Vec::new(),
    };
    let mut out = Vec::new();
    for way in ways {
        let xy: Vec<[f64; 2]> = way.iter().map(|&k| [pts[k][0], pts[k][1]]).collect();
        let (Some(w0), Some(w1)) = (plan_weights(&xy, hook0), plan_weights(&xy, hook1)) else { continue };
        let depth = |w: &[f64]| set.hook_z - way.iter().zip(w).map(|(&k, m)| m * pts[k][2]).sum::<f64>();
        let d = [depth(&w0), depth(&w1) - depth(&w0)];
        let step = [hook1[0] - hook0[0], hook1[1] - hook0[1]];
        for (j, &k) in way.iter().enumerate() {
            let mu = [w0[j], w1[j] - w0[j]];
            let from = [hook0[0] - pts[k][0], hook0[1] - pts[k][1]];
            let drop_m = set.hook_z - pts[k][2];
            for height in if set.across { vec![drop_m, 0.0] } else { vec![drop_m] } {
                let q = [
                    from[0] * from[0] + from[1] * from[1] + height * height,
                    2.0 * (from[0] * step[0] + from[1] * step[1]),
                    step[0] * step[0] + step[1] * step[1],
                ];
                // d/ds of μ √q / D is zero where 2 μ' q D + μ q' D - 2 μ q D' is.
                let q_d = poly_mul(&q, &d);
                let dq = [q[1], 2.0 * q[2]];
                let mut cubic = [0.0; 4];
                for (c, v) in cubic.iter_mut().zip(q_d.iter().map(|v| 2.0 * mu[1] * v)) {
                    *c += v;
                }
                for (c, v) in cubic.iter_mut().zip(poly_mul(&poly_mul(&mu, &dq), &d)) {
                    *c += v;
                }
                for (c, v) in cubic.iter_mut().zip(poly_mul(&mu, &q)) {
                    *c -= 2.0 * d[1] * v;
                }
                out.extend(roots_within_0_1(&cubic));
            }
        }
    }
    out
}

/// The barycentric weights of `p` among the points `xy` in plan (two: along
/// the line through them), whatever their sign; `None` where the points
/// coincide or lie in a line.
fn plan_weights(xy: &[[f64; 2]], p: [f64; 2]) -> Option<Vec<f64>> {
    match xy {
        [a, b] => {
            let along = [b[0] - a[0], b[1] - a[1]];
            let n2 = along[0] * along[0] + along[1] * along[1];
            (n2 > 1e-18).then(|| {
                let t = ((p[0] - a[0]) * along[0] + (p[1] - a[1]) * along[1]) / n2;
                vec![1.0 - t, t]
            })
        }
        [a, b, c] => barycentric([*a, *b, *c], p).map(Vec::from),
        _ => None,
    }
}

/// The product of two polynomials (coefficients from the constant up).
fn poly_mul(a: &[f64], b: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; a.len() + b.len() - 1];
    for (i, x) in a.iter().enumerate() {
        for (j, y) in b.iter().enumerate() {
            out[i + j] += x * y;
        }
    }
    out
}

/// The real roots strictly between 0 and 1 of the cubic `c` (coefficients
/// from the constant up): its sign changes over 64 equal steps and at its
/// own turning points, each narrowed by halving to the rounding; a root it
/// touches without crossing is not one of a turning point of the pull.
fn roots_within_0_1(c: &[f64; 4]) -> Vec<f64> {
    let scale = c.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    if !(scale > 0.0 && scale.is_finite()) {
        return Vec::new();
    }
    let p = |s: f64| ((c[3] * s + c[2]) * s + c[1]) * s + c[0];
    let mut cuts: Vec<f64> = (0..=64).map(|k| k as f64 / 64.0).collect();
    // The cubic's turning points: 3 c3 s² + 2 c2 s + c1 = 0.
    let (a, b, k) = (3.0 * c[3], 2.0 * c[2], c[1]);
    if a.abs() > 1e-12 * scale {
        let disc = b * b - 4.0 * a * k;
        if disc >= 0.0 {
            let r = disc.sqrt();
            cuts.extend([(-b - r) / (2.0 * a), (-b + r) / (2.0 * a)]);
        }
    } else if b.abs() > 0.0 {
        cuts.push(-k / b);
    }
    cuts.retain(|s| (0.0..=1.0).contains(s));
    cuts.sort_by(f64::total_cmp);
    let mut roots = Vec::new();
    for w in cuts.windows(2) {
        let (mut lo, mut hi) = (w[0], w[1]);
        let (plo, phi) = (p(lo), p(hi));
        if plo == 0.0 && lo > 0.0 {
            roots.push(lo);
        }
        if plo.signum() * phi.signum() < 0.0 {
            for _ in 0..80 {
                let mid = 0.5 * (lo + hi);
                if mid <= lo || mid >= hi {
                    break;
                }
                if p(mid).signum() == plo.signum() { lo = mid } else { hi = mid }
            }
            roots.push(0.5 * (lo + hi));
        }
    }
    roots
}

/// How far off level a load hangs on one or two legs (a spreader beam's
/// two plumb legs too) with its centre of gravity at `cog_m` (degrees), and
/// why, in words: on one leg it hangs with its centre of gravity plumb under
/// the lift point, on two with it under the line through them, which no
/// leg's length changes. `None` on three or four legs (their lengths hang
/// it level) or a spreader frame (its plumb legs keep the load turned as
/// the frame, which hangs level over the joint centre of gravity).
pub fn hanging_tilt(slings: &Slings, cog_m: [f64; 3]) -> Option<(f64, String)> {
    let pts = &slings.lift_points_m;
    if slings.spreader.as_ref().is_some_and(|s| s.width_m.is_some()) {
        return None;
    }
    match &pts[..] {
        [one] => {
            let off_m = off_its_line_m(pts, cog_m);
            let deg = off_m.atan2(one[2] - cog_m[2]).to_degrees();
            Some((
                deg,
                format!(
                    "on one leg the load hangs with its centre of gravity plumb under its lift point, which lies {off_m:.2} m off it in plan: it would hang {deg:.1}° off level, and liftplan plans a load level (at most {MAX_HANGING_TILT_DEG:.0}° off); give the lift point over the centre of gravity (rigging lift_points_m) or three or four legs, whose lengths set it level"
                ),
            ))
        }
        [a, b] => {
            let off_m = off_its_line_m(pts, cog_m);
            // Level, the load's up is the up it turns from.
            let deg = turn_about_line_deg(Vec3::from(*a), Vec3::from(*b), Vec3::z(), Vec3::from(cog_m));
            Some((
                deg,
                format!(
                    "the load's centre of gravity lies {off_m:.2} m off the line through its two lift points in plan: on two legs it would hang turned {deg:.1}° about that line, which no leg's length sets level, and liftplan plans a load level (at most {MAX_HANGING_TILT_DEG:.0}° off); give lift points either side of the centre of gravity (rigging lift_points_m), or three or four legs, whose lengths set it level"
                ),
            ))
        }
        _ => None,
    }
}

/// The most a load hangs off level on legs made for its centre of gravity
/// at `cog_m` when it lies up to `tol` off along x and y (degrees): it turns
/// until its centre of gravity is under what it hangs from, at least as far
/// above it as `arm`: the hook over three or four legs (the legs and the
/// load turn as one about it), the line through the lift points on two (the
/// load turns about it across the line; along it, about the hook, higher),
/// the lift point on one. So atan(√2 tol / arm), the offset's most in plan
/// over that height; on one or two legs, with how far the centre of gravity
/// as given already lies off the lift point or their line added to it.
///
/// A spreader hangs from the hook (by its top legs or its lug) and the load
/// from its pins on plumb legs, which keep the load turned as the spreader
/// is: the spreader and the load turn about the hook as one whose centre of
/// gravity stood the legs' length higher ([`spreader_arm_m`]), and a beam's
/// two legs also let the load turn about the line through its lift points
/// as two legs to a hook do; a beam's bound is the sum of the two.
pub fn tilt_bound_deg(slings: &Slings, size_m: [f64; 3], cog_m: [f64; 3], tol: f64, rigging_height_m: f64) -> f64 {
    let pts = &slings.lift_points_m;
    let lowest = pts.iter().map(|p| p[2]).fold(f64::INFINITY, f64::min);
    let off = std::f64::consts::SQRT_2 * tol;
    let over = |arm: f64| off.atan2(arm).to_degrees();
    // Under one or two lift points, from where the centre of gravity as
    // given already lies off them ([`hanging_tilt`]) too.
    let over_line = |arm: f64| (off + off_its_line_m(pts, cog_m)).atan2(arm).to_degrees();
    match (&slings.spreader, pts.len()) {
        (Some(s), _) if s.width_m.is_none() => over_line(lowest - cog_m[2]) + over(spreader_arm_m(s, pts, cog_m)),
        (Some(s), _) => over(spreader_arm_m(s, pts, cog_m)),
        (None, 1 | 2) => over_line(lowest - cog_m[2]),
        (None, _) => over(size_m[2] / 2.0 + rigging_height_m - cog_m[2]),
    }
}

/// How far the centre of gravity `cog_m` lies in plan off one lift point
/// (`pts` of one), or off the vertical plane through two (m); 0 for more.
fn off_its_line_m(pts: &[[f64; 3]], cog_m: [f64; 3]) -> f64 {
    match pts {
        [one] => (one[0] - cog_m[0]).hypot(one[1] - cog_m[1]),
        [a, b] => {
            let along = [b[0] - a[0], b[1] - a[1]];
            let n = along[0].hypot(along[1]);
            if n > 0.0 { ((cog_m[0] - a[0]) * along[1] - (cog_m[1] - a[1]) * along[0]).abs() / n } else { 0.0 }
        }
        _ => 0.0,
    }
}

/// How far above the load's centre of gravity `cog_m` a spreader and the
/// load hanging from it on plumb legs turn as one about the hook (m): the
/// spreader's pins `below_hook_m` under the hook, and the lowest lift point's
/// height above the centre of gravity (plumb legs keep the load turned as the
/// spreader, so its weight acts on the pins as if its centre of gravity were
/// the legs' length higher). Where this is not above zero, the two turn
/// over together ([`check_frame`] refuses it; two legs from a beam need lift
/// points above the centre of gravity anyway). The spreader's own weight,
/// which steadies it, is left out: the bound is the worse for it.
pub fn spreader_arm_m(spreader: &Spreader, lift_points_m: &[[f64; 3]], cog_m: [f64; 3]) -> f64 {
    let lowest = lift_points_m.iter().map(|p| p[2]).fold(f64::INFINITY, f64::min);
    spreader.below_hook_m + lowest - cog_m[2]
}

/// How far each leg pulls out of line with the shackle at its lift point
/// (the module's doc), for the pins `slings.pin_axes` gives (`None` where it
/// gives none), on a load of box `size_m` with its centre of gravity `cog_m`
/// from the box's centre as given (the legs' lengths are for it), anywhere
/// within `tol_m` of it along x and y and up to `tol_z_m` higher, hanging
/// `rigging_height_m` below the hook block's underside.
///
/// As rigged, a leg runs from its lift point to the hook over the centre of
/// gravity, or hangs plumb from a spreader's pin (the load level), and one
/// leg alone hangs plumb over the centre of gravity. The load may then
/// turn on its rigging, and its legs with it in its frame, by at most:
/// - three or four legs to the hook: nothing (their lengths hold the hook
///   where it is in the load's frame, whichever of them carry);
/// - two legs to the hook: the turn about the line through their lift
///   points that brings the centre of gravity under it, the hook over it,
///   worked out at the tolerance box's corners;
/// - one leg: the angle between its direction as rigged and the one from
///   the centre of gravity up to its lift point, at the box's corners;
/// - a spreader beam: that turn about the lift points' line, and the beam's
///   and the load's turn about the hook ([`spreader_arm_m`]) added to it;
///   a frame: that turn about the hook.
///
/// (An angle from a fixed direction, or about a fixed line, is largest over
/// a box at one of its corners while under 90°, since the directions within
/// that angle form a convex cone; a turn of a direction by one rotation and
/// then another is at most the two angles added.) A leg's angle out of line
/// is its angle as rigged plus that turn, at most 90°.
pub fn side_loading(
    slings: &Slings,
    size_m: [f64; 3],
    cog_m: [f64; 3],
    tol_m: f64,
    tol_z_m: f64,
    rigging_height_m: f64,
) -> Option<SideLoading> {
    let axes = slings.pin_axes.as_ref()?;
    let pts = &slings.lift_points_m;
    let corners: Vec<Vec3> = (0..8)
        .map(|k| {
            let side = |bit: usize| if k & bit == 0 { -1.0 } else { 1.0 };
            Vec3::new(
                cog_m[0] + side(1) * tol_m,
                cog_m[1] + side(2) * tol_m,
                cog_m[2] + if k & 4 == 0 { 0.0 } else { tol_z_m },
            )
        })
        .collect();
    let v = Vec3::from;
    let cog = v(cog_m);
    let hook = Vec3::new(cog_m[0], cog_m[1], size_m[2] / 2.0 + rigging_height_m);
    let most_over = |f: &dyn Fn(&Vec3) -> f64| corners.iter().map(f).fold(0.0f64, f64::max);
    // The turn about the line through two lift points that brings each
    // corner under it, from `rigged` (the hook's or the legs' side of it).
    let about_line = |rigged: Vec3| -> f64 { most_over(&|c| turn_about_line_deg(v(pts[0]), v(pts[1]), rigged, *c)) };
    let (rigged, turn_deg): (Vec<Vec3>, f64) = match (&slings.spreader, pts.len()) {
        (Some(s), _) => {
            let tilt = (std::f64::consts::SQRT_2 * tol_m)
                .atan2(spreader_arm_m(s, pts, [cog_m[0], cog_m[1], cog_m[2] + tol_z_m]))
                .to_degrees();
            let roll = if s.width_m.is_none() { about_line(Vec3::z()) } else { 0.0 };
            (vec![Vec3::z(); pts.len()], roll + tilt)
        }
        (None, 1) => {
            let rigged = (v(pts[0]) - cog).normalize();
            (vec![rigged], most_over(&|c| angle_deg(&rigged, &(v(pts[0]) - c))))
        }
        (None, 2) => {
            let legs = pts.iter().map(|p| (hook - v(*p)).normalize()).collect();
            (legs, about_line(hook - v(pts[0])))
        }
        (None, _) => (pts.iter().map(|p| (hook - v(*p)).normalize()).collect(), 0.0),
    };
    let out_of_line_deg = rigged
        .iter()
        .zip(axes)
        .map(|(leg, pin)| {
            let as_rigged = leg.dot(&v(*pin)).abs().min(1.0).asin().to_degrees();
            (as_rigged + turn_deg).min(90.0)
        })
        .collect();
    Some(SideLoading { out_of_line_deg, turn_deg })
}

/// How far a load hanging from the line through its lift points `a` and
/// `b` turns about that line (degrees) to bring the point `c` of its frame
/// under it, from where `from` (a direction in its frame: its up, or the
/// hook's side of the line) points up from the line. 0 where the line is
/// plumb, or a point.
fn turn_about_line_deg(a: Vec3, b: Vec3, from: Vec3, c: Vec3) -> f64 {
    let along = (b - a).try_normalize(1e-9).unwrap_or(Vec3::z());
    let across = |w: Vec3| w - along * w.dot(&along);
    angle_deg(&across(from), &-across(c - a))
}

/// The angle between two directions (degrees, 0 to 180).
fn angle_deg(a: &Vec3, b: &Vec3) -> f64 {
    a.cross(b).norm().atan2(a.dot(b)).to_degrees()
}

/// Where the square of half side `tol` about `centre` has its edges crossed
/// by the line through `a` and `b` (plan, m).
fn edge_crossings(a: [f64; 2], b: [f64; 2], centre: [f64; 2], tol: f64) -> Vec<[f64; 2]> {
    let d = [b[0] - a[0], b[1] - a[1]];
    let mut out = Vec::new();
    for axis in 0..2 {
        if d[axis].abs() < 1e-12 {
            continue;
        }
        let other = 1 - axis;
        for side in [-tol, tol] {
            let t = (centre[axis] + side - a[axis]) / d[axis];
            let v = a[other] + t * d[other];
            if (v - centre[other]).abs() <= tol {
                let mut p = [0.0; 2];
                (p[axis], p[other]) = (centre[axis] + side, v);
                out.push(p);
            }
        }
    }
    out
}

/// Takes in `c`, the check at the centre of gravity `at`, where it is worse.
fn worst_of(worst: &mut SlingCheck, c: &SlingCheck, at: [f64; 2]) {
    worst.max_angle_deg = worst.max_angle_deg.max(c.max_angle_deg);
    if c.max_leg_kg > worst.max_leg_kg {
        (worst.max_leg_kg, worst.max_leg, worst.worst_cog_m) = (c.max_leg_kg, c.max_leg, Some(at));
    }
    for (w, &kg) in worst.leg_most_kg.iter_mut().zip(&c.leg_most_kg) {
        *w = w.max(kg);
    }
    let top = c.spreader.as_ref().and_then(|s| s.top.as_ref());
    if let (Some(w), Some(t)) = (worst.spreader.as_mut().and_then(|s| s.top.as_mut()), top) {
        w.max_angle_deg = w.max_angle_deg.max(t.max_angle_deg);
        w.compression_kg = w.compression_kg.max(t.compression_kg);
        if t.max_leg_kg > w.max_leg_kg {
            (w.max_leg_kg, w.max_leg) = (t.max_leg_kg, t.max_leg);
        }
        for (most, &kg) in w.leg_most_kg.iter_mut().zip(&t.leg_most_kg) {
            *most = most.max(kg);
        }
    }
}

/// [`check`] for two legs hanging plumb from a beam's pins over the lift
/// points (the module's doc).
fn check_spreader(
    slings: &Slings,
    beam: &Spreader,
    load_kg: f64,
    size_m: [f64; 3],
    cog_m: [f64; 3],
    rigging_height_m: f64,
) -> Result<SlingCheck, String> {
    let pts = &slings.lift_points_m;
    if pts.len() != 2 {
        return Err(format!(
            "a spreader beam (rigging spreader) is checked with two sling legs hanging plumb from its pins: give legs = 2 or two lift_points_m, not {}",
            pts.len()
        ));
    }
    let (a, b) = (pts[0], pts[1]);
    let along = [b[0] - a[0], b[1] - a[1]];
    let span_m = along[0].hypot(along[1]);
    if !(span_m >= 0.1) {
        return Err(format!(
            "the two lift points lie {span_m:.2} m apart in plan: a spreader beam's pins stand over them and must be apart"
        ));
    }
    if beam.length_m + 1e-9 < span_m {
        return Err(format!(
            "the spreader beam, {:.2} m long, is shorter than the {span_m:.2} m between the lift points its legs hang plumb over: give a longer beam (spreader length_m) or lift points nearer together (lift_points_m)",
            beam.length_m
        ));
    }
    let dir = [along[0] / span_m, along[1] / span_m];
    let middle = [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
    let [hx, hy] = [size_m[0] / 2.0, size_m[1] / 2.0];
    for sign in [-1.0, 1.0] {
        let end = [middle[0] + sign * dir[0] * beam.length_m / 2.0, middle[1] + sign * dir[1] * beam.length_m / 2.0];
        if end[0].abs() > hx + 1e-9 || end[1].abs() > hy + 1e-9 {
            return Err(format!(
                "the spreader beam, {:.2} m long and centred over the lift points, reaches ({:.2}, {:.2}) m from the load's centre, beyond its {:.2} x {:.2} m footprint: liftplan keeps the rigging within the load's footprint and does not plan a beam beyond it; give lift points further in (lift_points_m) or a shorter beam",
                beam.length_m, end[0], end[1], size_m[0], size_m[1]
            ));
        }
    }
    let pins_z = size_m[2] / 2.0 + rigging_height_m - beam.below_hook_m;
    let leg_lengths_m = plumb_legs(pts, pins_z, "spreader beam")?;
    // The legs hang plumb: the lever rule along the beam. Off the beam's
    // line the load tilts about it, as it does on two legs to one hook.
    let along_cog = (cog_m[0] - a[0]) * dir[0] + (cog_m[1] - a[1]) * dir[1];
    let t = along_cog / span_m;
    if !(-1e-9..=1.0 + 1e-9).contains(&t) {
        return Err(outside());
    }
    let t = t.clamp(0.0, 1.0);
    let shares = [load_kg * (1.0 - t), load_kg * t];
    let max_leg = if shares[1] > shares[0] { 1 } else { 0 };
    // The load and the beam hang level with the hook over their joint
    // centre of gravity, the beam's at the middle of its pins.
    let total_kg = load_kg + beam.mass_kg;
    let hook_m = (load_kg * t * span_m + beam.mass_kg * span_m / 2.0) / total_kg;
    let top = match beam.top_leg_wll_kg {
        None => None,
        Some(leg_wll_kg) => {
            // The two top legs meet at the hook over the beam, as two legs
            // meet over a load: the same statics.
            let pins = [[a[0], a[1], pins_z], [b[0], b[1], pins_z]];
            let hook = [a[0] + dir[0] * hook_m, a[1] + dir[1] * hook_m];
            let Legs { up, lengths_m, max_angle_deg } = top_legs(hook, &pins, beam.below_hook_m, "beam")?;
            let pulls = two_legs(&pins, &up, total_kg)?;
            Some(TopLegs {
                max_angle_deg,
                max_leg_kg: pulls[0].max(pulls[1]),
                max_leg: if pulls[1] > pulls[0] { 2 } else { 1 },
                leg_wll_kg,
                leg_lengths_m: lengths_m,
                // Their pulls across the beam, equal and opposite.
                compression_kg: pulls[0] * up[0][0].hypot(up[0][1]),
                leg_most_kg: pulls.clone(),
                shackle_wll_kg: beam.top_shackles.as_ref().map(|s| s.wll_kg),
                out_of_line_deg: top_out_of_line_deg(beam.top_shackles.as_ref(), &up),
            })
        }
    };
    Ok(SlingCheck {
        cog_tolerance_m: 0.0,
        cog_tolerance_z_m: 0.0,
        worst_cog_m: None,
        tilt_deg: None,
        side_loading: None,
        legs: 2,
        max_angle_deg: 0.0,
        max_leg_kg: shares[max_leg],
        max_leg: max_leg + 1,
        leg_most_kg: shares.to_vec(),
        ratings: slings.ratings,
        points_given: slings.points_given,
        leg_lengths_m,
        spreader: Some(SpreaderCheck {
            length_m: beam.length_m,
            span_m,
            below_hook_m: beam.below_hook_m,
            carries_kg: load_kg,
            wll_kg: beam.wll_kg,
            hook_from_middle_m: hook_m - span_m / 2.0,
            top,
            width_m: None,
            hook_from_centre_m: None,
        }),
    })
}

/// [`check`] for four legs hanging plumb from a spreader frame's pins over
/// the four lift points. The frame, `length_m` along the load's x and
/// `width_m` along its y, is centred on the lift points, which it must reach
/// over, and lies within the load's footprint as a beam does. Four plumb
/// legs on a rigid load are not determinate: as four legs to a hook, one a
/// little long goes slack and three carry it, each by where the centre of
/// gravity lies in plan in their triangle, so the most over the ways of one
/// slack. The frame carries the load; four top legs, where the lift gives
/// them, carry the load and the frame from its pins to the hook over their
/// joint centre of gravity, checked as four legs to a hook are (any one
/// slack, 60° at most); without them it is a lifting frame hung by a lug,
/// which must be over that centre of gravity (where, is said).
pub fn check_frame(
    slings: &Slings,
    frame: &Spreader,
    load_kg: f64,
    size_m: [f64; 3],
    cog_m: [f64; 3],
    rigging_height_m: f64,
) -> Result<SlingCheck, String> {
    let pts = &slings.lift_points_m;
    if pts.len() != 4 {
        return Err(format!(
            "a spreader frame (rigging spreader with width_m) is checked with four sling legs hanging plumb from its corners: give legs = 4 or four lift_points_m, not {}",
            pts.len()
        ));
    }
    let (length_m, width_m) = (frame.length_m, frame.width_m.unwrap_or(0.0));
    let centre = [pts.iter().map(|p| p[0]).sum::<f64>() / 4.0, pts.iter().map(|p| p[1]).sum::<f64>() / 4.0];
    for (k, p) in pts.iter().enumerate() {
        if (p[0] - centre[0]).abs() > length_m / 2.0 + 1e-9 || (p[1] - centre[1]).abs() > width_m / 2.0 + 1e-9 {
            return Err(format!(
                "the spreader frame, {length_m:.2} x {width_m:.2} m and centred over the lift points, does not reach over lift point {} ({:.2}, {:.2}) m: give a larger frame (spreader length_m along the load's x, width_m along its y) or lift points nearer together",
                k + 1,
                p[0],
                p[1]
            ));
        }
    }
    let [hx, hy] = [size_m[0] / 2.0, size_m[1] / 2.0];
    if centre[0].abs() + length_m / 2.0 > hx + 1e-9 || centre[1].abs() + width_m / 2.0 > hy + 1e-9 {
        return Err(format!(
            "the spreader frame, {length_m:.2} x {width_m:.2} m and centred over the lift points, reaches beyond the load's {:.2} x {:.2} m footprint: liftplan keeps the rigging within the load's footprint and does not plan a frame beyond it; give lift points further in (lift_points_m) or a smaller frame",
            size_m[0], size_m[1]
        ));
    }
    let pins_z = size_m[2] / 2.0 + rigging_height_m - frame.below_hook_m;
    let leg_lengths_m = plumb_legs(pts, pins_z, "spreader frame")?;
    let arm_m = spreader_arm_m(frame, pts, cog_m);
    if !(arm_m > 1e-9) {
        let lowest = pts.iter().map(|p| p[2]).fold(f64::INFINITY, f64::min);
        return Err(format!(
            "the load hangs on plumb legs from a spreader frame {:.2} m below the hook, from lift points as low as z {lowest:.2} m from its box's centre, {:.2} m below its centre of gravity (z {:.2} m): the frame and the load, turning as one about the hook, would turn over (plumb legs keep the load turned as the frame is); give lift points higher on the load (rigging lift_points_m), or hang the frame farther below the hook (spreader below_hook_m, within rigging height_m)",
            frame.below_hook_m,
            cog_m[2] - lowest,
            cog_m[2]
        ));
    }
    // Plumb legs, one slack: the other three share the load as the centre
    // of gravity's place in their triangle in plan has it.
    let plumb = one_slack(|legs| {
        plan_shares(legs.map(|k| [pts[k][0], pts[k][1]]), [cog_m[0], cog_m[1]])
            .map(|shares| shares.map(|share| load_kg * share).to_vec())
    })
    .ok_or_else(outside)?;
    let (max_leg, max_leg_kg) = most_on_one(&plumb);
    let leg_most_kg = most_on_each(&plumb, 4);
    // The hook over the joint centre of gravity of the load and the frame,
    // the frame's at its centre.
    let total_kg = load_kg + frame.mass_kg;
    let joint = [0, 1].map(|a| (load_kg * cog_m[a] + frame.mass_kg * centre[a]) / total_kg);
    let top = match frame.top_leg_wll_kg {
        None => None,
        Some(leg_wll_kg) => {
            let pins: Vec<[f64; 3]> = pts.iter().map(|p| [p[0], p[1], pins_z]).collect();
            let Legs { up, lengths_m, max_angle_deg } = top_legs(joint, &pins, frame.below_hook_m, "frame")?;
            // Four legs to the hook, as four legs to a load's hook are.
            let pulls = one_slack(|legs| three_legs(&up, legs, total_kg)).ok_or_else(outside)?;
            let (most, most_kg) = most_on_one(&pulls);
            let across_kg = pulls.iter().map(|&(k, pull)| pull * up[k][0].hypot(up[k][1])).fold(0.0, f64::max);
            Some(TopLegs {
                max_angle_deg,
                max_leg_kg: most_kg,
                max_leg: most + 1,
                leg_wll_kg,
                leg_lengths_m: lengths_m,
                compression_kg: across_kg,
                leg_most_kg: most_on_each(&pulls, 4),
                shackle_wll_kg: frame.top_shackles.as_ref().map(|s| s.wll_kg),
                out_of_line_deg: top_out_of_line_deg(frame.top_shackles.as_ref(), &up),
            })
        }
    };
    Ok(SlingCheck {
        legs: 4,
        max_angle_deg: 0.0,
        max_leg_kg,
        max_leg: max_leg + 1,
        leg_most_kg,
        ratings: slings.ratings,
        points_given: slings.points_given,
        leg_lengths_m,
        spreader: Some(SpreaderCheck {
            length_m,
            span_m: length_m,
            below_hook_m: frame.below_hook_m,
            carries_kg: load_kg,
            wll_kg: frame.wll_kg,
            hook_from_middle_m: 0.0,
            top,
            width_m: Some(width_m),
            hook_from_centre_m: Some([joint[0] - centre[0], joint[1] - centre[1]]),
        }),
        cog_tolerance_m: 0.0,
        cog_tolerance_z_m: 0.0,
        worst_cog_m: None,
        tilt_deg: None,
        side_loading: None,
    })
}

/// The legs hanging plumb from a spreader's pins, `pins_z` high, down to
/// the lift points `pts`: their lengths (m); or which point is not below
/// the pins. `what`: "spreader beam" or "spreader frame".
fn plumb_legs(pts: &[[f64; 3]], pins_z: f64, what: &str) -> Result<Vec<f64>, String> {
    let mut lengths_m = Vec::with_capacity(pts.len());
    for (k, p) in pts.iter().enumerate() {
        let drop = pins_z - p[2];
        if !(drop > 1e-6) {
            return Err(format!(
                "sling leg {} takes the load at z {:.2} m from its box's centre, not below the {what}'s pins ({pins_z:.2} m: the load's top plus rigging height_m less spreader below_hook_m)",
                k + 1,
                p[2]
            ));
        }
        lengths_m.push(drop);
    }
    Ok(lengths_m)
}

/// A spreader's top legs from its `pins` up to the hook, `below_hook_m`
/// above them over `hook` (plan); refused where the spreader hangs on the
/// hook block itself, or the legs more than [`MAX_LEG_ANGLE_DEG`] from the
/// vertical. `what`: "beam" or "frame".
fn top_legs(hook: [f64; 2], pins: &[[f64; 3]], below_hook_m: f64, what: &str) -> Result<Legs, String> {
    let h = below_hook_m;
    if !(h > 1e-6) {
        return Err(format!(
            "a spreader {what} hung by top legs (spreader top_leg_wll_t) hangs below the hook block: give spreader below_hook_m above zero"
        ));
    }
    let legs = legs_to([hook[0], hook[1], pins[0][2] + h], pins).map_err(|_| outside())?;
    if legs.max_angle_deg > MAX_LEG_ANGLE_DEG + 1e-9 {
        return Err(format!(
            "the spreader {what}'s top legs hang up to {:.1}° from the vertical, more than the {MAX_LEG_ANGLE_DEG:.0}° slings are rated for: hang the {what} lower (spreader below_hook_m {h:.2} m, within rigging height_m)",
            legs.max_angle_deg
        ));
    }
    Ok(legs)
}

/// Four legs, any one of them slack (a leg a little long): each way the
/// other three may carry, with their shares as `shares_of` gives them
/// (`None`: they cannot), as each carrying leg (from 0) and its pull, way
/// after way; `None` where no way can carry it.
fn one_slack(shares_of: impl Fn([usize; 3]) -> Option<Vec<f64>>) -> Option<Vec<(usize, f64)>> {
    let pulls: Vec<(usize, f64)> = [[1, 2, 3], [0, 2, 3], [0, 1, 3], [0, 1, 2]]
        .into_iter()
        .filter_map(|legs| shares_of(legs).map(|shares| legs.into_iter().zip(shares).collect::<Vec<_>>()))
        .flatten()
        .collect();
    (!pulls.is_empty()).then_some(pulls)
}

/// The most each of `legs` legs carries over `pulls` (kg, 0 for a leg that
/// carries in none of them).
fn most_on_each(pulls: &[(usize, f64)], legs: usize) -> Vec<f64> {
    let mut most = vec![0.0; legs];
    for &(k, kg) in pulls {
        if let Some(m) = most.get_mut(k) {
            *m = f64::max(*m, kg);
        }
    }
    most
}

/// The leg (from 0) that carries the most of `pulls`, and what: the first
/// of the most where several carry it.
fn most_on_one(pulls: &[(usize, f64)]) -> (usize, f64) {
    pulls.iter().fold((0, 0.0), |(leg, most), &(k, kg)| if kg > most { (k, kg) } else { (leg, most) })
}

/// The shares of a load on three plumb legs at `pts` (plan) with its
/// centre of gravity at `cog`: its barycentric coordinates in their
/// triangle; `None` where it lies outside it (one share below zero) or the
/// three lie in a line.
fn plan_shares(pts: [[f64; 2]; 3], cog: [f64; 2]) -> Option<[f64; 3]> {
    let shares = barycentric(pts, cog)?;
    shares.iter().all(|&w| w >= -1e-9).then(|| shares.map(|w| w.max(0.0)))
}

/// The barycentric coordinates of `p` in the triangle `pts` (plan),
/// whatever their sign; `None` where the three lie in a line.
fn barycentric(pts: [[f64; 2]; 3], p: [f64; 2]) -> Option<[f64; 3]> {
    let [a, b, c] = pts;
    let det = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
    if det.abs() < 1e-9 {
        return None;
    }
    let wb = ((p[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (p[1] - a[1])) / det;
    let wc = ((b[0] - a[0]) * (p[1] - a[1]) - (p[0] - a[0]) * (b[1] - a[1])) / det;
    Some([1.0 - wb - wc, wb, wc])
}

/// Legs from their points up to a hook ([`legs_to`]).
struct Legs {
    /// Each one's unit vector from its point to the hook.
    up: Vec<[f64; 3]>,
    lengths_m: Vec<f64>,
    /// The steepest one's angle from the vertical (degrees).
    max_angle_deg: f64,
}

/// The legs from `points` up to `hook`; or which point (from 0) is not
/// below the hook.
fn legs_to(hook: [f64; 3], points: &[[f64; 3]]) -> Result<Legs, usize> {
    let mut legs = Legs { up: Vec::with_capacity(points.len()), lengths_m: Vec::new(), max_angle_deg: 0.0 };
    for (k, p) in points.iter().enumerate() {
        let d = [hook[0] - p[0], hook[1] - p[1], hook[2] - p[2]];
        if !(d[2] > 1e-6) {
            return Err(k);
        }
        let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        legs.max_angle_deg = legs.max_angle_deg.max(d[0].hypot(d[1]).atan2(d[2]).to_degrees());
        legs.up.push(d.map(|v| v / len));
        legs.lengths_m.push(len);
    }
    Ok(legs)
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
    use nalgebra as na;

    fn slings(legs: usize, size_m: [f64; 3]) -> Slings {
        Slings {
            lift_points_m: default_points(legs, size_m).unwrap(),
            points_given: false,
            ratings: Ratings::legs(8000.0),
            spreader: None,
            pin_axes: None,
        }
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
            ratings: Ratings::legs(9000.0),
            spreader: None,
            pin_axes: None,
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
        let high = Slings {
            lift_points_m: vec![[0.0, 0.0, 9.0]],
            points_given: true,
            ratings: Ratings::legs(1.0),
            spreader: None,
            pin_axes: None,
        };
        assert!(check(&high, 1.0, size, [0.0; 3], 3.0).unwrap_err().contains("not below the hook block"));
        // One leg: the whole load, whatever its angle.
        let one = check(&slings(1, size), 12_000.0, size, [0.3, 0.0, 0.0], 3.0).unwrap();
        assert_eq!((one.max_leg_kg, one.max_angle_deg), (12_000.0, 0.0));
        assert!(one.said().starts_with("1 leg at the top's centre"), "{}", one.said());
    }

    fn beam(top_leg_wll_kg: Option<f64>) -> Spreader {
        Spreader {
            length_m: 6.4,
            below_hook_m: 2.0,
            wll_kg: 20_000.0,
            mass_kg: 600.0,
            top_leg_wll_kg,
            width_m: None,
            top_shackles: None,
        }
    }

    /// Lift points 6 m apart on a 7 m load, 4 m of rigging: legs plumb
    /// from pins 2 m under the hook, 2 m long to the top; each carries half.
    /// The top legs carry load and beam by their angle (atan(3 / 2)), and
    /// press the beam with their pull across.
    #[test]
    fn a_spreader_beam_hangs_its_legs_plumb_and_its_top_legs_carry_it() {
        let size = [7.0, 2.0, 2.0];
        let mut s = Slings {
            lift_points_m: vec![[-3.0, 0.0, 1.0], [3.0, 0.0, 1.0]],
            points_given: true,
            ratings: Ratings::legs(8000.0),
            spreader: Some(beam(Some(12_000.0))),
            pin_axes: None,
        };
        let c = check(&s, 12_000.0, size, [0.0; 3], 4.0).unwrap();
        assert_eq!((c.max_angle_deg, c.max_leg_kg, c.leg_lengths_m.clone()), (0.0, 6000.0, vec![2.0, 2.0]));
        let b = c.spreader.clone().unwrap();
        assert_eq!((b.span_m, b.carries_kg, b.hook_from_middle_m), (6.0, 12_000.0, 0.0));
        let t = b.top.clone().unwrap();
        let (len, cos) = (13.0f64.sqrt(), 2.0 / 13.0f64.sqrt());
        assert!((t.max_leg_kg - 6300.0 / cos).abs() < 1e-6, "{t:?}");
        assert!((t.compression_kg - 6300.0 * 1.5).abs() < 1e-6 && t.leg_lengths_m == [len, len], "{t:?}");
        assert!((t.max_angle_deg - 1.5f64.atan().to_degrees()).abs() < 1e-9);
        assert_eq!(c.over_limit(), None);
        let said = c.said();
        for part in [
            "2 legs at the lift points given (rigging lift_points_m), hanging plumb from a spreader beam: the most on one leg (leg 1) 6.00 t",
            "legs 2.00 and 2.00 m long from lift point to pin; the beam 6.40 m long, its pins 6.00 m apart and 2.00 m below the hook block, carries 12.00 t of its 20.00 t working load limit: 60 %",
            "hung from the hook by 2 top legs up to 56.3° from the vertical",
            "top legs 3.61 and 3.61 m long from pin to hook",
            "pressing the beam with 9.45 t (93 kN)",
        ] {
            assert!(said.contains(part), "{part}\n{said}");
        }
        // Over the limits: each named, with what to give.
        s.ratings.leg_wll_kg = 5000.0;
        s.spreader.as_mut().unwrap().wll_kg = 10_000.0;
        s.spreader.as_mut().unwrap().top_leg_wll_kg = Some(7000.0);
        let over = check(&s, 12_000.0, size, [0.0; 3], 4.0).unwrap().over_limit().unwrap();
        for part in [
            "the sling legs and the spreader beam and the spreader's top legs cannot carry the load: 2 legs",
            "; give legs of a higher working load limit (rigging leg_wll_t); give a beam",
            "(spreader wll_t); give top legs of a higher working load limit (spreader top_leg_wll_t) or hang",
        ] {
            assert!(over.contains(part), "{part}: {over}");
        }
    }

    /// The centre of gravity 1 m towards the second point: the legs share
    /// the load by the lever rule; the hook hangs over the load's and the
    /// beam's joint centre of gravity, where the top legs' pulls balance
    /// across and carry both up.
    #[test]
    fn an_off_centre_load_hangs_from_the_beam_by_the_lever_rule() {
        let s = Slings {
            lift_points_m: default_points(2, [6.0, 2.0, 2.0]).unwrap(),
            points_given: false,
            ratings: Ratings::legs(8000.0),
            spreader: Some(Spreader { length_m: 6.0, below_hook_m: 3.0, ..beam(Some(12_000.0)) }),
            pin_axes: None,
        };
        let c = check(&s, 12_000.0, [6.0, 2.0, 2.0], [1.0, 0.0, 0.0], 5.0).unwrap();
        assert_eq!(c.max_leg, 2);
        assert!((c.max_leg_kg - 12_000.0 * 4.0 / 6.0).abs() < 1e-9, "{c:?}");
        let b = c.spreader.clone().unwrap();
        // (12 t at 1 m, 0.6 t at 0 m) from the pins' middle.
        let hook = 12_000.0 / 12_600.0;
        assert!((b.hook_from_middle_m - hook).abs() < 1e-12, "{b:?}");
        let t = b.top.unwrap();
        let runs = [3.0 + hook, 3.0 - hook];
        let (sin, cos) = (runs.map(|r| r / r.hypot(3.0)), runs.map(|r| 3.0 / r.hypot(3.0)));
        // The leg with the shorter run, over the second pin, carries more.
        let pull2 = t.max_leg_kg;
        let pull1 = pull2 * sin[1] / sin[0];
        assert_eq!(t.max_leg, 2);
        assert!((pull1 * cos[0] + pull2 * cos[1] - 12_600.0).abs() < 1e-6, "{t:?}");
        assert!((t.compression_kg - pull1 * sin[0]).abs() < 1e-6);
        assert!(
            c.said().starts_with("2 legs at the middles of the top's short edges, hanging plumb from a spreader beam")
        );
    }

    /// A lifting beam (no top legs) hangs by its lug, which must be over
    /// the centre of gravity: where that is, is said.
    #[test]
    fn a_lifting_beam_says_where_its_lug_must_be() {
        let s = Slings {
            lift_points_m: vec![[-3.0, 0.0, 1.0], [3.0, 0.0, 1.0]],
            points_given: true,
            ratings: Ratings::legs(8000.0),
            spreader: Some(Spreader { mass_kg: 0.0, ..beam(None) }),
            pin_axes: None,
        };
        let c = check(&s, 12_000.0, [7.0, 2.0, 2.0], [-0.5, 0.3, 0.0], 4.0).unwrap();
        let b = c.spreader.clone().unwrap();
        assert!(b.top.is_none() && (b.hook_from_middle_m + 0.5).abs() < 1e-12, "{b:?}");
        assert!(
            c.said().ends_with("hung from the hook by its lug, which must be over the centre of gravity, 0.50 m from the pins' middle towards leg 1 (a lug elsewhere tilts the beam)"),
            "{}",
            c.said()
        );
    }

    /// What a beam cannot be is refused, saying what to change.
    #[test]
    fn what_a_spreader_cannot_be_is_refused() {
        let size = [7.0, 2.0, 2.0];
        let two = vec![[-3.0, 0.0, 1.0], [3.0, 0.0, 1.0]];
        let refused = |points: Vec<[f64; 3]>, b: Spreader, height_m: f64| {
            let s = Slings {
                lift_points_m: points,
                points_given: true,
                ratings: Ratings::legs(8000.0),
                spreader: Some(b),
                pin_axes: None,
            };
            check(&s, 12_000.0, size, [0.0; 3], height_m).unwrap_err()
        };
        let four = default_points(4, size).unwrap();
        assert!(refused(four, beam(None), 4.0).contains("give legs = 2 or two lift_points_m, not 4"));
        let short = Spreader { length_m: 5.0, ..beam(None) };
        assert!(refused(two.clone(), short, 4.0).contains("5.00 m long, is shorter than the 6.00 m"));
        let long = Spreader { length_m: 7.2, ..beam(None) };
        assert!(
            refused(two.clone(), long, 4.0)
                .contains("reaches (-3.60, 0.00) m from the load's centre, beyond its 7.00 x 2.00 m footprint")
        );
        let low = Spreader { below_hook_m: 4.5, ..beam(None) };
        assert!(refused(two.clone(), low, 4.0).contains("not below the spreader beam's pins"));
        let flat = Spreader { below_hook_m: 1.5, ..beam(Some(9000.0)) };
        assert!(refused(two.clone(), flat, 4.0).contains("top legs hang up to 63.4° from the vertical"));
        let on_hook = Spreader { below_hook_m: 0.0, ..beam(Some(9000.0)) };
        assert!(refused(two.clone(), on_hook, 4.0).contains("give spreader below_hook_m above zero"));
        let s = Slings {
            lift_points_m: two,
            points_given: true,
            ratings: Ratings::legs(8000.0),
            spreader: Some(beam(None)),
            pin_axes: None,
        };
        assert!(
            check(&s, 12_000.0, size, [3.5, 0.0, 0.0], 4.0)
                .unwrap_err()
                .contains("outside the sling legs' lift points")
        );
    }

    /// Legs choked round the load may carry 0.8 of their straight pull;
    /// the shackle at each lift point carries its leg's pull. Each over its
    /// limit is named with what to give.
    #[test]
    fn choked_legs_and_shackles_are_checked_against_their_limits() {
        let size = [8.0, 3.0, 2.0];
        let straight = check(&slings(2, size), 12_000.0, size, [0.0; 3], 3.0).unwrap();
        let most = straight.max_leg_kg; // 10 t: 6 t at atan(4 / 3)
        assert!((most - 10_000.0).abs() < 1e-9 && straight.over_limit().is_some());
        let mut s = slings(2, size);
        s.ratings.leg_wll_kg = 12_000.0;
        assert_eq!(check(&s, 12_000.0, size, [0.0; 3], 3.0).unwrap().over_limit(), None);
        s.ratings.choked = true;
        let choked = check(&s, 12_000.0, size, [0.0; 3], 3.0).unwrap();
        assert_eq!(choked.max_leg_kg, most, "choking changes the limit, not the pull");
        assert!((choked.leg_limit_kg() - 9600.0).abs() < 1e-9);
        let said = choked.said();
        assert!(
            said.starts_with("2 legs at the middles of the top's short edges choked round the load, up to 53.1° from the vertical; the most on one leg (leg 1) 10.00 t (98 kN) of its 9.60 t working load limit choked (12.00 t in a straight pull, x 0.8): 104 %;"),
            "{said}"
        );
        let over = choked.over_limit().unwrap();
        assert!(
            over.starts_with("the sling legs cannot carry the load: 2 legs") && over.contains("(rigging leg_wll_t)"),
            "{over}"
        );
        s.ratings.choked = false;
        s.ratings.shackle_wll_kg = Some(9500.0);
        let shackled = check(&s, 12_000.0, size, [0.0; 3], 3.0).unwrap();
        assert!(
            shackled.said().contains(
                "of its 12.00 t working load limit: 83 %, and of its lift point's shackle's 9.50 t (in line): 105 %;"
            ),
            "{}",
            shackled.said()
        );
        let over = shackled.over_limit().unwrap();
        assert!(
            over.starts_with("the lift points' shackles cannot carry the load:")
                && over.ends_with("; give shackles of a higher working load limit (rigging shackle_wll_t)"),
            "{over}"
        );
        s.ratings.shackle_wll_kg = Some(10_000.0);
        assert_eq!(
            check(&s, 12_000.0, size, [0.0; 3], 3.0).unwrap().over_limit(),
            None,
            "a shackle at its limit holds"
        );
        // A lift point (lug) rated for less than its leg's pull.
        s.ratings.lift_point_wll_kg = Some(9000.0);
        let lugged = check(&s, 12_000.0, size, [0.0; 3], 3.0).unwrap();
        assert!(
            lugged.said().contains(
                "of its lift point's shackle's 10.00 t (in line): 100 %, and of the lift point's own 9.00 t: 111 %;"
            ),
            "{}",
            lugged.said()
        );
        let over = lugged.over_limit().unwrap();
        assert!(
            over.starts_with("the lift points cannot carry the load:")
                && over.ends_with(
                    "; give lift points of a higher working load limit (rigging lift_point_wll_t) or more legs"
                ),
            "{over}"
        );
    }

    /// A centre of gravity known to 1 m either way along x and y: the most
    /// on a leg is the worst over that square, at a corner (1 m along and
    /// 1 m off the legs' line), by the statics by hand; no finer sampling
    /// finds more; the lengths stay those for the centre of gravity given.
    #[test]
    fn a_centre_of_gravity_known_only_so_well_is_checked_at_its_worst() {
        let size = [8.0, 3.0, 2.0];
        let legs = slings(2, size);
        let given = check(&legs, 12_000.0, size, [0.0; 3], 3.0).unwrap();
        assert_eq!(check_within(&legs, 12_000.0, size, [0.0; 3], 0.0, 3.0).unwrap(), given);
        let c = check_within(&legs, 12_000.0, size, [0.0; 3], 1.0, 3.0).unwrap();
        // The near leg 3 m along and 1 m across from the hook, the far one
        // 5 m along and 1 m across, both 3 m down.
        let (far, near) = ((25.0f64 + 1.0 + 9.0).sqrt(), (9.0f64 + 1.0 + 9.0).sqrt());
        let (s_far, c_far, s_near, c_near) = (5.0 / far, 3.0 / far, 3.0 / near, 3.0 / near);
        let t_near = 12_000.0 * s_far / (s_near * c_far + s_far * c_near);
        assert!((c.max_leg_kg - t_near).abs() < 1e-6, "{c:?} {t_near}");
        assert!(c.max_leg_kg > given.max_leg_kg);
        let [x, y] = c.worst_cog_m.unwrap();
        assert!((x.abs() - 1.0).abs() < 1e-12 && (y.abs() - 1.0).abs() < 1e-12, "{x} {y}");
        assert_eq!(c.leg_lengths_m, given.leg_lengths_m);
        // On legs made for the middle, the load turns about the line through
        // its lift points (1 m above its centre of gravity) until its centre
        // of gravity is under it: √2 m off in plan, at most 54.7°.
        assert!((c.tilt_deg.unwrap() - 2.0f64.sqrt().atan().to_degrees()).abs() < 1e-9, "{:?}", c.tilt_deg);
        assert_eq!(given.tilt_deg, None);
        assert!(c.said().contains(": on two legs a load whose centre of gravity lies off hangs up to 54.7° off level; along the line through its lift points the legs' lengths set it level, across it no length does (it hangs with its centre of gravity under that line): at the trial lift, set the legs for it to hang level along the line and CHECK that it hangs level across it"), "{}", c.said());
        let finest = (0..41 * 41)
            .map(|n| [-1.0 + (n % 41) as f64 * 0.05, -1.0 + (n / 41) as f64 * 0.05, 0.0])
            .map(|cog| check(&legs, 12_000.0, size, cog, 3.0).unwrap())
            .fold(0.0f64, |m, c| m.max(c.max_leg_kg));
        assert!(finest <= c.max_leg_kg + 1e-9, "{finest} {}", c.max_leg_kg);
        assert!(c.said().contains("the worst with the centre of gravity within 1.00 m along x and y (load cog_tolerance_m, the worst over that square worked out; the most on a leg with it at ("), "{}", c.said());
        // Lift points 2 m apart with the centre of gravity 0.9 m along: known
        // to 0.2 m, it may lie beyond them.
        let close =
            Slings { lift_points_m: vec![[-1.0, 0.0, 1.0], [1.0, 0.0, 1.0]], points_given: true, ..legs.clone() };
        assert!(check_within(&close, 12_000.0, size, [0.9, 0.0, 0.0], 0.05, 3.0).is_ok());
        let e = check_within(&close, 12_000.0, size, [0.9, 0.0, 0.0], 0.2, 3.0).unwrap_err();
        assert!(
            e.starts_with("with the load's centre of gravity at (1.05, -0.20) m from its box's centre, within load cog_tolerance_m (0.20 m) of the given one: the load's centre of gravity (cog_m) lies outside"),
            "{e}"
        );
        // A spreader beam's top legs: the worst over the square too.
        // Pins 6 m apart, the load's share by the lever rule: 3.2 of 6 m.
        let on_beam = Slings {
            lift_points_m: vec![[-3.0, 0.0, 1.0], [3.0, 0.0, 1.0]],
            points_given: true,
            spreader: Some(beam(Some(10_000.0))),
            ..legs.clone()
        };
        let size = [7.0, 2.0, 2.0];
        let level = check(&on_beam, 12_000.0, size, [0.0; 3], 4.0).unwrap();
        let off = check_within(&on_beam, 12_000.0, size, [0.0; 3], 0.2, 4.0).unwrap();
        let (level_top, off_top) = (level.spreader.unwrap().top.unwrap(), off.spreader.unwrap().top.unwrap());
        assert!(off_top.max_leg_kg > level_top.max_leg_kg, "{off_top:?} {level_top:?}");
        assert!((off.max_leg_kg - 12_000.0 * 3.2 / 6.0).abs() < 1e-6, "{}", off.max_leg_kg);
    }

    /// One or two legs hang the load from its lift points' line: one at or
    /// below the centre of gravity is refused (the load would turn over);
    /// three or four hang it from the hook, above it, whatever their points.
    #[test]
    fn a_load_below_its_lift_points_line_turns_over() {
        let size = [8.0, 3.0, 2.0];
        let at = |z: f64, legs: usize| Slings {
            lift_points_m: default_points(legs, size).unwrap().into_iter().map(|p| [p[0], p[1], z]).collect(),
            points_given: true,
            ratings: Ratings::legs(20_000.0),
            spreader: None,
            pin_axes: None,
        };
        // Trunnions at mid-height, the centre of gravity 0.1 m below: fine.
        assert!(check(&at(0.0, 2), 12_000.0, size, [0.0, 0.0, -0.1], 4.0).is_ok());
        let e = check(&at(0.0, 2), 12_000.0, size, [0.0, 0.0, 0.0], 4.0).unwrap_err();
        assert!(e.starts_with("the load hangs on 2 legs from lift points as low as z 0.00 m from its box's centre, not above its centre of gravity (z 0.00 m): it would turn over"), "{e}");
        assert!(check(&at(-0.5, 1), 12_000.0, size, [0.0; 3], 4.0).unwrap_err().contains("on 1 leg from"));
        assert!(check(&at(-0.5, 4), 12_000.0, size, [0.0; 3], 4.0).is_ok());
        // The tilt's bound over the hook's height on four legs.
        let four = check_within(&at(-0.5, 4), 12_000.0, size, [0.0; 3], 0.2, 4.0).unwrap();
        assert!((four.tilt_deg.unwrap() - (0.2 * 2.0f64.sqrt()).atan2(5.0).to_degrees()).abs() < 1e-9);
    }

    /// The turning points of a leg's pull along a line: two legs 10 m apart
    /// at one height, the hook 3 m above them and 0.5 m off their line, the
    /// near leg's pull W (n - s) √(s² + k²) / (n v) (s along the line from
    /// it, k² = 0.5² + 3²) is most at s = (n + √(n² - 8k²)) / 4 and least
    /// at (n - √(n² - 8k²)) / 4, by hand; both found, to the rounding.
    #[test]
    fn a_leg_s_pull_turns_where_its_cubic_says() {
        let set = LegsToOneHook {
            points: vec![[-5.0, 0.0, 1.0], [5.0, 0.0, 1.0]],
            hook_z: 4.0,
            load_share: 1.0,
            own_centre: [0.0; 2],
            onto_line: None,
            across: false,
        };
        let (n, k2) = (10.0f64, 0.25 + 9.0);
        let (most, least) = ((n + (n * n - 8.0 * k2).sqrt()) / 4.0, (n - (n * n - 8.0 * k2).sqrt()) / 4.0);
        // Along the line 0.5 m off, from 0.5 m to 9.5 m from the first point.
        let found: Vec<f64> =
            pull_turning_points(&set, [-4.5, 0.5], [4.5, 0.5]).into_iter().map(|s| 0.5 + 9.0 * s).collect();
        for want in [most, least, n - most, n - least] {
            assert!(found.iter().any(|s| (s - want).abs() < 1e-9), "{want}: {found:?}");
        }
        let pull = |s: f64| (n - s) * (s * s + k2).sqrt();
        assert!(pull(most) > pull(most - 1e-3) && pull(most) > pull(most + 1e-3));
        // A cubic's roots within 0 and 1, and none of one that only touches 0.
        let roots = roots_within_0_1(&[-0.042, 0.41, -1.2, 1.0]);
        assert_eq!(roots.len(), 3, "{roots:?}");
        for (r, want) in roots.iter().zip([0.2, 0.3, 0.7]) {
            assert!((r - want).abs() < 1e-12, "{roots:?}");
        }
        assert!(roots_within_0_1(&[0.3, -1.0, 1.0, 0.0]).is_empty());
        assert!(roots_within_0_1(&[0.0; 4]).is_empty());
    }

    /// Over random riggings (two, three and four legs to the hook, their
    /// lift points at different heights; spreader beams and frames with top
    /// legs), no place of a 101 x 101 grid over the tolerance's square, nor
    /// of 2001 along each of its edges, finds more on a leg, on a top leg,
    /// across the top legs, or a steeper leg, than [`check_within`] does;
    /// and where the legs cannot carry the load at a place of the grid, it
    /// refuses.
    #[test]
    fn no_place_finds_more_than_the_worst_worked_out() {
        let mut rng = crate::rng::seeded(56, "random riggings");
        let mut unit = move || crate::rng::unit(&mut rng);
        let mut checked = [0usize; 5];
        for case in 0..60 {
            let kind = case % 5;
            let (cx, cy) = (unit() - 0.5, unit() - 0.5);
            let size = [12.0, 8.0, 3.0];
            let tol = 0.05 + 0.45 * unit();
            let h = 2.0 + 4.0 * unit();
            let around = |k: usize, n: usize, turn: f64, r: f64, z: f64| {
                let a = turn + std::f64::consts::TAU * k as f64 / n as f64;
                [cx + r * a.cos(), cy + r * a.sin(), z]
            };
            let turn = std::f64::consts::TAU * unit();
            let (points, spreader) = match kind {
                // Either side of the centre of gravity on a line through it.
                0 => (
                    vec![
                        around(0, 2, turn, 1.0 + 3.0 * unit(), 0.3 + unit()),
                        around(1, 2, turn, 1.0 + 3.0 * unit(), 0.3 + unit()),
                    ],
                    None,
                ),
                1 | 2 => {
                    let n = kind + 2;
                    (
                        (0..n)
                            .map(|k| around(k, n, turn + 0.5 * (unit() - 0.5), 1.0 + 3.0 * unit(), 1.5 * unit() - 0.2))
                            .collect(),
                        None,
                    )
                }
                3 => {
                    let half = 1.0 + 2.0 * unit();
                    let pts = vec![[cx - half, cy, 0.5 + unit()], [cx + half, cy, 0.5 + unit()]];
                    let beam = Spreader {
                        length_m: 2.0 * half + 0.2,
                        below_hook_m: 1.0 + unit(),
                        wll_kg: 50_000.0,
                        mass_kg: 2000.0 * unit(),
                        top_leg_wll_kg: Some(50_000.0),
                        width_m: None,
                        top_shackles: None,
                    };
                    (pts, Some(beam))
                }
                _ => {
                    let (l, w) = (2.0 + 2.0 * unit(), 1.5 + unit());
                    let pts: Vec<[f64; 3]> = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]]
                        .iter()
                        .map(|[sx, sy]| [cx + sx * (l / 2.0 - 0.3 * unit()), cy + sy * (w / 2.0 - 0.3 * unit()), 1.0])
                        .collect();
                    let frame = Spreader {
                        length_m: l + 1.0,
                        below_hook_m: 1.0 + unit(),
                        wll_kg: 50_000.0,
                        mass_kg: 2000.0 * unit(),
                        top_leg_wll_kg: Some(50_000.0),
                        width_m: Some(w + 1.0),
                        top_shackles: None,
                    };
                    (pts, Some(frame))
                }
            };
            let legs = Slings {
                lift_points_m: points,
                points_given: true,
                ratings: Ratings::legs(50_000.0),
                spreader,
                pin_axes: None,
            };
            let (load_kg, cog) = (10_000.0, [cx, cy, -0.5]);
            let found = check_within(&legs, load_kg, size, cog, tol, h);
            let n = 101;
            let across = |k: usize, n: usize| -tol + 2.0 * tol * k as f64 / (n - 1) as f64;
            let grid = (0..n * n).map(|k| [cx + across(k % n, n), cy + across(k / n, n)]);
            let edges = (0..4 * 2001).map(|k| {
                let t = across(k % 2001, 2001);
                [[cx + t, cy - tol], [cx + t, cy + tol], [cx - tol, cy + t], [cx + tol, cy + t]][k / 2001]
            });
            let places: Vec<[f64; 2]> = grid.chain(edges).collect();
            let Ok(c) = found else {
                continue;
            };
            checked[kind] += 1;
            let eps = 1e-9 * load_kg;
            let top = |c: &SlingCheck| c.spreader.as_ref().and_then(|s| s.top.clone());
            for [x, y] in places {
                let at = check(&legs, load_kg, size, [x, y, cog[2]], h)
                    .unwrap_or_else(|e| panic!("case {case}: ({x}, {y}) refused, the check was not: {e}"));
                let what = || format!("case {case} at ({x}, {y}): {at:?} against {c:?}");
                assert!(
                    at.max_leg_kg <= c.max_leg_kg + eps && at.max_angle_deg <= c.max_angle_deg + 1e-9,
                    "{}",
                    what()
                );
                for (kg, most) in at.leg_most_kg.iter().zip(&c.leg_most_kg) {
                    assert!(*kg <= most + eps, "{}", what());
                }
                if let (Some(t), Some(worst)) = (top(&at), top(&c)) {
                    assert!(t.max_leg_kg <= worst.max_leg_kg + eps, "{}", what());
                    assert!(t.compression_kg <= worst.compression_kg + eps, "{}", what());
                    assert!(t.max_angle_deg <= worst.max_angle_deg + 1e-9, "{}", what());
                    for (kg, most) in t.leg_most_kg.iter().zip(&worst.leg_most_kg) {
                        assert!(*kg <= most + eps, "{}", what());
                    }
                }
            }
        }
        assert!(checked.iter().all(|&n| n >= 6), "riggings checked of each kind: {checked:?}");
    }

    /// On four legs with one slack, the most on a leg is not at a corner of
    /// the tolerance's square but where an edge crosses a diagonal between
    /// lift points; on three legs, between places too. Over loads, heights
    /// and tolerances (and a centre of gravity off the middle), no place of
    /// a 101 x 101 grid over the square finds more than the check does, on
    /// a leg or on a spreader's top leg.
    #[test]
    fn no_finer_sampling_finds_more_on_a_leg() {
        let on_frame = Slings {
            lift_points_m: vec![[-3.0, -1.0, 1.0], [3.0, -1.0, 1.0], [3.0, 1.0, 1.0], [-3.0, 1.0, 1.0]],
            points_given: true,
            ratings: Ratings::legs(9000.0),
            spreader: Some(Spreader { below_hook_m: 3.0, ..frame(Some(12_000.0)) }),
            pin_axes: None,
        };
        let on_beam = Slings {
            lift_points_m: vec![[-3.0, 0.0, 1.0], [3.0, 0.0, 1.0]],
            spreader: Some(Spreader { below_hook_m: 3.0, ..beam(Some(12_000.0)) }),
            ..on_frame.clone()
        };
        let three = Slings {
            lift_points_m: vec![[-2.0, -1.0, 1.0], [2.5, -0.5, 1.0], [0.0, 1.0, 1.0]],
            points_given: true,
            ratings: Ratings::legs(8000.0),
            spreader: None,
            pin_axes: None,
        };
        let cases = [
            (slings(4, [4.0, 2.0, 2.0]), [4.0, 2.0, 2.0], [0.0; 3], 0.2, 3.0),
            (slings(4, [6.0, 4.0, 2.0]), [6.0, 4.0, 2.0], [0.0; 3], 0.5, 3.0),
            (slings(4, [8.0, 3.0, 3.0]), [8.0, 3.0, 3.0], [0.6, -0.3, 0.0], 0.3, 4.0),
            (slings(4, [5.0, 2.0, 3.0]), [5.0, 2.0, 3.0], [0.0; 3], 0.5, 2.0),
            (slings(2, [8.0, 3.0, 3.0]), [8.0, 3.0, 3.0], [0.2, 0.0, 0.0], 0.5, 4.0),
            (three, [6.0, 3.0, 2.0], [0.1, -0.1, 0.0], 0.3, 3.0),
            (on_frame, [7.0, 3.0, 2.0], [0.3, 0.1, 0.0], 0.3, 4.5),
            // (On the beam's line: off it, two legs hang the load turned.)
            (on_beam, [7.0, 3.0, 2.0], [0.3, 0.0, 0.0], 0.3, 4.5),
        ];
        let top = |c: &SlingCheck| c.spreader.as_ref().and_then(|s| s.top.as_ref()).map_or(0.0, |t| t.max_leg_kg);
        for (legs, size, cog, tol, h) in cases {
            let c = check_within(&legs, 5000.0, size, cog, tol, h).unwrap();
            let n = 101;
            let across = |k: usize| -tol + 2.0 * tol * k as f64 / (n - 1) as f64;
            let mut finest_each = vec![0.0f64; legs.lift_points_m.len()];
            let mut finest_each_top = vec![0.0f64; legs.lift_points_m.len()];
            let top_each = |c: &SlingCheck| {
                c.spreader.as_ref().and_then(|s| s.top.as_ref()).map(|t| t.leg_most_kg.clone()).unwrap_or_default()
            };
            let (finest, finest_top) = (0..n * n)
                .map(|k| [cog[0] + across(k % n), cog[1] + across(k / n), cog[2]])
                .map(|at| check(&legs, 5000.0, size, at, h).unwrap())
                .inspect(|c| {
                    finest_each.iter_mut().zip(&c.leg_most_kg).for_each(|(m, kg)| *m = m.max(*kg));
                    finest_each_top.iter_mut().zip(&top_each(c)).for_each(|(m, kg)| *m = m.max(*kg));
                })
                .fold((0.0f64, 0.0f64), |(m, t), c| (m.max(c.max_leg_kg), t.max(top(&c))));
            for (k, (fine, found)) in finest_each.iter().zip(&c.leg_most_kg).enumerate() {
                assert!(*fine <= found + 1e-9, "{size:?}: leg {k}: {fine} more than {found}");
            }
            for (k, (fine, found)) in finest_each_top.iter().zip(&top_each(&c)).enumerate() {
                assert!(*fine <= found + 1e-9, "{size:?}: top leg {k}: {fine} more than {found}");
            }
            assert_eq!(top_each(&c).len(), if top(&c) > 0.0 { legs.lift_points_m.len() } else { 0 });
            assert!(
                (c.leg_most_kg.iter().fold(0.0f64, |m, kg| m.max(*kg)) - c.max_leg_kg).abs() < 1e-9,
                "{:?} {}",
                c.leg_most_kg,
                c.max_leg_kg
            );
            assert!(
                finest <= c.max_leg_kg + 1e-9,
                "{size:?}: {finest} more than {} at {:?}",
                c.max_leg_kg,
                c.worst_cog_m
            );
            assert!(finest_top <= top(&c) + 1e-9, "{size:?}: a top leg {finest_top} more than {}", top(&c));
        }
    }

    fn frame(top_leg_wll_kg: Option<f64>) -> Spreader {
        Spreader {
            length_m: 6.0,
            below_hook_m: 2.0,
            wll_kg: 20_000.0,
            mass_kg: 600.0,
            top_leg_wll_kg,
            width_m: Some(2.0),
            top_shackles: None,
        }
    }

    /// A 6 x 2 m frame over the corners of a 6 x 2 m rectangle on a 7 m
    /// load, 4 m of rigging: legs plumb from pins 2 m under the hook, 2 m
    /// long. Centred, one leg slack leaves the two diagonal legs each half;
    /// the top legs (√10 m across, 2 m up) carry load and frame the same
    /// way. Off centre (1, 0.5), the worst way of one slack gives the third
    /// corner two thirds, by the triangle's coordinates by hand.
    /// The shackles at a spreader's top lugs: in line, against each top
    /// leg's most; with their pins given, each at the makers' share for its
    /// top leg's angle out of line as rigged, by hand: a frame's top leg
    /// from (3, -1) to the hook 2 m over the centre runs along (-3, 1, 2)/√14,
    /// square to a pin along (1, 3, 0), 53.3° out of line with one along x
    /// and 32.3° with one standing upright. A centre of gravity's tolerance
    /// changes the most on each, not the angles (the top legs and the frame
    /// hang as one piece).
    #[test]
    fn a_spreader_s_top_shackles_are_checked_in_line_and_for_side_loading() {
        let size = [7.0, 3.0, 2.0];
        let shackled = |wll_kg: f64, pin_axes: Option<Vec<[f64; 3]>>| Slings {
            lift_points_m: vec![[-3.0, -1.0, 1.0], [3.0, -1.0, 1.0], [3.0, 1.0, 1.0], [-3.0, 1.0, 1.0]],
            points_given: true,
            ratings: Ratings::legs(9000.0),
            spreader: Some(Spreader { top_shackles: Some(TopShackles { wll_kg, pin_axes }), ..frame(Some(12_000.0)) }),
            pin_axes: None,
        };
        // Each top leg carries up to 6.3 t up, along legs at cos 2/√14.
        let most_kg = 6300.0 * 14.0f64.sqrt() / 2.0;
        let c = check(&shackled(15_000.0, None), 12_000.0, size, [0.0; 3], 4.0).unwrap();
        let t = c.spreader.as_ref().unwrap().top.clone().unwrap();
        let (leg, carries_kg, limit_kg) = t.shackle_most_used().unwrap();
        assert!((carries_kg - most_kg).abs() < 1e-6 && limit_kg == 15_000.0 && leg == 0, "{t:?}");
        assert!(t.out_of_line_deg.is_empty());
        let said = c.said();
        assert!(said.contains(" working load limit: 98 %; of the top legs' shackles' 15.00 t at the spreader's lugs (in line): 79 %; top legs "), "{said}");
        assert_eq!(c.over_limit(), None);
        // Pins given: top leg 2's along x, 53.3° out of line, 66 % of 15 t.
        let unit = |v: [f64; 3]| {
            let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
            v.map(|x| x / n)
        };
        let pins = vec![unit([1.0, -3.0, 0.0]), [1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 0.0, 1.0]];
        let c = check(&shackled(15_000.0, Some(pins.clone())), 12_000.0, size, [0.0; 3], 4.0).unwrap();
        let t = c.spreader.as_ref().unwrap().top.clone().unwrap();
        let along_x = (3.0 / 14.0f64.sqrt()).asin().to_degrees();
        let upright = (2.0 / 14.0f64.sqrt()).asin().to_degrees();
        let want = [0.0, along_x, upright, upright];
        assert!(t.out_of_line_deg.iter().zip(want).all(|(a, b)| (a - b).abs() < 1e-9), "{:?}", t.out_of_line_deg);
        assert!((along_x - 53.30).abs() < 0.01 && (upright - 32.31).abs() < 0.01);
        let share = 0.7 - 0.2 * (along_x - 45.0) / 45.0;
        let (leg, carries_kg, limit_kg) = t.shackle_most_used().unwrap();
        assert!(leg == 1 && (carries_kg - most_kg).abs() < 1e-6 && (limit_kg - 15_000.0 * share).abs() < 1e-6);
        let over = c.over_limit().unwrap();
        assert!(over.starts_with("the spreader's top shackles cannot carry the load: "), "{over}");
        assert!(over.contains("the most used, top leg 2's, pulls 53.3° out of line with its pin as rigged (spreader top_pin_axes), may carry 66 % of it, 9.95 t"), "{over}");
        assert!(over.ends_with("give top shackles of a higher working load limit (spreader top_shackle_wll_t) or lugs turned for the top legs to pull square to their pins (spreader top_pin_axes)"), "{over}");
        // Every pin square to its leg: in line, as without pins.
        let square: Vec<[f64; 3]> =
            [[1.0, -3.0, 0.0], [1.0, 3.0, 0.0], [1.0, -3.0, 0.0], [1.0, 3.0, 0.0]].into_iter().map(unit).collect();
        let c = check(&shackled(15_000.0, Some(square.clone())), 12_000.0, size, [0.0; 3], 4.0).unwrap();
        let t = c.spreader.unwrap().top.unwrap();
        assert!(t.out_of_line_deg.iter().all(|deg| deg.abs() < 1e-9), "{:?}", t.out_of_line_deg);
        // A centre of gravity's tolerance: more on each, the angles as rigged.
        let tol = check_within(&shackled(15_000.0, Some(pins)), 12_000.0, size, [0.0; 3], 0.1, 4.0).unwrap();
        let t_tol = tol.spreader.unwrap().top.unwrap();
        assert!(
            t_tol.out_of_line_deg.iter().zip(want).all(|(a, b)| (a - b).abs() < 1e-9),
            "{:?}",
            t_tol.out_of_line_deg
        );
        assert!(t_tol.leg_most_kg.iter().all(|kg| *kg > most_kg), "{:?}", t_tol.leg_most_kg);
        // A beam's two top shackles, in line.
        let beam = Slings {
            lift_points_m: vec![[-3.0, 0.0, 1.0], [3.0, 0.0, 1.0]],
            points_given: true,
            ratings: Ratings::legs(9000.0),
            spreader: Some(Spreader {
                top_shackles: Some(TopShackles { wll_kg: 9000.0, pin_axes: Some(vec![[0.0, 1.0, 0.0]; 2]) }),
                below_hook_m: 3.0,
                ..beam(Some(12_000.0))
            }),
            pin_axes: None,
        };
        let c = check(&beam, 12_000.0, size, [0.5, 0.0, 0.0], 4.0).unwrap();
        let t = c.spreader.as_ref().unwrap().top.clone().unwrap();
        assert_eq!(t.out_of_line_deg, [0.0, 0.0]);
        let (leg, carries_kg, limit_kg) = t.shackle_most_used().unwrap();
        assert_eq!((leg, carries_kg, limit_kg), (1, t.leg_most_kg[1], 9000.0), "{t:?}");
        assert!(t.leg_most_kg[1] > t.leg_most_kg[0]);
    }

    #[test]
    fn a_spreader_frame_hangs_four_legs_plumb() {
        let size = [7.0, 3.0, 2.0];
        let mut s = Slings {
            lift_points_m: vec![[-3.0, -1.0, 1.0], [3.0, -1.0, 1.0], [3.0, 1.0, 1.0], [-3.0, 1.0, 1.0]],
            points_given: true,
            ratings: Ratings::legs(9000.0),
            spreader: Some(frame(Some(12_000.0))),
            pin_axes: None,
        };
        let c = check(&s, 12_000.0, size, [0.0; 3], 4.0).unwrap();
        assert_eq!((c.max_leg_kg, c.max_angle_deg, c.leg_lengths_m.clone()), (6000.0, 0.0, vec![2.0; 4]));
        let f = c.spreader.clone().unwrap();
        assert_eq!((f.width_m, f.hook_from_centre_m, f.carries_kg), (Some(2.0), Some([0.0, 0.0]), 12_000.0));
        let t = f.top.clone().unwrap();
        let (across, cos) = (10.0f64.sqrt(), 2.0 / 14.0f64.sqrt());
        assert!((t.max_leg_kg - 6300.0 / cos).abs() < 1e-6, "{t:?}");
        assert!((t.compression_kg - 6300.0 * across / 2.0).abs() < 1e-6, "{t:?}");
        assert!((t.max_angle_deg - across.atan2(2.0).to_degrees()).abs() < 1e-9);
        assert_eq!(c.over_limit(), None);
        let said = c.said();
        assert!(said.starts_with("4 legs at the lift points given (rigging lift_points_m), hanging plumb from a spreader frame: the most on one leg (leg 2, any one leg slack) 6.00 t"), "{said}");
        assert!(said.contains("the frame 6.00 x 2.00 m, its pins 2.00 m below the hook block, carries 12.00 t of its 20.00 t working load limit: 60 %, hung from the hook by 4 top legs up to 57.7° from the vertical"), "{said}");
        // Off centre, on a lifting frame (top legs from its corners would
        // hang more than 60° from the vertical to a hook over (0.95, 0.48)),
        // its lug over the joint centre of gravity.
        s.spreader = Some(frame(None));
        let lug = check(&s, 12_000.0, size, [1.0, 0.5, 0.0], 4.0).unwrap();
        assert!((lug.max_leg_kg - 8000.0).abs() < 1e-6 && lug.max_leg == 3, "{lug:?}");
        let [dx, dy] = lug.spreader.unwrap().hook_from_centre_m.unwrap();
        assert!((dx - 12.0 / 12.6).abs() < 1e-9 && (dy - 6.0 / 12.6).abs() < 1e-9);
        // Over its limit, named.
        s.spreader = Some(Spreader { wll_kg: 11_000.0, ..frame(Some(12_000.0)) });
        let over = check(&s, 12_000.0, size, [0.0; 3], 4.0).unwrap().over_limit().unwrap();
        assert!(
            over.starts_with("the spreader frame cannot carry the load")
                && over.contains("give a frame of a higher working load limit (spreader wll_t)"),
            "{over}"
        );
        // What a frame cannot be.
        s.spreader = Some(Spreader { length_m: 5.0, ..frame(Some(12_000.0)) });
        let e = check(&s, 12_000.0, size, [0.0; 3], 4.0).unwrap_err();
        assert!(e.contains("does not reach over lift point 1 (-3.00, -1.00) m"), "{e}");
        s.spreader = Some(Spreader { length_m: 8.0, ..frame(Some(12_000.0)) });
        let e = check(&s, 12_000.0, size, [0.0; 3], 4.0).unwrap_err();
        assert!(e.contains("reaches beyond the load's 7.00 x 3.00 m footprint"), "{e}");
        let two =
            Slings { lift_points_m: vec![[-3.0, 0.0, 1.0], [3.0, 0.0, 1.0]], spreader: Some(frame(None)), ..s.clone() };
        assert!(check(&two, 12_000.0, size, [0.0; 3], 4.0).unwrap_err().contains("checked with four sling legs"));
        // Known to 0.1 m, the worst over the square is more.
        s.spreader = Some(frame(Some(12_000.0)));
        let within = check_within(&s, 12_000.0, size, [0.0; 3], 0.1, 4.0).unwrap();
        assert!(within.max_leg_kg > 6000.0 && within.spreader.unwrap().top.unwrap().max_leg_kg > t.max_leg_kg);
    }

    #[test]
    fn the_side_loading_chart_is_read_straight_between_its_angles() {
        for (deg, share) in [(0.0, 1.0), (22.5, 0.85), (45.0, 0.7), (67.5, 0.6), (90.0, 0.5), (120.0, 0.5), (-3.0, 1.0)]
        {
            assert!((side_loading_factor(deg) - share).abs() < 1e-12, "{deg}: {}", side_loading_factor(deg));
        }
        assert_eq!(side_loading_factor(f64::NAN), 0.5);
    }

    /// The demo's vessel (8 x 3 x 3 m, 12 t) on two legs at the middles of
    /// its short edges, 4 m of rigging: each leg 45° from the vertical,
    /// 8.49 t. Pins across the legs' plane pull in line; along the load,
    /// 45° out of line (70 %: 8.40 t, less than the leg's pull); at 45° in
    /// plan, 30° out of line (80 %).
    #[test]
    fn a_leg_pulling_across_its_shackles_pin_side_loads_it() {
        let size = [8.0, 3.0, 3.0];
        let ratings =
            Ratings { shackle_wll_kg: Some(12_000.0), lift_point_wll_kg: Some(10_000.0), ..Ratings::legs(10_000.0) };
        let pinned = |axis: [f64; 3]| Slings { ratings, pin_axes: Some(vec![axis; 2]), ..slings(2, size) };
        let checked = |s: &Slings| {
            let mut c = check(s, 12_000.0, size, [0.0; 3], 4.0).unwrap();
            c.side_loading = side_loading(s, size, [0.0; 3], 0.0, 0.0, 4.0);
            c
        };
        let across = checked(&pinned([0.0, 1.0, 0.0]));
        let side = across.side_loading.clone().unwrap();
        assert_eq!((side.out_of_line_deg.clone(), side.turn_deg), (vec![0.0, 0.0], 0.0));
        let (leg, carries_kg, limit_kg) = across.shackle_most_used().unwrap();
        assert!(leg == 0 && (carries_kg - 6000.0 * 2.0f64.sqrt()).abs() < 1e-6 && limit_kg == 12_000.0);
        assert_eq!(across.over_limit(), None);
        let said = across.said();
        assert!(said.contains("and of the lift points' shackles' 12.00 t, less for side loading: the most used, leg 1's, pulled up to 0.0° out of line with its pin (rigging pin_axes), may carry 100 % of it, 12.00 t (the makers' chart"), "{said}");
        assert!(said.contains("the lift point's own 10.00 t, which must be its rating for a pull up to 0.0° out of its lug's plane: 85 %"), "{said}");
        let along = checked(&pinned([1.0, 0.0, 0.0]));
        let side = along.side_loading.clone().unwrap();
        assert!(side.out_of_line_deg.iter().all(|d| (d - 45.0).abs() < 1e-9), "{side:?}");
        assert!((along.shackle_most_used().unwrap().2 - 8400.0).abs() < 1e-6);
        let over = along.over_limit().unwrap();
        assert!(
            over.starts_with("the lift points' shackles cannot carry the load")
                && over.contains("the most used, leg 1's, pulled up to 45.0° out of line with its pin (rigging pin_axes), may carry 70 % of it, 8.40 t")
                && over.contains("and carries up to 8.49 t: 101 %")
                && over.ends_with("or lugs turned for their legs to pull square to the pins (rigging pin_axes)"),
            "{over}"
        );
        // Without the pins' directions the shackles are taken in line.
        assert_eq!(check(&pinned([1.0, 0.0, 0.0]), 12_000.0, size, [0.0; 3], 4.0).unwrap().over_limit(), None);
        let half = std::f64::consts::FRAC_1_SQRT_2;
        let turned = checked(&pinned([half, half, 0.0]));
        let side = turned.side_loading.unwrap();
        assert!(side.out_of_line_deg.iter().all(|d| (d - 30.0).abs() < 1e-9), "{side:?}");
        assert!((side_loading_factor(side.out_of_line_deg[0]) - 0.8).abs() < 1e-12);
        // Each shackle at its own leg's angle, against its own leg's pull:
        // the centre of gravity 1 m towards leg 1 (36.9° from the vertical,
        // 9.37 t) and leg 2 (51.3°, 7.20 t) pulled along its pin, 51.3° out
        // of line (67.2 %: 8.06 t). Leg 2's shackle is the most used (89 %),
        // though leg 1 carries more; both under their ratings.
        let mixed = Slings { ratings, pin_axes: Some(vec![[0.0, 1.0, 0.0], [1.0, 0.0, 0.0]]), ..slings(2, size) };
        let mut c = check(&mixed, 12_000.0, size, [-1.0, 0.0, 0.0], 4.0).unwrap();
        c.side_loading = side_loading(&mixed, size, [-1.0, 0.0, 0.0], 0.0, 0.0, 4.0);
        let (a1, a2) = (3.0f64.atan2(4.0), 5.0f64.atan2(4.0));
        let t2 = 12_000.0 / (a2.sin() / a1.sin() * a1.cos() + a2.cos());
        assert!(
            (c.leg_most_kg[1] - t2).abs() < 1e-6 && (c.leg_most_kg[0] - t2 * a2.sin() / a1.sin()).abs() < 1e-6,
            "{c:?}"
        );
        let (leg, carries_kg, limit_kg) = c.shackle_most_used().unwrap();
        assert_eq!(leg, 1);
        assert!(
            (carries_kg - t2).abs() < 1e-6 && (limit_kg - 12_000.0 * side_loading_factor(a2.to_degrees())).abs() < 1e-6
        );
        assert!(c.leg_most_kg[0] > limit_kg, "leg 1 carries more than leg 2's shackle may");
        assert_eq!(c.over_limit(), None);
        // Three or four legs to the hook hold it where it is in the load's
        // frame: no turn, whatever the tolerance.
        let four = Slings { ratings, pin_axes: Some(vec![[0.0, 1.0, 0.0]; 4]), ..slings(4, size) };
        let side = side_loading(&four, size, [0.2, 0.1, 0.0], 0.3, 0.2, 4.0).unwrap();
        assert_eq!(side.turn_deg, 0.0);
        let hook = Vec3::new(0.2, 0.1, 5.5);
        for (k, p) in four.lift_points_m.iter().enumerate() {
            let leg = (hook - Vec3::new(p[0], p[1], p[2])).normalize();
            assert!((side.out_of_line_deg[k] - leg.y.abs().asin().to_degrees()).abs() < 1e-9);
        }
    }

    /// One leg, or two to the hook: the load hangs with its centre of
    /// gravity under its lift point, or under the line through its two, and
    /// its legs turn with it in its frame. Over random loads, lift points,
    /// pins, centres of gravity and tolerances, the true angle out of line
    /// at random places within the tolerance, worked out from how the load
    /// hangs there, is never more than [`side_loading`]'s; and with no
    /// tolerance and the centre of gravity on the line, it is the same.
    #[test]
    fn no_place_within_the_tolerance_pulls_a_shackle_farther_out_of_line() {
        let mut rng = crate::rng::seeded(7, "side loading");
        let mut u = |lo: f64, hi: f64| crate::rng::uniform(&mut rng, lo, hi);
        for case in 0..400 {
            let legs = 1 + case % 2;
            let size = [u(2.0, 10.0), u(1.0, 4.0), u(1.0, 4.0)];
            let top = size[2] / 2.0;
            let pts: Vec<[f64; 3]> = if legs == 1 {
                vec![[u(-0.3, 0.3), u(-0.3, 0.3), top]]
            } else {
                let half = u(0.5, size[0] / 2.0);
                vec![[-half, u(-0.3, 0.3), top - u(0.0, 0.5)], [half, u(-0.3, 0.3), top - u(0.0, 0.5)]]
            };
            let axes: Vec<[f64; 3]> = (0..legs)
                .map(|_| {
                    let a = Vec3::new(u(-1.0, 1.0), u(-1.0, 1.0), u(-1.0, 1.0)).normalize();
                    [a.x, a.y, a.z]
                })
                .collect();
            let exact = case % 10 == 0;
            let (tol, tol_z) = if exact { (0.0, 0.0) } else { (u(0.0, 0.4), u(0.0, 0.3)) };
            let cog = if exact { [0.0, 0.0, u(-0.5, 0.0)] } else { [u(-0.2, 0.2), u(-0.2, 0.2), u(-0.5, 0.0)] };
            let height = u(1.0, 6.0);
            let s = Slings {
                lift_points_m: pts.clone(),
                points_given: true,
                ratings: Ratings::legs(1e6),
                spreader: None,
                pin_axes: Some(axes.clone()),
            };
            let side = side_loading(&s, size, cog, tol, tol_z, height).unwrap();
            let v = |p: [f64; 3]| Vec3::new(p[0], p[1], p[2]);
            let hook = Vec3::new(cog[0], cog[1], top + height);
            for sample in 0..50 {
                let c = if sample == 0 {
                    v(cog)
                } else {
                    Vec3::new(cog[0] + u(-tol, tol), cog[1] + u(-tol, tol), cog[2] + u(0.0, tol_z))
                };
                let legs_now: Vec<Vec3> = if legs == 1 {
                    vec![(v(pts[0]) - c).normalize()]
                } else {
                    let (a, b) = (v(pts[0]), v(pts[1]));
                    let along = (b - a).normalize();
                    let across = |w: Vec3| w - along * w.dot(&along);
                    let (from, to) = (across(hook - a), -across(c - a));
                    let turn = from.cross(&to).dot(&along).atan2(from.dot(&to));
                    let r = na::Rotation3::from_axis_angle(&na::Unit::new_normalize(along), turn);
                    let hook_now = a + r * (hook - a);
                    pts.iter().map(|p| (hook_now - v(*p)).normalize()).collect()
                };
                for (k, leg) in legs_now.iter().enumerate() {
                    let deg = leg.dot(&v(axes[k])).abs().min(1.0).asin().to_degrees();
                    assert!(
                        deg <= side.out_of_line_deg[k] + 1e-7,
                        "case {case}, leg {k}: {deg} out of line at {c:?}, more than {side:?}"
                    );
                    if exact {
                        assert!((deg - side.out_of_line_deg[k]).abs() < 1e-7, "case {case}: {deg} {side:?}");
                    }
                }
            }
        }
    }

    /// Plumb legs from a spreader keep the load turned as the spreader is:
    /// a frame and its load turn about the hook as one whose centre of
    /// gravity stands the legs' length higher, and turn over where that is
    /// not below the hook. A beam adds the turn about its lift points' line.
    #[test]
    fn a_spreader_and_its_load_turn_about_the_hook_as_one() {
        let size = [7.0, 3.0, 2.0];
        let corners = vec![[-3.0, -1.0, 1.0], [3.0, -1.0, 1.0], [3.0, 1.0, 1.0], [-3.0, 1.0, 1.0]];
        let on_frame = Slings {
            lift_points_m: corners.clone(),
            points_given: true,
            ratings: Ratings { shackle_wll_kg: Some(9000.0), ..Ratings::legs(9000.0) },
            spreader: Some(frame(Some(12_000.0))),
            pin_axes: Some(vec![[0.0, 1.0, 0.0]; 4]),
        };
        // Pins 2 m under the hook, lift points 1 m over the centre of
        // gravity: 3 m, not the hook's 5 m over it.
        let c = check_within(&on_frame, 12_000.0, size, [0.0; 3], 0.2, 4.0).unwrap();
        let want = (0.2 * 2.0f64.sqrt()).atan2(3.0).to_degrees();
        assert!((c.tilt_deg.unwrap() - want).abs() < 1e-9, "{:?} {want}", c.tilt_deg);
        let side = side_loading(&on_frame, size, [0.0; 3], 0.2, 0.0, 4.0).unwrap();
        assert!((side.turn_deg - want).abs() < 1e-9 && side.out_of_line_deg.iter().all(|d| (d - want).abs() < 1e-9));
        // Up to 0.5 m higher: 2.5 m.
        let side = side_loading(&on_frame, size, [0.0; 3], 0.2, 0.5, 4.0).unwrap();
        assert!((side.turn_deg - (0.2 * 2.0f64.sqrt()).atan2(2.5).to_degrees()).abs() < 1e-9);
        // Lift points at the load's underside, 1 m under its centre of
        // gravity, 0.8 m under the hook: the frame and the load turn over.
        let low = Slings {
            lift_points_m: corners.iter().map(|p| [p[0], p[1], -1.0]).collect(),
            spreader: Some(Spreader { below_hook_m: 0.8, ..frame(None) }),
            ..on_frame.clone()
        };
        let e = check(&low, 12_000.0, size, [0.0; 3], 4.0).unwrap_err();
        assert!(e.starts_with("the load hangs on plumb legs from a spreader frame 0.80 m below the hook, from lift points as low as z -1.00 m from its box's centre, 1.00 m below its centre of gravity (z 0.00 m): the frame and the load, turning as one about the hook, would turn over"), "{e}");
        let lower = Slings { spreader: Some(Spreader { below_hook_m: 1.5, ..frame(None) }), ..low };
        assert!(check(&lower, 12_000.0, size, [0.0; 3], 4.0).is_ok());
        // A beam over two lift points 1 m over the centre of gravity, its
        // pins 2 m under the hook: the turn about the points' line (√2 tol
        // over 1 m at most) and about the hook (over 3 m), added.
        let on_beam = Slings {
            lift_points_m: vec![[-3.0, 0.0, 1.0], [3.0, 0.0, 1.0]],
            spreader: Some(beam(Some(10_000.0))),
            pin_axes: Some(vec![[0.0, 1.0, 0.0]; 2]),
            ..on_frame.clone()
        };
        let c = check_within(&on_beam, 12_000.0, size, [0.0; 3], 0.2, 4.0).unwrap();
        let pitch = (0.2 * 2.0f64.sqrt()).atan2(3.0).to_degrees();
        let roll_bound = (0.2 * 2.0f64.sqrt()).atan2(1.0).to_degrees();
        assert!((c.tilt_deg.unwrap() - (roll_bound + pitch)).abs() < 1e-9, "{:?}", c.tilt_deg);
        let side = side_loading(&on_beam, size, [0.0; 3], 0.2, 0.0, 4.0).unwrap();
        // Across the line the centre of gravity lies at most 0.2 m off it.
        let roll = 0.2f64.atan2(1.0).to_degrees();
        assert!((side.turn_deg - (roll + pitch)).abs() < 1e-9, "{side:?} {roll} {pitch}");
    }

    /// On one leg the load hangs with its centre of gravity plumb under
    /// the lift point, on two under the line through them, whatever the
    /// legs' lengths: given off it by more than a degree's worth, refused
    /// (liftplan plans a load level), by hand; three or four legs, and a
    /// frame's plumb legs, hang it level wherever it lies.
    #[test]
    fn a_load_on_one_or_two_legs_hangs_with_its_centre_of_gravity_under_them() {
        let size = [8.0, 3.0, 3.0];
        let one = Slings { lift_points_m: vec![[0.5, 0.0, 1.5]], points_given: true, ..slings(1, size) };
        let (deg, why) = hanging_tilt(&one, [0.0, 0.0, -0.1]).unwrap();
        assert!((deg - 0.5f64.atan2(1.6).to_degrees()).abs() < 1e-9, "{deg}");
        let e = check_within(&one, 12_000.0, size, [0.0, 0.0, -0.1], 0.0, 4.0).unwrap_err();
        assert_eq!(e, why);
        assert!(e.starts_with("on one leg the load hangs with its centre of gravity plumb under its lift point, which lies 0.50 m off it in plan: it would hang 17.4° off level"), "{e}");
        let near = check_within(&one, 12_000.0, size, [0.49, 0.0, -0.1], 0.1, 4.0).unwrap();
        assert!(near.said().contains(": on one leg a load whose centre of gravity lies off hangs up to 5.4° off level, with its centre of gravity under its lift point, which no leg's length changes: at the trial lift, CHECK that it hangs level"), "{}", near.said());
        let four = check_within(&slings(4, size), 12_000.0, size, [0.2, 0.3, -0.1], 0.1, 4.0).unwrap();
        assert!(
            four.said().contains(": on legs of those lengths a load whose centre of gravity lies off hangs up to "),
            "{}",
            four.said()
        );
        // Two legs at the middles of the short edges, the centre of gravity
        // 0.3 m to one side, 1.6 m below them.
        let two = slings(2, size);
        let e = check_within(&two, 12_000.0, size, [0.2, 0.3, -0.1], 0.0, 4.0).unwrap_err();
        assert!(e.starts_with(&format!("the load's centre of gravity lies 0.30 m off the line through its two lift points in plan: on two legs it would hang turned {:.1}° about that line", 0.3f64.atan2(1.6).to_degrees())), "{e}");
        assert!(check_within(&two, 12_000.0, size, [0.2, 0.02, -0.1], 0.1, 4.0).is_ok());
        // Lift points at two heights: the line slopes, the turn is about it.
        let sloped =
            Slings { lift_points_m: vec![[-4.0, 0.0, 1.5], [4.0, 0.0, 0.5]], points_given: true, ..two.clone() };
        let (deg, _) = hanging_tilt(&sloped, [0.0, 0.3, -0.1]).unwrap();
        let (along, w) = (Vec3::new(8.0, 0.0, -1.0).normalize(), Vec3::new(4.0, 0.3, -1.6));
        let across = w - along * w.dot(&along);
        let down = -Vec3::z() - along * (-Vec3::z()).dot(&along);
        assert!((deg - across.angle(&down).to_degrees()).abs() < 1e-9, "{deg}");
        // Four legs, a spreader beam's two and a frame's four.
        assert_eq!(hanging_tilt(&slings(4, size), [0.2, 0.3, -0.1]), None);
        assert!(check_within(&slings(4, size), 12_000.0, size, [0.2, 0.3, -0.1], 0.0, 4.0).is_ok());
        let on_beam = Slings {
            lift_points_m: vec![[-3.0, 0.0, 1.5], [3.0, 0.0, 1.5]],
            points_given: true,
            spreader: Some(beam(None)),
            ..two.clone()
        };
        assert!(
            check_within(&on_beam, 12_000.0, size, [0.0, 0.3, -0.1], 0.0, 4.0)
                .unwrap_err()
                .contains("off the line through its two lift points")
        );
        let on_frame = Slings {
            lift_points_m: vec![[-3.0, -1.0, 1.5], [3.0, -1.0, 1.5], [3.0, 1.0, 1.5], [-3.0, 1.0, 1.5]],
            points_given: true,
            spreader: Some(frame(None)),
            ..two
        };
        assert_eq!(hanging_tilt(&on_frame, [0.0, 0.3, -0.1]), None);
    }
}
