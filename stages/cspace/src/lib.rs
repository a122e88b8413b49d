//! # liftplan-cspace: stage 4b, the hybrid configuration space
//!
//! Cai (2016, §4.4) observes that a crane's body and boom depend only on swing
//! and the radial joint (luff angle or trolley radius), so their collisions can
//! be precomputed once on a 2D grid, while the hanging parts (rope, hook block,
//! load) depend on all four joints and are checked online. This crate builds that
//! grid ([`CSpace`]) and the [`Checker`] every planner in `liftplan-plan` asks.
//!
//! Every table entry is *conservative for its whole cell*: a part is tested at
//! the cell centre, grown by the clearance plus a bound on how far any of its
//! points can move within the cell (rotation by half a swing step moves a point
//! at radius R by at most R·Δs/2, and so on). A cell marked free is free for
//! every configuration inside it; a configuration in a cell marked blocked may
//! still be free, which only costs the planner a little room.
//!
//! Per cell the grid also holds the longest rope (`max_hoist`) at which a
//! vertical cylinder around the hook line, wide enough for the load at any yaw
//! plus the clearance, is clear of the depth map. Most hoist and rotation checks
//! are then a single comparison; the rest are exact box queries against the
//! depth map, sampled so finely that consecutive samples' grown boxes cover the
//! swept volume (bounded-displacement sampling, see [`Checker::motion`]).
//!
//! Three strategies are built for the benchmark of issue 7: `hybrid` (the
//! above), `online` (no tables: every question is answered by box queries) and
//! `full` (hybrid plus the load envelope at every rope length of a hoist grid,
//! so that hoisting and rotation never query the map during planning).
//!
//! What this crate must not do: plan, or decide that a plan is safe. The
//! validator in `liftplan-plan` re-checks every plan with its own geometry.

mod boom;
pub mod by_query;
pub mod picture;

use liftplan_core::capacity::ChartConfig;
use liftplan_core::crane::Config;
use liftplan_core::crane::{CraneSetup, Dependence, LoadShape, PartKind};
use liftplan_core::lift::LiftTask;
use liftplan_core::obb::Obb;
use liftplan_depthmap::mdm::{Interval, Mdm, OBJ_GROUND};
use liftplan_depthmap::query::LeaveOut;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::f64::consts::TAU;

pub const NAME: &str = "cspace";
pub const VERSION: u32 = 1;

/// How collision questions are answered (for the strategy benchmark).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum Strategy {
    #[default]
    Hybrid,
    Online,
    Full,
}

/// `[cspace]` in `liftplan.toml`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Settings {
    /// Swing resolution (degrees).
    pub swing_step_deg: f64,
    /// Luff resolution of a mobile crane (degrees).
    pub luff_step_deg: f64,
    /// Trolley resolution of a tower crane (m).
    pub trolley_step_m: f64,
    pub strategy: Strategy,
    /// Largest movement of any point of the hanging parts over one online-checked piece of a move (m).
    pub sample_m: f64,
    /// Rope-length resolution of the `full` strategy's hoist grid (m).
    pub full_hoist_step_m: f64,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            swing_step_deg: 0.5,
            luff_step_deg: 0.5,
            trolley_step_m: 0.25,
            strategy: Strategy::Hybrid,
            sample_m: 0.3,
            full_hoist_step_m: 0.5,
        }
    }
}

impl Settings {
    pub fn check(&self) -> Result<(), String> {
        let ok = |v: f64, lo: f64, hi: f64| v.is_finite() && v >= lo && v <= hi;
        if !ok(self.swing_step_deg, 0.05, 10.0) || !ok(self.luff_step_deg, 0.05, 10.0) {
            return Err("[plan.cspace] swing_step_deg and luff_step_deg must be between 0.05 and 10 degrees".into());
        }
        if !ok(self.trolley_step_m, 0.01, 5.0)
            || !ok(self.sample_m, 0.005, 1.0)
            || !ok(self.full_hoist_step_m, 0.05, 10.0)
        {
            return Err("[plan.cspace] trolley_step_m (0.01..5), sample_m (0.005..1) and full_hoist_step_m (0.05..10) are out of range".into());
        }
        Ok(())
    }
}

/// Why a configuration fails a box query: the part's box is grown by the
/// clearance (less in a landing zone) and by the motion a sample stands for,
/// so a hit says the part comes closer to the obstacle than that, which
/// includes touching it; it is not a collision as such.
pub const TOO_CLOSE: &str = "closer than the clearance allows";

/// A [`Blocked::reason`]: the load, or a part of the crane, over an area
/// the lift says it must not be over (`not_over`, `crane_too`); the part is
/// [`Blocked::part`].
pub const OVER_NOT_OVER: &str = "over an area it must not be over";

/// Why a configuration or a move is not allowed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Blocked {
    /// What is wrong: [`TOO_CLOSE`], "capacity", "internal clearance", "joint limit".
    pub reason: String,
    /// The crane part concerned (for box queries).
    pub part: Option<PartKind>,
    /// The obstacle (object name from the depth map) for box queries.
    pub object: Option<String>,
    pub at: Config,
}

impl std::fmt::Display for Blocked {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let c = &self.at;
        write!(f, "{}", self.reason)?;
        if let Some(p) = self.part {
            write!(f, ": {}", p.name())?;
        }
        if let Some(o) = &self.object {
            write!(f, " and {o}")?;
        }
        write!(
            f,
            " at swing {:.1}°, radial {:.3}, hoist {:.2} m, load yaw {:.1}°",
            c.swing_rad.to_degrees(),
            c.radial,
            c.hoist_m,
            c.load_yaw_rad.to_degrees()
        )
    }
}

/// A blocked table entry: which part and which object.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CellHit {
    pub part: PartKind,
    pub obj: u32,
}

/// The precomputed tables.
#[derive(Debug, Clone)]
pub struct CSpace {
    pub strategy: Strategy,
    /// Swing columns over a full turn (rad, relative to the crane heading).
    pub ns: u32,
    pub swing_step: f64,
    /// Radial rows from `radial0` in steps of `radial_step` (rad or m).
    pub nr: u32,
    pub radial0: f64,
    pub radial_step: f64,
    /// Swing-only parts, per swing column (empty for `online`).
    pub swing_hits: Vec<Option<CellHit>>,
    /// Boom / trolley, per cell `k * ns + i` (empty for `online`).
    pub cell_hits: Vec<Option<CellHit>>,
    /// Longest clear rope per cell (m), `-inf` where none (empty for `online`).
    pub max_hoist: Vec<f32>,
    /// `full` only: per cell, bit b set when the load envelope collides at rope
    /// lengths in [hoist0 + b·step, hoist0 + (b+1)·step].
    pub hoist_bits: Vec<u64>,
    pub hoist0: f64,
    pub hoist_step: f64,
    /// Chart capacity (kg, before the reduction) at the row's largest radius;
    /// `None` where the chart does not permit a lift.
    pub row_capacity_kg: Vec<Option<f64>>,
    /// Chart cell of that capacity, for the report.
    pub row_chart_cell: Vec<String>,
    /// Shortest rope that keeps the load clear of the boom (internal clearance), per row.
    pub row_min_hoist: Vec<f64>,
    /// How far from the slewing axis, in plan, the crane's parts that stand
    /// or swing reach at most (m): a load farther off cannot meet them.
    pub own_reach_m: f64,
    pub build_ms: f64,
    /// Where the build time went.
    pub timings: BuildTimings,
}

