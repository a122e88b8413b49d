//! MSPGA for one crane (Cai 2016, ch. 4).
//!
//! A chromosome is a string of `length` configurations from the start to the
//! goal. Initialisation, crossover and mutation follow Tables 4.5-4.7; the
//! fitness is eq. 4.21 with the counts of eq. 4.22 and the motion cost of
//! eq. 4.23; the mutation rate adapts by eq. 4.25; selection is roulette with
//! elitism. Ali et al.'s fitness (eqs. 4.33-4.35) can be swapped in for the
//! benchmark.
//!
//! Determinism: every random draw comes from one seeded stream, in a fixed
//! order, on one thread; only the (pure) fitness evaluation runs in parallel.
//! The result does not depend on the number of threads.

use crate::path::{self, Move, Weights};
use liftplan_core::crane::{Config, Dependence};
use liftplan_core::rng::{self, Rng};
use liftplan_cspace::{Blocked, Checker};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// `[plan]` GA parameters (defaults: Cai Table 4.10).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct GaSettings {
    pub population: usize,
    /// Configurations per string, start and goal included.
    pub string_length: usize,
    pub crossover_rate: f64,
    pub mutation_rate: f64,
    /// Mutation scale for valid genes, as a fraction of each joint's range.
    pub small_scale: f64,
    /// Mutation scale for invalid genes.
    pub large_scale: f64,
    pub max_generations: usize,
    /// Stop when a feasible best has not improved for this many generations.
    pub stall_generations: usize,
    pub lambda1: f64,
    pub lambda2: f64,
    pub weights: Weights,
    /// Extra swing room beyond the start-goal span for intermediate genes (deg).
    pub swing_margin_deg: f64,
    /// When no feasible path is found either way round, start again from new
    /// random strings (their seeds derived from the project seed) up to this
    /// many times before giving up. 0: one run each way, as in the thesis.
    pub restarts: usize,
}

impl Default for GaSettings {
    fn default() -> Self {
        GaSettings {
            population: 100,
            string_length: 6,
            crossover_rate: 0.15,
            mutation_rate: 0.75,
            small_scale: 0.016,
            large_scale: 0.16,
            max_generations: 400,
            stall_generations: 120,
            lambda1: 1000.0,
            lambda2: 10.0,
            weights: Weights::default(),
            swing_margin_deg: 20.0,
            restarts: 2,
        }
    }
}

impl GaSettings {
    pub fn check(&self) -> Result<(), String> {
        if !(2..=10_000).contains(&self.population) || !(3..=64).contains(&self.string_length) {
            return Err("[plan.ga] population must be 2..10000 and string_length 3..64".into());
        }
        let rate = |v: f64| v.is_finite() && (0.0..=1.0).contains(&v);
        if !rate(self.crossover_rate) || !rate(self.mutation_rate) || !rate(self.small_scale) || !rate(self.large_scale)
        {
            return Err("[plan.ga] crossover_rate, mutation_rate, small_scale and large_scale must be in [0, 1]".into());
        }
        // A NaN or infinite term makes every fitness NaN or infinite, and the
        // GA's ranking meaningless.
        if !(self.lambda1.is_finite()
            && self.lambda1 > 0.0
            && self.lambda2.is_finite()
            && self.lambda2 >= 0.0
            && self.max_generations >= 1
            && self.max_generations <= 1_000_000)
        {
            return Err("[plan.ga] lambda1 must be positive, lambda2 non-negative (both finite), max_generations \
                        1..1000000"
                .into());
        }
        let w = &self.weights;
        let weights = [w.swing_per_deg, w.luff_per_deg, w.hoist_per_cm, w.rotate_per_deg];
        if !weights.iter().all(|v| v.is_finite() && *v >= 0.0) || !weights.iter().any(|v| *v > 0.0) {
            return Err("[plan.ga.weights] weights must be finite, non-negative and not all zero".into());
        }
        if !(self.swing_margin_deg.is_finite() && (0.0..=180.0).contains(&self.swing_margin_deg)) {
            return Err("[plan.ga] swing_margin_deg must be 0..180".into());
        }
        if self.restarts > 20 {
            return Err("[plan.ga] restarts must be 0..20".into());
        }
        Ok(())
    }
}

/// Which fitness function drives the GA.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Fitness {
    /// Cai eq. 4.21.
    Mspga,
    /// Ali et al., single-crane form (Cai eqs. 4.33-4.35).
    Ali,
}

/// The box the genes live in.
#[derive(Debug, Clone, Copy)]
pub struct Bounds {
    pub lo: [f64; 4],
    pub hi: [f64; 4],
}

impl Bounds {
    pub fn for_task(ck: &Checker, start: &Config, goal: &Config, margin_rad: f64) -> Bounds {
        let lim = ck.task.crane.limits();
        let (s0, s1) = (start.swing_rad.min(goal.swing_rad), start.swing_rad.max(goal.swing_rad));
        let (y0, y1) = (start.load_yaw_rad.min(goal.load_yaw_rad), start.load_yaw_rad.max(goal.load_yaw_rad));
        let hoist_hi = start.hoist_m.max(goal.hoist_m).min(lim.hoist_m.1);
        Bounds {
            lo: [s0 - margin_rad, lim.radial.0, lim.hoist_m.0, y0],
            hi: [s1 + margin_rad, lim.radial.1, hoist_hi, y1],
        }
    }

