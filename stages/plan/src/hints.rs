//! What a refusal at the pick or the set adds about why the load meets
//! something there, so that the engineer knows which input to correct: its
//! own copy in the plant model, a support it is declared sunk into (and
//! whether the model or the scans put that support's top there), or where
//! the scan point it meets stands.
//!
//! Words only: nothing here decides whether a lift is planned.

use crate::{Site, validate};
use liftplan_core::capacity::{CapacityTable, ChartConfig};
use liftplan_core::crane::{Config, CraneSetup, IkError, LoadPose, PartKind, Placement};
use liftplan_core::frame::Point3;
use liftplan_core::lift::LiftTask;
use liftplan_core::reeving::LongestRope;
use liftplan_depthmap::mdm::{OBJ_GROUND, OBJ_SCAN};

/// How much higher the plant model may have the top of what a load stands
/// on than the scans have it before a refusal there names the model's
/// height (m): more than scan noise and thinning.
pub const SUPPORT_TOPS_DIFFER_M: f64 = 0.03;

/// The hint for a refusal `blocked` of the load at its pick or set: the load
/// resting at `at`, checked at `lifted`; `key` names the position's height
/// (`pick z_m`, `set z_m`). Empty where the load is not what is blocked.
pub(crate) fn for_load(
    task: &LiftTask,
    site: &Site,
    blocked: &liftplan_cspace::Blocked,
    at: &Config,
    lifted: &Config,
    key: &str,
    at_pick: bool,
) -> String {
    if blocked.part != Some(PartKind::Load) {
        return String::new();
    }
    if let Some(itself) = itself_in_the_model(task, site, at, at_pick) {
        return itself;
    }
    let sunk = sunk(task, site, at, key);
    let scanned = matches!(blocked.object.as_deref(), Some("scanned structure" | "ground (scan)"));
    if sunk.is_empty() && scanned { scanned_near(task, site, lifted, at_pick) } else { sunk }
}

/// A plant model holds what a lift installs where it is installed: the load
/// at its set position meets its own copy there.
pub(crate) fn itself_in_the_model(task: &LiftTask, site: &Site, at: &Config, at_pick: bool) -> Option<String> {
    let yaw_key = if at_pick { "pick yaw_deg" } else { "set yaw_deg" };
    let copy = validate::model_group_filling(site.world, &task.crane.load_obb(at, &task.load))?;
    let name = &copy.group;
    let turned = if copy.turned { format!(" turned a quarter turn from the load's {yaw_key}") } else { String::new() };
    let yaw = if copy.turned {
        format!(", and CHECK {yaw_key}: the model has it turned 90° from it")
    } else {
        String::new()
    };
    Some(format!(
        "; the plant model's {name} fills the load's box there{turned} (their bounding boxes {:.0} % alike): if it is this load where it is installed, leave it out of the plant model ([plant] exclude = [\"{name}\"]){yaw}",
        copy.share * 100.0
    ))
}

/// A load declared lower than the top of what it stands on meets that where
/// it is lifted off (or lowered onto it): by how much. Where that top is
/// the plant model's and the scans have it lower, the model may stand too
/// high (a height datum within the model-against-scans check's 0.1 m): both.
pub(crate) fn sunk(task: &LiftTask, site: &Site, at: &Config, key: &str) -> String {
    let load = task.crane.load_obb(at, &task.load);
    let (c, underside) = (load.center, load.aabb().min[2]);
    // Under the load, not beside it: a square within its footprint at any
    // yaw. What starts under its lower half: a slab it is sunk through
    // starts above its underside.
    let r = load.half.x.min(load.half.y) * std::f64::consts::FRAC_1_SQRT_2;
    let map = site.map;
    let top = liftplan_cspace::highest_interval_below(map, c.x - r, c.x + r, c.y - r, c.y + r, c.z as f32);
    let Some(top) = top.filter(|t| t.zhi as f64 > underside + 0.02) else { return String::new() };
    let z = top.zhi as f64;
    let modelled = top.obj != OBJ_SCAN && top.obj != OBJ_GROUND;
    let scanned = site.world.points.highest_in([c.x - r, c.y - r], [c.x + r, c.y + r], c.z);
    match scanned.filter(|&scanned| modelled && scanned < z - SUPPORT_TOPS_DIFFER_M) {
        Some(scanned) => format!(
            "; the load's underside there, z = {underside:.2} m, is about {:.2} m below the top of what stands under it as the plant model has it ({}, up to z = {z:.2} m), but the scans have that top at z = {scanned:.2} m: CHECK [plant] translate_m's height (the model may stand {:.2} m too high) or {key}",
            z - underside,
            map.object_name(top),
            z - scanned
        ),
        None => format!(
            "; the load's underside there, z = {underside:.2} m, is about {:.2} m below the top of what stands under it (about z = {z:.2} m, as the depth map holds it): CHECK {key}",
            z - underside
        ),
    }
}