/// Build time by pass (ms).
#[derive(Debug, Clone, Copy, Default, Serialize)]
pub struct BuildTimings {
    pub rows_ms: f64,
    pub swing_ms: f64,
    pub radial_ms: f64,
    pub max_hoist_ms: f64,
    pub hoist_bits_ms: f64,
    /// Whether the longest-clear-rope dilation ran on a GPU ([`CSpace::build_on`]).
    pub dilation_on_gpu: bool,
}

fn ms_since(t: std::time::Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1e3
}

/// The things a build needs.
pub struct Problem<'a> {
    pub task: &'a LiftTask,
    pub chart: Option<&'a ChartConfig>,
    pub map: &'a Mdm,
}

/// Longest distance of a box corner from a point.
fn far_from(b: &Obb, p: &liftplan_core::frame::Point3) -> f64 {
    b.corners().iter().map(|c| (c - p).norm()).fold(0.0, f64::max)
}

fn is_luffing(crane: &CraneSetup) -> bool {
    !crane.model.is_tower()
}

/// What a part's box queries leave out, in the form both the CPU's and the
/// GPU's queries take. The carrier, outriggers and mast stand on the ground,
/// the superstructure and what turns with it swing just above it: ground up
/// to [`CraneSetup::standing_ground_top_z`] is not an obstacle for them, a
/// bank higher up is, as in the validator. The map's
/// intervals are the points grown by their radius, so here a ground point
/// up to that radius below the height still counts: the planner's side of
/// the rule is the more careful one.
fn left_out(crane: &CraneSetup, part: PartKind) -> Option<LeaveOut> {
    match part.dependence() {
        Dependence::Fixed | Dependence::Swing => Some(LeaveOut::up_to(OBJ_GROUND, crane.standing_ground_top_z())),
        Dependence::SwingRadial | Dependence::Full => None,
    }
}

impl CSpace {
    /// Builds the tables for a lift, on the CPU.
    pub fn build(p: &Problem, s: &Settings) -> CSpace {
        CSpace::build_on(p, s, None)
    }

    /// [`CSpace::build`], with the longest-clear-rope table's dilation on
    /// `gpu` where one is given ([`liftplan_depthmap::gpu::Gpu::window_max`],
    /// the CPU's bits; where the device refuses it, on the CPU, and
    /// [`BuildTimings::dilation_on_gpu`] says which). The same tables either
    /// way. The body and boom rows stay on the CPU: their box-query twin is
    /// [`by_query::rows_by_query`], and the boom marking has no GPU twin.
    pub fn build_on(p: &Problem, s: &Settings, gpu: Option<&liftplan_depthmap::gpu::Gpu>) -> CSpace {
        let t0 = std::time::Instant::now();
        let task = p.task;
        let crane = &task.crane;
        let lim = crane.limits();
        let swing_step = s.swing_step_deg.to_radians();
        let ns = (TAU / swing_step).round().max(8.0) as u32;
        let swing_step = TAU / ns as f64;
        let radial_step = if is_luffing(crane) { s.luff_step_deg.to_radians() } else { s.trolley_step_m };
        let nr = (((lim.radial.1 - lim.radial.0) / radial_step).ceil() as u32).max(1);
        let mut cs = CSpace {
            strategy: s.strategy,
            ns,
            swing_step,
            nr,
            radial0: lim.radial.0,
            radial_step,
            swing_hits: vec![],
            cell_hits: vec![],
            max_hoist: vec![],
            hoist_bits: vec![],
            hoist0: lim.hoist_m.0,
            hoist_step: s.full_hoist_step_m,
            row_capacity_kg: vec![],
            row_chart_cell: vec![],
            row_min_hoist: vec![],
            own_reach_m: own_reach_m(task),
            build_ms: 0.0,
            timings: BuildTimings::default(),
        };
        // Rows: chart capacity and internal clearance (cheap, every strategy).
        for k in 0..nr {
            let (a, b) = cs.row_range(k);
            // The largest radius of the row is where the chart is most restrictive.
            let worst = if is_luffing(crane) { a } else { b };
            let cap = p.chart.and_then(|c| task.check_capacity(c, worst).ok());
            cs.row_chart_cell.push(cap.as_ref().map(|c| c.capacity.cell.clone()).unwrap_or_default());
            cs.row_capacity_kg.push(match p.chart {
                Some(_) => cap.map(|c| c.capacity.capacity_kg),
                None => Some(f64::INFINITY),
            });
            cs.row_min_hoist.push(
                min_hoist_for_internal_clearance(
                    crane,
                    &task.load,
                    b.max(a),
                    task.gust_swing_per_m,
                    task.cog_tolerance_m,
                )
                .max(lim.hoist_m.0),
            );
        }
        cs.timings.rows_ms = ms_since(t0);
        if s.strategy == Strategy::Online {
            cs.build_ms = ms_since(t0);
            return cs;
        }
        let clearance = task.clearance_m;
        let radial_parts: Vec<PartKind> =
            crane.part_kinds().iter().copied().filter(|k| k.dependence() == Dependence::SwingRadial).collect();
        cs.swing_hits = by_query::rows_on_cpu(&cs, p, Dependence::Swing);
        cs.timings.swing_ms = ms_since(t0) - cs.timings.rows_ms;
        let t_radial = std::time::Instant::now();
        cs.cell_hits = match &crane.model.kind {
            liftplan_core::crane::CraneKind::Luffing(l) if radial_parts == [PartKind::Boom] => {
                boom::boom_hits(&cs, p, &l.boom, clearance)
            }
            _ => by_query::rows_on_cpu(&cs, p, Dependence::SwingRadial),
        };
        cs.timings.radial_ms = ms_since(t_radial);
        let t_hoist = std::time::Instant::now();
        cs.max_hoist = cs.max_hoist_table(p, gpu);
        cs.timings.max_hoist_ms = ms_since(t_hoist);
        if s.strategy == Strategy::Full {
            let t_bits = std::time::Instant::now();
            cs.hoist_bits = cs.build_hoist_bits(p, s);
            cs.timings.hoist_bits_ms = ms_since(t_bits);
        }
        cs.build_ms = ms_since(t0);
        cs
    }

    /// Swing value at the centre of column `i` (rad, in [0, 2π)).
    pub fn swing_center(&self, i: u32) -> f64 {
        (i as f64 + 0.5) * self.swing_step
    }

    /// The configuration at the centre of cell (i, k), rope `hoist_m`, load yaw 0.
    pub fn cell_center(&self, i: u32, k: u32, hoist_m: f64) -> Config {
        Config { swing_rad: self.swing_center(i), radial: self.row_center(k), hoist_m, load_yaw_rad: 0.0 }
    }

    pub fn row_center(&self, k: u32) -> f64 {
        self.radial0 + (k as f64 + 0.5) * self.radial_step
    }

    pub fn row_range(&self, k: u32) -> (f64, f64) {
        (self.radial0 + k as f64 * self.radial_step, self.radial0 + (k + 1) as f64 * self.radial_step)
    }

    /// Column of a swing value (any real angle).
    pub fn col(&self, swing_rad: f64) -> u32 {
        ((swing_rad.rem_euclid(TAU) / self.swing_step).floor() as u32).min(self.ns - 1)
    }

    /// Row of a radial value, `None` outside the crane's range.
    pub fn row(&self, radial: f64) -> Option<u32> {
        let k = ((radial - self.radial0) / self.radial_step).floor();
        if k < -1e-9 || !k.is_finite() {
            return None;
        }
        let k = k.max(0.0) as u32;
        if k < self.nr {
            Some(k)
        } else if (radial - (self.radial0 + self.nr as f64 * self.radial_step)).abs() < 1e-9 {
            Some(self.nr - 1)
        } else {
            None
        }
    }

