//! The wind speed up to which a mobile crane may lift a given load.
//!
//! A mobile crane's load chart gives one permissible wind speed for a
//! configuration (EN 13000): it holds for a load of up to 1.2 m² of wind
//! area per tonne of hook load. A load that catches more wind (a vessel, a
//! panel, a roof truss) may be lifted only at a lower speed, which the
//! crane manufacturers' rule (Liebherr's "method 2", the same in their
//! operating manuals) gives as
//!
//! ```text
//! v_max = v_chart · √(1.2 m²/t · m_H / A_W),   A_W = A_P · c_W
//! ```
//!
//! with `m_H` the hook load in tonnes (load, slings, hook block), `A_P` the
//! load's projected area facing the wind and `c_W` its drag coefficient;
//! where that comes out above the chart's speed, the chart's governs. The
//! 1.2 is the chart's assumption, not a drag coefficient.
//!
//! The chart's speed is that of the 3-second gust at the boom head, where a
//! mobile crane's anemometer sits. A forecast gives the 10-minute mean wind
//! at 10 m above the ground; EN 13000 relates the two by the gust's height
//! profile
//!
//! ```text
//! v(z) = [(z / 10 m)^0.14 + 0.4] · v_10
//! ```
//!
//! so the highest the lift raises the boom head gives the mean wind at
//! 10 m that gusts to the permissible speed there ([`gust_factor`]).
//!
//! The wind also pushes the hanging load off plumb. Held steadily by the
//! wind's force on it, `F = q · A_W` with `q = ρ v² / 2` (EN 13000's air
//! density, 1.25 kg/m³), against its weight `m_H g`, the load hangs at
//! `tan θ = F / (m_H g)` from the vertical, so `ℓ · tan θ` off plumb at
//! `ℓ` below the boom head ([`PermissibleWind::off_plumb_m`]); a gust that
//! arrives suddenly can swing it up to twice as far (a pendulum given a
//! sudden steady push, [`PermissibleWind::gust_swing_per_m`]), which the
//! plan keeps its clearance with unless the lift turns that off
//! ([`crate::lift::LiftTask::hanging_swept`]).
//! At the permissible speed of a load that catches more wind than the
//! chart holds for, `tan θ` is the same for every load: the reduction keeps
//! `v² A_W / m_H` at the chart's.
//!
//! The wind pushes on the hoist rope's falls too ([`RopeInWind`]): `n`
//! falls of diameter `d` hanging up to `ℓ` below the boom head catch
//! `A_R = n · d · ℓ · c_R` (a wire rope's drag coefficient [`ROPE_CW`]).
//! Pushed evenly along its length, a rope of length `r` hanging from the
//! head leans out at its end by what half that push at the end would give,
//! so anything hanging `s ≥ r` below the head lies at most
//! `(F s + f r² / 2) / (m_H g)` off plumb (`f` the push per metre of rope),
//! and `tan θ = ρ v² (A_W + A_R / 2) / (2 m_H g)` per metre bounds it for
//! every rope up to `ℓ`: the rope itself, leaning out most at its end, is
//! covered by its end's. The rope's weight, which steadies it, is left out
//! of `m_H`, the worse for it; the permissible speed is the manufacturer's
//! rule's, which counts the load's area alone (the rope is the crane's, in
//! its chart's own wind calculation).
//!
//! This module only works out those speeds. It must not decide whether a lift
//! may go ahead: the wind on site on the day is the crane driver's to read,
//! and the manufacturer's wind rules govern.

use crate::units::G_M_S2;
use serde::{Deserialize, Serialize};

/// Wind area per tonne of hook load a mobile crane's chart speed holds
/// for (m²/t).
pub const CHART_AREA_PER_TONNE_M2: f64 = 1.2;

/// The fastest wind speed a chart's sheet is read to state (m/s): a number
/// with a speed's unit beyond it is not a permissible wind speed (a
/// hurricane's is 33 m/s), and read back from `chart.json` it is refused
/// ([`crate::chart_json`]).
pub const MAX_CHART_WIND_MS: f64 = 100.0;

/// EN 13000's air density for the wind's pressure (kg/m³).
pub const AIR_DENSITY_KG_M3: f64 = 1.25;