/// What the load meets at `at` where only scan points stand, with no name
/// to find it by: where the nearest of them is, and on which side of the
/// load. At the pick it is most often the load itself, standing off the
/// position, yaw or size the lift gives it, beyond the cut-out.
pub(crate) fn scanned_near(task: &LiftTask, site: &Site, at: &Config, at_pick: bool) -> String {
    let load = task.crane.load_obb(at, &task.load);
    let Some((p, d)) = validate::nearest_scanned_point(site.world, &load, task.clearance_m + 1.0) else {
        return String::new();
    };
    let l = load.to_local(&Point3::new(p[0], p[1], p[2]));
    let excess = [0, 1, 2].map(|a| l[a].abs() - load.half[a]);
    let side = match (0..3).max_by(|&a, &b| excess[a].total_cmp(&excess[b])).unwrap_or(2) {
        _ if excess.iter().all(|e| *e <= 0.0) => "inside the load's box",
        0 => "beyond an end of the load's box (its size_m[0] side)",
        1 => "beside the load's box (its size_m[1] side)",
        _ if l[2] > 0.0 => "above the load's box",
        _ => "under the load's box",
    };
    let load_itself = if at_pick && side != "under the load's box" {
        ": if that is the load itself (standing off its pick position or yaw, or larger than size_m says, where the cut-out does not reach it), CHECK pick x_m, y_m, yaw_deg and size_m against the scans"
    } else {
        ""
    };
    format!(
        "; the scanned point nearest the load there is at x {:.2}, y {:.2}, z {:.2} m, {d:.2} m {side}{load_itself}",
        p[0], p[1], p[2]
    )
}

/// Why the lift's crane with a boom of `boom_m` could not hold the load at
/// `pose` (the pick or set position), where it could not: the crane model
/// has no such boom, the position is beyond its reach, or the boom's head
/// stands too low (or too high for the rope) there. A chart may list a
/// boom that carries the load at a radius where that boom cannot hang it at
/// the height asked.
fn boom_cannot_hold(task: &LiftTask, boom_m: f64, pose: &LoadPose, what: &str) -> Option<String> {
    let placement = Placement { boom_length_m: boom_m, ..task.crane.placement };
    let setup = match CraneSetup::new(task.crane.model.clone(), placement) {
        Ok(s) => s,
        Err(_) => return Some(format!("the crane model {} has no {boom_m:.2} m boom", task.crane.model.name)),
    };
    match setup.inverse(pose, &task.load) {
        Ok(_) => None,
        Err(IkError::OutOfReach { radius_m, min_m, max_m }) => Some(format!(
            "with it the crane reaches {min_m:.2} to {max_m:.2} m from its slewing axis, not the {what} position's {radius_m:.2} m"
        )),
        Err(IkError::RopeOutOfRange { z_m, hoist_m, min_m, highest_z_m, .. }) if hoist_m < min_m => Some(format!(
            "its head stands too low there: it hangs the load's underside at z = {highest_z_m:.2} m at the highest, under the {what} position's z = {z_m:.2} m"
        )),
        Err(IkError::RopeOutOfRange { hoist_m, max_m, .. }) => Some(format!(
            "its head stands too high there for the rope: the {what} position needs {hoist_m:.2} m of rope, the crane has {max_m:.2} m"
        )),
    }
}

