//! The hoist rope's falls (parts of line) and the hook block against the
//! hook load: what hangs from the rope (load, rigging, hook block) must be
//! within the falls reeved times what one fall may carry (the crane's
//! reeving table: `[hook] line_pull_t` in its file), what hangs from the
//! hook (load and rigging) within what the hook block is rated for
//! (`[hook] rated_t`), and the falls within what its sheaves take
//! (`max_falls`). The chart's capacities assume the crane
//! is reeved for the load; this says how many falls that takes, and checks
//! the falls the lift gives (`crane.falls`).
//!
//! The falls also take rope: where the crane file gives the hoist rope's
//! length (`[hook] rope_m`, less its dead wraps) and its run from the drum
//! to the boom's foot (`rope_lead_m`), the rope left past the boom's head,
//! shared by the falls, is how far the hook may hang below it
//! ([`rope_reach_m`]). Where that is less than the hook's travel, the lift's
//! crane is set up with it as its longest rope (`LiftSpec::resolve`), so
//! the planner, the validator and the pick and set all keep within it.
//!
//! The rope hanging below the boom head is part of the load, on every fall
//! (a crawler's capacity worksheet adds "the total weight of wire rope
//! below the boom point"). Where the crane file gives the rope's mass per
//! metre (`[hook] rope_kg_per_m`), it is counted at the longest rope the
//! lift is planned with ([`RopeWeight`]): the hook load is then the same all
//! along the path, and the planner keeps the hook within that rope as a
//! joint limit, so the count holds wherever the path goes. A lift that
//! hangs its load higher may give a shorter longest rope
//! (`crane.longest_rope_m`) and count less.
//!
//! What this module must not do: depend on the path (the hook load is the
//! same all along it), or say more than the crane file gives: a crane file
//! without a line pull has its falls unchecked, and says so.

use crate::lift::LiftTask;
use crate::units::KG_PER_TONNE;
use serde::{Deserialize, Serialize};

/// The most falls a lift or a crane file may give.
pub const MAX_FALLS: u32 = 64;

/// The reeving a lift is planned with, against its hook load.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Reeving {
    /// Load, rigging, hook block and the rope below the head where the
    /// crane file weighs it (kg): what the falls carry.
    pub hook_load_kg: f64,
    /// Load and rigging (kg): what the hook block carries on its hook.
    #[serde(default)]
    pub on_hook_kg: f64,
    /// The falls the lift gives (`crane.falls`).
    pub falls: Option<u32>,
    /// What one fall may carry (kg), where the crane file gives it.
    pub line_pull_kg: Option<f64>,
    /// What the hook block is rated for (kg), where the crane file gives it.
    pub block_rated_kg: Option<f64>,
    /// The most falls its sheaves take, where the crane file gives it.
    pub max_falls: Option<u32>,
    /// How far the falls let the hook hang below the boom head, where the
    /// crane file gives the hoist rope's length and the lift its falls.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rope: Option<RopeReach>,
    /// The hoist rope below the boom head, counted in `hook_load_kg`, where
    /// the crane file weighs it; none: not counted.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rope_weight: Option<RopeWeight>,
    /// The lift's own longest rope (m, `crane.longest_rope_m`), said here
    /// where neither the rope's reach nor its weight says it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lift_longest_m: Option<f64>,
    /// Whether the rope hangs from a tower crane's trolley (for the words).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub trolley: bool,
}

/// The hoist rope hanging below the boom head (a tower crane's trolley), as
/// part of the hook load: every fall at the longest rope the lift is planned
/// with, whatever the path.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RopeWeight {
    /// The rope's mass per metre (kg/m, `[hook] rope_kg_per_m`).
    pub kg_per_m: f64,
    /// The falls it is counted on.
    pub falls: u32,
    /// Whether those are the lift's (`crane falls`), or, where it gives
    /// none, the most the hook block's sheaves take (`[hook] max_falls`).
    pub falls_given: bool,
    /// The longest rope below the head the lift is planned with (m): the
    /// crane's joint limit for the lift.
    pub longest_m: f64,
    /// What sets [`Self::longest_m`].
    pub longest_from: LongestRope,
    /// Falls x longest rope x mass per metre (kg).
    pub kg: f64,
    /// Whether the rope hangs from a tower crane's trolley rather than a
    /// boom head (for the words).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub trolley: bool,
}

