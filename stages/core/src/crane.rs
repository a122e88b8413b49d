//! Cranes: geometry files, placement on site, forward and inverse kinematics.
//!
//! A crane model is a TOML file (see `cranes/*.toml` or [`builtin`]) describing the
//! crane's boxes in its own frame: origin on the slewing axis at ground level, X
//! along the carrier's heading, Z up, metres. A [`CraneSetup`] places a model on
//! site for one lift (position, heading, boom length) and maps a configuration to
//! the OBB of every part, as in the thesis (ch. 4.2, 4.4.1: body, cockpit,
//! counterweight, boom, load) plus the carrier, outriggers, hoist rope and hook
//! block that a real site needs. A mobile crane's file may also give its
//! [`Masses`], from which [`crate::outriggers`] estimates its pad loads.
//!
//! A [`Config`] is the thesis' 4-DOF configuration in SI units:
//! * luffing mobile crane: (swing, luff angle, hoist rope length, load yaw);
//! * tower crane: (swing, trolley radius, hoist rope length, load yaw).
//!
//! `swing_rad` is measured counter-clockwise from the carrier's heading; the
//! load's yaw is absolute (site frame): it keeps its orientation while the crane
//! swings unless the riggers rotate it, as in the thesis' experiments.

use crate::frame::{Mat3, Point3, Vec3, rot_z};
use crate::location::{Location, toml_error};
use crate::obb::Obb;
use serde::{Deserialize, Serialize};
use std::path::Path;

#[derive(Debug, thiserror::Error)]
pub enum CraneError {
    #[error("{0}: {1}")]
    File(Location, String),
    #[error("unknown built-in crane '{0}' (built in: {1})")]
    UnknownBuiltin(String, String),
}

/// A box of a crane in its own frame (metres). `center_x_m`/`center_y_m` locate
/// its centre in plan, `base_z_m` its underside.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoxPart {
    pub length_m: f64,
    pub width_m: f64,
    pub height_m: f64,
    #[serde(default)]
    pub center_x_m: f64,
    #[serde(default)]
    pub center_y_m: f64,
    #[serde(default)]
    pub base_z_m: f64,
}

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Outriggers {
    /// Distance between pad centres along the carrier.
    pub spread_length_m: f64,
    /// Distance between pad centres across the carrier.
    pub spread_width_m: f64,
    #[serde(default = "default_outrigger_height")]
    pub height_m: f64,
}

fn default_outrigger_height() -> f64 {
    0.6
}

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Boom {
    /// Boom foot pin, along the slewing frame's X (negative: behind the axis).
    pub pivot_x_m: f64,
    pub pivot_z_m: f64,
    pub width_m: f64,
    pub depth_m: f64,
    pub min_length_m: f64,
    pub max_length_m: f64,
    pub luff_min_deg: f64,
    pub luff_max_deg: f64,
    /// Boom head beyond the sheave the rope hangs from.
    #[serde(default)]
    pub head_length_m: f64,
}

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HookBlock {
    pub height_m: f64,
    pub width_m: f64,
    pub mass_kg: f64,
    /// Shortest rope between sheave and hook block top (two-blocking limit).
    pub min_rope_m: f64,
    pub max_rope_m: f64,
    /// What the hook block is rated to carry (t); none: not checked.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rated_t: Option<f64>,
    /// What one fall (part of line) of the hoist rope may carry (t), as the
    /// crane's reeving table gives it; none: the falls are not checked
    /// ([`crate::reeving`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub line_pull_t: Option<f64>,
    /// The most falls the hook block's sheaves take.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_falls: Option<u32>,
    /// The main hoist rope's length that may be paid out (m): its length
    /// less the dead wraps that stay on the drum. With the lift's falls it
    /// sets how far the hook may hang below the boom head or a tower
    /// crane's trolley ([`crate::reeving::rope_reach_m`]); none: not
    /// checked. With [`Self::rope_lead_m`].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rope_m: Option<f64>,
    /// The hoist rope from the drum to the boom's foot (m): from there it
    /// runs the boom's length to the head. On a tower crane, from the drum
    /// to the jib's root: from there it runs out to the trolley and, past
    /// its falls, on to the jib's head, the jib's length in all wherever
    /// the trolley stands.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rope_lead_m: Option<f64>,
    /// The hoist rope's mass per metre (kg/m), as its data sheet gives it:
    /// the rope hanging below the boom head (or the trolley), on every
    /// fall, is part of the load ([`crate::reeving::RopeWeight`]); none:
    /// not counted, and said so.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rope_kg_per_m: Option<f64>,
    /// The hoist rope's diameter (mm), as its data sheet gives it: its falls
    /// catch the wind ([`crate::wind::RopeInWind`]); none: worked out from
    /// [`Self::rope_kg_per_m`] at its widest, or, without that, not counted,
    /// and said so.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rope_diameter_mm: Option<f64>,
}

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Speeds {
    pub swing_deg_s: f64,
    #[serde(default)]
    pub luff_deg_s: f64,
    #[serde(default)]
    pub trolley_m_s: f64,
    pub hoist_m_s: f64,
    #[serde(default = "default_rotate_speed")]
    pub rotate_deg_s: f64,
}

fn default_rotate_speed() -> f64 {
    3.0
}

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Mast {
    pub width_m: f64,
    /// Height of the jib's underside above the crane base.
    pub height_m: f64,
}

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Jib {
    pub length_m: f64,
    pub width_m: f64,
    pub depth_m: f64,
    pub trolley_min_m: f64,
    pub trolley_max_m: f64,
}

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CounterJib {
    pub length_m: f64,
    pub width_m: f64,
    pub depth_m: f64,
}

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Trolley {
    pub length_m: f64,
    pub width_m: f64,
    pub height_m: f64,
}

/// A mobile crane's masses, for its outrigger loads ([`crate::outriggers`]):
/// each at its part's box centre in the crane file, the boom's along its
/// axis. Optional in the crane file; no outrigger load is worked out
/// without them. Whoever writes them answers for them: a manufacturer's
/// outrigger load figures govern.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Masses {
    /// The carrier with its outrigger boxes, at the carrier box's centre (t).
    pub carrier_t: f64,
    /// The superstructure with its winches and cockpit, counterweight and
    /// boom not included, at the superstructure box's centre (t).
    pub superstructure_t: f64,
    /// The counterweight as rigged for the chart configuration lifted with,
    /// at the counterweight box's centre (t); a lift's `crane =
    /// { counterweight_t }` overrides it.
    pub counterweight_t: f64,
    /// The boom with its head (t).
    pub boom_t: f64,
    /// Where the boom's centre of gravity lies along it from its pivot, as a
    /// share of its length (0 to 1).
    pub boom_cog_frac: f64,
}