    /// The box a swing-only part's column `i` asks: the part at the column's
    /// centre (and mid radial), grown by the clearance and by how far its
    /// farthest point moves within half a column.
    fn swing_box(&self, p: &Problem, kind: PartKind, i: u32) -> Option<Obb> {
        let crane = &p.task.crane;
        let lim = crane.limits();
        let mid_r = 0.5 * (lim.radial.0 + lim.radial.1);
        let c = Config { swing_rad: self.swing_center(i), radial: mid_r, hoist_m: lim.hoist_m.0, load_yaw_rad: 0.0 };
        let b = crane.part(kind, &c, &p.task.load)?;
        Some(b.expanded(p.task.clearance_m + crane.plan_reach_m(&b) * self.swing_step / 2.0))
    }

    /// The box a swing+radial part's cell (i, k) asks: the part at the cell
    /// centre, grown by the clearance and its motion within the cell.
    fn radial_box(&self, p: &Problem, kind: PartKind, i: u32, k: u32) -> Option<Obb> {
        let crane = &p.task.crane;
        let b = crane.part(kind, &self.cell_center(i, k, crane.limits().hoist_m.0), &p.task.load)?;
        Some(b.expanded(p.task.clearance_m + self.cell_motion(crane, &b)))
    }

    /// Bound on how far any point of a swing+radial part moves within a cell
    /// from its position at the cell centre.
    fn cell_motion(&self, crane: &CraneSetup, b: &Obb) -> f64 {
        let swing = crane.plan_reach_m(b) * self.swing_step / 2.0;
        let radial = match &crane.model.kind {
            // Luffing rotates the boom about its pivot; every point of it is
            // within (distance to the slewing base + pivot offset) of the pivot.
            liftplan_core::crane::CraneKind::Luffing(l) => {
                let far = far_from(b, &crane.slew_center()) + l.boom.pivot_x_m.hypot(l.boom.pivot_z_m);
                far * self.radial_step / 2.0
            }
            liftplan_core::crane::CraneKind::Tower(_) => self.radial_step / 2.0,
        };
        swing + radial
    }

    /// Bound on how far the rope sheave moves within a cell (m).
    fn sheave_motion(&self, crane: &CraneSetup, radial: f64) -> f64 {
        let (_, r) = crane.sheave_height_and_radius(radial);
        let swing = r * self.swing_step / 2.0;
        let radial_m = if is_luffing(crane) {
            crane.placement.boom_length_m * self.radial_step / 2.0
        } else {
            self.radial_step / 2.0
        };
        swing + radial_m
    }

    /// Radius of the vertical cylinder around the hook line that holds hook block
    /// and load at any yaw.
    fn envelope_radius(task: &LiftTask) -> f64 {
        task.load.yaw_invariant_radius().max(task.crane.model.hook.width_m * std::f64::consts::FRAC_1_SQRT_2)
    }

    /// Sheave to load underside, less the rope (m).
    fn hang_below_rope(task: &LiftTask) -> f64 {
        task.crane.model.hook.height_m + task.load.rigging_height_m + task.load.size_m[2]
    }

    /// How much wider the envelope's square must be for what hangs on up to
    /// `rope_m` of rope, anywhere in a cell whose sheave moves up to
    /// `motion` (m), hanging off as far as it may ([`LiftTask::hanging_swept`]:
    /// swung by a gust, off by the centre of gravity's tolerance): the
    /// checker grows each hanging box by that on every side, whose corners
    /// then reach √2 times as far at a yaw of 45°. 0 where neither applies.
    fn gust_reach_m(task: &LiftTask, rope_m: f64, motion: f64) -> f64 {
        std::f64::consts::SQRT_2
            * (task.gust_swing_per_m * (rope_m + Self::hang_below_rope(task) + 2.0 * motion) + task.cog_tolerance_m)
    }

    /// The longest clear rope of every cell (see [`CSpace::cell_max_hoist`]),
    /// from the map's cell tops dilated once by the widest envelope instead of
    /// a rectangle query per cell.
    ///
    /// Where the dilated top reaches the sheave, something in the envelope's
    /// square is at or above the sheave: crossing the sheave height (no clear
    /// rope) or entirely above it (an overhead structure, where the rope
    /// below may be clear). Those cells get the exact rectangle query: taken
    /// as "no clear rope", an overhead structure sent every hanging-part
    /// check under it to box queries (the demo under its plant model 100 m
    /// up searched for 25 s instead of 1 s).
    fn max_hoist_table(&mut self, p: &Problem, gpu: Option<&liftplan_depthmap::gpu::Gpu>) -> Vec<f32> {
        let task = p.task;
        let crane = &task.crane;
        let map = p.map;
        let spec = map.spec;
        let motion_max = (0..self.nr).map(|k| self.sheave_motion(crane, self.row_center(k))).fold(0.0, f64::max);
        let r_max = Self::envelope_radius(task)
            + task.clearance_m
            + motion_max
            + Self::gust_reach_m(task, crane.limits().hoist_m.1, motion_max);
        let (nx, ny) = (spec.nx as usize, spec.ny as usize);
        // Cells within r of any point of the sheave's cell are within w cells
        // of it; a window past the map's longer side covers all of it, as does
        // a reach that is not finite (never narrower for it).
        let w = match (r_max / spec.cell).ceil() {
            cells if cells.is_finite() => (cells as usize).saturating_add(1),
            _ => usize::MAX,
        }
        .min(nx.max(ny));
        let tops = map.pyramid.first().map(|l| l.2.as_slice()).unwrap_or(&[]);
        let on_device = gpu.and_then(|g| g.window_max(tops, nx, ny, w).ok());
        self.timings.dilation_on_gpu = on_device.is_some();
        let dilated = on_device.unwrap_or_else(|| liftplan_depthmap::dilate::window_max(tops, nx, ny, w));
        (0..self.nr * self.ns)
            .into_par_iter()
            .map(|idx| {
                let (i, k) = (idx % self.ns, idx / self.ns);
                let c = self.cell_center(i, k, 0.0);
                let sheave = crane.sheave(&c);
                let (Some(ci), Some(cj)) = (spec.col(sheave.x), spec.row(sheave.y)) else {
                    return self.cell_max_hoist(p, i, k);
                };
                let top = dilated[cj as usize * spec.nx as usize + ci as usize];
                let motion = self.sheave_motion(crane, c.radial);
                if top != f32::NEG_INFINITY && top as f64 >= sheave.z + motion {
                    return self.cell_max_hoist(p, i, k);
                }
                Self::rope_clear_of(task, sheave.z - motion, top).min(self.own_rope_cap(task, i, k))
            })
            .collect()
    }