/// The falls the hoist rope is counted on (its weight, its wind): the
/// lift's (`crane.falls`, given: true), else the most the hook block takes
/// (`hook.max_falls`, given: false); none where neither is known.
pub fn falls_counted(lift_falls: Option<u32>, max_falls: Option<u32>) -> Option<(u32, bool)> {
    match (lift_falls, max_falls) {
        (Some(n), _) => Some((n, true)),
        (None, most) => most.map(|m| (m, false)),
    }
}

/// The falls the rope is counted on, in words: "6 falls", or where the
/// lift gives none (`given` false), the hook block's most and why.
pub fn falls_counted_said(falls: u32, given: bool) -> String {
    if given {
        format!("{falls} fall{}", if falls == 1 { "" } else { "s" })
    } else {
        format!("{falls} falls (the most the hook block takes: the lift gives no crane falls)")
    }
}

/// What sets the longest rope a lift is planned with.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum LongestRope {
    /// The hook's travel in the crane file (`[hook] max_rope_m`).
    Travel,
    /// How far the hoist rope lets the hook down on the falls ([`RopeReach`]).
    Reach,
    /// The lift's `crane.longest_rope_m`.
    Lift,
}

impl RopeWeight {
    /// The rope on `falls` falls of `longest_m` each, at `kg_per_m`.
    pub fn new(kg_per_m: f64, falls: u32, falls_given: bool, longest_m: f64, longest_from: LongestRope) -> RopeWeight {
        RopeWeight {
            kg_per_m,
            falls,
            falls_given,
            longest_m,
            longest_from,
            kg: kg_per_m * f64::from(falls) * longest_m,
            trolley: false,
        }
    }

    /// Where the rope hangs from, in words.
    pub fn below(&self) -> &'static str {
        hangs_below(self.trolley)
    }

    /// In words, for the Reeving row: "the 0.94 t of hoist rope: 6 falls of
    /// up to 40.00 m below the boom head (crane longest_rope_m) at 3.90
    /// kg/m".
    pub fn said(&self) -> String {
        let falls = falls_counted_said(self.falls, self.falls_given);
        let longest = match self.longest_from {
            LongestRope::Lift => "crane longest_rope_m",
            LongestRope::Travel => "the hook's travel: give crane longest_rope_m to count less",
            LongestRope::Reach => "as far as the rope lets the hook down: give crane longest_rope_m to count less",
        };
        format!(
            "the {:.2} t of hoist rope: {falls} of up to {:.2} m {} ({longest}) at {:.2} kg/m",
            self.kg / KG_PER_TONNE,
            self.longest_m,
            self.below(),
            self.kg_per_m
        )
    }
}

/// The hoist rope against the falls ([`rope_reach_m`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RopeReach {
    /// The rope that may be paid out (m, `[hook] rope_m`).
    pub rope_m: f64,
    /// Drum to the boom's foot, or a tower crane's jib's root (m, `[hook]
    /// rope_lead_m`).
    pub lead_m: f64,
    /// The boom's length, or a tower crane's jib's (m): the rope's run from
    /// the foot (root) to the head and out to the falls.
    pub boom_m: f64,
    pub falls: u32,
    /// How far the hook may hang below the boom head on them (m).
    pub reach_m: f64,
    /// The hook's travel the crane file gives (`[hook] max_rope_m`): the
    /// rope limits the lift only where its reach is less.
    pub travel_m: f64,
    /// Whether the rope runs along a tower crane's jib to its trolley
    /// (for the words).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub trolley: bool,
}

/// "below the trolley" on a tower crane, "below the boom head" otherwise.
pub fn hangs_below(trolley: bool) -> &'static str {
    if trolley { "below the trolley" } else { "below the boom head" }
}

