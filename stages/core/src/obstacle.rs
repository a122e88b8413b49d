//! Obstacles placed by hand: what is on site now that neither the scans nor
//! the plant model hold.
//!
//! A delivery truck parked since the survey, a scaffold, stacked materials,
//! a site cabin: the engineer gives each as a box in the project file, and
//! the planner and the validator keep the crane and its load off it as they
//! keep them off the scans (by the lift's `clearance_m`), naming it
//! ("obstacle 'delivery truck'"). This is how a lift is re-planned when the
//! site has changed: add what is new, run again, and only the plan and its
//! document are made again (the scans, the model and the depth map are not
//! read anew).
//!
//! A box is a box: it is not checked against the scans (one given where a
//! scanned truck stands doubles it, which is safe), and it holds up a load
//! at the pick or set only as anything else under it does (its top within
//! `[plan] support_m` of the load's underside).

use crate::frame::{Point3, Vec3, rot_z};
use crate::obb::Obb;
use serde::{Deserialize, Serialize};

/// The most obstacles a project may give: each is checked at every
/// configuration the planner checks.
pub const MAX_OBSTACLES: usize = 200;
/// The longest side an obstacle may have (m): more is a size in millimetres.
pub const MAX_OBSTACLE_SIDE_M: f64 = 500.0;
/// The longest name (characters): the PDF says it.
pub const MAX_OBSTACLE_NAME: usize = 100;
/// How far from the site's origin an obstacle may stand (m): more than any
/// projected coordinate (a site in survey coordinates gives its northing,
/// millions of metres), so more is no place on site.
pub const MAX_OBSTACLE_OFFSET_M: f64 = 100_000_000.0;

/// One obstacle: a box standing `base_z_m` up, `size_m` long, wide and
/// high, its length along `yaw_deg` (anticlockwise from the site's x axis),
/// centred on `center_m` in plan. In the site frame, as the lifts' picks and
/// sets are.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Obstacle {
    pub name: String,
    /// Its centre in plan, [x, y] (m).
    pub center_m: [f64; 2],
    /// The height of its underside (m): the ground's where it stands on it.
    pub base_z_m: f64,
    /// Length (along `yaw_deg`), width and height (m).
    pub size_m: [f64; 3],
    #[serde(default)]
    pub yaw_deg: f64,
    /// The lifts it stands there for, by id (a truck that leaves after the
    /// first); empty: every lift.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub lifts: Vec<String>,
}

impl Obstacle {
    /// Why it is not an obstacle a project can give (`k`: its place in the
    /// file's list, from 0), naming the key.
    pub fn problem(&self, k: usize) -> Option<String> {
        let name = &self.name;
        if let Some(p) = name_problem("obstacle", k, name, MAX_OBSTACLE_NAME, "what it is: \"delivery truck\"") {
            return Some(p);
        }
        let finite = |v: &[f64]| v.iter().all(|x| x.is_finite());
        if !finite(&self.center_m) || !finite(&[self.base_z_m, self.yaw_deg]) {
            return Some(format!(
                "obstacle '{name}': center_m, base_z_m and yaw_deg must be finite numbers (metres, degrees)"
            ));
        }
        if self.center_m.iter().chain([&self.base_z_m]).any(|v| v.abs() > MAX_OBSTACLE_OFFSET_M) {
            return Some(format!(
                "obstacle '{name}' stands more than {MAX_OBSTACLE_OFFSET_M} m from the site's origin: give it in the frame of the lifts' pick and set"
            ));
        }
        if !self.size_m.iter().all(|s| s.is_finite() && *s > 0.0 && *s <= MAX_OBSTACLE_SIDE_M) {
            return Some(format!(
                "obstacle '{name}': size_m must be its length, width and height, each more than 0 and at most {MAX_OBSTACLE_SIDE_M} m, found {:?}",
                self.size_m
            ));
        }
        None
    }

    /// Its box in the site frame.
    pub fn obb(&self) -> Obb {
        let [l, w, h] = self.size_m;
        Obb::new(
            Point3::new(self.center_m[0], self.center_m[1], self.base_z_m + h / 2.0),
            rot_z(self.yaw_deg.to_radians()),
            Vec3::new(l / 2.0, w / 2.0, h / 2.0),
        )
    }

    /// Whether it stands there during lift `id`.
    pub fn during(&self, id: &str) -> bool {
        there_during(&self.lifts, id)
    }

    /// What the planner, the validator and their messages call it.
    pub fn called(&self) -> String {
        format!("obstacle '{}'", self.name)
    }

    /// It in words, for the PDF and the run's output, to the centimetre as
    /// the pick and set are: "delivery truck, 10.00 x 2.50 x 4.00 m at x
    /// 12.00, y -4.00 m, underside at z 0.00 m, turned 30.0°".
    pub fn said(&self) -> String {
        let [l, w, h] = self.size_m;
        let turned = if self.yaw_deg == 0.0 { String::new() } else { format!(", turned {:.1}°", self.yaw_deg) };
        format!(
            "{}, {l:.2} x {w:.2} x {h:.2} m at x {:.2}, y {:.2} m, underside at z {:.2} m{turned}",
            self.name, self.center_m[0], self.center_m[1], self.base_z_m
        )
    }
}