    /// Longest rope at which the hanging parts' yaw-invariant envelope,
    /// anywhere in cell (i, k), keeps [`INTERNAL_MARGIN_M`] off the crane's
    /// own parts that stand or swing (carrier, outriggers, superstructure,
    /// counterweight; a tower crane's mast and cab): under one it stays above
    /// its top, beside one that reaches up to the sheave no rope is vouched
    /// for (the exact check decides), and what lies above the sheave (a
    /// tower crane's jib) it hangs below. The map holds none of them, so a
    /// load picked beside the crane was planned through its carrier, which
    /// the validator refused. The boom is kept off by the row's shortest rope.
    fn own_rope_cap(&self, task: &LiftTask, i: u32, k: u32) -> f32 {
        let crane = &task.crane;
        let c = self.cell_center(i, k, 0.0);
        let sheave = crane.sheave(&c);
        let motion = self.sheave_motion(crane, c.radial);
        let r = Self::envelope_radius(task)
            + INTERNAL_MARGIN_M
            + motion
            + Self::gust_reach_m(task, crane.limits().hoist_m.1, motion);
        let o = crane.slew_center();
        if (sheave.x - o.x).hypot(sheave.y - o.y) - r * std::f64::consts::SQRT_2 > self.own_reach_m {
            return f32::INFINITY;
        }
        let mut cap = f32::INFINITY;
        for (_, b) in standing_parts(task, &c) {
            let a = b.aabb();
            let beside =
                (0..2).all(|d| a.min[d] - r <= [sheave.x, sheave.y][d] && [sheave.x, sheave.y][d] <= a.max[d] + r);
            if !beside || a.min[2] >= sheave.z + motion {
                continue;
            }
            if a.max[2] >= sheave.z - motion {
                return f32::NEG_INFINITY;
            }
            cap = cap.min((sheave.z - motion - a.max[2] - INTERNAL_MARGIN_M - Self::hang_below_rope(task)) as f32);
        }
        cap
    }

    /// Longest rope at which the hanging parts' yaw-invariant envelope,
    /// anywhere in cell (i, k), is clear: one rectangle query.
    fn cell_max_hoist(&self, p: &Problem, i: u32, k: u32) -> f32 {
        let task = p.task;
        let crane = &task.crane;
        let c = self.cell_center(i, k, 0.0);
        let sheave = crane.sheave(&c);
        let motion = self.sheave_motion(crane, c.radial);
        let r = Self::envelope_radius(task)
            + task.clearance_m
            + motion
            + Self::gust_reach_m(task, crane.limits().hoist_m.1, motion);
        let z_lo = sheave.z - motion;
        let z_hi = (sheave.z + motion) as f32;
        // A top that leaves less than the shortest rope clear leaves none
        // (1 cm past it, for the f32 tops: no rope the crane can have is
        // vouched for where the exact top would leave less).
        let enough = (z_lo - task.clearance_m - Self::hang_below_rope(task) - crane.limits().hoist_m.0 + 0.01) as f32;
        let top = highest_below_until(p.map, (sheave.x - r, sheave.x + r, sheave.y - r, sheave.y + r), z_hi, enough);
        Self::rope_clear_of(task, z_lo, top).min(self.own_rope_cap(task, i, k))
    }

    /// Longest rope with the load's underside the clearance above `top` (the
    /// highest obstacle under the envelope, `-inf`: none) when the sheave is no
    /// lower than `sheave_z_lo`.
    fn rope_clear_of(task: &LiftTask, sheave_z_lo: f64, top: f32) -> f32 {
        if top == f32::NEG_INFINITY {
            return f32::INFINITY;
        }
        (sheave_z_lo - top as f64 - task.clearance_m - Self::hang_below_rope(task)) as f32
    }

    fn build_hoist_bits(&self, p: &Problem, s: &Settings) -> Vec<u64> {
        let task = p.task;
        let crane = &task.crane;
        let lim = crane.limits();
        let nh = (((lim.hoist_m.1 - lim.hoist_m.0) / s.full_hoist_step_m).ceil() as usize).min(64);
        (0..self.nr * self.ns)
            .into_par_iter()
            .map(|idx| {
                let (i, k) = (idx % self.ns, idx / self.ns);
                let mut bits = 0u64;
                let c0 = self.cell_center(i, k, 0.0);
                let sheave = crane.sheave(&c0);
                let motion = self.sheave_motion(crane, c0.radial);
                let r = Self::envelope_radius(task) + task.clearance_m + motion;
                let own_cap = self.own_rope_cap(task, i, k) as f64;
                for b in 0..nh {
                    let h_lo = lim.hoist_m.0 + b as f64 * s.full_hoist_step_m;
                    let h_hi = h_lo + s.full_hoist_step_m;
                    let r = r + Self::gust_reach_m(task, h_hi, motion);
                    // Cylinder from the sheave down to the load underside at the longest rope.
                    let bottom = sheave.z - motion - h_hi - Self::hang_below_rope(task) - task.clearance_m;
                    let column = Obb::axis_aligned(
                        liftplan_core::frame::Point3::new(sheave.x, sheave.y, 0.5 * (bottom + sheave.z + motion)),
                        liftplan_core::frame::Vec3::new(r, r, 0.5 * (sheave.z + motion - bottom)),
                    );
                    if h_hi > own_cap || p.map.collides(&column) {
                        bits |= 1 << b;
                    }
                }
                bits
            })
            .collect()
    }
}

/// [`CSpace::own_reach_m`]: the parts that swing turn about the slewing
/// axis, so one swing gives their reach at every swing.
fn own_reach_m(task: &LiftTask) -> f64 {
    standing_parts(task, &task.pick).map(|(_, b)| task.crane.plan_reach_m(&b)).fold(0.0, f64::max)
}

/// The crane's parts that stand or swing at `c` (carrier, outriggers,
/// superstructure, counterweight; a tower crane's mast, cab and jibs): those
/// the hanging parts are kept off besides the boom, which the depth map
/// does not hold.
fn standing_parts<'a>(task: &'a LiftTask, c: &'a Config) -> impl Iterator<Item = (PartKind, Obb)> + 'a {
    let crane = &task.crane;
    crane
        .part_kinds()
        .iter()
        .filter(|k| matches!(k.dependence(), Dependence::Fixed | Dependence::Swing))
        .filter_map(move |&k| crane.part(k, c, &task.load).map(|b| (k, b)))
}

/// Highest top of intervals starting below `z_max` over a plan rectangle.
///
/// Down the max-height pyramid, branch and bound: a block no higher than
/// what was found is skipped, a block inside the rectangle whose top is
/// below `z_max` answers for all of its cells (each of its intervals
/// starts below its top), and only blocks holding something at or above
/// `z_max` are opened down to their cells. Walking every cell of the
/// rectangle instead, the longest-clear-rope table under a plant's tall
/// structures took 640 ms of a 660 ms C-space build (reports/cspace.md).
/// The same answer as the walk ([`highest_interval_below`]'s top).
pub fn highest_below(map: &Mdm, xa: f64, xb: f64, ya: f64, yb: f64, z_max: f32) -> f32 {
    highest_below_until(map, (xa, xb, ya, yb), z_max, f32::INFINITY)
}

/// [`highest_below`], stopping as soon as a top at or above `enough` is
/// found (and then answering that top, no higher than the exact answer):
/// for a caller to whom any top that high means the same.
pub fn highest_below_until(map: &Mdm, (xa, xb, ya, yb): (f64, f64, f64, f64), z_max: f32, enough: f32) -> f32 {
    let fast = map.max_top_in(xa, xb, ya, yb);
    if fast < z_max {
        return fast;
    }
    let s = map.spec;
    let (ci, cj) = (s.cols_between(xa, xb), s.rows_between(ya, yb));
    if ci.is_empty() || cj.is_empty() || map.pyramid.is_empty() {
        return highest_interval_below(map, xa, xb, ya, yb, z_max).map_or(f32::NEG_INFINITY, |iv| iv.zhi);
    }
    let top = map.pyramid.len() - 1;
    let mut best = f32::NEG_INFINITY;
    let (w, h, _) = map.pyramid[top];
    for bj in 0..h {
        for bi in 0..w {
            highest_in_block(map, (&ci, &cj), (top, bi, bj), (z_max, enough), &mut best);
        }
    }
    best
}

