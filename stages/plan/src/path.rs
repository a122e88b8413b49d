//! Paths: node configurations, the single-joint moves between them (the
//! post-processing of Cai §4.3.3), and their costs.
//!
//! Cranes are operated one motion class at a time. Between two node
//! configurations the load swings while it is high: if the load is higher at
//! the edge's start, the crane swings first, rotates the load, then luffs and
//! hoists; otherwise it luffs and hoists first, rotates, then swings. Within
//! luffing and hoisting, the motion that raises the load goes first.

use liftplan_core::crane::Config;
use liftplan_cspace::{Blocked, Checker, Joint};
use serde::{Deserialize, Serialize};

/// One single-joint move: `joint` goes to `to` starting from `from`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Move {
    pub joint: Joint,
    pub from: Config,
    pub to: Config,
}

impl Move {
    pub fn delta(&self) -> f64 {
        self.to.to_array()[self.joint.index()] - self.from.to_array()[self.joint.index()]
    }
}

/// Per-joint motion-cost weights (Cai Table 4.13: swing 1.0 /deg, luff 1.5 /deg,
/// sling 0.06 /cm, rotation 1.0 /deg). A tower crane's trolley uses the sling
/// weight per cm.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Weights {
    pub swing_per_deg: f64,
    pub luff_per_deg: f64,
    pub hoist_per_cm: f64,
    pub rotate_per_deg: f64,
}

impl Default for Weights {
    fn default() -> Self {
        Weights { swing_per_deg: 1.0, luff_per_deg: 1.5, hoist_per_cm: 0.06, rotate_per_deg: 1.0 }
    }
}

impl Weights {
    /// Weighted motion units of a joint change (the thesis' d1 term).
    pub fn cost(&self, joint: Joint, delta: f64, tower: bool) -> f64 {
        let d = delta.abs();
        match joint {
            Joint::Swing => self.swing_per_deg * d.to_degrees(),
            Joint::Radial if tower => self.hoist_per_cm * d * 100.0,
            Joint::Radial => self.luff_per_deg * d.to_degrees(),
            Joint::Hoist => self.hoist_per_cm * d * 100.0,
            Joint::Rotate => self.rotate_per_deg * d.to_degrees(),
        }
    }
}

/// Height of the load underside at a configuration.
pub fn load_height(ck: &Checker, c: &Config) -> f64 {
    ck.task.crane.load_bottom_z(c, &ck.task.load)
}

/// The single-joint moves of the edge `a -> b` in operating order.
pub fn edge_moves(ck: &Checker, a: &Config, b: &Config) -> Vec<Move> {
    const EPS: f64 = 1e-9;
    let mut out = Vec::with_capacity(4);
    let mut cur = *a;
    let mut go = |joint: Joint, v: f64, cur: &mut Config| {
        let mut arr = cur.to_array();
        if (arr[joint.index()] - v).abs() > EPS {
            arr[joint.index()] = v;
            let to = Config::from_array(arr);
            out.push(Move { joint, from: *cur, to });
            *cur = to;
        }
    };
    let luff_hoist = |cur: &mut Config, go: &mut dyn FnMut(Joint, f64, &mut Config)| {
        // Raise first: try luff then hoist, keep the order whose first move lifts the load.
        let mut luffed = *cur;
        luffed.radial = b.radial;
        let luff_raises = load_height(ck, &luffed) >= load_height(ck, cur);
        if luff_raises {
            go(Joint::Radial, b.radial, cur);
            go(Joint::Hoist, b.hoist_m, cur);
        } else {
            go(Joint::Hoist, b.hoist_m, cur);
            go(Joint::Radial, b.radial, cur);
        }
    };
    if load_height(ck, a) >= load_height(ck, b) {
        go(Joint::Swing, b.swing_rad, &mut cur);
        go(Joint::Rotate, b.load_yaw_rad, &mut cur);
        luff_hoist(&mut cur, &mut go);
    } else {
        luff_hoist(&mut cur, &mut go);
        go(Joint::Rotate, b.load_yaw_rad, &mut cur);
        go(Joint::Swing, b.swing_rad, &mut cur);
    }
    out
}

/// Appends `m` to a move list, merging it into the last move when both turn
/// the same joint the same way.
pub fn push_merged(out: &mut Vec<Move>, m: Move) {
    if let Some(last) = out.last_mut()
        && last.joint == m.joint
        && last.delta().signum() == m.delta().signum()
    {
        last.to = m.to;
        return;
    }
    out.push(m);
}

/// All moves of a node path, consecutive moves of one joint merged.
pub fn path_moves(ck: &Checker, nodes: &[Config]) -> Vec<Move> {
    let mut out: Vec<Move> = Vec::new();
    for w in nodes.windows(2) {
        for m in edge_moves(ck, &w[0], &w[1]) {
            push_merged(&mut out, m);
        }
    }
    out
}

/// Weighted motion units (d) and operation switches (sc) of a move list.
pub fn cost(moves: &[Move], w: &Weights, tower: bool) -> (f64, usize) {
    let d = moves.iter().map(|m| w.cost(m.joint, m.delta(), tower)).sum();
    let sc = moves.windows(2).filter(|p| p[0].joint != p[1].joint).count();
    (d, sc)
}

/// Checks every move continuously; the first problem.
pub fn check_moves(ck: &Checker, moves: &[Move]) -> Result<(), Blocked> {
    for m in moves {
        ck.motion(&m.from, m.joint, m.to.to_array()[m.joint.index()])?;
    }
    Ok(())
}

/// Checks an edge (its moves in operating order).
pub fn check_edge(ck: &Checker, a: &Config, b: &Config) -> Result<(), Blocked> {
    check_moves(ck, &edge_moves(ck, a, b))
}

/// Drops intermediate nodes while the shortcut edge is valid and no costlier:
/// fewer steps for the operator, deterministic.
pub fn shortcut(ck: &Checker, nodes: &[Config], w: &Weights) -> Vec<Config> {
    let tower = ck.task.crane.model.is_tower();
    let mut out = nodes.to_vec();
    let mut i = 0;
    while i + 2 < out.len() {
        let mut removed = false;
        for j in (i + 2..out.len()).rev() {
            let direct = edge_moves(ck, &out[i], &out[j]);
            let (d_direct, sc_direct) = cost(&direct, w, tower);
            let via = path_moves(ck, &out[i..=j]);
            let (d_via, sc_via) = cost(&via, w, tower);
            if d_direct + 10.0 * sc_direct as f64 <= d_via + 10.0 * sc_via as f64 + 1e-9
                && check_moves(ck, &direct).is_ok()
            {
                out.drain(i + 1..j);
                removed = true;
                break;
            }
        }
        if !removed {
            i += 1;
        }
    }
    out
}