/// How far below the boom head the hook may hang on `falls` falls (m, rope
/// from the head's sheave down to the hook block): the rope `rope_m` less
/// its run from the drum to the boom's foot (`lead_m`) and along the `boom_m`
/// boom, shared by the falls. Negative where the rope does not reach the
/// head. On a tower crane, below the trolley: the rope runs from the jib's
/// root out to the trolley, down and up its falls, and on to the jib's
/// head, so that `boom_m`, the jib's length, is its run along the jib
/// wherever the trolley stands.
pub fn rope_reach_m(rope_m: f64, lead_m: f64, boom_m: f64, falls: u32) -> f64 {
    (rope_m - lead_m - boom_m) / f64::from(falls.max(1))
}

impl RopeReach {
    /// In words, for the Reeving row; `lift_longest_m`, the lift's own
    /// longest rope where it gives one (within the reach, it is what limits
    /// the lift).
    pub fn said(&self, lift_longest_m: Option<f64>) -> String {
        let limits = if let Some(m) = lift_longest_m {
            format!(", more than the lift's own longest rope ({m:.2} m, crane longest_rope_m)")
        } else if self.reach_m < self.travel_m {
            format!(": the longest rope planned with (hook travel {:.2} m)", self.travel_m)
        } else {
            format!(", more than the hook's travel ({:.2} m), which holds", self.travel_m)
        };
        format!("{}{limits}", self.reach_said())
    }

    /// How far the rope lets the hook down, in words.
    pub fn reach_said(&self) -> String {
        let run = if self.trolley {
            format!("{:.1} m to the jib's root and the {:.1} m jib", self.lead_m, self.boom_m)
        } else {
            format!("{:.1} m to the boom's foot and the {:.1} m boom", self.lead_m, self.boom_m)
        };
        format!(
            "the hoist rope's {:.0} m (less {run}) on {} fall{} lets the hook hang {:.2} m {}",
            self.rope_m,
            self.falls,
            if self.falls == 1 { "" } else { "s" },
            self.reach_m,
            hangs_below(self.trolley)
        )
    }
}

impl Reeving {
    /// The task's reeving; `None` where neither the crane file (line pull,
    /// block rating, the rope's weight) nor the lift (falls) gives anything
    /// to check or count.
    pub fn of(task: &LiftTask) -> Option<Reeving> {
        let hook = &task.crane.model.hook;
        let r = Reeving {
            hook_load_kg: task.hook_load_kg(),
            on_hook_kg: task.load_mass_kg + task.rigging_mass_kg,
            falls: task.falls,
            line_pull_kg: hook.line_pull_t.map(|t| t * KG_PER_TONNE),
            block_rated_kg: hook.rated_t.map(|t| t * KG_PER_TONNE),
            max_falls: hook.max_falls,
            rope: task.rope_reach.clone(),
            rope_weight: task.rope_weight.clone(),
            lift_longest_m: task.longest_rope_m,
            trolley: task.crane.model.is_tower(),
        };
        (r.falls.is_some()
            || r.line_pull_kg.is_some()
            || r.block_rated_kg.is_some()
            || r.rope_weight.is_some()
            || r.lift_longest_m.is_some())
        .then_some(r)
    }

    /// The fewest falls that carry the hook load, where the line pull is
    /// known. Where the rope below the head is counted, each fall added
    /// hangs its own length of rope too: n falls carry the rest and n
    /// lengths of rope (none, `u32::MAX`, where a fall cannot carry even
    /// its own rope).
    pub fn least_falls(&self) -> Option<u32> {
        let pull = self.line_pull_kg?;
        let (rest, per_fall) = match &self.rope_weight {
            Some(w) => (self.hook_load_kg - w.kg, w.kg / f64::from(w.falls.max(1))),
            None => (self.hook_load_kg, 0.0),
        };
        if per_fall >= pull {
            return Some(u32::MAX);
        }
        let n = ((rest / (pull - per_fall)) * (1.0 - 1e-12)).ceil().max(1.0);
        Some(if n >= f64::from(u32::MAX) { u32::MAX } else { n as u32 })
    }