/// [`highest_below`] within pyramid block `bi, bj` of level `lvl`.
fn highest_in_block(
    map: &Mdm,
    (ci, cj): (&std::ops::Range<u32>, &std::ops::Range<u32>),
    (lvl, bi, bj): (usize, u32, u32),
    (z_max, enough): (f32, f32),
    best: &mut f32,
) {
    if *best >= enough {
        return;
    }
    let (x0, x1) = (bi << lvl, (bi + 1) << lvl);
    let (y0, y1) = (bj << lvl, (bj + 1) << lvl);
    if x1 <= ci.start || x0 >= ci.end || y1 <= cj.start || y0 >= cj.end {
        return;
    }
    let (w, _, data) = &map.pyramid[lvl];
    let m = data[(bj * w + bi) as usize];
    if m <= *best {
        return;
    }
    let inside = x0 >= ci.start && x1 <= ci.end && y0 >= cj.start && y1 <= cj.end;
    if m < z_max && (inside || lvl == 0) {
        *best = m;
        return;
    }
    if lvl == 0 {
        for iv in map.cell(bi, bj).iter().filter(|iv| iv.zlo < z_max) {
            *best = best.max(iv.zhi);
        }
        return;
    }
    // The highest child first: what it finds prunes the others.
    let (cw, ch, below) = &map.pyramid[lvl - 1];
    let mut children: Vec<(f32, u32, u32)> = [(0, 0), (1, 0), (0, 1), (1, 1)]
        .into_iter()
        .map(|(di, dj)| (2 * bi + di, 2 * bj + dj))
        .filter(|&(ki, kj)| ki < *cw && kj < *ch)
        .map(|(ki, kj)| (below[(kj * cw + ki) as usize], ki, kj))
        .collect();
    children.sort_by(|a, b| b.0.total_cmp(&a.0));
    for (_, ki, kj) in children {
        highest_in_block(map, (ci, cj), (lvl - 1, ki, kj), (z_max, enough), best);
    }
}

/// The interval with the highest top among those starting below `z_max`
/// over a plan rectangle (of equal tops, the first met), cell by cell: what
/// [`highest_below`] finds, with the object it belongs to.
pub fn highest_interval_below(map: &Mdm, xa: f64, xb: f64, ya: f64, yb: f64, z_max: f32) -> Option<&Interval> {
    let s = map.spec;
    let mut top: Option<&Interval> = None;
    for j in s.rows_between(ya, yb) {
        for i in s.cols_between(xa, xb) {
            for iv in map.cell(i, j).iter().filter(|iv| iv.zlo < z_max) {
                if top.is_none_or(|t| iv.zhi > t.zhi) {
                    top = Some(iv);
                }
            }
        }
    }
    top
}

/// Shortest rope at which the load and its rigging stay clear of the boom
/// (after Cai eqs. 4.31-4.32), up to luff `luff_max`. The boom runs from the
/// sheave down towards the crane, so a point `h` below the sheave and `x`
/// from the hook line towards the crane is `h·cos(luff) - x·sin(luff)` from
/// the boom's axis; that must exceed half the boom depth, plus the load's
/// bounding sphere for its centre (off the hook line by its centre of
/// gravity) and nothing for the top corners of the rigging (a prism on the
/// load's footprint up to the hook block), each with [`INTERNAL_MARGIN_M`]
/// to spare. Swung by a gust (`gust_swing_per_m`,
/// [`LiftTask::hanging_swept`]), each box is wider by the swing at its
/// underside on every side, so its corners reach √2 times that farther: the
/// load's sphere grows by that, the rigging's corners come that much closer
/// to the crane; so they do by √2 times the centre of gravity's tolerance
/// (`cog_tolerance_m`), by which the checker grows the load and its rigging
/// as well. A tower crane's jib is level above the hook: the rope limits
/// suffice.
pub fn min_hoist_for_internal_clearance(
    crane: &CraneSetup,
    load: &LoadShape,
    luff_max: f64,
    gust_swing_per_m: f64,
    cog_tolerance_m: f64,
) -> f64 {
    match &crane.model.kind {
        liftplan_core::crane::CraneKind::Luffing(l) => {
            let (sin, cos) = (luff_max.sin().max(0.0), luff_max.cos().max(0.05));
            let half_depth = l.boom.depth_m / 2.0 + INTERNAL_MARGIN_M;
            let hook = crane.model.hook.height_m;
            let widen = std::f64::consts::SQRT_2 * gust_swing_per_m;
            // The load's centre, `h = hoist + hook + rigging + half its
            // height` down: h·cos - off·sin ≥ R + widen·(h + half its
            // height) + half the boom.
            let (centre_den, rigging_den) = (cos - widen, cos - widen * sin);
            if centre_den <= 0.0 || rigging_den <= 0.0 {
                return f64::INFINITY;
            }
            let off_line = load.cog_m[0].hypot(load.cog_m[1]);
            let off_cog = std::f64::consts::SQRT_2 * cog_tolerance_m;
            let centre =
                (load.bounding_radius() + off_cog + half_depth + off_line * sin + widen * load.size_m[2] / 2.0)
                    / centre_den
                    - hook
                    - load.rigging_height_m
                    - load.size_m[2] / 2.0;
            // The rigging's top corners, `h = hoist + hook` down:
            // h·cos - (r + widen·(h + rigging))·sin ≥ half the boom.
            let rigging = (half_depth + (load.yaw_invariant_radius() + off_cog + widen * load.rigging_height_m) * sin)
                / rigging_den
                - hook;
            centre.max(rigging)
        }
        liftplan_core::crane::CraneKind::Tower(_) => f64::NEG_INFINITY,
    }
}

/// What [`min_hoist_for_internal_clearance`] keeps between the load or its
/// rigging and the boom (m); the validator asks for 1 cm.
pub const INTERNAL_MARGIN_M: f64 = 0.05;

/// A crane joint, for single-joint moves.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Joint {
    Swing,
    Radial,
    Hoist,
    Rotate,
}

impl Joint {
    pub fn index(self) -> usize {
        match self {
            Joint::Swing => 0,
            Joint::Radial => 1,
            Joint::Hoist => 2,
            Joint::Rotate => 3,
        }
    }
}

/// A plan-view convex polygon over which the load may come closer to obstacles
/// (the landing zones at pick and set, where it must meet its supports).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LandingZone {
    pub polygon: Vec<[f64; 2]>,
    pub clearance_m: f64,
}

impl LandingZone {
    /// Zone over a load box's footprint grown by `margin_m`.
    pub fn around(load_box: &Obb, margin_m: f64, clearance_m: f64) -> LandingZone {
        let grown = load_box.expanded(margin_m);
        LandingZone { polygon: grown.footprint(), clearance_m }
    }

    /// Does the zone hold the whole footprint of `b`?
    pub fn holds(&self, b: &Obb) -> bool {
        // The zone is convex: the box's footprint (the hull of its corners) is
        // inside exactly when every corner is.
        b.corners().iter().all(|c| inside_convex(&self.polygon, &[c.x, c.y]))
    }
}