/// A wire rope's drag coefficient (EN 13001-2's and ISO 4302's for ropes).
pub const ROPE_CW: f64 = 1.2;

/// The least mass per metre a steel wire rope has for its diameter
/// squared (kg/m per mm²): about 0.0036 for a six-strand rope on a fibre
/// core, 0.0040 on a steel core, 0.0045 to 0.0052 for the compacted and
/// rotation-resistant ropes of mobile cranes. Where the crane file gives
/// the rope's mass per metre and not its diameter, the diameter is worked
/// out at this, the widest a rope of that mass may be, so its wind is not
/// under-counted.
pub const LIGHTEST_ROPE_KG_PER_M_MM2: f64 = 0.0034;

/// The hoist rope's falls in the wind (the module's doc).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RopeInWind {
    /// The falls counted: the lift's (`crane falls`), or where it gives
    /// none, the most the hook block's sheaves take (`[hook] max_falls`).
    pub falls: u32,
    pub falls_given: bool,
    /// The rope's diameter (mm).
    pub diameter_mm: f64,
    /// Whether the crane file gives it (`[hook] rope_diameter_mm`), or it is
    /// worked out from the rope's mass per metre
    /// ([`LIGHTEST_ROPE_KG_PER_M_MM2`]).
    pub diameter_given: bool,
    /// The longest rope below the boom head the lift is planned with (m).
    pub longest_m: f64,
    /// `falls · diameter · longest_m · ROPE_CW` (m²).
    pub wind_area_m2: f64,
}

impl RopeInWind {
    /// `falls` falls of `diameter_mm` hanging up to `longest_m`.
    pub fn new(falls: u32, falls_given: bool, diameter_mm: f64, diameter_given: bool, longest_m: f64) -> RopeInWind {
        RopeInWind {
            falls,
            falls_given,
            diameter_mm,
            diameter_given,
            longest_m,
            wind_area_m2: f64::from(falls) * diameter_mm / 1000.0 * longest_m * ROPE_CW,
        }
    }

    /// The diameter of a steel wire rope of `kg_per_m`, at its widest
    /// ([`LIGHTEST_ROPE_KG_PER_M_MM2`]), in mm.
    pub fn widest_diameter_mm(kg_per_m: f64) -> f64 {
        (kg_per_m / LIGHTEST_ROPE_KG_PER_M_MM2).sqrt()
    }

    /// In words: "the hoist rope's 6 falls of 28 mm, up to 35.0 m below the
    /// boom head, catch A_R = 7.1 m² at cW 1.2".
    pub fn said(&self) -> String {
        let falls = crate::reeving::falls_counted_said(self.falls, self.falls_given);
        let diameter = if self.diameter_given {
            format!("{:.0} mm", self.diameter_mm)
        } else {
            format!(
                "{:.0} mm (the widest a steel wire rope of its mass per metre is, hook.rope_kg_per_m; the crane file gives no hook.rope_diameter_mm)",
                self.diameter_mm
            )
        };
        format!(
            "the hoist rope's {falls} of {diameter}, up to {:.1} m below the boom head, catch A_R = {:.1} m² at cW {ROPE_CW}",
            self.longest_m, self.wind_area_m2
        )
    }
}

/// EN 13000's 3-second gust at `height_m` above the ground over the
/// 10-minute mean wind speed at 10 m: (z / 10 m)^0.14 + 0.4, heights under
/// 10 m taken as 10 m (1.4 there).
pub fn gust_factor(height_m: f64) -> f64 {
    (height_m.max(10.0) / 10.0).powf(0.14) + 0.4
}

/// A load box's largest side facing the wind, its length and height (m),
/// from its size (length, width, height): its area where the lift gives
/// none.
pub fn largest_side_m(size_m: [f64; 3]) -> [f64; 2] {
    [size_m[0].max(size_m[1]), size_m[2]]
}