/// The crane file as written: every section optional, checked by [`CraneModel::from_raw`].
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCrane {
    name: String,
    kind: String,
    #[serde(default)]
    source: String,
    carrier: Option<BoxPart>,
    outriggers: Option<Outriggers>,
    superstructure: Option<BoxPart>,
    cockpit: Option<BoxPart>,
    counterweight: Option<BoxPart>,
    boom: Option<Boom>,
    mast: Option<Mast>,
    jib: Option<Jib>,
    counter_jib: Option<CounterJib>,
    cab: Option<BoxPart>,
    trolley: Option<Trolley>,
    masses: Option<Masses>,
    hook: HookBlock,
    speeds: Speeds,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LuffingCrane {
    pub carrier: BoxPart,
    pub outriggers: Outriggers,
    pub superstructure: BoxPart,
    pub cockpit: BoxPart,
    pub counterweight: BoxPart,
    pub boom: Boom,
    /// For the outrigger loads; `None` where the crane file gives none.
    pub masses: Option<Masses>,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TowerCrane {
    pub mast: Mast,
    pub jib: Jib,
    pub counter_jib: CounterJib,
    pub counterweight: BoxPart,
    pub cab: BoxPart,
    pub trolley: Trolley,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "lowercase")]
pub enum CraneKind {
    Luffing(LuffingCrane),
    Tower(TowerCrane),
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CraneModel {
    pub name: String,
    pub source: String,
    pub kind: CraneKind,
    pub hook: HookBlock,
    pub speeds: Speeds,
}

const BUILTINS: &[(&str, &str)] = &[
    ("ltm-1100", include_str!("cranes/ltm-1100.toml")),
    ("ac-700", include_str!("cranes/ac-700.toml")),
    ("tower-hh-60", include_str!("cranes/tower-hh-60.toml")),
];

/// Names of the built-in crane models.
pub fn builtin_names() -> Vec<&'static str> {
    BUILTINS.iter().map(|b| b.0).collect()
}

/// TOML text of a built-in crane model, for `init` to copy into `cranes/`.
pub fn builtin_text(name: &str) -> Option<&'static str> {
    BUILTINS.iter().find(|b| b.0 == name).map(|b| b.1)
}

/// A built-in crane model by name.
pub fn builtin(name: &str) -> Result<CraneModel, CraneError> {
    let text = builtin_text(name).ok_or_else(|| CraneError::UnknownBuiltin(name.into(), builtin_names().join(", ")))?;
    CraneModel::from_toml(Path::new(&format!("<built-in {name}>")), text)
}

impl CraneModel {
    pub fn from_toml(path: &Path, text: &str) -> Result<CraneModel, CraneError> {
        let raw: RawCrane = toml::from_str(text).map_err(|e| {
            let (loc, msg) = toml_error(path, text, &e);
            CraneError::File(loc, msg)
        })?;
        Self::from_raw(path, raw)
    }

    pub fn from_file(path: &Path) -> Result<CraneModel, CraneError> {
        let text = crate::location::read_text(path).map_err(|e| match e {
            crate::location::TextReadError::Io(e) => CraneError::File(Location::file(path), e.to_string()),
            crate::location::TextReadError::NotUtf8(at, why) => CraneError::File(at, why),
        })?;
        Self::from_toml(path, &text)
    }

    fn from_raw(path: &Path, r: RawCrane) -> Result<CraneModel, CraneError> {
        let err = |what: &str| CraneError::File(Location::file(path), what.to_string());
        let missing = |sec: &str| err(&format!("kind = \"{}\" needs a [{sec}] section", r.kind));
        let foreign = |present: &[(&str, bool)], other: &str| -> Result<(), CraneError> {
            match present.iter().find(|p| p.1) {
                Some((sec, _)) => {
                    Err(err(&format!("section [{sec}] belongs to a {other} crane, not kind = \"{}\"", r.kind)))
                }
                None => Ok(()),
            }
        };
        let kind = match r.kind.as_str() {
            "luffing" => {
                foreign(
                    &[
                        ("mast", r.mast.is_some()),
                        ("jib", r.jib.is_some()),
                        ("counter_jib", r.counter_jib.is_some()),
                        ("trolley", r.trolley.is_some()),
                        ("cab", r.cab.is_some()),
                    ],
                    "tower",
                )?;
                CraneKind::Luffing(LuffingCrane {
                    carrier: r.carrier.ok_or_else(|| missing("carrier"))?,
                    outriggers: r.outriggers.ok_or_else(|| missing("outriggers"))?,
                    superstructure: r.superstructure.ok_or_else(|| missing("superstructure"))?,
                    cockpit: r.cockpit.ok_or_else(|| missing("cockpit"))?,
                    counterweight: r.counterweight.ok_or_else(|| missing("counterweight"))?,
                    boom: r.boom.ok_or_else(|| missing("boom"))?,
                    masses: r.masses,
                })
            }
            "tower" => {
                foreign(
                    &[
                        ("carrier", r.carrier.is_some()),
                        ("outriggers", r.outriggers.is_some()),
                        ("superstructure", r.superstructure.is_some()),
                        ("cockpit", r.cockpit.is_some()),
                        ("boom", r.boom.is_some()),
                        ("masses", r.masses.is_some()),
                    ],
                    "luffing",
                )?;
                CraneKind::Tower(TowerCrane {
                    mast: r.mast.ok_or_else(|| missing("mast"))?,
                    jib: r.jib.ok_or_else(|| missing("jib"))?,
                    counter_jib: r.counter_jib.ok_or_else(|| missing("counter_jib"))?,
                    counterweight: r.counterweight.ok_or_else(|| missing("counterweight"))?,
                    cab: r.cab.ok_or_else(|| missing("cab"))?,
                    trolley: r.trolley.ok_or_else(|| missing("trolley"))?,
                })
            }
            other => {
                return Err(err(&format!("kind = \"{other}\": expected \"luffing\" or \"tower\"")));
            }
        };
        let m = CraneModel { name: r.name, source: r.source, kind, hook: r.hook, speeds: r.speeds };
        m.check().map_err(|e| err(&e))?;
        Ok(m)
    }

