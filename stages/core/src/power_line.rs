//! Overhead power lines: conductors no part of the crane, its rope or its
//! load may come within the approach distance of.
//!
//! Thin wires are what laser scans show worst (a few points, or none, on a
//! conductor 12 mm across), and a line's voltage is nowhere in the scans or
//! the plant model, so a line is given by hand: where its conductor is held
//! (the pole or tower tops, in order), how far it sags below the straight
//! line between two supports at mid-span, and its voltage; where known, the
//! least it sags (a conductor cold and carrying little hangs higher) and
//! how far the wind may swing it sideways (its blowout). The distance
//! kept is the lift's own `approach_m` where given, else OSHA 29 CFR
//! 1926.1408 Table A's for the voltage ([`table_a_m`]); over 1,000 kV the
//! line's owner must give it.
//!
//! The planner and the validator keep every part off what they are given
//! (the lift's clearance, and in the lift-off and set-down what hangs need
//! only not touch), so a line goes to them as boxes round its conductor
//! ([`PowerLine::boxes`]) grown by the approach distance (and the few
//! centimetres a lift-off may come nearer a box than its clearance; the
//! plan stage's `power_line_boxes`): a part off a box is the approach
//! distance off the conductor, and in the rest of the lift the clearance
//! beyond it. Each span hangs as a parabola (its
//! sag at mid-span), cut into pieces of at most [`PIECE_M`], each box
//! holding its piece of the curve at every sag from `least_sag_m` to
//! `sag_m`, hanging plumb or swung about the line between its supports by
//! up to `swing_deg` either way.
//!
//! What this module must not do: take a line's position from the scans
//! (it is what the engineer gives), or work out a conductor's sag or swing
//! from its temperature, current, tension or the wind: `sag_m` is to be
//! the most it sags, and where `swing_deg` or `least_sag_m` is not given
//! the conductor is taken as hanging plumb at `sag_m`, the approach
//! distance the only margin for its swing and rise.

use crate::frame::{Mat3, Point3, Vec3};
use crate::obb::Obb;
use nalgebra as na;
use serde::{Deserialize, Serialize};

/// The most supports one line may give.
pub const MAX_SUPPORTS: usize = 100;
/// The longest span between two supports (m).
pub const MAX_SPAN_M: f64 = 2_000.0;
/// The most a span may sag (m).
pub const MAX_SAG_M: f64 = 100.0;
/// The most a conductor may be given to swing from plumb (degrees).
pub const MAX_SWING_DEG: f64 = 80.0;
/// The longest piece of conductor one box holds (m).
pub const PIECE_M: f64 = 2.0;
/// The longest name (characters): the PDF says it.
pub const MAX_NAME: usize = 100;
/// How far from the site's origin a support may stand (m), as an
/// obstacle ([`crate::obstacle::MAX_OBSTACLE_OFFSET_M`]).
pub const MAX_OFFSET_M: f64 = crate::obstacle::MAX_OBSTACLE_OFFSET_M;

/// One overhead line, in the site frame as the lifts' picks and sets are.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PowerLine {
    pub name: String,
    /// Where the conductor is held, in order along the line: [x, y, z] (m).
    pub points_m: Vec<[f64; 3]>,
    /// How far the conductor hangs below the straight line between two
    /// supports at mid-span, the most it sags (hot, loaded) (m).
    pub sag_m: f64,
    /// The least it sags at mid-span (cold, carrying little) (m); none:
    /// `sag_m` (taken as hanging there).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub least_sag_m: Option<f64>,
    /// How far the wind may swing the conductor sideways, about the line
    /// between its supports, from hanging plumb (its blowout) (degrees);
    /// none: not swinging (the approach distance the only margin for it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub swing_deg: Option<f64>,
    /// Its voltage, phase to phase (kV).
    pub voltage_kv: f64,
    /// The distance every part keeps from it (m); none: OSHA 1926.1408
    /// Table A's for the voltage.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub approach_m: Option<f64>,
    /// The lifts it is there for, by id; empty: every lift.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub lifts: Vec<String>,
}