/// A lift's `wind`: what the chart allows and what the load catches.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WindSpec {
    /// The permissible wind speed the load chart gives for the
    /// configuration (m/s); where left out, the one its sheet states.
    #[serde(default)]
    pub chart_ms: Option<f64>,
    /// The load's drag coefficient.
    pub cw: f64,
    /// The load's projected area facing the wind (m²); where left out, its
    /// box's largest side.
    #[serde(default)]
    pub area_m2: Option<f64>,
    /// Whether the plan keeps its clearance with what hangs from the crane
    /// swung as far as a sudden gust at the permissible speed can swing it
    /// ([`PermissibleWind::gust_swing_per_m`]); on unless turned off.
    #[serde(default = "plan_for_swing_by_default")]
    pub plan_for_swing: bool,
}

fn plan_for_swing_by_default() -> bool {
    true
}

impl WindSpec {
    /// Why the values are not ones a lift can have, naming the key.
    pub fn problem(&self) -> Option<String> {
        let ok = |v: f64, hi: f64| v.is_finite() && v > 0.0 && v <= hi;
        if let Some(v) = self.chart_ms
            && !ok(v, 50.0)
        {
            return Some(format!("wind chart_ms must be a wind speed in m/s, above 0 and at most 50, found {v}"));
        }
        if !ok(self.cw, 5.0) {
            return Some(format!(
                "wind cw must be a drag coefficient above 0 and at most 5 (1.2 to 2.4 for most loads), found {}",
                self.cw
            ));
        }
        match self.area_m2 {
            Some(a) if !ok(a, 10_000.0) => {
                Some(format!("wind area_m2 must be an area in m², above 0 and at most 10000, found {a}"))
            }
            _ => None,
        }
    }
}

/// The permissible wind speed for a load, and what it was worked out from.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PermissibleWind {
    pub chart_ms: f64,
    /// Where the chart's speed was read from its sheet (`Sheet!A41`), not
    /// given by the lift.
    pub chart_cell: Option<String>,
    pub cw: f64,
    /// The projected area (m²), and where it is the box's largest side,
    /// that side's length and height (m).
    pub area_m2: f64,
    pub box_side_m: Option<[f64; 2]>,
    /// Load, slings and hook block (kg).
    pub hook_load_kg: f64,
    /// `area_m2 · cw` (m²).
    pub wind_area_m2: f64,
    /// The speed the load may be lifted up to (m/s): the chart's or less.
    pub permissible_ms: f64,
    /// The highest the boom head rises in the lift, above the ground the
    /// crane stands on (m), where the plan is known.
    #[serde(default)]
    pub boom_head_m: Option<f64>,
    /// The longest the load hangs below the boom head in the lift, from the
    /// sheave to the load's underside (m), where the plan is known.
    #[serde(default)]
    pub longest_hang_m: Option<f64>,
    /// The hoist rope's falls in the wind, where counted.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rope: Option<RopeInWind>,
    /// Why the rope's wind is not counted, where it is not and that was asked.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rope_not_counted: Option<String>,
}

impl PermissibleWind {
    /// Works it out for the chart's speed `chart_ms` (read from `chart_cell`
    /// where the sheet states it), `spec`'s drag and area, a load box of
    /// `size_m` (length, width, height) and a hook load of `hook_load_kg`.
    pub fn of(
        chart_ms: f64,
        chart_cell: Option<String>,
        spec: &WindSpec,
        size_m: [f64; 3],
        hook_load_kg: f64,
    ) -> PermissibleWind {
        let side = largest_side_m(size_m);
        let (area_m2, box_side_m) = match spec.area_m2 {
            Some(a) => (a, None),
            None => (side[0] * side[1], Some(side)),
        };
        let wind_area_m2 = area_m2 * spec.cw;
        let reduced = chart_ms * (CHART_AREA_PER_TONNE_M2 * hook_load_kg / 1000.0 / wind_area_m2).sqrt();
        PermissibleWind {
            chart_ms,
            chart_cell,
            cw: spec.cw,
            area_m2,
            box_side_m,
            hook_load_kg,
            wind_area_m2,
            permissible_ms: reduced.min(chart_ms),
            boom_head_m: None,
            longest_hang_m: None,
            rope: None,
            rope_not_counted: None,
        }
    }