fn inside_convex(poly: &[[f64; 2]], p: &[f64; 2]) -> bool {
    let n = poly.len();
    if n < 3 {
        return false;
    }
    let mut sign = 0.0;
    for k in 0..n {
        let a = poly[k];
        let b = poly[(k + 1) % n];
        let cr = (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
        if cr.abs() < 1e-12 {
            continue;
        }
        if sign == 0.0 {
            sign = cr.signum();
        } else if cr.signum() != sign {
            return false;
        }
    }
    true
}

/// How far the hanging parts may move, horizontally and vertically (m), over
/// the piece of a move that one configuration's check stands for.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Sweep {
    horizontal_m: f64,
    vertical_m: f64,
}

impl Sweep {
    const NONE: Sweep = Sweep { horizontal_m: 0.0, vertical_m: 0.0 };

    /// Swinging and turning the load move every hanging point on a horizontal
    /// circle, hoisting moves it straight up or down, a trolley moves it along
    /// the jib; luffing moves the sheave on a circle in the boom's plane, so the
    /// load moves both ways.
    fn of(joint: Joint, luffing: bool, reach_m: f64) -> Sweep {
        let (horizontal, vertical) = match joint {
            Joint::Swing | Joint::Rotate => (true, false),
            Joint::Hoist => (false, true),
            Joint::Radial => (true, luffing),
        };
        Sweep { horizontal_m: if horizontal { reach_m } else { 0.0 }, vertical_m: if vertical { reach_m } else { 0.0 } }
    }
}

/// Counters of what the checker did (for the strategy benchmark).
///
/// Every thread counts in its own cache line: one shared pair of atomics,
/// bumped from every thread thousands of times per string, cost the GA a
/// tenth of its time in cache-line transfers.
#[derive(Debug, Default)]
pub struct Counters {
    slots: [CounterSlot; COUNTER_SLOTS],
}

const COUNTER_SLOTS: usize = 32;

#[derive(Debug, Default)]
#[repr(align(128))]
struct CounterSlot {
    lookups: std::sync::atomic::AtomicU64,
    box_queries: std::sync::atomic::AtomicU64,
}

impl Counters {
    fn slot(&self) -> &CounterSlot {
        use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};
        static NEXT: AtomicUsize = AtomicUsize::new(0);
        thread_local!(static SLOT: usize = NEXT.fetch_add(1, Relaxed) % COUNTER_SLOTS);
        &self.slots[SLOT.with(|s| *s)]
    }

    fn total(&self, pick: impl Fn(&CounterSlot) -> &std::sync::atomic::AtomicU64) -> u64 {
        self.slots.iter().map(|s| pick(s).load(std::sync::atomic::Ordering::Relaxed)).sum()
    }

    /// Table lookups so far.
    pub fn lookups(&self) -> u64 {
        self.total(|s| &s.lookups)
    }

    /// Box queries against the depth map so far.
    pub fn box_queries(&self) -> u64 {
        self.total(|s| &s.box_queries)
    }
}

/// The collision, clearance, capacity and internal-clearance checker the
/// planners share.
pub struct Checker<'a> {
    pub cs: &'a CSpace,
    pub map: &'a Mdm,
    pub task: &'a LiftTask,
    pub landing: Vec<LandingZone>,
    pub sample_m: f64,
    pub counters: Counters,
}

impl<'a> Checker<'a> {
    pub fn new(cs: &'a CSpace, map: &'a Mdm, task: &'a LiftTask, landing: Vec<LandingZone>, sample_m: f64) -> Self {
        Checker { cs, map, task, landing, sample_m, counters: Counters::default() }
    }

    fn count(&self, box_query: bool) {
        self.count_n(box_query, 1);
    }

    /// Adds `n` at once: hot loops count locally and add once (an atomic add
    /// per table lookup cost the planner ~8 %).
    fn count_n(&self, box_query: bool, n: u64) {
        use std::sync::atomic::Ordering::Relaxed;
        let slot = self.counters.slot();
        if box_query {
            slot.box_queries.fetch_add(n, Relaxed);
        } else {
            slot.lookups.fetch_add(n, Relaxed);
        }
    }

    fn blocked(&self, reason: &str, part: Option<PartKind>, obj: Option<u32>, at: &Config) -> Blocked {
        Blocked {
            reason: reason.into(),
            part,
            object: obj.map(|o| self.map.objects.get(o as usize).cloned().unwrap_or_else(|| format!("object {o}"))),
            at: *at,
        }
    }

    /// Joint ranges, chart capacity and internal clearance at one configuration.
    pub fn limits_ok(&self, c: &Config) -> Result<(), Blocked> {
        let lim = self.task.crane.limits();
        let Some(k) = self.cs.row(c.radial) else {
            return Err(self.blocked("joint limit (radial)", None, None, c));
        };
        if !(c.hoist_m >= lim.hoist_m.0 - 1e-9 && c.hoist_m <= lim.hoist_m.1 + 1e-9) {
            return Err(self.blocked("joint limit (rope length)", None, None, c));
        }
        if let Some((a, b)) = self.task.swing_range_rad
            && !(c.swing_rad >= a - 1e-9 && c.swing_rad <= b + 1e-9)
        {
            return Err(self.blocked("joint limit (permitted swing range)", None, None, c));
        }
        self.row_ok(k, c)
    }

    /// Chart capacity and internal clearance of radial row `k`, at `c`.
    fn row_ok(&self, k: u32, c: &Config) -> Result<(), Blocked> {
        match self.cs.row_capacity_kg[k as usize] {
            Some(cap) if self.task.effective_capacity_kg(cap) >= self.task.gross_kg() => {}
            _ => return Err(self.blocked("capacity (outside the load chart or over capacity)", None, None, c)),
        }
        if c.hoist_m < self.cs.row_min_hoist[k as usize] - 1e-9 {
            return Err(self.blocked("internal clearance (load too close to the boom)", Some(PartKind::Load), None, c));
        }
        Ok(())
    }

    /// Body and boom in table cell (i, k), reported at `c`.
    fn cell_structure_ok(&self, i: u32, k: u32, c: &Config) -> Result<(), Blocked> {
        let cs = self.cs;
        match cs.swing_hits[i as usize].or(cs.cell_hits[(k * cs.ns + i) as usize]) {
            Some(h) => Err(self.blocked(TOO_CLOSE, Some(h.part), Some(h.obj), c)),
            None => Ok(()),
        }
    }

    /// Body and boom at one configuration (tables, or box queries online).
    fn structure_ok(&self, c: &Config) -> Result<(), Blocked> {
        let cs = self.cs;
        if cs.strategy != Strategy::Online {
            self.count(false);
            return self.cell_structure_ok(cs.col(c.swing_rad), cs.row(c.radial).unwrap_or(0), c);
        }
        let crane = &self.task.crane;
        for &kind in crane.part_kinds() {
            if matches!(kind.dependence(), Dependence::Swing | Dependence::SwingRadial) {
                let Some(b) = crane.part(kind, c, &self.task.load) else { continue };
                self.count(true);
                // Like a table cell: the box covers every configuration within
                // half a grid step of this one, which is how far apart a move's
                // samples are.
                let grow = self.task.clearance_m
                    + if kind.dependence() == Dependence::Swing {
                        crane.plan_reach_m(&b) * cs.swing_step / 2.0
                    } else {
                        cs.cell_motion(crane, &b)
                    };
                let leave = left_out(crane, kind);
                if let Some(h) = self.map.hit_where(&b.expanded(grow), |iv| LeaveOut::counts(leave, iv)) {
                    return Err(self.blocked(TOO_CLOSE, Some(kind), Some(h.interval.obj), c));
                }
            }
        }
        Ok(())
    }