/// The most lines a project may give.
pub const MAX_LINES: usize = 50;
/// The most conductor the lines may give together (m): each piece of
/// [`PIECE_M`] is a box the planner and the validator check.
pub const MAX_CONDUCTOR_M: f64 = 10_000.0;

/// The first line of `lines` a project cannot give, its place in the list
/// and why; `lift_ids`: the project's lifts, which a line's `lifts` must
/// name.
pub fn problem_of(lines: &[PowerLine], lift_ids: &[&str]) -> Option<(usize, String)> {
    if lines.len() > MAX_LINES {
        return Some((MAX_LINES, format!("{} power lines: a project gives at most {MAX_LINES}", lines.len())));
    }
    for (k, l) in lines.iter().enumerate() {
        if let Some(p) = l.problem(k) {
            return Some((k, p));
        }
        let before = lines[..k].iter().map(|e| e.name.as_str());
        if let Some(p) = crate::obstacle::name_or_lifts_problem("power line", &l.name, before, &l.lifts, lift_ids) {
            return Some((k, p));
        }
    }
    let total: f64 = lines.iter().map(PowerLine::length_m).sum();
    if total > MAX_CONDUCTOR_M {
        return Some((
            0,
            format!(
                "the power lines give {total:.1} m of conductor together, more than the {MAX_CONDUCTOR_M:.0} m liftplan checks: give the spans near the lifts"
            ),
        ));
    }
    None
}

/// OSHA 29 CFR 1926.1408 Table A: the minimum clearance from a line of
/// `voltage_kv` (m; the table's feet converted), `None` over 1,000 kV,
/// where the line's owner or a registered engineer sets it.
pub fn table_a_m(voltage_kv: f64) -> Option<f64> {
    const FOOT_M: f64 = 0.3048;
    let feet = match voltage_kv {
        v if v <= 50.0 => 10.0,
        v if v <= 200.0 => 15.0,
        v if v <= 350.0 => 20.0,
        v if v <= 500.0 => 25.0,
        v if v <= 750.0 => 35.0,
        v if v <= 1_000.0 => 45.0,
        _ => return None,
    };
    Some(feet * FOOT_M)
}

impl PowerLine {
    /// Whether it is there during lift `id`.
    pub fn during(&self, id: &str) -> bool {
        crate::obstacle::there_during(&self.lifts, id)
    }

    /// The distance every part keeps from it (m), and whence: the line's
    /// own `approach_m` or Table A's. `None` only for a line [`Self::problem`]
    /// refuses.
    pub fn approach(&self) -> Option<(f64, &'static str)> {
        match self.approach_m {
            Some(a) => Some((a, "approach_m")),
            None => table_a_m(self.voltage_kv).map(|a| (a, "OSHA 1926.1408 Table A")),
        }
    }