    fn clamp(&self, a: &mut [f64; 4]) {
        for j in 0..4 {
            a[j] = a[j].clamp(self.lo[j], self.hi[j]);
        }
    }
}

/// A scored chromosome.
#[derive(Debug, Clone)]
pub struct Scored {
    pub genes: Vec<Config>,
    /// Per gene: node valid (collision, clearance, limits).
    pub valid: Vec<bool>,
    pub n: usize,
    pub d: f64,
    pub sc: usize,
    pub fitness: f64,
}

/// Collision and constraint counts of a string (eq. 4.22): node problems (no),
/// structure problems on edges (nf), hanging-part problems on edges (nr), and
/// limit / capacity / internal-clearance problems (nc); with the string's moves,
/// built once per edge for both the checks and the motion cost.
fn violations(ck: &Checker, genes: &[Config]) -> (Vec<bool>, usize, Vec<Move>) {
    let mut valid = Vec::with_capacity(genes.len());
    let mut n = 0;
    for g in genes {
        let ok = ck.config(g).is_ok();
        valid.push(ok);
        n += usize::from(!ok);
    }
    let mut moves = Vec::new();
    for w in genes.windows(2) {
        let edge = path::edge_moves(ck, &w[0], &w[1]);
        if let Err(b) = path::check_moves(ck, &edge) {
            n += 1;
            // A structural hit is counted again: it is the harder one to fix.
            if b.part.is_some_and(|p| p.dependence() != Dependence::Full) {
                n += 1;
            }
        }
        for m in edge {
            path::push_merged(&mut moves, m);
        }
    }
    (valid, n, moves)
}

/// Eq. 4.21 for a collision-free string whose motion term (weighted distance
/// plus the switch penalty) is `m`.
pub fn feasible_fitness(s: &GaSettings, m: f64) -> f64 {
    s.lambda1 * (1.0 + s.lambda1 / m.max(1e-9))
}

pub fn score(ck: &Checker, genes: Vec<Config>, s: &GaSettings, kind: Fitness) -> Scored {
    let tower = ck.task.crane.model.is_tower();
    let (valid, n, moves) = violations(ck, &genes);
    let (d, sc) = path::cost(&moves, &s.weights, tower);
    let fitness = match kind {
        Fitness::Mspga => {
            if n > 0 {
                s.lambda1 / n as f64
            } else {
                feasible_fitness(s, d + s.lambda2 * (1.0 + sc as f64))
            }
        }
        Fitness::Ali => {
            // Eq. 4.34 in the thesis' units (deg, deg, cm, deg); C the share of colliding genes.
            let unit = |a: &Config| {
                [a.swing_rad.to_degrees(), a.radial.to_degrees(), a.hoist_m * 100.0, a.load_yaw_rad.to_degrees()]
            };
            let dist: f64 = genes
                .windows(2)
                .map(|w| {
                    let (a, b) = (unit(&w[0]), unit(&w[1]));
                    (0..4).map(|j| (a[j] - b[j]).powi(2)).sum::<f64>().sqrt()
                })
                .sum();
            let c = n as f64 / genes.len() as f64;
            s.lambda1 / (dist.max(1e-9) * (1.0 + c))
        }
    };
    Scored { genes, valid, n, d, sc, fitness }
}

/// What a GA run produced.
#[derive(Debug, Clone, Serialize)]
pub struct GaResult {
    #[serde(skip)]
    pub best: Option<Scored>,
    pub generations: usize,
    pub evaluations: usize,
    /// Generation at which the first feasible string appeared.
    pub first_feasible: Option<usize>,
    pub best_fitness: Vec<f64>,
    pub mean_fitness: Vec<f64>,
}

fn random_gene(rng: &mut Rng, b: &Bounds) -> [f64; 4] {
    let mut a = [0.0; 4];
    for j in 0..4 {
        a[j] = rng::uniform(rng, b.lo[j], b.hi[j].max(b.lo[j] + 1e-12));
    }
    a
}

/// Table 4.5.
fn initial(rng: &mut Rng, start: &Config, goal: &Config, b: &Bounds, len: usize) -> Vec<Config> {
    let mut g = Vec::with_capacity(len);
    g.push(*start);
    let mut c1 = *start;
    c1.hoist_m = rng::uniform(rng, b.lo[2], start.hoist_m.max(b.lo[2] + 1e-9));
    g.push(c1);
    for _ in 2..len - 2 {
        g.push(Config::from_array(random_gene(rng, b)));
    }
    let mut c_end = *goal;
    c_end.hoist_m = rng::uniform(rng, b.lo[2], goal.hoist_m.max(b.lo[2] + 1e-9));
    g.push(c_end);
    g.push(*goal);
    g
}