    /// Why the lift cannot be reeved as given, with what to change; `None`
    /// where it can.
    pub fn refused(&self) -> Option<String> {
        let t = |kg: f64| kg / KG_PER_TONNE;
        if let Some(rated) = self.block_rated_kg.filter(|r| self.on_hook_kg > r * (1.0 + 1e-12)) {
            return Some(format!(
                "the load and its rigging ({:.2} t) are more than the hook block is rated for ({:.2} t, [hook] rated_t in the crane file): rig another hook block",
                t(self.on_hook_kg),
                t(rated)
            ));
        }
        let (least, pull) = (self.least_falls()?, self.line_pull_kg?);
        if let Some(w) = self.rope_weight.as_ref().filter(|_| least == u32::MAX) {
            return Some(format!(
                "a fall of the hoist rope carries {:.2} t (line pull, [hook] line_pull_t), no more than its own {:.2} m {} weighs at {:.2} kg/m ({:.2} t): no reeving carries the load; give crane longest_rope_m",
                t(pull),
                w.longest_m,
                w.below(),
                w.kg_per_m,
                t(w.kg_per_m * w.longest_m)
            ));
        }
        if let Some(most) = self.max_falls.filter(|m| least > *m) {
            return Some(format!(
                "the hook load ({:.2} t) needs {least} falls of {:.2} t each, more than the hook block's sheaves take ({most}, [hook] max_falls): rig another hook block",
                t(self.hook_load_kg),
                t(pull)
            ));
        }
        match self.falls {
            Some(n) if n < least => Some(format!(
                "the hook load ({:.2} t: {}) is more than {n} fall{} of {:.2} t each carr{} ({:.2} t): reeve at least {least} falls (crane falls)",
                t(self.hook_load_kg),
                self.made_of(),
                if n == 1 { "" } else { "s" },
                t(pull),
                if n == 1 { "ies" } else { "y" },
                t(f64::from(n) * pull)
            )),
            _ => None,
        }
    }

    /// What the hook load is made of, in words.
    fn made_of(&self) -> String {
        match &self.rope_weight {
            Some(w) => format!("load, rigging, hook block and {:.2} t of hoist rope", w.kg / KG_PER_TONNE),
            None => "load, rigging and hook block".to_string(),
        }
    }

    /// In words, for the run's line and the PDF.
    pub fn said(&self) -> String {
        let t = |kg: f64| kg / KG_PER_TONNE;
        let pct = |kg: f64| 100.0 * self.hook_load_kg / kg;
        let mut parts = vec![format!("hook load {:.2} t ({})", t(self.hook_load_kg), self.made_of())];
        parts.push(match (self.falls, self.line_pull_kg, self.least_falls()) {
            (Some(n), Some(pull), Some(least)) => format!(
                "on {n} fall{} of {:.2} t each: {:.2} t, {:.0} % (at least {least} needed)",
                if n == 1 { "" } else { "s" },
                t(pull),
                t(f64::from(n) * pull),
                pct(f64::from(n) * pull)
            ),
            (None, Some(pull), Some(least)) => format!(
                "needs at least {least} fall{} of {:.2} t each: THE LIFT GIVES NO FALLS (crane falls): REEVE AT LEAST {least}",
                if least == 1 { "" } else { "s" },
                t(pull)
            ),
            (Some(n), _, _) => format!(
                "on {n} fall{}, NOT CHECKED: the crane file gives no line pull per fall ([hook] line_pull_t)",
                if n == 1 { "" } else { "s" }
            ),
            _ => "its falls not checked: the crane file gives no line pull per fall ([hook] line_pull_t)".to_string(),
        });
        if let Some(rated) = self.block_rated_kg {
            parts.push(format!(
                "the hook block rated {:.2} t, carrying {:.2} t of load and rigging: {:.0} %",
                t(rated),
                t(self.on_hook_kg),
                100.0 * self.on_hook_kg / rated
            ));
        }
        parts.extend(self.rope.as_ref().map(|r| r.said(self.lift_longest_m)));
        parts.push(match &self.rope_weight {
            Some(w) => w.said(),
            None => "the hoist rope's own weight not counted: the crane file gives no [hook] rope_kg_per_m".to_string(),
        });
        if let (None, None, Some(m)) = (&self.rope, &self.rope_weight, self.lift_longest_m) {
            parts.push(format!(
                "the hook kept within {m:.2} m of rope {} (crane longest_rope_m)",
                hangs_below(self.trolley)
            ));
        }
        parts.join("; ")
    }