    /// Rope, hook block and load at one configuration, each box grown by the
    /// clearance (less inside a landing zone) and by how far its points may
    /// move over the piece of a move the configuration stands for.
    fn hanging_exact(&self, c: &Config, sweep: Sweep, landing: bool) -> Result<(), Blocked> {
        let parts = self.task.crane.hanging_parts(c, &self.task.load);
        let load_box = &parts[0].1;
        let zone = if landing { self.landing.iter().find(|z| z.holds(load_box)) } else { None };
        let clearance = zone.map(|z| z.clearance_m).unwrap_or(self.task.clearance_m);
        // Over the piece the sheave may stand up to `vertical_m` higher and
        // each part hang that much lower: as far below it as a gust swings.
        let sheave_z = self.task.crane.sheave(c).z + sweep.vertical_m;
        for (queried, (kind, b)) in (1..).zip(parts) {
            let grown = b.expanded(clearance).expanded_by_motion(sweep.horizontal_m, sweep.vertical_m);
            let grown = self.task.hanging_swept(kind, &grown, sheave_z);
            if let Some(h) = self.map.hit(&grown) {
                self.count_n(true, queried);
                return Err(self.blocked(TOO_CLOSE, Some(kind), Some(h.interval.obj), c));
            }
        }
        self.count_n(true, parts.len() as u64);
        // The load and its rigging off the crane's own parts that stand or
        // swing, as the validator asks ([`Self::own_rope_cap`]), swung as
        // off the site.
        let o = self.task.crane.slew_center();
        for (kind, b) in parts.iter().filter(|(k, _)| matches!(k, PartKind::Load | PartKind::Rigging)) {
            let grown = b.expanded(INTERNAL_MARGIN_M).expanded_by_motion(sweep.horizontal_m, sweep.vertical_m);
            let grown = self.task.hanging_swept(*kind, &grown, sheave_z);
            // Most of the time the load is far out: nothing of the crane there.
            let plan_radius = grown.half.x.hypot(grown.half.y);
            if (grown.center.x - o.x).hypot(grown.center.y - o.y) - plan_radius > self.cs.own_reach_m {
                continue;
            }
            for (own, own_box) in standing_parts(self.task, c) {
                if grown.intersects(&own_box) {
                    return Err(Blocked {
                        reason: TOO_CLOSE.into(),
                        part: Some(*kind),
                        object: Some(format!("the crane's {}", own.name())),
                        at: *c,
                    });
                }
            }
        }
        Ok(())
    }

    /// Can the hanging parts' check at rope lengths up to `h_max` in the cell of
    /// `c` be answered from the tables?
    fn hanging_lookup(&self, c: &Config, h_max: f64) -> bool {
        let cs = self.cs;
        if cs.strategy == Strategy::Online {
            return false;
        }
        let (i, k) = (cs.col(c.swing_rad), cs.row(c.radial).unwrap_or(0));
        self.count(false);
        self.table_covers((k * cs.ns + i) as usize, h_max)
    }

    /// Do the tables vouch for the hanging parts in cell `idx` at rope lengths
    /// up to `h_max`?
    fn table_covers(&self, idx: usize, h_max: f64) -> bool {
        let cs = self.cs;
        if h_max <= cs.max_hoist[idx] as f64 {
            return true;
        }
        if cs.strategy != Strategy::Full {
            return false;
        }
        let b_hi = ((h_max - cs.hoist0) / cs.hoist_step).floor() as i64;
        if !(0..64).contains(&b_hi) {
            return false;
        }
        // Longer ropes hang lower: the column test at bucket b covers every
        // shorter rope too, so one bit decides.
        cs.hoist_bits[idx] & (1 << b_hi) == 0
    }

    /// The load's footprint, grown by `grow_m` in plan, off every area the
    /// lift says the load must not be over, and the swinging parts' off
    /// those the crane may not be over either, by
    /// [`liftplan_core::lift::NOT_OVER_MARGIN_M`]. Not in the tables: an area
    /// has no height, and is no obstacle to anything else.
    fn not_over_ok(&self, c: &Config, grow_m: f64) -> Result<(), Blocked> {
        match self.task.not_over_near(c, grow_m + liftplan_core::lift::NOT_OVER_MARGIN_M, true) {
            None => Ok(()),
            Some((part, a)) => Err(Blocked {
                reason: OVER_NOT_OVER.into(),
                part: Some(part),
                object: Some(format!("not_over '{}'", a.name)),
                at: *c,
            }),
        }
    }

    /// How far (m) a point of a part that turns with the swing can move per
    /// unit of `joint` from `from`, for the areas the crane may not be over:
    /// on a swing, the farthest corner of those parts from the slewing axis
    /// (the radial joint stays put); on a luff, the boom's farthest corner
    /// from its foot pin, which the rope and hook hang from; on a trolley
    /// move, one; hoisting and turning the load move none of them sideways.
    fn crane_lever(&self, joint: Joint, from: &Config) -> f64 {
        let crane = &self.task.crane;
        let swinging = crane.part_kinds().iter().filter(|k| k.dependence() != liftplan_core::crane::Dependence::Fixed);
        match joint {
            Joint::Swing => swinging
                .filter_map(|&k| crane.part(k, from, &self.task.load))
                .map(|b| crane.plan_reach_m(&b))
                .fold(0.0, f64::max),
            Joint::Radial if is_luffing(crane) => {
                crane.part(PartKind::Boom, from, &self.task.load).map_or(0.0, |boom| 2.0 * boom.half.norm())
            }
            Joint::Radial => 1.0,
            Joint::Hoist | Joint::Rotate => 0.0,
        }
    }

    /// [`Self::not_over_ok`] over the joint range [x0, x1] of a move: the
    /// middle's footprint grown by half the range's horizontal travel
    /// covers the range; where it meets an area the range is halved, down
    /// to pieces of `sample_m` travel, which must pass.
    fn not_over_piece(&self, a: &[f64; 4], joint: Joint, x0: f64, x1: f64, lever: f64) -> Result<(), Blocked> {
        let travel = (x1 - x0).abs() * lever;
        let xm = 0.5 * (x0 + x1);
        let sweep = Sweep::of(joint, is_luffing(&self.task.crane), travel / 2.0);
        // Hanging lower over the range (a hoist, a luff), the load swings
        // farther in a gust than at the middle: by what it hangs lower, with
        // the sheave risen as far as the load sank.
        let grow_m = sweep.horizontal_m + self.task.gust_swing_per_m * 2.0 * sweep.vertical_m;
        match self.not_over_ok(&self.with(a, joint, xm), grow_m) {
            Err(_) if travel > self.sample_m && grow_m > 0.0 => {
                self.not_over_piece(a, joint, x0, xm, lever)?;
                self.not_over_piece(a, joint, xm, x1, lever)
            }
            done => done,
        }
    }

    /// Everything at one configuration: limits, capacity, internal clearance,
    /// body, boom, the hanging parts and the areas the load must not be over.
    pub fn config(&self, c: &Config) -> Result<(), Blocked> {
        self.limits_ok(c)?;
        self.structure_ok(c)?;
        self.not_over_ok(c, 0.0)?;
        if self.hanging_lookup(c, c.hoist_m) {
            return Ok(());
        }
        self.hanging_exact(c, Sweep::NONE, true)
    }