    /// This with the hoist rope's falls in the wind, or why they are not
    /// counted.
    pub fn with_rope(self, rope: Result<RopeInWind, String>) -> PermissibleWind {
        let (rope, rope_not_counted) = match rope {
            Ok(r) => (Some(r), None),
            Err(why) => (None, Some(why)),
        };
        PermissibleWind { rope, rope_not_counted, ..self }
    }

    /// How far off plumb the permissible wind holds the load steadily, per
    /// metre it hangs below the boom head: `tan θ = ρ v² A_W / (2 m_H g)`,
    /// with half the hoist rope's area added to `A_W` where it is counted
    /// (the module's doc).
    pub fn off_plumb_per_m(&self) -> f64 {
        let area_m2 = self.wind_area_m2 + self.rope.as_ref().map_or(0.0, |r| r.wind_area_m2 / 2.0);
        0.5 * AIR_DENSITY_KG_M3 * self.permissible_ms.powi(2) * area_m2 / (self.hook_load_kg * G_M_S2)
    }

    /// How far a sudden gust at the permissible wind can swing what hangs,
    /// per metre it hangs below the boom head: twice the steady push's
    /// [`Self::off_plumb_per_m`] (a pendulum given a sudden steady push
    /// swings out to twice where the push holds it).
    pub fn gust_swing_per_m(&self) -> f64 {
        2.0 * self.off_plumb_per_m()
    }

    /// How far off plumb (m) the permissible wind holds the load's underside
    /// at the longest it hangs in the lift, where that is known; a sudden
    /// gust can swing it up to twice as far.
    pub fn off_plumb_m(&self) -> Option<f64> {
        self.longest_hang_m.map(|l| l * self.off_plumb_per_m())
    }

    /// The 10-minute mean wind speed at 10 m above the ground that gusts to
    /// the permissible speed at the highest the boom head rises (m/s), where
    /// that height is known ([`gust_factor`]).
    pub fn mean_at_10m_ms(&self) -> Option<f64> {
        self.boom_head_m.map(|z| self.permissible_ms / gust_factor(z))
    }

    /// Whether the load catches more wind than the chart's speed holds for.
    pub fn reduced(&self) -> bool {
        self.permissible_ms < self.chart_ms
    }

    /// In words, for the PDF.
    pub fn said(&self) -> String {
        self.said_with("")
    }