/// What a pick or set over capacity (at `radius_m`, the rigid crane's) could
/// be lifted with instead, as far as the charts read tell: how far out the
/// lift's boom and configuration carry the gross load (the crane set up that
/// much nearer), and which of the configuration's other boom lengths, and
/// which other configurations of the same chart file, carry it there. Each
/// read as the lift reads its own (its radius allowance and capacity
/// reduction); a boom length that could not hang the load at the position
/// (too short to reach it, its head too low) is said to be so. Words only:
/// the lift is refused all the same.
pub(crate) fn over_capacity(
    task: &LiftTask,
    table: &CapacityTable,
    chart: &ChartConfig,
    what: &str,
    radius_m: f64,
) -> String {
    let gross = task.gross_kg();
    let tower = task.crane.model.is_tower();
    let boom = task.chart_boom_m();
    let allowance = task.radius_allowance_m;
    let carries = |c: &ChartConfig, boom_m: f64, r: f64| {
        c.lookup(boom_m, r + allowance).ok().filter(|k| task.effective_capacity_kg(k.capacity_kg) >= gross)
    };
    let on_boom = if tower { String::new() } else { format!(" on its {boom:.2} m boom") };
    let farthest =
        chart.radii_m.iter().rev().find_map(|&row| carries(chart, boom, row - allowance).map(|k| (row - allowance, k)));
    let mut said = match farthest.filter(|(r, _)| *r > 0.0) {
        Some((r, k)) => format!(
            "; '{}'{on_boom} carries {gross:.0} kg out to a radius of {r:.2} m ({}): the crane set up with its slewing axis that near the {what} position could lift it",
            chart.name, k.cell
        ),
        None => format!("; '{}'{on_boom} carries {gross:.0} kg at no radius", chart.name),
    };
    let used = chart.lookup(boom, radius_m + allowance).ok().map(|k| k.boom_m);
    let pose = if what == "pick" { &task.pick_pose } else { &task.set_pose };
    // The other boom lengths that carry it there: those that can hang the
    // load at the position, and those that cannot (said apart, with why).
    let (mut booms, mut booms_cannot) = (Vec::new(), Vec::new());
    for &b in chart.boom_lengths_m.iter().filter(|&&b| !tower && Some(b) != used) {
        let Some(k) = carries(chart, b, radius_m) else { continue };
        match boom_cannot_hold(task, b, pose, what) {
            None => booms.push(format!("the {b:.2} m boom ({:.0} kg, {}; boom_m)", k.capacity_kg, k.cell)),
            Some(why) => booms_cannot.push(format!(
                "; the chart's {b:.2} m boom carries it at {radius_m:.2} m ({:.0} kg, {}), BUT {why}",
                k.capacity_kg, k.cell
            )),
        }
    }
    let file =
        |c: &ChartConfig| c.cells.iter().flatten().next().map(|k| k.cell.split(" [").next().unwrap_or("").to_string());
    let configs: Vec<String> = table
        .configs
        .iter()
        .filter(|c| c.name != chart.name && file(c).is_some() && file(c) == file(chart))
        .filter_map(|c| {
            carries(c, boom, radius_m)
                .map(|k| format!("'{}' ({:.0} kg, {}; chart_config)", c.name, k.capacity_kg, k.cell))
        })
        .collect();
    booms.extend(configs);
    said += &if booms.is_empty() {
        format!(
            "; at {radius_m:.2} m no other {}configuration of its chart file carries it{}",
            if tower { "" } else { "boom length and no other " },
            if booms_cannot.is_empty() { "" } else { " where the crane could hang it" }
        )
    } else {
        format!("; at {radius_m:.2} m it is carried by {}", booms.join(", "))
    };
    said += &booms_cannot.concat();
    if let Some(w) = task.rope_weight.as_ref().filter(|w| w.longest_from != LongestRope::Lift) {
        said += &format!(
            "; {:.0} kg of the gross is the hoist rope, counted at {:.2} m on each of {} falls: a shorter crane.longest_rope_m, if the lift's hook need not hang so low, counts less",
            w.kg, w.longest_m, w.falls
        );
        // What the ends need (to the centimetre above), and the gross on it.
        let (ends, named) = match &task.resume_from {
            Some((now, _)) => ([now, &task.set], "where the load hangs now and the set"),
            None => ([&task.pick, &task.set], "the pick and the set"),
        };
        let need_m = (ends.iter().map(|c| c.hoist_m).fold(0.0, f64::max) * 100.0).ceil() / 100.0;
        let on_need = gross - w.kg + w.kg_per_m * f64::from(w.falls) * need_m;
        let here = chart.lookup(boom, radius_m + allowance).ok().map(|k| task.effective_capacity_kg(k.capacity_kg));
        if let Some(cap) = here.filter(|_| need_m < w.longest_m) {
            said += &format!(
                "; {named} need {need_m:.2} m of it: with longest_rope_m = {need_m:.2} (the path may need more) the gross would be {on_need:.0} kg, {} the {cap:.0} kg the chart gives at {radius_m:.2} m",
                if on_need <= cap { "within" } else { "still more than" }
            );
        }
    }
    said
}