    /// Sanity of dimensions: positive sizes, ordered ranges, finite numbers.
    fn check(&self) -> Result<(), String> {
        let pos = |name: &str, v: f64| {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(format!("{name} must be a positive number of metres, found {v}"))
            }
        };
        let boxp = |name: &str, b: &BoxPart| -> Result<(), String> {
            pos(&format!("{name}.length_m"), b.length_m)?;
            pos(&format!("{name}.width_m"), b.width_m)?;
            pos(&format!("{name}.height_m"), b.height_m)?;
            if ![b.center_x_m, b.center_y_m, b.base_z_m].iter().all(|v| v.is_finite()) {
                return Err(format!("{name} has a non-finite position"));
            }
            Ok(())
        };
        pos("hook.height_m", self.hook.height_m)?;
        pos("hook.width_m", self.hook.width_m)?;
        if !(self.hook.mass_kg.is_finite() && self.hook.mass_kg >= 0.0) {
            return Err("hook.mass_kg must be >= 0".into());
        }
        if !(self.hook.min_rope_m >= 0.0 && self.hook.max_rope_m > self.hook.min_rope_m) {
            return Err("hook rope range must satisfy 0 <= min_rope_m < max_rope_m".into());
        }
        for (name, t) in [("hook.rated_t", self.hook.rated_t), ("hook.line_pull_t", self.hook.line_pull_t)] {
            if let Some(t) = t.filter(|t| !(t.is_finite() && *t > 0.0 && *t <= 10_000.0)) {
                return Err(format!("{name} must be more than 0 and at most 10000 t, found {t}"));
            }
        }
        if let Some(n) = self.hook.max_falls.filter(|n| !(1..=crate::reeving::MAX_FALLS).contains(n)) {
            return Err(format!("hook.max_falls must be 1 to {}, found {n}", crate::reeving::MAX_FALLS));
        }
        for (name, m) in [("hook.rope_m", self.hook.rope_m), ("hook.rope_lead_m", self.hook.rope_lead_m)] {
            if let Some(m) = m.filter(|m| !(m.is_finite() && *m >= 0.0 && *m <= 10_000.0)) {
                return Err(format!("{name} must be 0 to 10000 m, found {m}"));
            }
        }
        if let Some(w) = self.hook.rope_kg_per_m.filter(|w| !(w.is_finite() && *w > 0.0 && *w <= 100.0)) {
            return Err(format!("hook.rope_kg_per_m must be more than 0 and at most 100 kg/m, found {w}"));
        }
        if let Some(d) = self.hook.rope_diameter_mm.filter(|d| !(d.is_finite() && *d > 0.0 && *d <= 200.0)) {
            return Err(format!("hook.rope_diameter_mm must be more than 0 and at most 200 mm, found {d}"));
        }
        match (self.hook.rope_m, self.hook.rope_lead_m, &self.kind) {
            (Some(_), None, CraneKind::Tower(_)) => {
                return Err("hook.rope_m needs hook.rope_lead_m, the rope from the drum to the jib's root (m)".into());
            }
            (Some(_), None, _) => {
                return Err("hook.rope_m needs hook.rope_lead_m, the rope from the drum to the boom's foot (m)".into());
            }
            (None, Some(_), _) => return Err("hook.rope_lead_m is read only with hook.rope_m".into()),
            _ => {}
        }
        pos("speeds.swing_deg_s", self.speeds.swing_deg_s)?;
        pos("speeds.hoist_m_s", self.speeds.hoist_m_s)?;
        match &self.kind {
            CraneKind::Luffing(l) => {
                boxp("carrier", &l.carrier)?;
                boxp("superstructure", &l.superstructure)?;
                boxp("cockpit", &l.cockpit)?;
                boxp("counterweight", &l.counterweight)?;
                if let Some(m) = &l.masses {
                    for (name, t) in [
                        ("masses.carrier_t", m.carrier_t),
                        ("masses.superstructure_t", m.superstructure_t),
                        ("masses.counterweight_t", m.counterweight_t),
                        ("masses.boom_t", m.boom_t),
                    ] {
                        if !(t.is_finite() && (0.0..=10_000.0).contains(&t)) {
                            return Err(format!("{name} must be a mass in tonnes from 0 to 10000, found {t}"));
                        }
                    }
                    if !(m.boom_cog_frac > 0.0 && m.boom_cog_frac < 1.0) {
                        return Err(format!(
                            "masses.boom_cog_frac must lie between 0 and 1 (a share of the boom's length from its pivot), found {}",
                            m.boom_cog_frac
                        ));
                    }
                }
                pos("outriggers.spread_length_m", l.outriggers.spread_length_m)?;
                pos("outriggers.spread_width_m", l.outriggers.spread_width_m)?;
                pos("boom.width_m", l.boom.width_m)?;
                pos("boom.depth_m", l.boom.depth_m)?;
                pos("boom.min_length_m", l.boom.min_length_m)?;
                pos("speeds.luff_deg_s", self.speeds.luff_deg_s)?;
                if l.boom.max_length_m < l.boom.min_length_m {
                    return Err("boom.max_length_m is below boom.min_length_m".into());
                }
                if !(l.boom.luff_min_deg >= -5.0
                    && l.boom.luff_max_deg <= 89.0
                    && l.boom.luff_min_deg < l.boom.luff_max_deg)
                {
                    return Err("boom luff range must lie within -5..89 degrees, min below max".into());
                }
            }
            CraneKind::Tower(t) => {
                pos("mast.width_m", t.mast.width_m)?;
                pos("mast.height_m", t.mast.height_m)?;
                pos("jib.length_m", t.jib.length_m)?;
                pos("jib.width_m", t.jib.width_m)?;
                pos("jib.depth_m", t.jib.depth_m)?;
                pos("counter_jib.length_m", t.counter_jib.length_m)?;
                boxp("counterweight", &t.counterweight)?;
                boxp("cab", &t.cab)?;
                pos("trolley.length_m", t.trolley.length_m)?;
                pos("speeds.trolley_m_s", self.speeds.trolley_m_s)?;
                if !(t.jib.trolley_min_m >= 0.0
                    && t.jib.trolley_min_m < t.jib.trolley_max_m
                    && t.jib.trolley_max_m <= t.jib.length_m)
                {
                    return Err("jib trolley range must satisfy 0 <= trolley_min_m < trolley_max_m <= length_m".into());
                }
            }
        }
        Ok(())
    }

    pub fn is_tower(&self) -> bool {
        matches!(self.kind, CraneKind::Tower(_))
    }

    /// The words the plan's text uses for this kind of crane's parts and
    /// motions: a tower crane's PDF must not speak of its outriggers.
    pub fn words(&self) -> CraneWords {
        if self.is_tower() {
            CraneWords {
                arm: "jib",
                radial_axis: "trolley",
                radial_motion: "trolleying",
                heading: "the crane's heading (the lift's heading_deg, the crane model's +X axis along the jib)",
                moving_structure: "jib, counter-jib and trolley",
                body: "the jib, counter-jib, counterweight or cab",
                radial_part: "the trolley",
                set_up: "foundation, mast and its ties, counterweight",
                support_loads: "the loads on the crane's foundation and ties",
            }
        } else {
            CraneWords {
                arm: "boom",
                radial_axis: "luff",
                radial_motion: "luffing",
                heading: "the carrier's heading (the lift's heading_deg, the crane model's +X axis)",
                moving_structure: "boom and superstructure",
                body: "the superstructure, cockpit or counterweight",
                radial_part: "the boom",
                set_up: "ground bearing, outriggers, counterweight",
                support_loads: "ground bearing pressure and outrigger loads",
            }
        }
    }
}

/// Names for a crane's parts and motions in the plan's text ([`CraneModel::words`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CraneWords {
    /// What reaches out and carries the hook: "boom" or "jib".
    pub arm: &'static str,
    /// The joint that sets the radius: "luff" or "trolley".
    pub radial_axis: &'static str,
    /// The motion that changes the radius: "luffing" or "trolleying".
    pub radial_motion: &'static str,
    /// What swing is measured from.
    pub heading: &'static str,
    /// What moves with swing besides what hangs, as one phrase.
    pub moving_structure: &'static str,
    /// What turns with swing alone (the C-space picture's red).
    pub body: &'static str,
    /// What moves with the radius too (the C-space picture's orange).
    pub radial_part: &'static str,
    /// What to check of the set-up on site.
    pub set_up: &'static str,
    /// The loads the crane puts on what it stands on, which the plan does not work out.
    pub support_loads: &'static str,
}

/// Where a crane stands for a lift, in the site frame.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Placement {
    /// Slewing axis at ground level.
    pub x_m: f64,
    pub y_m: f64,
    pub z_m: f64,
    /// Carrier heading, counter-clockwise from site +X.
    pub heading_rad: f64,
    /// Main boom length for this lift (luffing cranes; ignored for tower cranes).
    pub boom_length_m: f64,
}

/// A crane configuration (see the module docs for the meaning per crane kind).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Config {
    pub swing_rad: f64,
    /// Luff angle above horizontal (rad) for a luffing crane; trolley radius (m)
    /// for a tower crane.
    pub radial: f64,
    /// Rope length from the sheave to the top of the hook block (m).
    pub hoist_m: f64,
    /// Absolute yaw of the load in the site frame (rad).
    pub load_yaw_rad: f64,
}

impl Config {
    pub fn to_array(&self) -> [f64; 4] {
        [self.swing_rad, self.radial, self.hoist_m, self.load_yaw_rad]
    }
    pub fn from_array(a: [f64; 4]) -> Config {
        Config { swing_rad: a[0], radial: a[1], hoist_m: a[2], load_yaw_rad: a[3] }
    }
}