    /// [`Self::said`] with `also` (a clause opening with "; ") before the
    /// closing words that the manufacturer's rules govern.
    pub fn said_with(&self, also: &str) -> String {
        let area = match self.box_side_m {
            Some([l, h]) => format!("{:.1} m² of its box's largest side, {l:.2} x {h:.2} m,", self.area_m2),
            None => format!("{:.1} m² (wind area_m2)", self.area_m2),
        };
        let per_tonne = self.wind_area_m2 / (self.hook_load_kg / 1000.0);
        let from = self.chart_cell.as_ref().map(|c| format!(" ({c})")).unwrap_or_default();
        let at_height = match (self.boom_head_m, self.mean_at_10m_ms()) {
            (Some(z), Some(mean)) => format!(
                "; it is the 3 s gust at the boom head, which rises to {z:.1} m above the crane's ground in this lift, where a 10-minute mean wind of {mean:.1} m/s at 10 m above the ground gusts to {:.1} m/s (EN 13000's profile, v(z) = [(z/10 m)^0.14 + 0.4] · v_10)",
                self.permissible_ms
            ),
            _ => String::new(),
        };
        let rope = match (&self.rope, &self.rope_not_counted) {
            (Some(r), _) => format!("; {}", r.said()),
            (None, Some(why)) => format!("; the wind on the hoist rope is not counted: {why}"),
            (None, None) => String::new(),
        };
        let formula = if self.rope.is_some() { "ρ v² (A_W + A_R / 2) / (2 m_H g)" } else { "ρ v² A_W / (2 m_H g)" };
        let off_plumb = match (self.longest_hang_m, self.off_plumb_m()) {
            (Some(l), Some(x)) => format!(
                "; at that speed the wind holds the load {x:.2} m off plumb where it hangs longest in this lift, {l:.1} m below the boom head, and a sudden gust can swing it {:.2} m (tan θ = {formula}, ρ = {AIR_DENSITY_KG_M3} kg/m³)",
                2.0 * x
            ),
            _ => String::new(),
        };
        format!(
            "{}: the chart's {:.1} m/s{from} holds for up to {CHART_AREA_PER_TONNE_M2:.1} m² of wind area per tonne of hook load; this load catches {:.1} m² ({area} at cW {:.2}) on {:.1} t, {per_tonne:.2} m² per tonne (v = v_chart · √(1.2 m²/t · m_H / A_W)){at_height}{rope}{off_plumb}{also}; the crane manufacturer's wind rules govern",
            if self.reduced() {
                format!("AT MOST {:.1} m/s FOR THIS LOAD, less than the chart's", self.permissible_ms)
            } else {
                format!("at most {:.1} m/s, the chart's", self.permissible_ms)
            },
            self.chart_ms,
            self.wind_area_m2,
            self.cw,
            self.hook_load_kg / 1000.0
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The manufacturer's two worked examples: a standard load (85 t, 50 m²
    /// at cW 1.2, chart 9 m/s: 11.73 m/s, so the chart's 9 m/s governs) and
    /// a large one (65 t, 200 m² at cW 1.4, chart 11.1 m/s: 5.86 m/s).
    #[test]
    fn the_worked_examples_come_out() {
        let standard = PermissibleWind::of(
            9.0,
            None,
            &WindSpec { chart_ms: None, cw: 1.2, area_m2: Some(50.0), plan_for_swing: true },
            [1.0; 3],
            85_000.0,
        );
        assert_eq!(standard.permissible_ms, 9.0);
        assert!(!standard.reduced());
        let unreduced = 9.0 * (1.2f64 * 85.0 / 60.0).sqrt();
        assert!((unreduced - 11.73).abs() < 5e-3, "{unreduced}");
        let large = PermissibleWind::of(
            11.1,
            None,
            &WindSpec { chart_ms: None, cw: 1.4, area_m2: Some(200.0), plan_for_swing: true },
            [1.0; 3],
            65_000.0,
        );
        assert!((large.permissible_ms - 5.86).abs() < 5e-3 && large.reduced(), "{large:?}");
        assert!(large.said().starts_with("AT MOST 5.9 m/s FOR THIS LOAD, less than the chart's: the chart's 11.1 m/s holds for up to 1.2 m² of wind area per tonne of hook load; this load catches 280.0 m² (200.0 m² (wind area_m2) at cW 1.40) on 65.0 t, 4.31 m² per tonne"), "{}", large.said());
        // Without an area, the box's largest side: 8 x 3 m of an 8 x 3 x 3 m box.
        let vessel = PermissibleWind::of(
            9.8,
            Some("Main!A41".into()),
            &WindSpec { chart_ms: None, cw: 1.2, area_m2: None, plan_for_swing: true },
            [3.0, 8.0, 3.0],
            12_900.0,
        );
        assert_eq!((vessel.area_m2, vessel.box_side_m), (24.0, Some([8.0, 3.0])));
        assert!((vessel.permissible_ms - 9.8 * (1.2f64 * 12.9 / 28.8).sqrt()).abs() < 1e-12);
        assert!(
            vessel.said().contains("(24.0 m² of its box's largest side, 8.00 x 3.00 m, at cW 1.20)"),
            "{}",
            vessel.said()
        );
    }

    /// EN 13000's gust profile: 1.4 times the 10 m mean at 10 m and below,
    /// 1.65 at 50 m; the mean at 10 m for the permissible speed at the
    /// boom head's highest, said with it.
    #[test]
    fn the_mean_wind_at_10_m_is_worked_out_for_the_boom_heads_height() {
        assert_eq!(gust_factor(10.0), 1.4);
        assert_eq!(gust_factor(3.0), 1.4);
        assert!((gust_factor(50.0) - (5f64.powf(0.14) + 0.4)).abs() < 1e-15);
        assert!((gust_factor(50.0) - 1.6527).abs() < 1e-4, "{}", gust_factor(50.0));
        let spec = WindSpec { chart_ms: None, cw: 1.2, area_m2: None, plan_for_swing: true };
        let mut vessel = PermissibleWind::of(9.8, None, &spec, [3.0, 8.0, 3.0], 12_900.0);
        assert_eq!(vessel.mean_at_10m_ms(), None);
        assert!(!vessel.said().contains("boom head"), "{}", vessel.said());
        vessel.boom_head_m = Some(50.0);
        let mean = vessel.mean_at_10m_ms().unwrap();
        assert!((mean * gust_factor(50.0) - vessel.permissible_ms).abs() < 1e-12);
        assert!(
            vessel.said().contains(&format!("; it is the 3 s gust at the boom head, which rises to 50.0 m above the crane's ground in this lift, where a 10-minute mean wind of {mean:.1} m/s at 10 m above the ground gusts to {:.1} m/s (EN 13000's profile, v(z) = [(z/10 m)^0.14 + 0.4] · v_10); the crane manufacturer's wind rules govern", vessel.permissible_ms)),
            "{}",
            vessel.said()
        );
    }

    /// The wind's push on the hanging load: the force at the permissible
    /// speed over the weight, times how far it hangs; the same angle for
    /// every load whose speed is reduced (the chart's 1.2 m²/t at the
    /// chart's speed), a smaller one where the chart's speed governs.
    #[test]
    fn the_load_hangs_off_plumb_as_the_wind_pushes_it() {
        let spec = WindSpec { chart_ms: None, cw: 1.2, area_m2: None, plan_for_swing: true };
        let mut vessel = PermissibleWind::of(9.8, None, &spec, [3.0, 8.0, 3.0], 16_000.0);
        assert!(vessel.reduced());
        let force_n = 0.5 * 1.25 * vessel.permissible_ms.powi(2) * 28.8;
        assert!((vessel.off_plumb_per_m() - force_n / (16_000.0 * 9.80665)).abs() < 1e-15);
        let at_chart = 0.5 * 1.25 * 9.8f64.powi(2) * 1.2 / (1000.0 * 9.80665);
        assert!((vessel.off_plumb_per_m() - at_chart).abs() < 1e-12, "{}", vessel.off_plumb_per_m());
        let small = PermissibleWind::of(9.8, None, &WindSpec { area_m2: Some(2.0), ..spec }, [1.0; 3], 16_000.0);
        assert!(!small.reduced() && small.off_plumb_per_m() < at_chart / 5.0);
        assert_eq!(vessel.off_plumb_m(), None);
        assert!(!vessel.said().contains("off plumb"));
        vessel.longest_hang_m = Some(30.0);
        let x = vessel.off_plumb_m().unwrap();
        assert!((x - 30.0 * at_chart).abs() < 1e-12 && (0.2..0.25).contains(&x), "{x}");
        assert!(
            vessel.said().contains(&format!("; at that speed the wind holds the load {x:.2} m off plumb where it hangs longest in this lift, 30.0 m below the boom head, and a sudden gust can swing it {:.2} m (tan θ = ρ v² A_W / (2 m_H g), ρ = 1.25 kg/m³); the crane manufacturer's", 2.0 * x)),
            "{}",
            vessel.said()
        );
    }

    /// The hoist rope's falls add half their area to what pushes the load
    /// off plumb, and that bounds, worked out step by step down a rope
    /// pushed along its length (its weight in it or not), how far the rope,
    /// the hook and what hangs below lie off plumb, for every rope up to the
    /// longest: met at the end of the longest rope with its weight left out.
    #[test]
    fn the_hoist_rope_s_wind_is_half_its_area_at_the_load() {
        let spec = WindSpec { chart_ms: Some(9.8), cw: 1.2, area_m2: Some(10.0), plan_for_swing: true };
        let plain = PermissibleWind::of(9.8, None, &spec, [3.0, 3.0, 3.0], 20_000.0);
        let rope = RopeInWind::new(6, true, 28.0, true, 35.0);
        assert!((rope.wind_area_m2 - 6.0 * 0.028 * 35.0 * 1.2).abs() < 1e-12);
        let roped = plain.clone().with_rope(Ok(rope.clone()));
        let ratio = roped.off_plumb_per_m() / plain.off_plumb_per_m();
        assert!((ratio - (12.0 + rope.wind_area_m2 / 2.0) / 12.0).abs() < 1e-12, "{ratio}");
        assert_eq!(roped.permissible_ms, plain.permissible_ms);
        // Down the rope: the push per metre of rope and at its end, the
        // weight at its end and (or not) the rope's own, 3.9 kg/m a fall.
        let q = 0.5 * AIR_DENSITY_KG_M3 * roped.permissible_ms.powi(2);
        let (f_per_m, end_n, weight_n) = (q * rope.wind_area_m2 / 35.0, q * 12.0, 20_000.0 * G_M_S2);
        let per_m = roped.off_plumb_per_m();
        for rope_m in [2.0, 10.0, 20.0, 35.0] {
            for rope_kg_per_m in [0.0, 6.0 * 3.9] {
                let (steps, mut off_m) = (20_000, 0.0);
                let ds = rope_m / steps as f64;
                for k in 0..steps {
                    let below_m = rope_m - (k as f64 + 0.5) * ds;
                    let across = end_n + f_per_m * below_m;
                    let down = weight_n + rope_kg_per_m * G_M_S2 * below_m;
                    off_m += across / down * ds;
                    // Along the rope: within its end's bound.
                    assert!(off_m <= per_m * rope_m + 1e-9, "{rope_m} m: {off_m} at {k}");
                }
                // The hook, and 5 m below it, the load's underside.
                for hang_m in [rope_m, rope_m + 5.0] {
                    let at_m = off_m + (hang_m - rope_m) * end_n / weight_n;
                    assert!(at_m <= per_m * hang_m + 1e-9, "{rope_m} m, {hang_m} m: {at_m}");
                    if rope_m == 35.0 && hang_m == rope_m && rope_kg_per_m == 0.0 {
                        assert!((at_m - per_m * hang_m).abs() < 1e-9 * hang_m, "{at_m} {}", per_m * hang_m);
                    }
                }
            }
        }
        // In words, with the formula it is worked out by.
        let mut w = roped.clone();
        w.longest_hang_m = Some(40.0);
        let said = w.said();
        assert!(said.contains("; the hoist rope's 6 falls of 28 mm, up to 35.0 m below the boom head, catch A_R = 7.1 m² at cW 1.2; at that speed the wind holds the load"), "{said}");
        assert!(said.contains("(tan θ = ρ v² (A_W + A_R / 2) / (2 m_H g), ρ = 1.25 kg/m³)"), "{said}");
        let guessed = RopeInWind::new(10, false, RopeInWind::widest_diameter_mm(3.9), false, 35.0);
        assert!((guessed.diameter_mm - 33.87).abs() < 0.01, "{}", guessed.diameter_mm);
        assert!(guessed.said().starts_with("the hoist rope's 10 falls (the most the hook block takes: the lift gives no crane falls) of 34 mm (the widest a steel wire rope of its mass per metre is"), "{}", guessed.said());
        let unknown = plain.clone().with_rope(Err("the crane file gives neither".into()));
        assert_eq!(unknown.off_plumb_per_m(), plain.off_plumb_per_m());
        assert!(
            unknown.said().contains("; the wind on the hoist rope is not counted: the crane file gives neither"),
            "{}",
            unknown.said()
        );
    }

    #[test]
    fn the_charts_cell_is_said() {
        let spec = WindSpec { chart_ms: None, cw: 1.2, area_m2: None, plan_for_swing: true };
        let vessel = PermissibleWind::of(9.8, Some("Main!A41".into()), &spec, [3.0, 8.0, 3.0], 12_900.0);
        assert!(vessel.said().contains(": the chart's 9.8 m/s (Main!A41) holds for"), "{}", vessel.said());
    }

    #[test]
    fn values_no_lift_has_are_named() {
        let w = |chart_ms, cw, area_m2| WindSpec { chart_ms, cw, area_m2, plan_for_swing: true }.problem();
        assert_eq!(w(Some(9.8), 1.2, None), None);
        assert_eq!(w(None, 1.2, None), None);
        assert!(w(Some(0.0), 1.2, None).unwrap().contains("wind chart_ms"));
        assert!(w(Some(9.8), f64::NAN, None).unwrap().contains("wind cw"));
        assert!(w(Some(9.8), 1.2, Some(-3.0)).unwrap().contains("wind area_m2"));
    }
}