/// Table 4.6 for one pair of parents.
fn crossover(rng: &mut Rng, a: &Scored, b: &Scored) -> Vec<Config> {
    let len = a.genes.len();
    let mut child = a.genes.clone();
    for k in 1..len - 1 {
        let (va, vb) = (a.valid[k], b.valid[k]);
        let pick_b = match (va, vb) {
            (true, false) => false,
            (false, true) => true,
            (true, true) if k == 1 => b.genes[k].hoist_m < a.genes[k].hoist_m,
            (true, true) if k == len - 2 => b.genes[k].hoist_m > a.genes[k].hoist_m,
            _ => rng::unit(rng) < 0.5,
        };
        if pick_b {
            child[k] = b.genes[k];
        }
    }
    child
}

/// Table 4.7 with the adaptive rate of eq. 4.25.
fn mutate(rng: &mut Rng, genes: &mut [Config], valid: &[bool], rate: f64, b: &Bounds, s: &GaSettings) {
    let len = genes.len();
    for k in 1..len - 1 {
        if rng::unit(rng) >= rate {
            continue;
        }
        let scale = if valid.get(k).copied().unwrap_or(false) { s.small_scale } else { s.large_scale };
        let mut a = genes[k].to_array();
        let joints: &[usize] = if k == 1 || k == len - 2 { &[2] } else { &[0, 1, 2, 3] };
        for &j in joints {
            a[j] += rng::normal(rng) * scale * (b.hi[j] - b.lo[j]);
        }
        b.clamp(&mut a);
        genes[k] = Config::from_array(a);
    }
}

/// Runs the GA from `start` to `goal`.
pub fn run(
    ck: &Checker,
    start: &Config,
    goal: &Config,
    s: &GaSettings,
    kind: Fitness,
    seed: u64,
    purpose: &str,
) -> GaResult {
    let mut rng = rng::seeded(seed, purpose);
    let b = Bounds::for_task(ck, start, goal, s.swing_margin_deg.to_radians());
    let mut pop: Vec<Vec<Config>> =
        (0..s.population).map(|_| initial(&mut rng, start, goal, &b, s.string_length)).collect();
    let mut result = GaResult {
        best: None,
        generations: 0,
        evaluations: 0,
        first_feasible: None,
        best_fitness: vec![],
        mean_fitness: vec![],
    };
    let mut stall = 0;
    for generation in 0..s.max_generations {
        let scored: Vec<Scored> = pop.into_par_iter().map(|g| score(ck, g, s, kind)).collect();
        result.evaluations += scored.len();
        result.generations = generation + 1;
        let mean = scored.iter().map(|c| c.fitness).sum::<f64>() / scored.len() as f64;
        // Ties go to the lowest index, so the choice is deterministic.
        let best_idx = (0..scored.len()).fold(0, |bi, i| if scored[i].fitness > scored[bi].fitness { i } else { bi });
        let best = &scored[best_idx];
        let improved = result.best.as_ref().is_none_or(|o| best.fitness > o.fitness * (1.0 + 1e-9));
        if improved {
            result.best = Some(best.clone());
            stall = 0;
        } else {
            stall += 1;
        }
        if best.n == 0 && result.first_feasible.is_none() {
            result.first_feasible = Some(generation);
        }
        result.best_fitness.push(result.best.as_ref().map(|b| b.fitness).unwrap_or(0.0));
        result.mean_fitness.push(mean);
        // Converged: a feasible best that stopped improving, or (a dead end,
        // e.g. the long way round through a wall) no progress for twice as long.
        let feasible = result.best.as_ref().is_some_and(|b| b.n == 0);
        if (feasible && stall >= s.stall_generations) || stall >= 2 * s.stall_generations {
            break;
        }
        // Roulette selection with elitism.
        let total: f64 = scored.iter().map(|c| c.fitness).sum();
        let spin = |rng: &mut Rng| {
            let mut x = rng::unit(rng) * total;
            for (i, c) in scored.iter().enumerate() {
                x -= c.fitness;
                if x <= 0.0 {
                    return i;
                }
            }
            scored.len() - 1
        };
        let mut next = Vec::with_capacity(s.population);
        next.push(result.best.as_ref().map(|b| b.genes.clone()).unwrap_or_else(|| best.genes.clone()));
        while next.len() < s.population {
            let pa = &scored[spin(&mut rng)];
            let mut child = if rng::unit(&mut rng) < s.crossover_rate {
                let pb = &scored[spin(&mut rng)];
                crossover(&mut rng, pa, pb)
            } else {
                pa.genes.clone()
            };
            let rate = if pa.fitness < mean {
                (s.mutation_rate + (mean - pa.fitness) / mean).min(1.0)
            } else {
                s.mutation_rate
            };
            mutate(&mut rng, &mut child, &pa.valid, rate, &b, s);
            next.push(child);
        }
        pop = next;
    }
    result
}

/// The first problem of a string, for the failure message.
pub fn first_problem(ck: &Checker, genes: &[Config]) -> Option<Blocked> {
    for g in genes {
        if let Err(b) = ck.config(g) {
            return Some(b);
        }
    }
    genes.windows(2).find_map(|w| path::check_edge(ck, &w[0], &w[1]).err())
}
