//! The body and boom rows built the thesis' way (Cai 2016, §4.4): one box
//! query of the depth map per swing column and per (swing, radial) cell, on
//! the CPU or batched on the GPU.
//!
//! [`CSpace::build`] answers the swing rows and, for every crane but the
//! luffing boom, the cell rows with these same box queries on the CPU; the
//! luffing boom's rows it marks obstacle by obstacle (`boom.rs`), which on a
//! 2-core CPU is faster than either path here. The benchmark builds the rows
//! this way on both paths to compare them with each other and with the
//! thesis' GPU figure.
//!
//! Both paths ask the same boxes (`CSpace::swing_box`,
//! `CSpace::radial_box`) and give the same rows, entry for entry: the GPU's
//! box queries return the CPU's answers by construction
//! ([`liftplan_depthmap::gpu::Gpu::hits_where`]), each part leaves out the
//! same object on both (`ignored_object`), and a cell or column takes
//! the first part, in the crane's part order, that meets something.
//!
//! Must not: open a device or choose one (the caller brings it), or stand in
//! for the boom marking in [`CSpace::build`]: its rows differ from these on a
//! few hundred cells, and the table must not depend on the machine.

use crate::{CSpace, CellHit, Problem, counts_for, ignored_object};
use liftplan_core::crane::{Dependence, PartKind};
use liftplan_core::obb::Obb;
use liftplan_depthmap::gpu::{Gpu, GpuMap, ScreenCounts};
use rayon::prelude::*;

/// Where the box queries run.
#[derive(Clone, Copy)]
pub enum Queries<'a> {
    Cpu,
    /// A device, with the problem's depth map already on it.
    Gpu(&'a Gpu, &'a GpuMap),
}

/// Rows built by box queries, with the GPU's share of the answers.
#[derive(Debug, Clone, PartialEq)]
pub struct QueryRows {
    /// Per swing column, as [`CSpace::swing_hits`].
    pub swing_hits: Vec<Option<CellHit>>,
    /// Per cell `k * ns + i`, as [`CSpace::cell_hits`].
    pub cell_hits: Vec<Option<CellHit>>,
    /// Boxes the device answered and left to the CPU (all zero on the CPU).
    pub screen: ScreenCounts,
}

/// Builds the swing and cell rows of `cs`'s grid by one box query each
/// (each part in turn, where the earlier parts met nothing).
pub fn rows_by_query(cs: &CSpace, p: &Problem, on: Queries) -> Result<QueryRows, String> {
    let kinds = |dep: Dependence| -> Vec<PartKind> {
        p.task.crane.part_kinds().iter().copied().filter(|k| k.dependence() == dep).collect()
    };
    let mut screen = ScreenCounts::default();
    let swing_hits = first_hits(
        cs.ns as usize,
        &kinds(Dependence::Swing),
        |kind, i| cs.swing_box(p, kind, i as u32),
        p,
        on,
        &mut screen,
    )?;
    let ns = cs.ns as usize;
    let cell_hits = first_hits(
        (cs.nr * cs.ns) as usize,
        &kinds(Dependence::SwingRadial),
        |kind, idx| cs.radial_box(p, kind, (idx % ns) as u32, (idx / ns) as u32),
        p,
        on,
        &mut screen,
    )?;
    Ok(QueryRows { swing_hits, cell_hits, screen })
}

/// For each of `n` entries, the first of `kinds` whose box meets the map.
fn first_hits(
    n: usize,
    kinds: &[PartKind],
    box_of: impl Fn(PartKind, usize) -> Option<Obb> + Sync,
    p: &Problem,
    on: Queries,
    screen: &mut ScreenCounts,
) -> Result<Vec<Option<CellHit>>, String> {
    let mut hits: Vec<Option<CellHit>> = vec![None; n];
    for &kind in kinds {
        // Only the entries no earlier part has blocked ask this part's box.
        let (entries, boxes): (Vec<usize>, Vec<Obb>) = (0..n)
            .into_par_iter()
            .filter(|&e| hits[e].is_none())
            .filter_map(|e| box_of(kind, e).map(|b| (e, b)))
            .unzip();
        let answers = match on {
            Queries::Cpu => boxes.par_iter().map(|b| p.map.hit_where(b, |iv| counts_for(kind, iv))).collect(),
            Queries::Gpu(gpu, gpu_map) => {
                let (answers, counts) = gpu.hits_where(gpu_map, p.map, &boxes, ignored_object(kind))?;
                screen.free_on_gpu += counts.free_on_gpu;
                screen.hit_on_gpu += counts.hit_on_gpu;
                screen.left_to_cpu += counts.left_to_cpu;
                screen.screen_ms += counts.screen_ms;
                screen.prepare_ms += counts.prepare_ms;
                screen.exact_ms += counts.exact_ms;
                answers
            }
        };
        for (e, answer) in entries.into_iter().zip(answers) {
            hits[e] = answer.map(|h| CellHit { part: kind, obj: h.interval.obj });
        }
    }
    Ok(hits)
}