/// The crane parts liftplan checks.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PartKind {
    Carrier,
    Outriggers,
    Superstructure,
    Cockpit,
    Counterweight,
    Boom,
    Mast,
    Jib,
    CounterJib,
    Cab,
    Trolley,
    Rope,
    HookBlock,
    /// Slings and spreader between the hook block and the load: a box over the
    /// load's footprint, from the load's top to the hook block's underside.
    Rigging,
    Load,
}

/// How high above the level the crane is set up on the scanned ground may
/// be and still be the ground it stands on (m): uneven ground, mats, kerbs
/// ([`CraneSetup::standing_ground_top_z`]).
pub const STANDING_GROUND_M: f64 = 0.5;

/// Which joints a part's pose depends on; the hybrid C-space precomputes the
/// first three classes and checks `Full` online.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dependence {
    Fixed,
    Swing,
    SwingRadial,
    Full,
}

impl PartKind {
    pub fn name(self) -> &'static str {
        match self {
            PartKind::Carrier => "carrier",
            PartKind::Outriggers => "outriggers",
            PartKind::Superstructure => "superstructure",
            PartKind::Cockpit => "cockpit",
            PartKind::Counterweight => "counterweight",
            PartKind::Boom => "boom",
            PartKind::Mast => "mast",
            PartKind::Jib => "jib",
            PartKind::CounterJib => "counter-jib",
            PartKind::Cab => "cab",
            PartKind::Trolley => "trolley",
            PartKind::Rope => "hoist rope",
            PartKind::HookBlock => "hook block",
            PartKind::Rigging => "rigging",
            PartKind::Load => "load",
        }
    }

    pub fn dependence(self) -> Dependence {
        match self {
            PartKind::Carrier | PartKind::Outriggers | PartKind::Mast => Dependence::Fixed,
            PartKind::Superstructure
            | PartKind::Cockpit
            | PartKind::Counterweight
            | PartKind::Jib
            | PartKind::CounterJib
            | PartKind::Cab => Dependence::Swing,
            PartKind::Boom | PartKind::Trolley => Dependence::SwingRadial,
            PartKind::Rope | PartKind::HookBlock | PartKind::Rigging | PartKind::Load => Dependence::Full,
        }
    }
}

/// The load as the crane carries it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LoadShape {
    /// Box size along the load's own x, y, z (m).
    pub size_m: [f64; 3],
    /// Centre of gravity relative to the box centre, in the load frame (m).
    pub cog_m: [f64; 3],
    /// Hook block underside to the top of the load (slings, spreader) (m).
    pub rigging_height_m: f64,
}

impl LoadShape {
    /// Radius of the vertical cylinder about the hook line that holds the load
    /// at any yaw.
    pub fn yaw_invariant_radius(&self) -> f64 {
        let hx = self.size_m[0] / 2.0;
        let hy = self.size_m[1] / 2.0;
        let (cx, cy) = (self.cog_m[0], self.cog_m[1]);
        [(hx, hy), (hx, -hy), (-hx, hy), (-hx, -hy)]
            .iter()
            .map(|(x, y)| ((x - cx).powi(2) + (y - cy).powi(2)).sqrt())
            .fold(0.0, f64::max)
    }

    /// Radius of the sphere about the load centre that holds it (r_TG, eq. 4.31).
    pub fn bounding_radius(&self) -> f64 {
        0.5 * (self.size_m[0].powi(2) + self.size_m[1].powi(2) + self.size_m[2].powi(2)).sqrt()
    }
}

/// The rope from the sheave down to the hook.
fn rope_below(sheave: Point3, slew: Mat3, c: &Config) -> Obb {
    let h = c.hoist_m.max(0.0);
    Obb::new(Point3::new(sheave.x, sheave.y, sheave.z - h / 2.0), slew, Vec3::new(0.05, 0.05, h / 2.0))
}

/// The slings and spreader: the load's footprint, `rigging_height_m` tall, on top of it.
fn rigging_above(l: &Obb, load: &LoadShape) -> Obb {
    let h = load.rigging_height_m.max(0.0);
    let mut b = Obb::new(l.center + Vec3::z() * (l.half.z + h / 2.0), l.axes, l.half);
    b.half.z = h / 2.0;
    b
}

/// A load pose: box-centre plan position, underside height and yaw (site frame).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LoadPose {
    pub x_m: f64,
    pub y_m: f64,
    /// Height of the load's underside.
    pub z_m: f64,
    pub yaw_rad: f64,
}

/// Joint ranges of a crane set up for a lift.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct JointLimits {
    /// `None`: the crane slews freely through 360 degrees.
    pub swing_rad: Option<(f64, f64)>,
    pub radial: (f64, f64),
    pub hoist_m: (f64, f64),
}

#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum IkError {
    #[error("the hook would be {radius_m:.2} m from the slewing axis; this crane reaches {min_m:.2} to {max_m:.2} m")]
    OutOfReach { radius_m: f64, min_m: f64, max_m: f64 },
    /// The load's underside at `z_m` would need a rope of `hoist_m`; at the
    /// same radius the rope's range hangs it from `lowest_z_m` to
    /// `highest_z_m`.
    #[error(
        "the load's underside at z = {z_m:.2} m is out of the hook's reach there: at this radius, with the hook block, rigging and load below the rope, it can hang from z = {lowest_z_m:.2} to {highest_z_m:.2} m (rope {min_m:.2} to {max_m:.2} m; it would need {hoist_m:.2} m)"
    )]
    RopeOutOfRange { z_m: f64, hoist_m: f64, min_m: f64, max_m: f64, lowest_z_m: f64, highest_z_m: f64 },
}

/// A crane model placed on site for one lift.
#[derive(Debug, Clone, PartialEq)]
pub struct CraneSetup {
    pub model: CraneModel,
    pub placement: Placement,
}

/// The crane's parts at one configuration.
#[derive(Debug, Clone)]
pub struct CranePose {
    pub parts: Vec<(PartKind, Obb)>,
}

impl CranePose {
    pub fn get(&self, kind: PartKind) -> Option<&Obb> {
        self.parts.iter().find(|p| p.0 == kind).map(|p| &p.1)
    }
}

impl CraneSetup {
    pub fn new(model: CraneModel, placement: Placement) -> Result<CraneSetup, String> {
        if let CraneKind::Luffing(l) = &model.kind {
            let b = placement.boom_length_m;
            if !(b >= l.boom.min_length_m - 1e-9 && b <= l.boom.max_length_m + 1e-9) {
                return Err(format!(
                    "boom length {b} m is outside the {} boom range {}..{} m",
                    model.name, l.boom.min_length_m, l.boom.max_length_m
                ));
            }
        }
        let p = placement;
        if ![p.x_m, p.y_m, p.z_m, p.heading_rad].iter().all(|v| v.is_finite()) {
            return Err("crane position and heading must be finite numbers".into());
        }
        Ok(CraneSetup { model, placement })
    }

    /// How far the superstructure of a mobile crane reaches from its
    /// slewing axis in plan (m), and which of its parts (superstructure,
    /// cockpit, counterweight) reaches that far: the circle its tail sweeps
    /// as it slews, which people are kept out of. `None` for a tower crane,
    /// whose slewing parts turn high overhead.
    pub fn tail_swing_m(&self) -> Option<(f64, PartKind)> {
        if self.model.is_tower() {
            return None;
        }
        let at = Config { swing_rad: 0.0, radial: 0.0, hoist_m: 0.0, load_yaw_rad: 0.0 };
        let load = LoadShape { size_m: [1.0; 3], cog_m: [0.0; 3], rigging_height_m: 0.0 };
        [PartKind::Superstructure, PartKind::Cockpit, PartKind::Counterweight]
            .into_iter()
            .filter_map(|k| Some((self.plan_reach_m(&self.part(k, &at, &load)?), k)))
            .max_by(|a, b| a.0.total_cmp(&b.0))
    }