    /// Why it is not a line a project can give (`k`: its place in the
    /// file's list, from 0), naming the key.
    pub fn problem(&self, k: usize) -> Option<String> {
        let name = &self.name;
        let example = "which line: \"11 kV feeder to the pump house\"";
        if let Some(p) = crate::obstacle::name_problem("power_line", k, name, MAX_NAME, example) {
            return Some(p);
        }
        if !(2..=MAX_SUPPORTS).contains(&self.points_m.len()) {
            return Some(format!(
                "power line '{name}': points_m gives {} points: give where its conductor is held, 2 to {MAX_SUPPORTS} pole or tower tops in order along it",
                self.points_m.len()
            ));
        }
        for (i, p) in self.points_m.iter().enumerate() {
            if !p.iter().all(|v| v.is_finite() && v.abs() <= MAX_OFFSET_M) {
                return Some(format!(
                    "power line '{name}': points_m[{i}] must be [x, y, z] in metres in the frame of the lifts' pick and set, found {p:?}"
                ));
            }
        }
        for (i, w) in self.points_m.windows(2).enumerate() {
            let plan = (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]);
            if !(1.0..=MAX_SPAN_M).contains(&plan) {
                return Some(format!(
                    "power line '{name}': points_m[{i}] and points_m[{}] are {plan:.2} m apart in plan: a span is 1 to {MAX_SPAN_M} m",
                    i + 1
                ));
            }
        }
        if !(self.sag_m.is_finite() && (0.0..=MAX_SAG_M).contains(&self.sag_m)) {
            return Some(format!(
                "power line '{name}': sag_m must be 0 to {MAX_SAG_M} m (the most its conductor hangs below the straight line between two supports), found {}",
                self.sag_m
            ));
        }
        if let Some(least) = self.least_sag_m.filter(|l| !(l.is_finite() && (0.0..=self.sag_m).contains(l))) {
            return Some(format!(
                "power line '{name}': least_sag_m must be 0 to sag_m ({} m; the least and the most its conductor sags), found {least}",
                self.sag_m
            ));
        }
        if let Some(swing) = self.swing_deg.filter(|s| !(s.is_finite() && (0.0..=MAX_SWING_DEG).contains(s))) {
            return Some(format!(
                "power line '{name}': swing_deg must be 0 to {MAX_SWING_DEG} degrees (how far the wind swings its conductor sideways from hanging plumb), found {swing}"
            ));
        }
        if !(self.voltage_kv.is_finite() && self.voltage_kv > 0.0) {
            return Some(format!("power line '{name}': voltage_kv must be positive, found {}", self.voltage_kv));
        }
        match self.approach_m {
            Some(a) if !(a.is_finite() && a > 0.0 && a <= 100.0) => {
                Some(format!("power line '{name}': approach_m must be more than 0 and at most 100 m, found {a}"))
            }
            None if table_a_m(self.voltage_kv).is_none() => Some(format!(
                "power line '{name}' is over 1,000 kV ({} kV), beyond OSHA 1926.1408 Table A: give the approach distance its owner sets as approach_m",
                self.voltage_kv
            )),
            _ => None,
        }
    }

    /// The length of its spans' chords (m).
    pub fn length_m(&self) -> f64 {
        (0..self.points_m.len().saturating_sub(1)).map(|i| self.chord_m(i)).sum()
    }

    /// The straight distance between span `i`'s supports (m).
    fn chord_m(&self, i: usize) -> f64 {
        let (a, b) = (self.points_m[i], self.points_m[i + 1]);
        ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2) + (b[2] - a[2]).powi(2)).sqrt()
    }

    /// The conductor at `t` (0 to 1) along span `i` hanging plumb at its
    /// most sag: the straight line between its supports less the sag's
    /// parabola, `sag_m` at mid-span ([`Self::swung`] unswung).
    pub fn at(&self, i: usize, t: f64) -> [f64; 3] {
        let p = self.swung(i, t, self.sag_m, 0.0);
        [p.x, p.y, p.z]
    }

    /// The conductor at `t` along span `i` sagging `sag_m` at mid-span and
    /// swung `swing_rad` about the straight line between its supports.
    pub fn swung(&self, i: usize, t: f64, sag_m: f64, swing_rad: f64) -> Point3 {
        let (a, b) = (Vec3::from(self.points_m[i]), Vec3::from(self.points_m[i + 1]));
        let turn = na::Rotation3::from_axis_angle(&na::Unit::new_normalize(b - a), swing_rad);
        let hangs = turn * Vec3::new(0.0, 0.0, -4.0 * sag_m * t * (1.0 - t));
        Point3::from(a + (b - a) * t + hangs)
    }

    /// The least and the most it sags at mid-span (m) and how far it swings
    /// either way (radians), as given.
    fn hangs(&self) -> (f64, f64, f64) {
        (self.least_sag_m.unwrap_or(self.sag_m), self.sag_m, self.swing_deg.unwrap_or(0.0).to_radians())
    }

    /// Boxes holding every point within `grow_m` of the conductor wherever
    /// it hangs (at any sag from the least to the most, swung by up to
    /// `swing_deg` either way), one per piece of at most [`PIECE_M`] along
    /// each span.
    pub fn boxes(&self, grow_m: f64) -> Vec<Obb> {
        let (least, most, swing) = self.hangs();
        let plumb_at_most = least == most && swing == 0.0;
        let mut out = Vec::new();
        for i in 0..self.points_m.len().saturating_sub(1) {
            let n = (self.chord_m(i) / PIECE_M).ceil().max(1.0) as usize;
            let dt = 1.0 / n as f64;
            // Between its ends a piece of the parabola lies below their
            // chord by at most sag · dt² (its second derivative is -8 sag).
            let dev = self.sag_m * dt * dt;
            for k in 0..n {
                let (p, q) = (self.at(i, k as f64 * dt), self.at(i, (k + 1) as f64 * dt));
                let along = Vec3::new(q[0] - p[0], q[1] - p[1], q[2] - p[2]);
                let len = along.norm();
                let x = along / len;
                // Spans are at least 1 m apart in plan: x is never vertical.
                let y = Vec3::new(-x.y, x.x, 0.0).normalize();
                let z = x.cross(&y);
                let center = Point3::new((p[0] + q[0]) / 2.0, (p[1] + q[1]) / 2.0, (p[2] + q[2]) / 2.0);
                let axes = Mat3::from_columns(&[x, y, z]);
                if plumb_at_most {
                    out.push(Obb::new(center, axes, Vec3::new(len / 2.0 + grow_m + dev, grow_m, grow_m + dev)));
                    continue;
                }
                // At each point along the span, where the conductor may
                // hang is a sector about the line between the supports: its
                // extent along each axis is at the least or the most sag,
                // plumb or swung fully one way (the axes are the span's
                // horizontal square and two in its vertical plane, and the
                // swing's part along each is monotonic in its angle). Its
                // ends bound a piece's curves but for their bow, at most
                // `dev` as above.
                let (mut lo, mut hi) = (Vec3::repeat(f64::INFINITY), Vec3::repeat(f64::NEG_INFINITY));
                for t in [k as f64 * dt, (k + 1) as f64 * dt] {
                    for sag in [least, most] {
                        for angle in [-swing, 0.0, swing] {
                            let local = axes.transpose() * (self.swung(i, t, sag, angle) - center);
                            lo = lo.inf(&local);
                            hi = hi.sup(&local);
                        }
                    }
                }
                let middle = axes * ((lo + hi) / 2.0);
                out.push(Obb::new(center + middle, axes, (hi - lo) / 2.0 + Vec3::repeat(grow_m + dev)));
            }
        }
        out
    }

    /// In words, for the run's output and the PDF.
    pub fn said(&self) -> String {
        let (approach, whence) = self.approach().unwrap_or((f64::NAN, "?"));
        let at = |p: &[f64; 3]| format!("({:.2}, {:.2}, {:.2})", p[0], p[1], p[2]);
        // A long line's supports are in the project file: the PDF gives its ends.
        let held = match &self.points_m[..] {
            [first, .., last] if self.points_m.len() > 3 => {
                format!("{} supports from {} to {}", self.points_m.len(), at(first), at(last))
            }
            all => all.iter().map(at).collect::<Vec<_>>().join(", "),
        };
        let sags = match self.least_sag_m {
            Some(least) if least < self.sag_m => format!("{least:.2} to {:.2}", self.sag_m),
            _ => format!("{:.2}", self.sag_m),
        };
        let swings = match self.swing_deg {
            Some(s) if s > 0.0 => format!(", swinging up to {s:.0} degrees either way in the wind"),
            Some(_) => ", not swinging in the wind (swing_deg = 0)".to_string(),
            None => ", its swing in the wind not given (taken as hanging plumb)".to_string(),
        };
        format!(
            "power line '{}', {} kV, held at {held} m, sagging {sags} m at mid-span{swings}: kept {approach:.2} m off ({whence})",
            self.name, self.voltage_kv
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line() -> PowerLine {
        PowerLine {
            name: "11 kV feeder".into(),
            points_m: vec![[-20.0, 30.0, 9.0], [10.0, 25.0, 10.0], [40.0, 32.0, 9.5]],
            sag_m: 1.2,
            least_sag_m: None,
            swing_deg: None,
            voltage_kv: 11.0,
            approach_m: None,
            lifts: vec![],
        }
    }

    #[test]
    fn table_a_in_metres() {
        assert_eq!(table_a_m(11.0), Some(10.0 * 0.3048));
        assert_eq!(table_a_m(50.0), Some(10.0 * 0.3048));
        assert_eq!(table_a_m(132.0), Some(15.0 * 0.3048));
        assert_eq!(table_a_m(400.0), Some(25.0 * 0.3048));
        assert_eq!(table_a_m(1_000.0), Some(45.0 * 0.3048));
        assert_eq!(table_a_m(1_100.0), None);
        assert_eq!(line().approach(), Some((3.048, "OSHA 1926.1408 Table A")));
        let own = PowerLine { approach_m: Some(6.0), ..line() };
        assert_eq!(own.approach(), Some((6.0, "approach_m")));
        assert_eq!(
            line().said(),
            "power line '11 kV feeder', 11 kV, held at (-20.00, 30.00, 9.00), (10.00, 25.00, 10.00), (40.00, 32.00, 9.50) m, sagging 1.20 m at mid-span, its swing in the wind not given (taken as hanging plumb): kept 3.05 m off (OSHA 1926.1408 Table A)"
        );
        let still = PowerLine { swing_deg: Some(0.0), ..line() };
        assert!(still.said().contains("sagging 1.20 m at mid-span, not swinging in the wind (swing_deg = 0): kept"));
        let moving = PowerLine { least_sag_m: Some(0.4), swing_deg: Some(35.0), ..line() };
        assert!(
            moving.said().contains("m, sagging 0.40 to 1.20 m at mid-span, swinging up to 35 degrees either way in the wind: kept 3.05 m off"),
            "{}",
            moving.said()
        );
        let mut long = line();
        long.points_m.push([70.0, 40.0, 9.0]);
        assert!(long.said().contains("held at 4 supports from (-20.00, 30.00, 9.00) to (70.00, 40.00, 9.00) m"));
    }

    /// Every point within the growth of the conductor lies in a box, and
    /// the conductor's lowest point is the sag below the chord.
    #[test]
    fn the_boxes_hold_the_conductor_and_its_surround() {
        let l = line();
        let grow = 1.5;
        let boxes = l.boxes(grow);
        let mid = l.at(0, 0.5);
        assert!((mid[2] - (9.5 - 1.2)).abs() < 1e-12, "{mid:?}");
        let mut rng = crate::rng::seeded(7, "power line boxes");
        let mut u = || crate::rng::unit(&mut rng);
        for _ in 0..20_000 {
            let i = (u() * 2.0) as usize;
            let c = l.at(i, u());
            // A point within grow of the conductor, in any direction.
            let dir = Vec3::new(u() - 0.5, u() - 0.5, u() - 0.5).normalize();
            let r = grow * u().sqrt() * 0.999;
            let p = Point3::new(c[0] + dir.x * r, c[1] + dir.y * r, c[2] + dir.z * r);
            assert!(boxes.iter().any(|b| b.distance_sq_to_point(&p) == 0.0), "{p:?} near {c:?} is in no box");
        }
        // Not much more: a point 2 m beside the middle of a span is in none.
        let beside = Point3::new(mid[0], mid[1] + grow + 2.0, mid[2]);
        assert!(boxes.iter().all(|b| b.distance_sq_to_point(&beside) > 0.0));
        // Given neither, it hangs plumb at its sag: the same boxes.
        let still = PowerLine { least_sag_m: Some(1.2), swing_deg: Some(0.0), ..line() };
        assert_eq!(still.boxes(grow), boxes);
    }

    /// A conductor that sags less when cold and swings in the wind: every
    /// point within the growth of it, at any sag between the least and the
    /// most and any swing up to the most either way, lies in a box; and the
    /// boxes reach beside and above where a plumb conductor's do, as far as
    /// the swing and the rise take it, and not much further.
    #[test]
    fn the_boxes_hold_the_conductor_wherever_it_sags_and_swings() {
        // Long spans, steep and level, a deep sag: the swing moves it metres.
        let l = PowerLine {
            points_m: vec![[-60.0, 30.0, 12.0], [40.0, 10.0, 30.0], [120.0, 40.0, 28.0]],
            sag_m: 6.0,
            least_sag_m: Some(2.5),
            swing_deg: Some(40.0),
            ..line()
        };
        let grow = 1.0;
        let boxes = l.boxes(grow);
        let mut rng = crate::rng::seeded(11, "power line swinging");
        let mut u = || crate::rng::unit(&mut rng);
        for _ in 0..40_000 {
            let i = (u() * 2.0) as usize;
            let (t, sag, angle) = (u(), 2.5 + 3.5 * u(), (u() * 2.0 - 1.0) * 40f64.to_radians());
            let c = l.swung(i, t, sag, angle);
            let dir = Vec3::new(u() - 0.5, u() - 0.5, u() - 0.5).normalize();
            let p = c + dir * (grow * u().sqrt() * 0.999);
            assert!(boxes.iter().any(|b| b.distance_sq_to_point(&p) == 0.0), "{p:?} near {c:?} is in no box");
        }
        // At mid-span of the level span: swung fully, the conductor is
        // 6 sin 40 = 3.86 m beside where it hangs; cold and swung fully,
        // 6 - 2.5 cos 40 = 4.08 m above. Beyond those by more than the
        // growth and the boxes' rounding (a piece's bow and its ends'
        // spread), no box.
        let plumb = l.swung(1, 0.5, 6.0, 0.0);
        let across = Vec3::new(-30.0, 80.0, 0.0).normalize();
        let in_any = |p: Point3| boxes.iter().any(|b| b.distance_sq_to_point(&p) == 0.0);
        assert!(in_any(plumb + across * (3.86 + grow - 0.05)));
        assert!(!in_any(plumb + across * (3.86 + grow + 0.3)));
        assert!(in_any(plumb + Vec3::z() * (4.08 + grow - 0.05)));
        assert!(!in_any(plumb + Vec3::z() * (4.08 + grow + 0.3)));
        assert!(!in_any(plumb - Vec3::z() * (grow + 0.3)), "not below where it hangs lowest");
    }

    #[test]
    fn what_cannot_be_a_line_is_refused_naming_the_key() {
        assert_eq!(line().problem(0), None);
        let cases = [
            (PowerLine { name: " ".into(), ..line() }, "power_line[0] needs a name"),
            (PowerLine { points_m: vec![[0.0, 0.0, 9.0]], ..line() }, "points_m gives 1 points"),
            (PowerLine { points_m: vec![[0.0, 0.0, 9.0], [0.5, 0.0, 9.0]], ..line() }, "0.50 m apart in plan"),
            (PowerLine { points_m: vec![[0.0, 0.0, f64::NAN], [5.0, 0.0, 9.0]], ..line() }, "points_m[0] must be"),
            (PowerLine { sag_m: -1.0, ..line() }, "sag_m must be 0 to 100 m"),
            (PowerLine { least_sag_m: Some(1.5), ..line() }, "least_sag_m must be 0 to sag_m (1.2 m"),
            (PowerLine { least_sag_m: Some(f64::NAN), ..line() }, "least_sag_m must be 0 to sag_m"),
            (PowerLine { swing_deg: Some(-5.0), ..line() }, "swing_deg must be 0 to 80 degrees"),
            (PowerLine { swing_deg: Some(85.0), ..line() }, "swing_deg must be 0 to 80 degrees"),
            (PowerLine { voltage_kv: 0.0, ..line() }, "voltage_kv must be positive"),
            (PowerLine { voltage_kv: 1_200.0, ..line() }, "give the approach distance its owner sets as approach_m"),
            (PowerLine { approach_m: Some(0.0), ..line() }, "approach_m must be more than 0"),
        ];
        for (l, said) in cases {
            let p = l.problem(0).unwrap_or_default();
            assert!(p.contains(said), "{said}: {p}");
        }
        assert_eq!(PowerLine { voltage_kv: 1_200.0, approach_m: Some(20.0), ..line() }.problem(0), None);
    }
}