/// The first problem of a project's obstacles, if any: too many, one that
/// is not an obstacle, two of one name (a message naming it would not say
/// which), or one for a lift the project does not have (`lift_ids`).
pub fn problem_of(obstacles: &[Obstacle], lift_ids: &[&str]) -> Option<(usize, String)> {
    if obstacles.len() > MAX_OBSTACLES {
        return Some((
            MAX_OBSTACLES,
            format!("{} obstacles: a project gives at most {MAX_OBSTACLES}", obstacles.len()),
        ));
    }
    for (k, o) in obstacles.iter().enumerate() {
        if let Some(p) = o.problem(k) {
            return Some((k, p));
        }
        let before = obstacles[..k].iter().map(|e| e.name.as_str());
        if let Some(p) = name_or_lifts_problem("obstacle", &o.name, before, &o.lifts, lift_ids) {
            return Some((k, p));
        }
    }
    None
}

/// Of the `k`-th (from 0) of a project's `key` list of things given by hand
/// (`[[obstacle]]`, `[[power_line]]`): a name that is blank or longer than
/// `max` characters (`example`: what a name says, and one).
pub fn name_problem(key: &str, k: usize, name: &str, max: usize, example: &str) -> Option<String> {
    if name.trim().is_empty() {
        return Some(format!("{key}[{k}] needs a name ({example})"));
    }
    (name.chars().count() > max).then(|| format!("{key}[{k}]'s name is longer than {max} characters"))
}

/// Whether a thing given by hand for the lifts `lifts` (by id; none: every
/// lift) is there during lift `id`.
pub fn there_during(lifts: &[String], id: &str) -> bool {
    lifts.is_empty() || lifts.iter().any(|l| l == id)
}

/// Of one thing in a project's list of things given by hand (`what`:
/// "obstacle", "power line"): named as one `before` it (a message naming it
/// would not say which), or given for a lift the project does not have
/// (`lift_ids`).
pub fn name_or_lifts_problem<'a>(
    what: &str,
    name: &str,
    mut before: impl Iterator<Item = &'a str>,
    lifts: &[String],
    lift_ids: &[&str],
) -> Option<String> {
    if before.any(|n| n == name) {
        return Some(format!("{what} '{name}' is named twice: give each its own name"));
    }
    let l = lifts.iter().find(|l| !lift_ids.contains(&l.as_str()))?;
    Some(format!(
        "{what} '{name}' is for lift '{l}', which the project does not have ({})",
        if lift_ids.is_empty() { "it has none".to_string() } else { format!("its lifts: {}", lift_ids.join(", ")) }
    ))
}

/// The obstacles that stand there during lift `id`, as the named boxes the
/// planner and the validator keep off.
pub fn boxes_during(obstacles: &[Obstacle], id: &str) -> Vec<(Obb, String)> {
    obstacles.iter().filter(|o| o.during(id)).map(|o| (o.obb(), o.called())).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn truck() -> Obstacle {
        Obstacle {
            name: "delivery truck".into(),
            center_m: [12.0, -4.0],
            base_z_m: 0.5,
            size_m: [10.0, 2.5, 4.0],
            yaw_deg: 90.0,
            lifts: vec![],
        }
    }

    #[test]
    fn an_obstacles_box_stands_on_its_base_along_its_yaw() {
        let a = truck().obb().aabb();
        // Turned 90°: its length runs along y.
        for (got, want) in a.min.iter().zip([10.75, -9.0, 0.5]).chain(a.max.iter().zip([13.25, 1.0, 4.5])) {
            assert!((got - want).abs() < 1e-9, "{a:?}");
        }
        assert_eq!(
            truck().said(),
            "delivery truck, 10.00 x 2.50 x 4.00 m at x 12.00, y -4.00 m, underside at z 0.50 m, turned 90.0°"
        );
        assert_eq!(boxes_during(&[truck()], "L-1")[0].1, "obstacle 'delivery truck'");
        // One that leaves after the first lift.
        let first_only = Obstacle { lifts: vec!["L-1".into()], ..truck() };
        assert_eq!(boxes_during(std::slice::from_ref(&first_only), "L-1").len(), 1);
        assert!(boxes_during(&[first_only], "L-2").is_empty());
    }

    #[test]
    fn obstacles_that_are_not_boxes_on_site_are_refused_by_name() {
        assert_eq!(problem_of(&[truck()], &[]), None);
        let with = |f: fn(&mut Obstacle)| {
            let mut o = truck();
            f(&mut o);
            problem_of(&[truck_named("first"), o], &["L-1", "L-2"]).expect("refused")
        };
        let (k, why) = with(|o| o.size_m[2] = 0.0);
        assert_eq!(k, 1);
        assert!(why.contains("obstacle 'delivery truck': size_m") && why.contains("[10.0, 2.5, 0.0]"), "{why}");
        assert!(with(|o| o.size_m[0] = 4000.0).1.contains("at most 500"));
        assert!(with(|o| o.center_m[1] = f64::NAN).1.contains("finite"));
        assert!(with(|o| o.center_m[0] = 2e8).1.contains("frame of the lifts' pick and set"));
        // A site in survey coordinates: its northing is millions of metres.
        assert_eq!(
            problem_of(&[Obstacle { center_m: [512_345.0, 5_412_345.0], base_z_m: 102.0, ..truck() }], &[]),
            None
        );
        assert!(with(|o| o.name = " ".into()).1.contains("obstacle[1] needs a name"));
        assert!(with(|o| o.name = "first".into()).1.contains("'first' is named twice"));
        let lift_3 = with(|o| o.lifts = vec!["L-1".into(), "L-3".into()]).1;
        assert!(
            lift_3.contains("is for lift 'L-3', which the project does not have (its lifts: L-1, L-2)"),
            "{lift_3}"
        );
        let many = vec![truck(); MAX_OBSTACLES + 1];
        assert!(problem_of(&many, &[]).unwrap().1.contains("at most 200"));
    }

    fn truck_named(name: &str) -> Obstacle {
        Obstacle { name: name.into(), ..truck() }
    }
}
