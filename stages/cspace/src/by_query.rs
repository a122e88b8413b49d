//! The body and boom rows built the thesis' way (Cai 2016, §4.4): one box
//! query of the depth map per swing column and per (swing, radial) cell, on
//! the CPU or batched on the GPU.
//!
//! [`CSpace::build`] takes the swing rows and, for every crane but the
//! luffing boom, the cell rows from this module's CPU path; the luffing
//! boom's rows it marks obstacle by obstacle (`boom.rs`), which on a 2-core
//! CPU is faster than either path here. The benchmark builds the rows
//! this way on both paths to compare them with each other and with the
//! thesis' GPU figure.
//!
//! Both paths ask the same boxes (`CSpace::swing_box`,
//! `CSpace::radial_box`) and give the same rows, entry for entry: the GPU's
//! box queries return the CPU's answers by construction
//! ([`liftplan_depthmap::gpu::Gpu::hits_where`]), each part leaves out the
//! same intervals on both (`left_out`), and a cell or column takes
//! the first part, in the crane's part order, that meets something.
//!
//! Must not: open a device or choose one (the caller brings it), or stand in
//! for the boom marking in [`CSpace::build`]: its rows differ from these on a
//! few hundred cells, and the table must not depend on the machine.

use crate::{CSpace, CellHit, Problem, left_out};
use liftplan_core::crane::{Dependence, PartKind};
use liftplan_core::obb::Obb;
use liftplan_depthmap::gpu::{Gpu, GpuMap, ScreenCounts};
use liftplan_depthmap::query::{Hit, LeaveOut};
use rayon::prelude::*;
use std::convert::Infallible;

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
    let mut screen = ScreenCounts::default();
    let mut answer = |kind: PartKind, boxes: &[Obb]| -> Result<Vec<Option<Hit>>, String> {
        match on {
            Queries::Cpu => Ok(on_cpu(p, kind, boxes)),
            Queries::Gpu(gpu, gpu_map) => {
                let (answers, counts) = gpu.hits_where(gpu_map, p.map, boxes, left_out(&p.task.crane, kind))?;
                screen.add(&counts);
                Ok(answers)
            }
        }
    };
    let swing_hits = rows_with(cs, p, Dependence::Swing, &mut answer)?;
    let cell_hits = rows_with(cs, p, Dependence::SwingRadial, &mut answer)?;
    Ok(QueryRows { swing_hits, cell_hits, screen })
}

/// The swing rows (`Dependence::Swing`) or the cell rows
/// (`Dependence::SwingRadial`) on the CPU: what [`CSpace::build`] puts in
/// [`CSpace::swing_hits`], and in [`CSpace::cell_hits`] for every crane but
/// a luffing boom.
pub(crate) fn rows_on_cpu(cs: &CSpace, p: &Problem, dep: Dependence) -> Vec<Option<CellHit>> {
    let Ok(rows) = rows_with(cs, p, dep, &mut |kind, boxes: &[Obb]| Ok::<_, Infallible>(on_cpu(p, kind, boxes)));
    rows
}

/// For each swing column (`Dependence::Swing`) or cell (`SwingRadial`), the
/// first part of that dependence whose box meets the map; `answer` answers
/// one part's boxes in one batch.
fn rows_with<E>(
    cs: &CSpace,
    p: &Problem,
    dep: Dependence,
    answer: &mut impl FnMut(PartKind, &[Obb]) -> Result<Vec<Option<Hit>>, E>,
) -> Result<Vec<Option<CellHit>>, E> {
    let ns = cs.ns as usize;
    let (n, swing) = if dep == Dependence::Swing { (ns, true) } else { ((cs.nr * cs.ns) as usize, false) };
    let box_of = |kind: PartKind, e: usize| {
        if swing { cs.swing_box(p, kind, e as u32) } else { cs.radial_box(p, kind, (e % ns) as u32, (e / ns) as u32) }
    };
    let kinds: Vec<PartKind> = p.task.crane.part_kinds().iter().copied().filter(|k| k.dependence() == dep).collect();
    let mut hits: Vec<Option<CellHit>> = vec![None; n];
    for kind in kinds {
        // Only the entries no earlier part has blocked ask this part's box.
        let (entries, boxes): (Vec<usize>, Vec<Obb>) = (0..n)
            .into_par_iter()
            .filter(|&e| hits[e].is_none())
            .filter_map(|e| box_of(kind, e).map(|b| (e, b)))
            .unzip();
        for (e, answer) in entries.into_iter().zip(answer(kind, &boxes)?) {
            hits[e] = answer.map(|h| CellHit { part: kind, obj: h.interval.obj });
        }
    }
    Ok(hits)
}

/// The CPU's exact queries of one part's boxes.
fn on_cpu(p: &Problem, kind: PartKind, boxes: &[Obb]) -> Vec<Option<Hit>> {
    let leave = left_out(&p.task.crane, kind);
    boxes.par_iter().map(|b| p.map.hit_where(b, |iv| LeaveOut::counts(leave, iv))).collect()
}
