//! Baseline planners on the same checker, for the benchmarks: RRT-Connect with
//! Zhang & Hammad's modifications (selective sampling: only collision-free
//! samples are kept; anytime shortening of the found path) and PRM as in the
//! PathGuider paper (random free samples, k nearest neighbours, shortest path).
//! Ali et al.'s GA is [`crate::mspga::run`] with [`crate::mspga::Fitness::Ali`].

use crate::mspga::Bounds;
use crate::path::{self, Weights};
use liftplan_core::crane::Config;
use liftplan_core::rng;
use liftplan_cspace::Checker;
use serde::{Deserialize, Serialize};

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct BaselineSettings {
    pub rrt_iterations: usize,
    /// Largest joint change per RRT extension, as a fraction of each joint's range.
    pub rrt_step: f64,
    pub goal_bias: f64,
    pub prm_samples: usize,
    pub prm_neighbours: usize,
}

impl Default for BaselineSettings {
    fn default() -> Self {
        BaselineSettings { rrt_iterations: 4000, rrt_step: 0.1, goal_bias: 0.1, prm_samples: 400, prm_neighbours: 10 }
    }
}

impl BaselineSettings {
    /// Ranges that keep a baseline's work and memory bounded: RRT grows a tree
    /// node per iteration, PRM compares every sample with every other.
    pub fn check(&self) -> Result<(), String> {
        let unit = |v: f64| v.is_finite() && (0.0..=1.0).contains(&v);
        if !(1..=1_000_000).contains(&self.rrt_iterations) || !(unit(self.rrt_step) && self.rrt_step > 0.0) {
            return Err("[plan.baselines] rrt_iterations must be 1..1000000 and rrt_step in (0, 1]".into());
        }
        if !unit(self.goal_bias) {
            return Err("[plan.baselines] goal_bias must be in [0, 1]".into());
        }
        if !(2..=20_000).contains(&self.prm_samples) || !(1..=100).contains(&self.prm_neighbours) {
            return Err("[plan.baselines] prm_samples must be 2..20000 and prm_neighbours 1..100".into());
        }
        Ok(())
    }
}

/// A baseline's answer.
#[derive(Debug, Clone, Serialize)]
pub struct BaselineResult {
    pub nodes: Vec<Config>,
    pub found: bool,
    pub iterations: usize,
    pub edge_checks: usize,
}

fn metric(a: &Config, b: &Config, w: &Weights, tower: bool) -> f64 {
    use liftplan_cspace::Joint::*;
    w.cost(Swing, b.swing_rad - a.swing_rad, tower)
        + w.cost(Radial, b.radial - a.radial, tower)
        + w.cost(Hoist, b.hoist_m - a.hoist_m, tower)
        + w.cost(Rotate, b.load_yaw_rad - a.load_yaw_rad, tower)
}

fn sample(r: &mut rng::Rng, b: &Bounds) -> Config {
    let mut a = [0.0; 4];
    for j in 0..4 {
        a[j] = rng::uniform(r, b.lo[j], b.hi[j].max(b.lo[j] + 1e-12));
    }
    Config::from_array(a)
}

fn steer(from: &Config, to: &Config, b: &Bounds, frac: f64) -> Config {
    let (a, t) = (from.to_array(), to.to_array());
    let mut ratio: f64 = 1.0;
    for j in 0..4 {
        let range = (b.hi[j] - b.lo[j]).max(1e-9);
        let d = (t[j] - a[j]).abs();
        if d > frac * range {
            ratio = ratio.min(frac * range / d);
        }
    }
    let mut out = [0.0; 4];
    for j in 0..4 {
        out[j] = a[j] + (t[j] - a[j]) * ratio;
    }
    Config::from_array(out)
}