    /// How far in plan the farthest corner of `b` lies from the slewing
    /// axis (m): how far a swing of one radian moves it, at most.
    pub fn plan_reach_m(&self, b: &crate::obb::Obb) -> f64 {
        let o = self.slew_center();
        b.corners().iter().map(|p| ((p.x - o.x).powi(2) + (p.y - o.y).powi(2)).sqrt()).fold(0.0, f64::max)
    }

    /// An upper bound on how far in plan any part that turns with the
    /// swing reaches from the slewing axis (m), at any configuration: the
    /// boom or jib out to its head with the trolley, rope and hook block,
    /// and the superstructure's boxes; not the load or its rigging. Worked
    /// out from the crane file's sizes alone, for a cheap first test before
    /// the parts are placed ([`crate::lift::LiftTask::not_over_near`]).
    pub fn swinging_reach_m(&self) -> f64 {
        // A box's corners lie within |x| + |y| of its centre's offsets
        // and half sizes.
        let boxed = |b: &BoxPart| b.center_x_m.abs() + b.length_m / 2.0 + b.center_y_m.abs() + b.width_m / 2.0;
        let hook = self.model.hook.width_m;
        let parts = match &self.model.kind {
            CraneKind::Luffing(l) => {
                // Along the boom, from its foot pin out to its head, its
                // axis lies pivot_x_m + s·cos(luff) from the slewing axis.
                let head = l.boom.pivot_x_m + self.placement.boom_length_m + l.boom.head_length_m;
                let boom = head.abs().max(l.boom.pivot_x_m.abs()) + (l.boom.width_m + l.boom.depth_m) / 2.0;
                [boxed(&l.superstructure), boxed(&l.cockpit), boxed(&l.counterweight), boom + hook]
            }
            CraneKind::Tower(t) => {
                let out = t.jib.length_m.max(t.jib.trolley_max_m + t.trolley.length_m / 2.0 + hook);
                let jib = out + t.jib.width_m.max(t.trolley.width_m).max(hook) / 2.0;
                let counter_jib = t.counter_jib.length_m + t.counter_jib.width_m / 2.0;
                [jib, counter_jib, boxed(&t.counterweight), boxed(&t.cab)]
            }
        };
        parts.into_iter().fold(0.0, f64::max)
    }

    pub fn slew_center(&self) -> Point3 {
        Point3::new(self.placement.x_m, self.placement.y_m, self.placement.z_m)
    }

    /// The highest the scanned ground may be and still be the ground the
    /// crane stands on (m, site frame): the set-up level plus
    /// [`STANDING_GROUND_M`]. The carrier, outriggers and mast stand on the
    /// ground, so none of it is an obstacle for them; the superstructure and
    /// what turns with it swing just above it, so ground up to this height
    /// is not one for them either, while a bank rising above it is. The
    /// planner and the validator both apply this rule.
    pub fn standing_ground_top_z(&self) -> f64 {
        self.placement.z_m + STANDING_GROUND_M
    }

    /// Horizontal unit vector of the boom/jib at `swing_rad`.
    pub fn boom_dir(&self, swing_rad: f64) -> Vec3 {
        let a = self.placement.heading_rad + swing_rad;
        Vec3::new(a.cos(), a.sin(), 0.0)
    }

    /// Height of the rope sheave above the slewing base, and the hook radius, at
    /// a radial joint value.
    pub fn sheave_height_and_radius(&self, radial: f64) -> (f64, f64) {
        match &self.model.kind {
            CraneKind::Luffing(l) => {
                let len = self.placement.boom_length_m;
                (l.boom.pivot_z_m + len * radial.sin(), l.boom.pivot_x_m + len * radial.cos())
            }
            CraneKind::Tower(t) => (t.mast.height_m - t.trolley.height_m, radial),
        }
    }

    /// Working radius (m): horizontal distance from the slewing axis to the hook.
    pub fn radius_m(&self, radial: f64) -> f64 {
        self.sheave_height_and_radius(radial).1
    }

    /// The rope sheave point in the site frame.
    pub fn sheave(&self, c: &Config) -> Point3 {
        let (h, r) = self.sheave_height_and_radius(c.radial);
        self.slew_center() + self.boom_dir(c.swing_rad) * r + Vec3::z() * h
    }

    /// Joint ranges from the crane's geometry alone; the load chart narrows the
    /// radial range further (see the charts stage).
    pub fn limits(&self) -> JointLimits {
        let hoist = (self.model.hook.min_rope_m, self.model.hook.max_rope_m);
        match &self.model.kind {
            CraneKind::Luffing(l) => JointLimits {
                swing_rad: None,
                radial: (l.boom.luff_min_deg.to_radians(), l.boom.luff_max_deg.to_radians()),
                hoist_m: hoist,
            },
            CraneKind::Tower(t) => {
                JointLimits { swing_rad: None, radial: (t.jib.trolley_min_m, t.jib.trolley_max_m), hoist_m: hoist }
            }
        }
    }

    /// The load box at a configuration.
    pub fn load_obb(&self, c: &Config, load: &LoadShape) -> Obb {
        self.load_below(self.sheave(c), c, load)
    }

    /// Load, rigging, hook block and rope at one configuration, in that order:
    /// the boxes [`Self::part`] gives for them, from one evaluation of the
    /// sheave and the rotations (the planner checks these at every sample).
    pub fn hanging_parts(&self, c: &Config, load: &LoadShape) -> [(PartKind, Obb); 4] {
        let s = self.sheave(c);
        let slew = rot_z(self.placement.heading_rad + c.swing_rad);
        let l = self.load_below(s, c, load);
        [
            (PartKind::Load, l),
            (PartKind::Rigging, rigging_above(&l, load)),
            (PartKind::HookBlock, self.hook_block_below(s, slew, c)),
            (PartKind::Rope, rope_below(s, slew, c)),
        ]
    }

    fn hook_block_below(&self, sheave: Point3, slew: Mat3, c: &Config) -> Obb {
        let hook = &self.model.hook;
        Obb::new(
            Point3::new(sheave.x, sheave.y, sheave.z - c.hoist_m - hook.height_m / 2.0),
            slew,
            Vec3::new(hook.width_m / 2.0, hook.width_m / 2.0, hook.height_m / 2.0),
        )
    }

    fn load_below(&self, s: Point3, c: &Config, load: &LoadShape) -> Obb {
        let drop = c.hoist_m + self.model.hook.height_m + load.rigging_height_m + load.size_m[2] / 2.0;
        let r = rot_z(c.load_yaw_rad);
        let cog = r * Vec3::new(load.cog_m[0], load.cog_m[1], 0.0);
        Obb::new(
            Point3::new(s.x - cog.x, s.y - cog.y, s.z - drop),
            r,
            Vec3::new(load.size_m[0] / 2.0, load.size_m[1] / 2.0, load.size_m[2] / 2.0),
        )
    }