    /// Whether the cover is to ask that the falls be checked first: the
    /// lift gives none where the crane file could check them.
    pub fn falls_not_given(&self) -> bool {
        self.falls.is_none() && self.line_pull_kg.is_some()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn reeving(falls: Option<u32>) -> Reeving {
        Reeving {
            hook_load_kg: 16_500.0,
            on_hook_kg: 13_000.0,
            falls,
            line_pull_kg: Some(8000.0),
            block_rated_kg: Some(63_000.0),
            max_falls: Some(8),
            rope: None,
            rope_weight: None,
            lift_longest_m: None,
            trolley: false,
        }
    }

    const NOT_WEIGHED: &str = "; the hoist rope's own weight not counted: the crane file gives no [hook] rope_kg_per_m";

    /// 16.5 t on falls of 8 t: three carry it (24 t), two do not (16 t).
    #[test]
    fn the_falls_carry_the_hook_load_or_are_refused() {
        assert_eq!(reeving(None).least_falls(), Some(3));
        assert_eq!(reeving(Some(4)).refused(), None);
        assert_eq!(
            reeving(Some(4)).said(),
            format!(
                "hook load 16.50 t (load, rigging and hook block); on 4 falls of 8.00 t each: 32.00 t, 52 % (at least 3 needed); the hook block rated 63.00 t, carrying 13.00 t of load and rigging: 21 %{NOT_WEIGHED}"
            )
        );
        assert_eq!(reeving(Some(3)).refused(), None);
        let two = reeving(Some(2)).refused().unwrap();
        assert_eq!(
            two,
            "the hook load (16.50 t: load, rigging and hook block) is more than 2 falls of 8.00 t each carry (16.00 t): reeve at least 3 falls (crane falls)"
        );
        // Exactly on a fall's worth: that many carry it.
        let even = Reeving { hook_load_kg: 16_000.0, ..reeving(Some(2)) };
        assert_eq!((even.least_falls(), even.refused()), (Some(2), None));
        // No falls given: said in capitals, not refused.
        let none = reeving(None);
        assert!(none.refused().is_none() && none.falls_not_given());
        assert!(none.said().contains(
            "needs at least 3 falls of 8.00 t each: THE LIFT GIVES NO FALLS (crane falls): REEVE AT LEAST 3"
        ));
    }

    /// A block rated below the hook load, and one whose sheaves take too
    /// few falls, are refused; a crane file without a line pull checks
    /// nothing of the falls, and says so.
    #[test]
    fn the_hook_block_limits_the_load_and_the_falls() {
        // The block carries the load and rigging, not itself.
        assert_eq!(Reeving { block_rated_kg: Some(13_000.0), ..reeving(Some(4)) }.refused(), None);
        let light = Reeving { block_rated_kg: Some(12_000.0), ..reeving(Some(4)) };
        assert!(
            light.refused().unwrap().starts_with(
                "the load and its rigging (13.00 t) are more than the hook block is rated for (12.00 t, [hook] rated_t"
            ),
            "{:?}",
            light.refused()
        );
        let few = Reeving { max_falls: Some(2), ..reeving(None) };
        assert!(
            few.refused().unwrap().contains("needs 3 falls of 8.00 t each, more than the hook block's sheaves take (2")
        );
        let unknown = Reeving { line_pull_kg: None, block_rated_kg: None, ..reeving(Some(4)) };
        assert_eq!(unknown.refused(), None);
        assert!(unknown.said().ends_with(&format!(
            "on 4 falls, NOT CHECKED: the crane file gives no line pull per fall ([hook] line_pull_t){NOT_WEIGHED}"
        )));
        assert!(!unknown.falls_not_given());
    }

    /// The rope below the head is every fall at the longest rope, and the
    /// falls carry it with the rest: 16.5 t and 4 x 40 m x 3.9 kg/m.
    #[test]
    fn the_hoist_rope_below_the_head_is_part_of_the_load() {
        let w = RopeWeight::new(3.9, 4, true, 40.0, LongestRope::Lift);
        assert!((w.kg - 624.0).abs() < 1e-9);
        let r = Reeving { hook_load_kg: 16_500.0 + w.kg, rope_weight: Some(w), ..reeving(Some(4)) };
        assert_eq!(
            r.said(),
            "hook load 17.12 t (load, rigging, hook block and 0.62 t of hoist rope); on 4 falls of 8.00 t each: 32.00 t, 54 % (at least 3 needed); the hook block rated 63.00 t, carrying 13.00 t of load and rigging: 21 %; the 0.62 t of hoist rope: 4 falls of up to 40.00 m below the boom head (crane longest_rope_m) at 3.90 kg/m"
        );
        // 16.5 t goes on 3 falls of 5.8 t (17.4 t); with 1.29 t of rope, not.
        let bare = Reeving { line_pull_kg: Some(5_800.0), ..reeving(Some(3)) };
        assert_eq!(bare.refused(), None);
        let heavy = RopeWeight::new(3.9, 3, true, 110.0, LongestRope::Travel);
        let r = Reeving { hook_load_kg: 16_500.0 + heavy.kg, rope_weight: Some(heavy), ..bare.clone() };
        assert_eq!(
            r.refused().unwrap(),
            "the hook load (17.79 t: load, rigging, hook block and 1.29 t of hoist rope) is more than 3 falls of 5.80 t each carry (17.40 t): reeve at least 4 falls (crane falls)"
        );
        // On 4 falls the rope is 1.72 t and the hook load 18.22 t, which 4 x
        // 5.8 t carry: 4 is the least, counting each fall's rope.
        let four = RopeWeight::new(3.9, 4, true, 110.0, LongestRope::Travel);
        let on_four =
            Reeving { hook_load_kg: 16_500.0 + four.kg, rope_weight: Some(four), falls: Some(4), ..bare.clone() };
        assert_eq!((on_four.least_falls(), on_four.refused()), (Some(4), None));
        // Rope so heavy that each fall added carries little more than its
        // own: 16.5 t on falls of 5.8 t with 5 t of rope each takes 21.
        let w = RopeWeight::new(50.0, 3, true, 100.0, LongestRope::Travel);
        let steep = Reeving { hook_load_kg: 16_500.0 + w.kg, rope_weight: Some(w), ..bare.clone() };
        assert_eq!(steep.least_falls(), Some(21));
        let w = RopeWeight::new(60.0, 3, true, 100.0, LongestRope::Travel);
        let none = Reeving { hook_load_kg: 16_500.0 + w.kg, rope_weight: Some(w), ..bare.clone() };
        assert_eq!(none.least_falls(), Some(u32::MAX));
        assert_eq!(
            none.refused().unwrap(),
            "a fall of the hoist rope carries 5.80 t (line pull, [hook] line_pull_t), no more than its own 100.00 m below the boom head weighs at 60.00 kg/m (6.00 t): no reeving carries the load; give crane longest_rope_m"
        );
        assert!(r.said().ends_with("the 1.29 t of hoist rope: 3 falls of up to 110.00 m below the boom head (the hook's travel: give crane longest_rope_m to count less) at 3.90 kg/m"), "{}", r.said());
        let unsaid = RopeWeight::new(3.9, 8, false, 90.0, LongestRope::Reach);
        assert!(unsaid.said().contains("8 falls (the most the hook block takes: the lift gives no crane falls) of up to 90.00 m below the boom head (as far as the rope lets the hook down: give crane longest_rope_m to count less)"), "{}", unsaid.said());
    }
}