/// RRT-Connect.
pub fn rrt_connect(
    ck: &Checker,
    start: &Config,
    goal: &Config,
    s: &BaselineSettings,
    w: &Weights,
    seed: u64,
) -> BaselineResult {
    let tower = ck.task.crane.model.is_tower();
    let mut r = rng::seeded(seed, "rrt-connect");
    let b = Bounds::for_task(ck, start, goal, 20f64.to_radians());
    // Trees as (config, parent) lists.
    let mut ta: Vec<(Config, usize)> = vec![(*start, usize::MAX)];
    let mut tb: Vec<(Config, usize)> = vec![(*goal, usize::MAX)];
    let mut swapped = false;
    let mut checks = 0;
    let nearest = |t: &[(Config, usize)], q: &Config| {
        (0..t.len()).fold(0, |bi, i| if metric(&t[i].0, q, w, tower) < metric(&t[bi].0, q, w, tower) { i } else { bi })
    };
    for it in 0..s.rrt_iterations {
        let target = if rng::unit(&mut r) < s.goal_bias { tb[0].0 } else { sample(&mut r, &b) };
        if ck.config(&target).is_err() {
            continue; // selective sampling
        }
        let na = nearest(&ta, &target);
        let q_new = steer(&ta[na].0, &target, &b, s.rrt_step);
        checks += 1;
        if path::check_edge(ck, &ta[na].0, &q_new).is_err() {
            std::mem::swap(&mut ta, &mut tb);
            swapped = !swapped;
            continue;
        }
        ta.push((q_new, na));
        // Connect the other tree greedily.
        let mut nb = nearest(&tb, &q_new);
        loop {
            let q = steer(&tb[nb].0, &q_new, &b, s.rrt_step);
            checks += 1;
            if path::check_edge(ck, &tb[nb].0, &q).is_err() {
                break;
            }
            tb.push((q, nb));
            nb = tb.len() - 1;
            if metric(&q, &q_new, w, tower) < 1e-9 {
                // Joined: assemble start -> goal.
                let walk = |t: &[(Config, usize)], mut i: usize| {
                    let mut v = Vec::new();
                    while i != usize::MAX {
                        v.push(t[i].0);
                        i = t[i].1;
                    }
                    v
                };
                let mut from_a = walk(&ta, ta.len() - 1);
                from_a.reverse();
                let from_b = walk(&tb, nb);
                let mut nodes: Vec<Config> = from_a;
                nodes.extend(from_b.into_iter().skip(1));
                if swapped {
                    nodes.reverse();
                }
                // Anytime shortening.
                let nodes = path::shortcut(ck, &nodes, w);
                return BaselineResult { nodes, found: true, iterations: it + 1, edge_checks: checks };
            }
        }
        std::mem::swap(&mut ta, &mut tb);
        swapped = !swapped;
    }
    BaselineResult { nodes: vec![], found: false, iterations: s.rrt_iterations, edge_checks: checks }
}

/// PRM: free samples, k-nearest roadmap, Dijkstra by weighted motion cost.
pub fn prm(
    ck: &Checker,
    start: &Config,
    goal: &Config,
    s: &BaselineSettings,
    w: &Weights,
    seed: u64,
) -> BaselineResult {
    let tower = ck.task.crane.model.is_tower();
    let mut r = rng::seeded(seed, "prm");
    let b = Bounds::for_task(ck, start, goal, 20f64.to_radians());
    let mut nodes = vec![*start, *goal];
    let mut tries = 0;
    while nodes.len() < s.prm_samples + 2 && tries < s.prm_samples * 20 {
        tries += 1;
        let q = sample(&mut r, &b);
        if ck.config(&q).is_ok() {
            nodes.push(q);
        }
    }
    let n = nodes.len();
    let mut adj: Vec<Vec<(usize, f64)>> = vec![vec![]; n];
    let mut checks = 0;
    for i in 0..n {
        let mut near: Vec<(f64, usize)> =
            (0..n).filter(|&j| j != i).map(|j| (metric(&nodes[i], &nodes[j], w, tower), j)).collect();
        near.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        for &(d, j) in near.iter().take(s.prm_neighbours) {
            if adj[i].iter().any(|e| e.0 == j) {
                continue;
            }
            checks += 1;
            if path::check_edge(ck, &nodes[i], &nodes[j]).is_ok() && path::check_edge(ck, &nodes[j], &nodes[i]).is_ok()
            {
                adj[i].push((j, d));
                adj[j].push((i, d));
            }
        }
    }
    // Dijkstra (n is small: O(n^2) keeps it simple and deterministic).
    let mut dist = vec![f64::INFINITY; n];
    let mut prev = vec![usize::MAX; n];
    let mut done = vec![false; n];
    dist[0] = 0.0;
    for _ in 0..n {
        let Some(u) = (0..n).filter(|&i| !done[i] && dist[i].is_finite()).min_by(|&a, &b| dist[a].total_cmp(&dist[b]))
        else {
            break;
        };
        done[u] = true;
        for &(v, c) in &adj[u] {
            if dist[u] + c < dist[v] {
                dist[v] = dist[u] + c;
                prev[v] = u;
            }
        }
    }
    if !dist[1].is_finite() {
        return BaselineResult { nodes: vec![], found: false, iterations: n, edge_checks: checks };
    }
    let mut path_nodes = vec![];
    let mut i = 1;
    while i != usize::MAX {
        path_nodes.push(nodes[i]);
        i = prev[i];
    }
    path_nodes.reverse();
    BaselineResult { nodes: path_nodes, found: true, iterations: n, edge_checks: checks }
}