    /// A single-joint move from `from` to the joint value `to`, continuously.
    ///
    /// With the tables, whose answers cover whole cells, the move is walked
    /// cell by cell: every cell it enters is looked up, and the stretches of
    /// the move in cells where the tables cannot vouch for the hanging parts
    /// are checked exactly ([`Self::exact_piece`]). Online, the body and boom
    /// are checked at sub-steps at most one grid step apart and the hanging
    /// parts exactly over the whole move.
    pub fn motion(&self, from: &Config, joint: Joint, to: f64) -> Result<(), Blocked> {
        let v0 = from.to_array()[joint.index()];
        if (to - v0).abs() < 1e-12 {
            return self.config(from);
        }
        let crane = &self.task.crane;
        // How far (m) a hanging point can move per unit of the joint.
        let lever = match joint {
            Joint::Swing => {
                crane.radius_m(from.radial)
                    + self.task.load.bounding_radius()
                    + self.task.load.cog_m[0].hypot(self.task.load.cog_m[1])
            }
            Joint::Radial => {
                if is_luffing(crane) {
                    crane.placement.boom_length_m
                } else {
                    1.0
                }
            }
            Joint::Hoist => 1.0,
            Joint::Rotate => self.task.load.bounding_radius() * 2.0,
        };
        if !self.task.not_over.is_empty() {
            let crane_too = self.task.not_over.iter().any(|a| a.crane_too);
            let lever = if crane_too { lever.max(self.crane_lever(joint, from)) } else { lever };
            self.not_over_piece(&from.to_array(), joint, v0, to, lever)?;
        }
        if self.cs.strategy == Strategy::Online {
            self.motion_sampled(from, joint, to, lever)
        } else {
            self.motion_by_cells(from, joint, to, lever)
        }
    }

    fn motion_by_cells(&self, from: &Config, joint: Joint, to: f64, lever: f64) -> Result<(), Blocked> {
        let cs = self.cs;
        let a = from.to_array();
        let v0 = a[joint.index()];
        let end = self.with(&a, joint, to);
        // The joint moves monotonically: its range, and the row's capacity and
        // internal clearance for a move that stays in one row, hold at both ends.
        self.limits_ok(from)?;
        self.limits_ok(&end)?;
        let h_max = from.hoist_m.max(end.hoist_m);
        // The move's cells: along the swing columns or the radial rows for those
        // joints (cell j spans [origin + j·step, origin + (j+1)·step)), else the one
        // cell it turns or hoists in.
        let grid = match joint {
            Joint::Swing => Some((0.0, cs.swing_step)),
            Joint::Radial => Some((cs.radial0, cs.radial_step)),
            Joint::Hoist | Joint::Rotate => None,
        };
        let cell_of = |v: f64| grid.map(|(origin, step)| ((v - origin) / step).floor() as i64).unwrap_or(0);
        let (j0, j1) = (cell_of(v0), cell_of(to));
        if j0.abs_diff(j1) > 4 * (cs.ns as u64 + cs.nr as u64) {
            return Err(self.blocked("joint limit (move longer than the crane's range)", None, None, from));
        }
        let up = to > v0;
        let (i_from, k_from) = (cs.col(from.swing_rad), cs.row(from.radial).unwrap_or(0));
        // Every cell the move enters is one lookup, counted once for the move.
        self.count_n(false, j0.abs_diff(j1) + 1);
        // Start of the stretch the tables cannot vouch for, if one is open.
        let mut run: Option<f64> = None;
        let mut j = j0;
        loop {
            let (xa, xb) = match grid {
                Some((origin, step)) => {
                    let (lo, hi) = (origin + j as f64 * step, origin + (j + 1) as f64 * step);
                    if up { (v0.max(lo), to.min(hi)) } else { (v0.min(hi), to.max(lo)) }
                }
                None => (v0, to),
            };
            let (i, k) = match joint {
                Joint::Swing => (j.rem_euclid(cs.ns as i64) as u32, k_from),
                Joint::Radial => (i_from, j.clamp(0, cs.nr as i64 - 1) as u32),
                Joint::Hoist | Joint::Rotate => (i_from, k_from),
            };
            let at = self.with(&a, joint, xa);
            if joint == Joint::Radial {
                self.row_ok(k, &at)?;
            }
            self.cell_structure_ok(i, k, &at)?;
            if self.table_covers((k * cs.ns + i) as usize, h_max) {
                if let Some(r0) = run.take() {
                    self.exact_piece(&a, joint, r0, xa, lever)?;
                }
            } else if run.is_none() {
                run = Some(xa);
            }
            if j == j1 {
                if let Some(r0) = run {
                    self.exact_piece(&a, joint, r0, xb, lever)?;
                }
                return Ok(());
            }
            j += if up { 1 } else { -1 };
        }
    }

    /// Online: body and boom at sub-steps at most one grid step apart (each
    /// box query covers half a step either way), the hanging parts exactly.
    fn motion_sampled(&self, from: &Config, joint: Joint, to: f64, lever: f64) -> Result<(), Blocked> {
        let cs = self.cs;
        let mut a = from.to_array();
        let v0 = a[joint.index()];
        let step = match joint {
            Joint::Swing => cs.swing_step,
            Joint::Radial => cs.radial_step,
            Joint::Hoist | Joint::Rotate => f64::INFINITY,
        };
        let n = if step.is_finite() { (((to - v0).abs() / step).ceil() as usize).max(1) } else { 1 };
        for s in 0..=n {
            a[joint.index()] = v0 + (to - v0) * s as f64 / n as f64;
            let c = Config::from_array(a);
            self.limits_ok(&c)?;
            self.structure_ok(&c)?;
        }
        self.exact_piece(&a, joint, v0, to, lever)
    }

    /// Exact check of the hanging parts over the joint range [x0, x1] of a move.
    ///
    /// The configuration at the middle, with the boxes grown by half the travel
    /// of the range (`lever` metres per joint unit) the way the joint moves them
    /// (swing, load rotation and a tower crane's trolley only horizontally,
    /// hoisting only vertically, luffing both ways), covers every configuration
    /// of the range. Far from obstacles one such query settles a long range;
    /// where it hits, the range is halved, down to pieces of `sample_m` travel,
    /// which must pass. Only those smallest pieces (and hoisting, see below)
    /// may use a landing zone's reduced clearance.
    fn exact_piece(&self, a: &[f64; 4], joint: Joint, x0: f64, x1: f64, lever: f64) -> Result<(), Blocked> {
        let travel = (x1 - x0).abs() * lever;
        let xm = 0.5 * (x0 + x1);
        let mid = self.with(a, joint, xm);
        let sweep = Sweep::of(joint, is_luffing(&self.task.crane), travel / 2.0);
        // Hoisting keeps the load's footprint, so a landing zone holds all of
        // the range or none of it, and the grown box is the exact swept volume:
        // one query answers for every piece the range would be halved into.
        if travel <= self.sample_m || joint == Joint::Hoist {
            return self.hanging_exact(&mid, sweep, true);
        }
        if self.hanging_exact(&mid, sweep, false).is_ok() {
            return Ok(());
        }
        self.exact_piece(a, joint, x0, xm, lever)?;
        self.exact_piece(a, joint, xm, x1, lever)
    }

    fn with(&self, a: &[f64; 4], joint: Joint, v: f64) -> Config {
        let mut b = *a;
        b[joint.index()] = v;
        Config::from_array(b)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn convex_inside() {
        let sq = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        assert!(inside_convex(&sq, &[0.5, 0.5]));
        assert!(!inside_convex(&sq, &[1.5, 0.5]));
    }
}