    /// Underside height of the load at a configuration.
    pub fn load_bottom_z(&self, c: &Config, load: &LoadShape) -> f64 {
        let s = self.sheave(c);
        s.z - c.hoist_m - self.model.hook.height_m - load.rigging_height_m - load.size_m[2]
    }

    /// One part's box at a configuration, or `None` if this crane has no such part.
    pub fn part(&self, kind: PartKind, c: &Config, load: &LoadShape) -> Option<Obb> {
        let o = self.slew_center();
        let fixed = rot_z(self.placement.heading_rad);
        let slew = rot_z(self.placement.heading_rad + c.swing_rad);
        let place_box = |b: &BoxPart, r: &Mat3| {
            let local = Vec3::new(b.center_x_m, b.center_y_m, b.base_z_m + b.height_m / 2.0);
            Obb::new(o + r * local, *r, Vec3::new(b.length_m / 2.0, b.width_m / 2.0, b.height_m / 2.0))
        };
        match (&self.model.kind, kind) {
            (_, PartKind::Load) => Some(self.load_obb(c, load)),
            (_, PartKind::Rigging) => Some(rigging_above(&self.load_obb(c, load), load)),
            (_, PartKind::Rope) => Some(rope_below(self.sheave(c), slew, c)),
            (_, PartKind::HookBlock) => Some(self.hook_block_below(self.sheave(c), slew, c)),
            (CraneKind::Luffing(l), PartKind::Carrier) => Some(place_box(&l.carrier, &fixed)),
            (CraneKind::Luffing(l), PartKind::Outriggers) => {
                let g = &l.outriggers;
                let b = BoxPart {
                    length_m: g.spread_length_m + 0.8,
                    width_m: g.spread_width_m + 0.8,
                    height_m: g.height_m,
                    center_x_m: l.carrier.center_x_m,
                    center_y_m: 0.0,
                    base_z_m: 0.0,
                };
                Some(place_box(&b, &fixed))
            }
            (CraneKind::Luffing(l), PartKind::Superstructure) => Some(place_box(&l.superstructure, &slew)),
            (CraneKind::Luffing(l), PartKind::Cockpit) => Some(place_box(&l.cockpit, &slew)),
            (CraneKind::Luffing(l), PartKind::Counterweight) => Some(place_box(&l.counterweight, &slew)),
            (CraneKind::Luffing(l), PartKind::Boom) => {
                let d = self.boom_dir(c.swing_rad);
                let u = d * c.radial.cos() + Vec3::z() * c.radial.sin();
                let pivot = o + slew * Vec3::new(l.boom.pivot_x_m, 0.0, l.boom.pivot_z_m);
                let len = self.placement.boom_length_m + l.boom.head_length_m;
                let side = Vec3::new(-d.y, d.x, 0.0);
                let up = u.cross(&side);
                Some(Obb::new(
                    pivot + u * (len / 2.0),
                    Mat3::from_columns(&[u, side, up]),
                    Vec3::new(len / 2.0, l.boom.width_m / 2.0, l.boom.depth_m / 2.0),
                ))
            }
            (CraneKind::Tower(t), PartKind::Mast) => {
                let b = BoxPart {
                    length_m: t.mast.width_m,
                    width_m: t.mast.width_m,
                    height_m: t.mast.height_m,
                    center_x_m: 0.0,
                    center_y_m: 0.0,
                    base_z_m: 0.0,
                };
                Some(place_box(&b, &fixed))
            }
            (CraneKind::Tower(t), PartKind::Jib) => {
                let b = BoxPart {
                    length_m: t.jib.length_m,
                    width_m: t.jib.width_m,
                    height_m: t.jib.depth_m,
                    center_x_m: t.jib.length_m / 2.0,
                    center_y_m: 0.0,
                    base_z_m: t.mast.height_m,
                };
                Some(place_box(&b, &slew))
            }
            (CraneKind::Tower(t), PartKind::CounterJib) => {
                let g = &t.counter_jib;
                let b = BoxPart {
                    length_m: g.length_m,
                    width_m: g.width_m,
                    height_m: g.depth_m,
                    center_x_m: -g.length_m / 2.0,
                    center_y_m: 0.0,
                    base_z_m: t.mast.height_m,
                };
                Some(place_box(&b, &slew))
            }
            (CraneKind::Tower(t), PartKind::Counterweight) => Some(place_box(&t.counterweight, &slew)),
            (CraneKind::Tower(t), PartKind::Cab) => Some(place_box(&t.cab, &slew)),
            (CraneKind::Tower(t), PartKind::Trolley) => {
                let tr = &t.trolley;
                let b = BoxPart {
                    length_m: tr.length_m,
                    width_m: tr.width_m,
                    height_m: tr.height_m,
                    center_x_m: c.radial,
                    center_y_m: 0.0,
                    base_z_m: t.mast.height_m - tr.height_m,
                };
                Some(place_box(&b, &slew))
            }
            _ => None,
        }
    }

    /// The parts this crane has, in a fixed order.
    pub fn part_kinds(&self) -> &'static [PartKind] {
        match self.model.kind {
            CraneKind::Luffing(_) => &[
                PartKind::Carrier,
                PartKind::Outriggers,
                PartKind::Superstructure,
                PartKind::Cockpit,
                PartKind::Counterweight,
                PartKind::Boom,
                PartKind::Rope,
                PartKind::HookBlock,
                PartKind::Rigging,
                PartKind::Load,
            ],
            CraneKind::Tower(_) => &[
                PartKind::Mast,
                PartKind::Jib,
                PartKind::CounterJib,
                PartKind::Counterweight,
                PartKind::Cab,
                PartKind::Trolley,
                PartKind::Rope,
                PartKind::HookBlock,
                PartKind::Rigging,
                PartKind::Load,
            ],
        }
    }

    /// Every part at a configuration.
    pub fn pose(&self, c: &Config, load: &LoadShape) -> CranePose {
        CranePose { parts: self.part_kinds().iter().filter_map(|&k| self.part(k, c, load).map(|o| (k, o))).collect() }
    }

    /// Inverse kinematics: the configuration that holds the load at `pose`.
    ///
    /// The boom length is fixed for a lift, so the solution is unique: swing from
    /// the hook's bearing, radial joint from the hook's radius, rope length from the
    /// load's height. Swing is returned in (-pi, pi].
    pub fn inverse(&self, pose: &LoadPose, load: &LoadShape) -> Result<Config, IkError> {
        let r = rot_z(pose.yaw_rad);
        let cog = r * Vec3::new(load.cog_m[0], load.cog_m[1], 0.0);
        let hook = Point3::new(pose.x_m + cog.x, pose.y_m + cog.y, 0.0);
        let o = self.slew_center();
        let (dx, dy) = (hook.x - o.x, hook.y - o.y);
        let radius = (dx * dx + dy * dy).sqrt();
        let swing = crate::units::wrap_pi(dy.atan2(dx) - self.placement.heading_rad);
        let lim = self.limits();
        let radial = match &self.model.kind {
            CraneKind::Luffing(l) => {
                let len = self.placement.boom_length_m;
                let (rmin, rmax) = (self.radius_m(lim.radial.1), self.radius_m(lim.radial.0));
                let cosv = (radius - l.boom.pivot_x_m) / len;
                if !(radius >= rmin - 1e-9 && radius <= rmax + 1e-9) || !(-1.0..=1.0).contains(&cosv) {
                    return Err(IkError::OutOfReach { radius_m: radius, min_m: rmin, max_m: rmax });
                }
                cosv.clamp(-1.0, 1.0).acos()
            }
            CraneKind::Tower(t) => {
                if !(radius >= t.jib.trolley_min_m - 1e-9 && radius <= t.jib.trolley_max_m + 1e-9) {
                    return Err(IkError::OutOfReach {
                        radius_m: radius,
                        min_m: t.jib.trolley_min_m,
                        max_m: t.jib.trolley_max_m,
                    });
                }
                radius
            }
        };
        let (h, _) = self.sheave_height_and_radius(radial);
        let hoist = o.z + h - self.model.hook.height_m - load.rigging_height_m - load.size_m[2] - pose.z_m;
        if !(hoist >= lim.hoist_m.0 - 1e-9 && hoist <= lim.hoist_m.1 + 1e-9) {
            return Err(IkError::RopeOutOfRange {
                z_m: pose.z_m,
                hoist_m: hoist,
                min_m: lim.hoist_m.0,
                max_m: lim.hoist_m.1,
                lowest_z_m: pose.z_m - (lim.hoist_m.1 - hoist),
                highest_z_m: pose.z_m + (hoist - lim.hoist_m.0),
            });
        }
        Ok(Config { swing_rad: swing, radial, hoist_m: hoist, load_yaw_rad: pose.yaw_rad })
    }

    /// The load pose at a configuration (forward kinematics of the load).
    pub fn load_pose(&self, c: &Config, load: &LoadShape) -> LoadPose {
        let b = self.load_obb(c, load);
        LoadPose { x_m: b.center.x, y_m: b.center.y, z_m: b.center.z - load.size_m[2] / 2.0, yaw_rad: c.load_yaw_rad }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mobile() -> CraneSetup {
        let m = builtin("ltm-1100").unwrap();
        CraneSetup::new(m, Placement { x_m: 10.0, y_m: -5.0, z_m: 0.5, heading_rad: 0.3, boom_length_m: 40.0 }).unwrap()
    }

    fn load() -> LoadShape {
        LoadShape { size_m: [4.0, 2.0, 3.0], cog_m: [0.3, -0.2, 0.0], rigging_height_m: 4.0 }
    }

    /// The ltm-1100's counterweight, 1.6 m long and 3.0 m wide centred
    /// 3.8 m behind the slewing axis, reaches farthest: its back corners,
    /// √(4.6² + 1.5²) m out, at every swing and wherever the crane stands.
    #[test]
    fn the_tail_swing_is_the_counterweights_back_corners() {
        let c = mobile();
        let (r, part) = c.tail_swing_m().unwrap();
        assert_eq!(part, PartKind::Counterweight);
        assert!((r - (4.6f64 * 4.6 + 1.5 * 1.5).sqrt()).abs() < 1e-9, "{r}");
        for swing in [0.4, 2.0, -2.9] {
            let at = Config { swing_rad: swing, radial: 0.5, hoist_m: 10.0, load_yaw_rad: 0.0 };
            let far = c.plan_reach_m(&c.part(PartKind::Counterweight, &at, &load()).unwrap());
            assert!((far - r).abs() < 1e-9, "{far} at {swing}");
        }
        let tower = CraneSetup::new(builtin("tower-hh-60").unwrap(), c.placement).unwrap();
        assert_eq!(tower.tail_swing_m(), None);
    }

    /// No part that swings reaches farther than the bound at any swing,
    /// luff or trolley radius and rope in the cranes' limits, nor is the
    /// bound far beyond the farthest they reach.
    #[test]
    fn the_swinging_reach_bounds_every_swinging_part() {
        let tower = CraneSetup::new(builtin("tower-hh-60").unwrap(), mobile().placement).unwrap();
        for crane in [mobile(), tower] {
            let (lim, bound) = (crane.limits(), crane.swinging_reach_m());
            let mut farthest: f64 = 0.0;
            for k in 0..=40 {
                let t = k as f64 / 40.0;
                let at = Config {
                    swing_rad: 7.0 * t - 3.0,
                    radial: lim.radial.0 + (lim.radial.1 - lim.radial.0) * t,
                    hoist_m: lim.hoist_m.0 + (lim.hoist_m.1 - lim.hoist_m.0) * (1.0 - t),
                    load_yaw_rad: 0.0,
                };
                for kind in crane.part_kinds() {
                    if kind.dependence() == Dependence::Fixed || matches!(kind, PartKind::Load | PartKind::Rigging) {
                        continue;
                    }
                    farthest = farthest.max(crane.plan_reach_m(&crane.part(*kind, &at, &load()).unwrap()));
                }
            }
            assert!(farthest <= bound && bound < farthest + 3.0, "{}: {farthest} against {bound}", crane.model.name);
        }
    }

    #[test]
    fn builtins_parse() {
        for n in builtin_names() {
            let m = builtin(n).unwrap();
            assert!(!m.source.is_empty(), "{n} must say where its dimensions come from");
        }
    }

    /// A crane file's masses are checked; a tower crane has none.
    #[test]
    fn masses_are_checked() {
        let ac = builtin_text("ac-700").unwrap();
        let bad = ac.replace("boom_cog_frac = 0.4", "boom_cog_frac = 1.4");
        let e = CraneModel::from_toml(Path::new("c.toml"), &bad).unwrap_err().to_string();
        assert!(e.contains("masses.boom_cog_frac must lie between 0 and 1"), "{e}");
        let bad = ac.replace("boom_t = 38.0", "boom_t = -38.0");
        let e = CraneModel::from_toml(Path::new("c.toml"), &bad).unwrap_err().to_string();
        assert!(e.contains("masses.boom_t must be a mass in tonnes"), "{e}");
        let masses = &ac[ac.find("[masses]").unwrap()..ac.find("[hook]").unwrap()];
        let tower = builtin_text("tower-hh-60").unwrap().replace("[speeds]", &format!("{masses}[speeds]"));
        let e = CraneModel::from_toml(Path::new("t.toml"), &tower).unwrap_err().to_string();
        assert!(e.contains("section [masses] belongs to a luffing crane"), "{e}");
    }

    /// The hook block's rating, line pull and falls, and the hoist rope's
    /// length, where a crane file gives them, are read and checked.
    #[test]
    fn the_hook_blocks_reeving_is_read_and_checked() {
        let ac = builtin("ac-700").unwrap();
        assert_eq!((ac.hook.rated_t, ac.hook.line_pull_t, ac.hook.max_falls), (Some(100.0), Some(10.0), Some(10)));
        assert_eq!((ac.hook.rope_m, ac.hook.rope_lead_m), (Some(600.0), Some(20.0)));
        assert_eq!(builtin("ltm-1100").unwrap().hook.line_pull_t, None);
        let text = builtin_text("ac-700").unwrap();
        for (from, to, said) in [
            ("line_pull_t = 10.0", "line_pull_t = 0.0", "hook.line_pull_t must be more than 0"),
            ("rated_t = 100.0", "rated_t = inf", "hook.rated_t must be more than 0"),
            ("max_falls = 10", "max_falls = 0", "hook.max_falls must be 1 to 64"),
            ("max_falls = 10", "max_falls = 65", "hook.max_falls must be 1 to 64"),
            ("rope_m = 600.0", "rope_m = -1.0", "hook.rope_m must be 0 to 10000 m, found -1"),
            ("rope_lead_m = 20.0", "rope_lead_m = nan", "hook.rope_lead_m must be 0 to 10000 m"),
            ("rope_lead_m = 20.0\n", "", "hook.rope_m needs hook.rope_lead_m"),
            ("rope_m = 600.0\n", "", "hook.rope_lead_m is read only with hook.rope_m"),
        ] {
            let e = CraneModel::from_toml(Path::new("c.toml"), &text.replace(from, to)).unwrap_err().to_string();
            assert!(e.contains(said), "{to}: {e}");
        }
        assert_eq!(ac.hook.rope_kg_per_m, Some(3.9));
        for bad in ["0.0", "-3.9", "nan", "101.0"] {
            let weighed = text.replace("rope_kg_per_m = 3.9", &format!("rope_kg_per_m = {bad}"));
            let e = CraneModel::from_toml(Path::new("c.toml"), &weighed).unwrap_err().to_string();
            assert!(e.contains("hook.rope_kg_per_m must be more than 0 and at most 100 kg/m"), "{bad}: {e}");
        }
        assert_eq!(ac.hook.rope_diameter_mm, Some(28.0));
        for bad in ["0.0", "-28.0", "inf", "201.0"] {
            let wide = text.replace("rope_diameter_mm = 28.0", &format!("rope_diameter_mm = {bad}"));
            let e = CraneModel::from_toml(Path::new("c.toml"), &wide).unwrap_err().to_string();
            assert!(e.contains("hook.rope_diameter_mm must be more than 0 and at most 200 mm"), "{bad}: {e}");
        }
        let tower = builtin_text("tower-hh-60").unwrap();
        let hook_end = tower.find("[hook]").map(|k| k + "[hook]\n".len()).unwrap();
        let weighed = format!("{}rope_kg_per_m = 1.6\n{}", &tower[..hook_end], &tower[hook_end..]);
        assert_eq!(CraneModel::from_toml(Path::new("t.toml"), &weighed).unwrap().hook.rope_kg_per_m, Some(1.6));
        // A tower crane's rope runs from the drum to the jib's root.
        let roped = format!("{}rope_m = 300.0\nrope_lead_m = 10.0\n{}", &tower[..hook_end], &tower[hook_end..]);
        let t = CraneModel::from_toml(Path::new("t.toml"), &roped).unwrap();
        assert_eq!((t.hook.rope_m, t.hook.rope_lead_m), (Some(300.0), Some(10.0)));
        let unled = format!("{}rope_m = 300.0\n{}", &tower[..hook_end], &tower[hook_end..]);
        let e = CraneModel::from_toml(Path::new("t.toml"), &unled).unwrap_err().to_string();
        assert!(e.contains("hook.rope_m needs hook.rope_lead_m, the rope from the drum to the jib's root (m)"), "{e}");
    }

    #[test]
    fn hanging_parts_are_the_parts() {
        let c = mobile();
        for q in [
            Config { swing_rad: 0.0, radial: 0.5, hoist_m: 12.0, load_yaw_rad: 0.0 },
            Config { swing_rad: -2.7, radial: 1.2, hoist_m: 3.5, load_yaw_rad: 1.1 },
            Config { swing_rad: 7.0, radial: 0.2, hoist_m: 40.0, load_yaw_rad: -0.4 },
        ] {
            for (kind, b) in c.hanging_parts(&q, &load()) {
                assert_eq!(Some(b), c.part(kind, &q, &load()), "{kind:?} at {q:?}");
            }
        }
    }

    #[test]
    fn ik_fk_roundtrip_luffing() {
        let c = mobile();
        for (x, y, z, yaw) in [(30.0, 10.0, 1.0, 0.4), (0.0, 12.0, 5.0, -2.0), (-15.0, -20.0, 0.0, 3.0)] {
            let p = LoadPose { x_m: x, y_m: y, z_m: z, yaw_rad: yaw };
            let q = c.inverse(&p, &load()).unwrap();
            let back = c.load_pose(&q, &load());
            assert!(
                (back.x_m - x).abs() < 1e-9 && (back.y_m - y).abs() < 1e-9 && (back.z_m - z).abs() < 1e-9,
                "{back:?}"
            );
            assert!((back.yaw_rad - yaw).abs() < 1e-12);
        }
    }

    #[test]
    fn radius_falls_as_luff_rises() {
        let c = mobile();
        let mut last = f64::INFINITY;
        for deg in (0..=80).step_by(5) {
            let r = c.radius_m((deg as f64).to_radians());
            assert!(r < last);
            last = r;
        }
        // At 0 degrees the hook hangs a full boom length beyond the pivot.
        let CraneKind::Luffing(l) = &c.model.kind else { panic!() };
        assert!((c.radius_m(0.0) - (l.boom.pivot_x_m + 40.0)).abs() < 1e-12);
    }

    #[test]
    fn out_of_reach_is_an_error() {
        let c = mobile();
        let e = c.inverse(&LoadPose { x_m: 200.0, y_m: 0.0, z_m: 0.0, yaw_rad: 0.0 }, &load()).unwrap_err();
        assert!(matches!(e, IkError::OutOfReach { .. }));
        let e = c.inverse(&LoadPose { x_m: 30.0, y_m: 0.0, z_m: 80.0, yaw_rad: 0.0 }, &load()).unwrap_err();
        let IkError::RopeOutOfRange { highest_z_m, .. } = e else { panic!("{e}") };
        // The highest it reaches, it is solved at, on the shortest rope.
        let top = c.inverse(&LoadPose { x_m: 30.0, y_m: 0.0, z_m: highest_z_m, yaw_rad: 0.0 }, &load()).unwrap();
        assert!((top.hoist_m - c.limits().hoist_m.0).abs() < 1e-9);
        assert!(e.to_string().contains("the load's underside at z = 80.00 m is out of the hook's reach there"), "{e}");
    }

    #[test]
    fn tower_roundtrip() {
        let m = builtin("tower-hh-60").unwrap();
        let c = CraneSetup::new(m, Placement { x_m: 0.0, y_m: 0.0, z_m: 0.0, heading_rad: 0.0, boom_length_m: 0.0 })
            .unwrap();
        let p = LoadPose { x_m: 20.0, y_m: 25.0, z_m: 3.0, yaw_rad: 1.0 };
        let q = c.inverse(&p, &load()).unwrap();
        let back = c.load_pose(&q, &load());
        assert!((back.x_m - 20.0).abs() < 1e-9 && (back.z_m - 3.0).abs() < 1e-9);
        assert!(c.pose(&q, &load()).get(PartKind::Trolley).is_some());
    }

    #[test]
    fn boom_box_spans_pivot_to_tip() {
        let c = mobile();
        let q = Config { swing_rad: 0.5, radial: 0.9, hoist_m: 10.0, load_yaw_rad: 0.0 };
        let boom = c.part(PartKind::Boom, &q, &load()).unwrap();
        let s = c.sheave(&q);
        // The sheave lies on the boom's axis, inside the box.
        assert!(boom.contains(&s));
        let hook = c.part(PartKind::HookBlock, &q, &load()).unwrap();
        assert!((hook.center.z - (s.z - 10.0 - c.model.hook.height_m / 2.0)).abs() < 1e-9);
    }

    #[test]
    fn bad_files_name_the_line() {
        let e =
            CraneModel::from_toml(Path::new("c.toml"), "name = \"x\"\nkind = \"luffing\"\nbogus = 1\n").unwrap_err();
        assert!(e.to_string().contains("c.toml:"), "{e}");
        let text = builtin_text("ltm-1100").unwrap().replace("kind = \"luffing\"", "kind = \"crawler\"");
        let e = CraneModel::from_toml(Path::new("c.toml"), &text).unwrap_err();
        assert!(e.to_string().contains("expected \"luffing\" or \"tower\""), "{e}");
    }
}
