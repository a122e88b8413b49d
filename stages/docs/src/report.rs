//! The layout of one lift's document.

use crate::pdf::{A4, Doc, LETTER, line_height_mm, shortened, text_width_mm, wrap};
use crate::pictures::{self, SiteView};
use crate::{DocsError, Inputs, Paper, Result, Settings};
use liftplan_core::capacity::ChartConfig;
use liftplan_core::image::{Image, Rgb};
use liftplan_core::lift::LiftTask;
use liftplan_core::location::parse_cell_range;
use liftplan_core::obb::Obb;
use liftplan_plan::LiftPlan;
use liftplan_plan::steps::SetDown;

const INK: [u8; 3] = [20, 20, 20];
const GREY: [u8; 3] = [90, 90, 90];

fn opt(v: Option<f64>, digits: usize) -> String {
    v.map(|x| format!("{x:.digits$}")).unwrap_or_else(|| "—".into())
}

/// Input rows the inputs page shows at most above the chart plot, and at
/// least where the page has less room left (the chart then goes on).
const INPUT_ROWS_HERE: usize = 16;
const MIN_INPUT_ROWS_HERE: usize = 4;

/// A page's heading at `y`, ruled under; wrapped where it is wider than
/// the page (a step's words, from a move of hundreds of metres or degrees,
/// ran off the sheet's edge). Returns where the page's text goes on.
pub(crate) fn heading(d: &mut Doc, y: f32, s: &str) -> f32 {
    let lines = crate::pdf::wrap_bold(s, d.size.w - 30.0, 13.0);
    for (n, line) in lines.iter().enumerate() {
        d.text(15.0, y + line_height_mm(13.0) * n as f32, line, 13.0, true, [25, 55, 110]);
    }
    let below = heading_below(d, y, s);
    d.line(15.0, below - 7.0, d.size.w - 15.0, below - 7.0, 0.6, [25, 55, 110]);
    below
}

/// Where the page's text goes on under [`heading`] `s` drawn at `y`.
fn heading_below(d: &Doc, y: f32, s: &str) -> f32 {
    let lines = crate::pdf::wrap_bold(s, d.size.w - 30.0, 13.0).len().max(1);
    y + line_height_mm(13.0) * (lines - 1) as f32 + 9.0
}

/// Where the inputs page's next `need_mm` go: at `y`, or at the top of a
/// new "Inputs (continued)" page if they would run past the page's foot. A
/// survey of many scans has more lines than one page holds, and a line drawn
/// below the page is a line the signer never sees.
fn inputs_room(d: &mut Doc, y: f32, need_mm: f32) -> f32 {
    room_on_page(d, y, need_mm, "Inputs (continued)")
}

/// One input's row at `y` (on a new page under `continued` where it does
/// not fit): its hash, and its name whole, wrapped where it is long (a
/// chart's file name ran off the sheet); returns the y below it.
fn input_row(d: &mut Doc, y: f32, name: &str, hash: &str, continued: &str) -> f32 {
    let lines = wrap(name, d.size.w - 15.0 - 50.0, 8.0);
    let mut y = room_on_page(d, y, 4.2 * lines.len() as f32, continued);
    d.text(15.0, y, hash, 8.0, false, GREY);
    for line in &lines {
        d.text(50.0, y, line, 8.0, false, INK);
        y += 4.2;
    }
    y
}

/// Where the next `need_mm` go: at `y`, or under `continued` at the top of
/// a new page if they would run past the page's foot.
fn room_on_page(d: &mut Doc, y: f32, need_mm: f32, continued: &str) -> f32 {
    if y + need_mm <= d.size.h - FOOT_MM {
        return y;
    }
    d.new_page();
    heading(d, 20.0, continued)
}

/// The steps' table's columns, on a page whose text is `w` mm wide: their
/// headers, widths (mm) and which are right-aligned.
fn steps_columns(w: f32) -> ([&'static str; 8], [f32; 8], [bool; 8]) {
    (
        ["Step", "Operation", "Amount", "Radius m", "Capacity t", "Util. %", "Clear. m", "Closest obstacle"],
        [11.0, 24.0, 20.0, 17.0, 19.0, 15.0, 16.0, w - 122.0],
        [true, false, true, true, true, true, true, false],
    )
}

/// The steps' table at `y`, its rows on as many pages as they take, each
/// further page under "Steps (continued)", none drawn lower than 40 mm from
/// a page's foot; a row taller than a page holds (a step naming what it
/// comes closest to in the longest words a plan.json may hold) is split
/// over pages ([`crate::pdf::split_table_row`]). Returns the y below it.
fn steps_table(d: &mut Doc, mut y: f32, widths: &[f32], right: &[bool], header: &[&str], rows: &[Vec<String>]) -> f32 {
    const SIZE_PT: f32 = 8.0;
    const CONTINUED: &str = "Steps (continued)";
    let header_mm = crate::pdf::table_row_mm(SIZE_PT);
    let room_below = |d: &Doc, y: f32| d.size.h - 40.0 - y - header_mm;
    let fresh_y = heading_below(d, 20.0, CONTINUED);
    let rows: Vec<Vec<String>> =
        rows.iter().flat_map(|row| crate::pdf::split_table_row(widths, row, SIZE_PT, room_below(d, fresh_y))).collect();
    let heights = Doc::table_row_heights(widths, &rows, SIZE_PT);
    let mut start = 0;
    while start < rows.len() {
        // A row that does not fit here does on a page of its own.
        if heights[start] > room_below(d, y) && y > fresh_y + 1e-3 {
            d.new_page();
            y = heading(d, 20.0, CONTINUED);
        }
        // As many rows as the page holds, at least one.
        let room = room_below(d, y);
        let mut end = start + 1;
        let mut used = heights[start];
        while end < rows.len() && used + heights[end] <= room {
            used += heights[end];
            end += 1;
        }
        y = d.table(15.0, y, widths, right, header, &rows[start..end], SIZE_PT);
        start = end;
        if start < rows.len() {
            d.new_page();
            y = heading(d, 20.0, CONTINUED);
        }
    }
    y
}

/// A clause as a sentence: its first letter upper-case, a full stop after.
fn sentence(clause: &str) -> String {
    let mut c = clause.chars();
    match c.next() {
        Some(f) => format!("{}{}.", f.to_uppercase(), c.as_str()),
        None => String::new(),
    }
}

/// A paragraph of the sign-off page at `y`, on a further page if it does
/// not fit on this one (the more a site's checks have to say, the more the
/// page holds); returns the y below it.
fn sign_off_paragraph(d: &mut Doc, y: f32, w: f32, text: &str) -> f32 {
    paragraph_on_pages(d, y, w, text, 9.5, "Review and sign-off (continued)")
}

/// Space kept free at the foot of a page (mm).
const FOOT_MM: f32 = 15.0;

/// The least height (mm) the cover leaves the site overview; with less it
/// goes on the next page.
const MIN_OVERVIEW_MM: f32 = 80.0;

/// The stages' lines on the inputs page from `y`, `w` wide, going on to
/// further pages where they do not fit; returns the y below the last.
fn input_lines(d: &mut Doc, mut y: f32, lines: &[String], w: f32) -> f32 {
    for line in lines {
        y = paragraph_on_pages(d, y, w, line, 9.0, "Inputs (continued)");
    }
    y
}

/// A paragraph at `y`, `w` wide: on a further page, under `continued`,
/// where it does not fit on this one, and run on over pages where it does
/// not fit on one (the more a site has to say, the more it takes; a
/// paragraph of many long names ran past the foot); returns the y below it.
fn paragraph_on_pages(d: &mut Doc, y: f32, w: f32, text: &str, size: f32, continued: &str) -> f32 {
    let lines = wrap(text, w, size);
    let step = line_height_mm(size);
    let mut y = room_on_page(d, y, lines.len() as f32 * step, continued);
    for line in &lines {
        y = room_on_page(d, y, step, continued);
        d.text(15.0, y, line, size, false, [30, 30, 30]);
        y += step;
    }
    y
}

/// The type size (pt) of [`key_values`]' rows.
const ROW_PT: f32 = 9.0;

/// The least type size (pt) the cover's summary box is set in to keep all
/// its rows on the cover, before they run on to the next page.
const COVER_SUMMARY_MIN_PT: f32 = 8.0;

/// How tall [`key_values`] draws `rows` at `x` with keys `key_w` wide (mm).
fn key_values_height(d: &Doc, x: f32, rows: &[(&str, String)], key_w: f32) -> f32 {
    key_values_height_at(d, x, rows, key_w, ROW_PT)
}

/// [`key_values_height`] in type of `size` pt.
fn key_values_height_at(d: &Doc, x: f32, rows: &[(&str, String)], key_w: f32, size: f32) -> f32 {
    let width = key_values_width(d, x, key_w);
    let line = crate::pdf::line_height_mm(size);
    rows.iter()
        .map(|(_, v)| row_step_mm(size) + (crate::pdf::wrap(v, width, size).len().max(1) - 1) as f32 * line)
        .sum()
}

/// From one row's first line to the next row's (mm): 5 mm at [`ROW_PT`].
fn row_step_mm(size: f32) -> f32 {
    5.0 * size / ROW_PT
}

/// How wide [`key_values`] wraps the values: to as far from the sheet's
/// right edge as the keys are from its left, so that rows inside a frame
/// (the cover's verdict box) keep off it on both sides.
fn key_values_width(d: &Doc, x: f32, key_w: f32) -> f32 {
    d.size.w - x - (x + key_w)
}

/// Rows of a key and its value, the value wrapped to as far from the
/// page's right edge as the keys are from its left ([`key_values_width`]).
fn key_values(d: &mut Doc, x: f32, y: f32, rows: &[(&str, String)], key_w: f32) -> f32 {
    key_values_at(d, x, y, rows, key_w, ROW_PT)
}

/// [`key_values`], going on under `continued` at the top of a further page
/// where a row does not fit on this one, and running a row on over pages
/// where it is longer than a page (forty power lines' words took more).
fn key_values_on_pages(d: &mut Doc, x: f32, y: f32, rows: &[(&str, String)], key_w: f32, continued: &str) -> f32 {
    key_values_in(d, x, y, rows, key_w, ROW_PT, Some(continued))
}

/// [`key_values`] in type of `size` pt.
fn key_values_at(d: &mut Doc, x: f32, y: f32, rows: &[(&str, String)], key_w: f32, size: f32) -> f32 {
    key_values_in(d, x, y, rows, key_w, size, None)
}

/// [`key_values`] in type of `size` pt, going on under `continued` where
/// one is given ([`key_values_on_pages`]), else where they fall.
fn key_values_in(
    d: &mut Doc,
    x: f32,
    mut y: f32,
    rows: &[(&str, String)],
    key_w: f32,
    size: f32,
    continued: Option<&str>,
) -> f32 {
    let step = line_height_mm(size);
    let room = |d: &mut Doc, y: f32, need_mm: f32| continued.map_or(y, |c| room_on_page(d, y, need_mm, c));
    for (k, v) in rows {
        let lines = wrap(v, key_values_width(d, x, key_w), size);
        y = room(d, y, step * lines.len().saturating_sub(1) as f32 + row_step_mm(size));
        d.text(x, y, k, size, true, GREY);
        for (n, line) in lines.iter().enumerate() {
            if n > 0 {
                y = room(d, y + step, 0.0);
            }
            d.text(x + key_w, y, line, size, false, INK);
        }
        y += row_step_mm(size);
    }
    y
}

/// The cover's verdict box at `y`: the verdict, then `rows`; as many rows as
/// fit above the footer, the rest in a box of its own at the top of the
/// next page, under "Summary (continued from the cover)" (a lift with many
/// things to check first ran off the foot of the cover). Where the next
/// goes.
///
/// Rows that fit on the cover only in smaller type are set in it, down to
/// [`COVER_SUMMARY_MIN_PT`]: the cover is what the crew reads on site, and
/// every row of it is better there in type a little smaller than on the
/// next page.
fn summary_box(d: &mut Doc, mut y: f32, rows: &[(&str, String)], (verdict, ok): (&str, bool)) -> f32 {
    let (key_x, key_w) = (19.0, 34.0);
    let w = d.size.w - 30.0;
    let (fill, edge) = if ok { ([232, 245, 233], [46, 125, 50]) } else { ([251, 233, 231], [198, 40, 40]) };
    let foot = d.size.h - FOOT_MM;
    // The box's top on the cover (the verdict's line) and its foot's margin.
    let (cover_top, margin) = (14.0, 2.0);
    let size = [ROW_PT, 8.5, COVER_SUMMARY_MIN_PT]
        .into_iter()
        .find(|&pt| y + cover_top + key_values_height_at(d, key_x, rows, key_w, pt) + margin <= foot)
        .unwrap_or(ROW_PT);
    // A row longer than a continued box holds (the warnings of a survey of
    // many scans) goes on in rows of as many lines as one holds, keyed once.
    const CONTINUED: &str = "Summary (continued from the cover)";
    let continued_top = heading_below(d, 20.0, CONTINUED) + 7.0;
    let lines_held =
        ((foot - continued_top - margin - row_step_mm(size)) / line_height_mm(size)).floor().max(0.0) as usize;
    let width = key_values_width(d, key_x, key_w);
    let rows: Vec<(&str, String)> = rows
        .iter()
        .flat_map(|(key, value)| {
            let lines = wrap(value, width, size);
            if lines.len() <= lines_held + 1 {
                return vec![(*key, value.clone())];
            }
            let keys = std::iter::once(*key).chain(std::iter::repeat(""));
            keys.zip(lines.chunks(lines_held + 1).map(|c| c.join(" "))).collect()
        })
        .collect();
    let mut rest = &rows[..];
    let mut first = true;
    loop {
        // The rows start under the verdict on the cover, at the box's top after.
        let top = if first { cover_top } else { 7.0 };
        let mut fit = 0;
        let mut rows_h = 0.0;
        while fit < rest.len() {
            let h = key_values_height_at(d, key_x, &rest[fit..fit + 1], key_w, size);
            // On the cover the verdict alone where the first row does not
            // fit under it; on a further page at least one row.
            if (fit > 0 || first) && y + top + rows_h + h + margin > foot {
                break;
            }
            rows_h += h;
            fit += 1;
        }
        let box_h = top + rows_h + margin;
        d.fill_rect(15.0, y, w, box_h, fill);
        d.frame(15.0, y, w, box_h, 1.0, edge);
        if first {
            d.text(19.0, y + 7.0, verdict, 11.0, true, if ok { [27, 94, 32] } else { [183, 28, 28] });
        }
        key_values_at(d, key_x, y + top, &rest[..fit], key_w, size);
        y += box_h + 6.0;
        rest = &rest[fit..];
        if rest.is_empty() {
            return y;
        }
        d.new_page();
        y = heading(d, 20.0, CONTINUED);
        first = false;
    }
}

/// A step's clearance for the steps table: "none near" where nothing lay
/// within the validator's search.
fn clearance_cell(m: f64) -> String {
    if m.is_finite() { format!("{m:.2}") } else { "none near".to_string() }
}

/// What the sign-off page flags for a check on site or in the inputs, in a
/// few words each, for the cover.
/// Whether a plant model and scans were both given but barely meet, so
/// that where the model stands was not checked (a model a datum off in
/// height, or beside the scanned area).
fn model_unchecked(inp: &Inputs, plan: &LiftPlan) -> bool {
    inp.mesh.is_some() && inp.cloud.is_some() && plan.model_vs_scans.is_none()
}

/// The check before signing of the scans registration merged with a
/// warning ([`Inputs::scans_warned`]): their lines on the inputs page and
/// the sign-off page ([`scans_warned_paragraph`]) say what it is (a station
/// that alone places a scan along a corridor, a post only one scan shows, a
/// scan the last alignment against all the others moved).
fn scans_warned_said(warned: &[(String, String)]) -> Option<String> {
    let count = match warned {
        [] => return None,
        [_] => "one scan".to_string(),
        many => format!("{} scans", many.len()),
    };
    let names: Vec<&str> = warned.iter().map(|(name, _)| name.as_str()).collect();
    Some(format!("what registration warned of {count} merged ({}; inputs page)", names.join(", ")))
}

/// The sign-off page's paragraph on the scans registration merged with a
/// warning: the warnings' own words, since the obstacles those scans show
/// stand where the alignments the warnings doubt put them.
fn scans_warned_paragraph(warned: &[(String, String)]) -> Option<String> {
    let (head, they, asks) = match warned {
        [] => return None,
        [(name, _)] => {
            (format!("SCAN '{name}' WAS MERGED WITH A WARNING"), "it shows stands where it was", "THE WARNING ASKS")
        }
        many => (
            format!("{} SCANS WERE MERGED WITH A WARNING", many.len()),
            "they show stands where they were",
            "THE WARNINGS ASK",
        ),
    };
    let words: Vec<&str> = warned.iter().map(|(_, w)| w.strip_suffix('.').unwrap_or(w)).collect();
    Some(format!(
        "{head} from registration: {}. Every obstacle {they} placed: CHECK WHAT {asks} before signing, or have the scans registered without it.",
        words.join(". ")
    ))
}

/// `warned_read`: [`warned_cells_read`], where the chart was read.
fn checks_before_signing(
    inp: &Inputs,
    task: &LiftTask,
    plan: &LiftPlan,
    wind: &Wind,
    warned_read: Option<&[(String, Vec<usize>)]>,
) -> Vec<String> {
    let sm = &plan.summary;
    let mut v = Vec::new();
    if task.resumes() {
        v.push("that the crane shows where the lift resumes".to_string());
    }
    if resume_check(inp, task).is_some_and(|a| !a.agrees) {
        v.push("where the lift resumes, against the plan it continues (cover)".to_string());
    }
    if !sm.power_lines.is_empty() {
        v.push("the power lines: where they run, how low and how high they hang, how far the wind swings them and their voltage".to_string());
    }
    if sm.reeving.as_ref().is_some_and(|r| r.falls_not_given()) {
        v.push("the falls to reeve the hoist rope with (the lift gives none: Reeving)".to_string());
    }
    match sm.line_like.len() {
        0 => {}
        1 => v.push("what the line-like scan points near the crane are: an overhead line no one gave?".to_string()),
        n => v.push(format!(
            "what the {n} runs of line-like scan points near the crane are: overhead lines no one gave?"
        )),
    }
    if sm.power_lines.iter().any(|l| l.contains(liftplan_plan::SUPPORT_NOT_SEEN)) {
        v.push("where a power line runs: the scans do not show a support it gives (inputs page)".to_string());
    }
    match sm.other_cranes.len() {
        0 => {}
        1 => v.push("the other lift's crane within this one's reach: not checked against it".to_string()),
        n => v.push(format!("the {n} other lifts' cranes within this one's reach: not checked against them")),
    }
    match sm.obstacles.len() {
        0 => {}
        1 => v.push("the obstacle placed by hand, where it stands".to_string()),
        n => v.push(format!("the {n} obstacles placed by hand, where they stand")),
    }
    if let Some((_, boom)) = inp.one_column_charts.iter().find(|(id, _)| *id == task.id) {
        v.push(format!("that the chart of one column is the {boom:.1} m boom's"));
    }
    if !inp.scans_left_out.0.is_empty() {
        v.push(format!("{} scans left out unregistered", inp.scans_left_out.0.len()));
    }
    match inp.scans_passed_by.len() {
        0 => {}
        1 => v.push("the file among the scans passed by as holding no scan: is it none?".to_string()),
        n => v.push(format!("the {n} files among the scans passed by as holding no scan: is none a scan?")),
    }
    match inp.inputs_not_read.len() {
        0 => {}
        1 => v.push("the file in the input folders not read: is it no scan, model or chart of this lift?".to_string()),
        _ => {
            v.push("the files in the input folders not read: is none a scan, model or chart of this lift?".to_string())
        }
    }
    v.extend(scans_warned_said(&inp.scans_warned));
    if inp.site_level_unconfirmed.is_some() {
        v.push("the site's level (the scanner did not level itself)".to_string());
    }
    if let Some(w) = chart_warnings(inp, task) {
        let read = warned_read.map(<[_]>::len);
        let (warnings, name) = if w.len() == 1 {
            ("1 warning".to_string(), "it names")
        } else {
            (format!("{} warnings", w.len()), "they name")
        };
        v.push(format!(
            "the load chart cells read with a warning ({warnings}{})",
            match read {
                Some(0) => format!("; no step reads a cell {name}"),
                Some(1) => format!("; the steps read 1 cell {name}"),
                Some(n) => format!("; the steps read {n} cells {name}"),
                None => String::new(),
            }
        ));
    }
    if plan.model_vs_scans.as_ref().is_some_and(|a| a.disagrees()) {
        v.push("the plant model disagrees with the scans".to_string());
    }
    if model_unchecked(inp, plan) {
        v.push("where the plant model stands (the scans barely meet it)".to_string());
    }
    if sm.coverage.as_ref().is_some_and(|c| c.load_passes_unscanned()) {
        v.push("ground under the load that no scan saw".to_string());
    }
    if sm.coverage.as_ref().is_some_and(|c| c.load_passes_unknown()) {
        v.push("ground under the load outside the plant model (there are no scans)".to_string());
    }
    if plan.validator.set_up_ground.is_none() {
        v.push(if task.crane.model.is_tower() {
            "the tower crane's base level (no ground was scanned around its mast)".to_string()
        } else {
            "the crane's set-up level (no ground was scanned under it)".to_string()
        });
    }
    if plan.load_cutout.points > 0 && sm.load_as_scanned.as_ref().is_some_and(|l| l.needs_checking()) {
        v.push("the load's size or pick position against its scan".to_string());
    }
    if !sm.passes_left_out.is_empty() {
        v.push("what [plant] exclude left out of the model, in the lift's way".to_string());
    }
    if !sm.under_pads.is_empty() {
        v.push("what lies in the ground under the outrigger pads".to_string());
    }
    if sm.counterweight_disagrees_kg.is_some() {
        v.push("the counterweight (the lift's is not its chart configuration's)".to_string());
    }
    if task.crane.model.is_tower() {
        v.push("the wind speed the load may be lifted in (the tower crane's manual: Wind)".to_string());
    } else {
        if let Some(swing) = wind.as_ref().ok().and_then(|(w, _)| gust_swing_past_clearance_m(task, plan, w)) {
            v.push(format!(
                "the load's swing in the wind (a sudden gust at the permissible speed can swing it {swing:.2} m, more than the {:.2} m clearance the plan keeps)",
                task.clearance_m
            ));
        }
        match wind {
            Err(_) => v.push("the wind speed the load may be lifted in (not worked out)".to_string()),
            Ok((_, other)) if !other.is_empty() => {
                v.push("the chart's wind speed (the lift's chart_ms is not what its sheet states)".to_string())
            }
            Ok((w, _)) if w.reduced() => {
                v.push("the wind speed the load may be lifted in (less than the chart's)".to_string())
            }
            Ok(_) => {}
        }
    }
    if !sm.pads_tip_in.is_empty() {
        v.push("the crane file's masses (they would tip the crane)".to_string());
    } else if sm.highest_pad.is_some_and(|(_, p)| p.needs_checking(task.ground.as_ref())) {
        v.push("the ground under the outrigger pads (more than it may bear)".to_string());
    }
    if sm.set_on.as_ref().is_some_and(|s| s.tips()) {
        v.push("the load's centre of gravity over what holds it at its set position".to_string());
    }
    for a in sm.against_model.iter().filter(|a| !a.agrees()) {
        v.push(format!("the {} position against the plant model's {}", a.at, a.object));
    }
    match sm.set_down() {
        SetDown::Rests(_) => {}
        SetDown::Above(_) => v.push("the set-down ends above its support".to_string()),
        SetDown::OverNothing => v.push("nothing known under the set position".to_string()),
    }
    if tower_base_off_ground_m(task, plan).is_some() {
        v.push("the tower crane's base level".to_string());
    }
    v
}

/// What [`wind_of`] works out, or why not.
type Wind =
    std::result::Result<(liftplan_core::wind::PermissibleWind, Vec<liftplan_core::capacity::StatedOnChart>), String>;

/// The wind speed the lift's load may be lifted in, with the speeds its
/// chart's sheet states otherwise, or why it is not worked out
/// ([`LiftTask::permissible_wind`], with what the chart's sheet states);
/// with the highest the plan raises the boom head and the longest it hangs
/// the load.
fn wind_of(inp: &Inputs, task: &LiftTask, plan: &LiftPlan) -> Wind {
    let stated = inp.chart_wind.iter().find(|(name, _)| *name == task.chart_config).map_or(&[][..], |(_, s)| &s[..]);
    task.permissible_wind(stated).map(|(mut w, other)| {
        (w.boom_head_m, w.longest_hang_m) = (Some(boom_head_highest_m(task, plan)), Some(longest_hang_m(task, plan)));
        (w, other)
    })
}

/// The plan's configurations at which its highs and lows are reached: its
/// start and the end of each move, as each move changes one joint steadily.
fn move_ends(plan: &LiftPlan) -> impl Iterator<Item = &liftplan_core::crane::Config> {
    std::iter::once(&plan.start).chain(plan.moves.iter().map(|m| &m.to))
}

/// The highest the boom head rises in the plan, above the ground the crane
/// stands on (m): at the end of a move, as a luff raises or lowers it
/// steadily and a swing, hoist or turn of the load leaves it.
fn boom_head_highest_m(task: &LiftTask, plan: &LiftPlan) -> f64 {
    move_ends(plan).map(|c| task.crane.sheave(c).z - task.crane.placement.z_m).fold(f64::NEG_INFINITY, f64::max)
}

/// The longest the load hangs below the boom head in the plan, from the
/// sheave to the load's underside (m): rope, hook block, rigging and load,
/// longest at the end of a move, as a hoist pays the rope out steadily and
/// the other joints leave it.
fn longest_hang_m(task: &LiftTask, plan: &LiftPlan) -> f64 {
    move_ends(plan)
        .map(|c| task.crane.sheave(c).z - task.crane.load_bottom_z(c, &task.load))
        .fold(f64::NEG_INFINITY, f64::max)
}

/// Whether a sudden gust at the permissible wind can swing the load farther
/// than the clearance the plan keeps (twice the steady push's
/// [`liftplan_core::wind::PermissibleWind::off_plumb_m`]), and how far;
/// never where the plan keeps its clearance with the load so swung.
fn gust_swing_past_clearance_m(
    task: &LiftTask,
    plan: &LiftPlan,
    w: &liftplan_core::wind::PermissibleWind,
) -> Option<f64> {
    if plan.gust_swing_per_m > 0.0 {
        return None;
    }
    w.off_plumb_m().map(|x| 2.0 * x).filter(|swing| *swing > task.clearance_m)
}

/// How the plan keeps its clearance with what hangs off where the crane
/// holds it, for the PDF: swung as far as a gust can swing it, where it was
/// planned so; off by its centre of gravity's tolerance, where the lift
/// gives one (`LiftTask::hanging_swept`).
fn hanging_swept_said(task: &LiftTask, plan: &LiftPlan) -> Option<String> {
    let gust = (plan.gust_swing_per_m > 0.0).then(|| {
        format!(
            "the rope, hook and load measured swung sideways as far as a sudden gust at the permissible wind can swing them, {:.1} cm per metre they hang below the boom head (wind plan_for_swing)",
            100.0 * plan.gust_swing_per_m
        )
    });
    let cog = (task.cog_tolerance_m > 0.0).then(|| {
        format!(
            "the load and rigging {:.2} m off along its x and y, where its centre of gravity may lie (load cog_tolerance_m)",
            task.cog_tolerance_m
        )
    });
    let said: Vec<String> = gust.into_iter().chain(cog).collect();
    (!said.is_empty()).then(|| format!("{}, but in the lift-off and set-down", said.join(", and ")))
}

/// What reading the lift's chart configuration warned of, where it did.
fn chart_warnings<'a>(inp: &'a Inputs, task: &LiftTask) -> Option<&'a [String]> {
    inp.chart_warnings.iter().find(|(name, w)| *name == task.chart_config && !w.is_empty()).map(|(_, w)| w.as_slice())
}

/// Which of the cells the chart's warnings name (a warning opens with its
/// `sheet!cell`) this plan's steps read, and in which steps. A step reads
/// the cells between the radii it starts and ends at
/// ([`LiftTask::chart_cells_between`]).
fn warned_cells_read(
    task: &LiftTask,
    plan: &LiftPlan,
    chart: &ChartConfig,
    warned: &[String],
) -> Vec<(String, Vec<usize>)> {
    let mut read: Vec<(String, Vec<usize>)> = Vec::new();
    let mut from_m = task.crane.radius_m(plan.start.radial);
    for step in &plan.steps {
        for cell in task.chart_cells_between(chart, from_m, step.radius_m) {
            // "file [sheet!cell]": the cell as the warnings name it.
            let Some(at) = cell.rsplit_once(" [").map(|(_, c)| c.trim_end_matches(']').to_string()) else { continue };
            if !warned.iter().any(|w| warning_names(w, &at)) {
                continue;
            }
            match read.iter_mut().find(|(c, _)| *c == at) {
                Some((_, steps)) if steps.last() != Some(&step.n) => steps.push(step.n),
                Some(_) => {}
                None => read.push((at, vec![step.n])),
            }
        }
        from_m = step.radius_m;
    }
    read
}

/// Whether a chart warning names the cell `at` ("sheet!cell"): a warning
/// opens with the cell it is about ("Main boom 360!H28: footnote mark
/// ...") or the range of cells ("Main boom 360!A6:M44: 281 numbers written
/// as text ...").
fn warning_names(warning: &str, at: &str) -> bool {
    let named = warning.split(": ").next().unwrap_or_default();
    let (Some((sheet, range)), Some((at_sheet, cell))) = (named.rsplit_once('!'), at.rsplit_once('!')) else {
        return false;
    };
    let (Some((first, last)), Some((cell, _))) = (parse_cell_range(range), parse_cell_range(cell)) else {
        return false;
    };
    sheet == at_sheet && (first.0..=last.0).contains(&cell.0) && (first.1..=last.1).contains(&cell.1)
}

/// [`warned_cells_read`] as a clause of the sign-off page's sentence.
fn warned_cells_said(read: &[(String, Vec<usize>)]) -> String {
    if read.is_empty() {
        return "; no step of this plan reads a cell they name".to_string();
    }
    let said: Vec<String> = read
        .iter()
        .map(|(cell, steps)| format!("{cell} in step{} {}", if steps.len() > 1 { "s" } else { "" }, runs(steps)))
        .collect();
    format!("; THIS PLAN READS {}", said.join("; "))
}

/// Increasing step numbers as runs: "2, 3 to 8, 10".
fn runs(n: &[usize]) -> String {
    let mut said: Vec<String> = Vec::new();
    let mut k = 0;
    while k < n.len() {
        let mut end = k;
        while end + 1 < n.len() && n[end + 1] == n[end] + 1 {
            end += 1;
        }
        said.push(match end - k {
            0 => n[k].to_string(),
            1 => format!("{}, {}", n[k], n[end]),
            _ => format!("{} to {}", n[k], n[end]),
        });
        k = end + 1;
    }
    said.join(", ")
}

/// How far a tower crane's base stands above (+) or below (-) the median of
/// the scanned ground around its mast, where that is more than the set-up
/// tolerance.
fn tower_base_off_ground_m(task: &LiftTask, plan: &LiftPlan) -> Option<f64> {
    let g = plan.validator.set_up_ground.as_ref().filter(|_| task.crane.model.is_tower())?;
    let off = task.crane.placement.z_m - g.median_m;
    (off.abs() > liftplan_plan::validate::SET_UP_LEVEL_TOLERANCE_M).then_some(off)
}

/// The grid bearing (degrees clockwise from the site's +Y, in [0, 360)) of a
/// direction `a_rad` counter-clockwise from the site's +X.
fn grid_bearing_deg(a_rad: f64) -> f64 {
    let b = (90.0 - a_rad.to_degrees()).rem_euclid(360.0);
    // Rounding to a tenth must not print 360.0.
    if b >= 359.95 { 0.0 } else { b }
}

/// The cover's title and the lift's description from the top of the page;
/// returns the y where the rest begins. A long lift id and a description of
/// a paragraph wrap, pushing the rest down.
fn cover_heading(d: &mut Doc, w: f32, id: &str, description: &str) -> f32 {
    let mut title_y = 22.0;
    for (k, line) in crate::pdf::wrap_bold(&format!("Lift plan {id}"), w, 22.0).iter().enumerate() {
        title_y = 22.0 + k as f32 * line_height_mm(22.0);
        d.text(15.0, title_y, line, 22.0, true, [25, 55, 110]);
    }
    let below_description = d.paragraph(15.0, title_y + 8.0, w, description, 11.0);
    (below_description + 4.6).max(40.0)
}

/// Whether the lift's `resume_from` is where the plan it continues has the
/// load, where it names one ([`Inputs::resume_checks`]).
fn resume_check<'a>(inp: &'a Inputs, task: &LiftTask) -> Option<&'a liftplan_plan::resumed::Agreement> {
    inp.resume_checks.iter().find(|(id, _)| *id == task.id).map(|(_, a)| a)
}

/// A [`resume_check`] in words: "Checked: ..." or, where the pose is not
/// the plan's (or could not be compared), "NOT CONFIRMED ...".
fn resume_check_said(a: &liftplan_plan::resumed::Agreement) -> String {
    if a.agrees {
        format!("Checked: {}", a.said)
    } else {
        format!("NOT CONFIRMED BY THE PLAN IT CONTINUES: {}", a.said)
    }
}

/// Where a lift resumed part way starts, in words, for the cover: the
/// plan it continues where the lift names it, the crane's configuration as
/// its steps give one, and the load's place; then whether that is where the
/// plan it continues has the load (`check`).
fn resumes_said(task: &LiftTask, check: Option<&liftplan_plan::resumed::Agreement>) -> Option<String> {
    let (c, pose) = task.resume_from.as_ref()?;
    let after = task
        .resumes_plan
        .as_ref()
        .map(|r| format!(", after step {} of plan {} (resumes_plan)", r.after_step, r.revision))
        .unwrap_or_default();
    Some(format!(
        "PART WAY THROUGH THE LIFT{after}: this plan starts where the load hangs now (resume_from), not at its pick: swing {:.1}°, {}, hoist {:.2} m, load yaw {:.1}°, the load's underside at ({:.2}, {:.2}, {:.2}) m; CHECK THE CRANE SHOWS THAT before step 1, and that the load hangs still{}",
        c.swing_rad.to_degrees(),
        radial_said(task, c.radial),
        c.hoist_m,
        pose.yaw_rad.to_degrees(),
        pose.x_m,
        pose.y_m,
        pose.z_m,
        check.map(|a| format!(". {}", resume_check_said(a))).unwrap_or_default()
    ))
}

/// A configuration's luff ("luff 62.3°") or, for a tower crane, trolley
/// radius ("trolley 24.72 m").
fn radial_said(task: &LiftTask, radial: f64) -> String {
    if task.crane.model.is_tower() {
        format!("trolley {radial:.2} m")
    } else {
        format!("luff {:.1}°", radial.to_degrees())
    }
}

/// Every page's footer on a sheet `sheet_w_mm` wide. The project's name is
/// what gives way, not the lift or the date (the footer itself is shortened
/// to leave the page number). The plan's revision is on every page, so that
/// a page of the crew's copy names the plan it belongs to.
fn footer(sheet_w_mm: f32, project: &str, id: &str, revision: &str, date: &str) -> String {
    let head = format!("liftplan {} — ", env!("CARGO_PKG_VERSION"));
    let tail = format!(" — lift {id}, plan {revision} — issued {date}");
    let room = sheet_w_mm - 30.0 - text_width_mm("page 99 of 99", 8.0) - 6.0;
    let project = shortened(project, (room - text_width_mm(&head, 8.0) - text_width_mm(&tail, 8.0)).max(20.0), 8.0);
    format!("{head}{project}{tail}")
}

/// A picture's size in pixels: as given, or a quarter of it each way when
/// built for fuzzing (`cargo fuzz` sets `--cfg fuzzing`), where a document
/// with its pictures at full size takes seconds a run; the same is drawn.
fn px(n: u32) -> u32 {
    if cfg!(fuzzing) { n / 4 } else { n }
}

pub fn document(
    inp: &Inputs,
    s: &Settings,
    site: &SiteView,
    task: &LiftTask,
    plan: &LiftPlan,
    chart: Option<&ChartConfig>,
    cspace: Option<&Image>,
) -> Result<(Vec<u8>, usize, Image, Option<Image>)> {
    let size = match s.paper {
        Paper::A4 => A4,
        Paper::Letter => LETTER,
    };
    let mut d = Doc::new(&format!("Lift plan {}", task.id), size).map_err(DocsError::Other)?;
    let w = size.w - 30.0;
    let sm = &plan.summary;
    let words = task.crane.model.words();
    // Worked out once for the cover's row, its checks and the sign-off page.
    let wind = wind_of(inp, task, plan);
    // The obstacles placed by hand that stand there during this lift, for
    // the pictures, the inputs page and the steps' words.
    let obstacles: Vec<&liftplan_core::obstacle::Obstacle> =
        inp.obstacles.iter().filter(|o| o.during(&task.id)).collect();

    // Page 1: cover and summary.
    d.new_page();
    let mut y = cover_heading(&mut d, w, &task.id, &task.description);
    y = key_values(
        &mut d,
        15.0,
        y,
        &[
            ("Project", inp.project.clone()),
            ("Lift", format!("{}, plan {} (on every page)", task.id, sm.revision)),
            (
                "Load",
                format!(
                    "{} — {:.2} t, {:.1} × {:.1} × {:.1} m, centre of gravity ({:.2}, {:.2}, {:.2}) m from the box's centre{}",
                    task.load_name,
                    task.load_mass_kg / 1000.0,
                    task.load.size_m[0],
                    task.load.size_m[1],
                    task.load.size_m[2],
                    task.load.cog_m[0],
                    task.load.cog_m[1],
                    task.load.cog_m[2],
                    match (task.cog_tolerance_m > 0.0, task.cog_tolerance_z_m > 0.0) {
                        (true, false) => format!(" ± {:.2} m along x and y (cog_tolerance_m)", task.cog_tolerance_m),
                        (true, true) => format!(
                            " ± {:.2} m along x and y (cog_tolerance_m), ± {:.2} m in height (cog_tolerance_z_m)",
                            task.cog_tolerance_m, task.cog_tolerance_z_m
                        ),
                        (false, true) => format!(" ± {:.2} m in height (cog_tolerance_z_m)", task.cog_tolerance_z_m),
                        (false, false) => String::new(),
                    }
                ),
            ),
            (
                "Gross load",
                match &task.rope_weight {
                    Some(w) => format!(
                        "{:.2} t (load + rigging + hook block + {:.2} t of hoist rope + deductions)",
                        task.gross_kg() / 1000.0,
                        w.kg / 1000.0
                    ),
                    None => format!("{:.2} t (load + rigging + hook block + deductions)", task.gross_kg() / 1000.0),
                },
            ),
            (
                "Crane",
                format!(
                    "{} at ({:.2}, {:.2}) m, heading {:.1}°, {}",
                    task.crane.model.name,
                    task.crane.placement.x_m,
                    task.crane.placement.y_m,
                    task.crane.placement.heading_rad.to_degrees(),
                    if task.crane.model.is_tower() {
                        "tower crane".to_string()
                    } else {
                        format!("boom {:.1} m", task.crane.placement.boom_length_m)
                    }
                ),
            ),
            ("Chart configuration", task.chart_config.clone()),
            ("Date", inp.date.clone()),
            (
                "Planner",
                format!("liftplan {} — {:?}, seed {}", env!("CARGO_PKG_VERSION"), plan.planner, plan.planning.seed),
            ),
        ],
        42.0,
    );
    // Summary box.
    y += 3.0;
    let ok = plan.validator.ok;
    let crit = if sm.critical {
        // Where the crane could stand for it not to be, where one was found.
        let elsewhere = sm.not_critical_at.as_ref().map(|said| format!("; {said}")).unwrap_or_default();
        format!("CRITICAL LIFT (over {:.0} %){elsewhere}", task.critical_pct)
    } else {
        format!("not critical (limit {:.0} %)", task.critical_pct)
    };
    let mut rows = vec![
        (
            "Max utilisation",
            format!(
                "{:.1} % in step {} — chart cell {}",
                sm.max_utilisation_pct, sm.max_utilisation_step, sm.max_utilisation_cell
            ),
        ),
        ("Critical lift", crit),
        (
            "Min clearance",
            if sm.min_clearance_m.is_finite() {
                format!(
                    "{:.2} m in step {} ({}); required {:.2} m, {:.2} m over landing zones{}",
                    sm.min_clearance_m,
                    sm.min_clearance_step,
                    sm.min_clearance_what,
                    plan.clearance_m,
                    plan.landing_clearance_m,
                    hanging_swept_said(task, plan).map(|s| format!("; {s}")).unwrap_or_default()
                )
            } else if task.resumes() && sm.steps <= 1 {
                "no step before the set-down (the load hangs above its set position)".to_string()
            } else if sm.steps <= 2 && !task.resumes() {
                "no step between the lift-off and the set-down (the load is set back where it was lifted)".to_string()
            } else {
                format!(
                    "nothing within the validator's search ({:.2} m) in any step {}",
                    liftplan_plan::validate::search_cutoff_m(plan.clearance_m),
                    if task.resumes() { "before the set-down" } else { "between the lift-off and the set-down" }
                )
            },
        ),
        (
            "Motion",
            format!(
                "{} steps: swing {:.1}°, {} {:.1}{}, hoist/lower {:.2} m, rotate {:.1}°",
                sm.steps,
                sm.swing_deg,
                words.radial_axis,
                sm.luff_or_trolley,
                if task.crane.model.is_tower() { " m" } else { "°" },
                sm.hoist_m,
                sm.rotate_deg
            ),
        ),
    ];
    if let Some(said) = resumes_said(task, resume_check(inp, task)) {
        rows.insert(0, ("RESUMED", said));
    }
    rows.push((
        "Slings",
        match &sm.slings {
            Some(c) => format!("{} (hook over the centre of gravity)", c.said()),
            None => "not checked: the lift gives no working load limit for its legs (rigging leg_wll_t, with legs or lift_points_m)".to_string(),
        },
    ));
    rows.push((
        "Reeving",
        match &sm.reeving {
            Some(r) => r.said(),
            None => "not checked: the crane file gives no line pull per fall nor hook block rating ([hook] line_pull_t, rated_t), and the lift no falls (crane falls)".to_string(),
        },
    ));
    if let Some((n, p)) = sm.highest_pad {
        let counterweight = sm.pads_counterweight_said().map(|c| format!(" with {c}")).unwrap_or_default();
        rows.push((
            "Outrigger pads",
            format!(
                "in step {n}, the most: {}; an estimate from the crane file's masses{counterweight} (sign-off page)",
                p.said(task.ground.as_ref())
            ),
        ));
    }
    // The wind: a limit the crew works to, as the chart's capacity is: next
    // to the utilisation, ahead of the clearances and the rigging's figures,
    // where rows that do not fit on the cover run on to the next page.
    let after_critical = rows.iter().position(|(k, _)| *k == "Critical lift").map_or(rows.len(), |i| i + 1);
    if task.crane.model.is_tower() {
        // Not worked out (a mobile crane's chart rule), but what the
        // manual's rule needs is said.
        let side = liftplan_core::wind::largest_side_m(task.load.size_m);
        rows.insert(
            after_critical,
            (
                "Wind",
                format!(
                    "NOT WORKED OUT for a tower crane: its manual's in-service wind rules govern, for the crane and for a load that catches much wind for its mass; this load's largest side, {:.2} x {:.2} m ({:.1} m²), on {:.2} t of hook load: CHECK the wind speed it may be lifted in; the plan keeps its clearance with the load hanging plumb",
                    side[0],
                    side[1],
                    side[0] * side[1],
                    task.least_hanging_kg() / 1000.0
                ),
            ),
        );
    } else {
        // With the height the boom head rises to, for the mean wind at
        // 10 m a forecast gives, and how far the wind pushes the load.
        rows.insert(
            after_critical,
            (
            "Wind",
            match &wind {
                Ok((w, other)) => {
                    let swing = match gust_swing_past_clearance_m(task, plan, w) {
                        Some(swing) => format!(
                            "; A GUST CAN SWING THE LOAD {swing:.2} m, MORE THAN THE {:.2} m CLEARANCE THE PLAN KEEPS (wind plan_for_swing = false): tag lines, a lower wind limit or more clearance",
                            task.clearance_m
                        ),
                        None if plan.gust_swing_per_m > 0.0 => format!(
                            "; the plan keeps its {:.2} m clearance with the load swung so (wind plan_for_swing)",
                            task.clearance_m
                        ),
                        None => String::new(),
                    };
                    let sheet = if other.is_empty() {
                        String::new()
                    } else {
                        format!(
                            "; BUT THE CHART'S SHEET STATES {}: CHECK wind chart_ms against the chart",
                            other.iter().map(|o| format!("{:.1} m/s ({})", o.value, o.cell)).collect::<Vec<_>>().join(", ")
                        )
                    };
                    w.said_with(&format!("{swing}{sheet}"))
                }
                Err(why) => format!("not worked out: {why}"),
            },
            ),
        );
    }
    // What the sign-off page asks the signer to check, named on the cover
    // where it is read first.
    // The chart cells read with a warning and the steps that read them,
    // for the cover, the steps' pages and the sign-off page.
    let warned_read = match (chart, chart_warnings(inp, task)) {
        (Some(c), Some(w)) => Some(warned_cells_read(task, plan, c, w)),
        _ => None,
    };
    let checks = checks_before_signing(inp, task, plan, &wind, warned_read.as_deref());
    if !checks.is_empty() {
        // First in the verdict's box, under the verdict, before the figures:
        // on the cover however many rows run on to the next page.
        rows.insert(0, ("CHECK FIRST", format!("{} (sign-off page)", checks.join("; "))));
    }
    let verdict = if ok {
        format!("VALIDATED — independent check of {} samples found no problem", plan.validator.samples)
    } else {
        "REJECTED — do not lift".to_string()
    };
    y = summary_box(&mut d, y, &rows, (&verdict, ok));
    // The other lifts' loads where they stand during this one, as the plan
    // stage checked against them (lifts are made in the order listed), and
    // the obstacles placed by hand that stand there during it.
    let k = inp.tasks.iter().position(|t| t.id == task.id).unwrap_or(0);
    let mut others: Vec<(Obb, Rgb)> =
        liftplan_plan::other_loads(&inp.tasks, k).into_iter().map(|(b, _)| (b, pictures::OTHER_LOAD)).collect();
    let other_loads = others.len();
    others.extend(obstacles.iter().map(|o| (o.obb(), pictures::OBSTACLE)));
    let with_obstacles = others.len();
    // The conductors, as a band 0.3 m wide round wherever they may hang.
    for l in inp.power_lines.iter().filter(|l| l.during(&task.id)) {
        others.extend(l.boxes(0.15).into_iter().map(|b| (b, pictures::POWER_LINE)));
    }
    let with_power_lines = others.len();
    others.extend(plan.summary.line_like.iter().map(|l| (l.obb(0.25), pictures::LINE_LIKE)));
    let overview = pictures::overview(site, task, plan, &others, px(1400), px(1000));
    let tail = task.crane.tail_swing_m();
    let coverage = plan.summary.coverage.as_ref();
    let under_m2 =
        coverage.map(|c| c.kept_out.as_ref().map_or(c.under_load.passed_m2, |k| k.area_m2)).filter(|m2| *m2 > 0.0);
    let fall_zone = coverage
        .and_then(|c| c.kept_out.as_ref())
        .map_or(String::new(), |k| format!(" and {:.1} m round it for what may fall (fall_zone_m),", k.fall_zone_m));
    let under = if fall_zone.is_empty() { "from under the load" } else { "from under the load and its fall zone" };
    let keep_out = match (tail.is_some(), under_m2.is_some()) {
        (true, true) => format!("; keep people out of the tail's swing, and {under} while it moves"),
        (true, false) => "; keep people out of the tail's swing".to_string(),
        (false, true) => format!("; keep people {under} while it moves"),
        (false, false) => String::new(),
    };
    let caption = format!(
        "Site overview (top view, north up): crane {}{}, load path in red{}, load at set in light blue{}{}{}{}{}{}{}{keep_out}.",
        if task.resumes() { "where the lift resumes (the load hanging)" } else { "at the pick position" },
        match tail {
            Some((r, part)) =>
                format!(", its tail's swing in magenta ({} {r:.2} m from the slewing axis)", part.name()),
            None => String::new(),
        },
        match under_m2 {
            Some(m2) if plan.gust_swing_per_m > 0.0 => {
                format!(", the ground under it, as far as a gust may swing it,{fall_zone} in pink ({m2:.0} m²)")
            }
            Some(m2) if task.cog_tolerance_m > 0.0 => format!(
                ", the ground under it, as far off as its centre of gravity's tolerance lets it hang,{fall_zone} in pink ({m2:.0} m²)"
            ),
            Some(m2) => format!(", the ground under it{fall_zone} in pink ({m2:.0} m²)"),
            None => String::new(),
        },
        if other_loads == 0 { "" } else { ", other lifts' loads in violet" },
        if with_obstacles == other_loads { "" } else { ", obstacles placed by hand in teal" },
        if with_power_lines == with_obstacles { "" } else { ", power lines in orange" },
        if others.len() == with_power_lines {
            ""
        } else {
            ", line-like scan points no power line given runs along in cyan"
        },
        match (task.not_over.is_empty(), task.not_over.iter().any(|a| a.crane_too)) {
            (true, _) => "",
            (false, false) => ", areas the load must never be over outlined in green",
            (false, true) =>
                ", areas the load (and the crane, where the inputs page says so) must never be over outlined in green",
        },
        if task.crane_stands_in.is_empty() { "" } else { ", areas the crane may stand in outlined in blue" },
        match plan
            .summary
            .coverage
            .as_ref()
            .map(|c| (!c.under_load.unscanned_cells.is_empty(), !c.under_crane.unscanned_cells.is_empty()))
        {
            Some((true, true)) => ", ground no scan saw under the load in black, under the crane only in grey",
            Some((true, false)) => ", ground under the load that no scan saw in black",
            Some((false, true)) => ", ground under the crane that no scan saw in grey",
            _ => "",
        }
    );
    let caption_lines = crate::pdf::wrap(&caption, w, 8.5);
    // A cover with much to say (a resumed lift, many checks) leaves the
    // overview too little room: it goes on a page of its own, not drawn
    // small or past the footer.
    let caption_h = caption_lines.len() as f32 * crate::pdf::line_height_mm(8.5) + 3.0;
    if y + caption_h + MIN_OVERVIEW_MM > size.h - 22.0 {
        d.new_page();
        y = heading(&mut d, 20.0, "Site overview (continued from the cover)");
    }
    for (n, line) in caption_lines.iter().enumerate() {
        if n > 0 {
            y += crate::pdf::line_height_mm(8.5);
        }
        d.text(15.0, y, line, 8.5, false, GREY);
    }
    y += 3.0;
    let avail = size.h - 22.0 - y;
    let img_w = (avail * 1.4).min(w);
    d.image(&overview, 15.0 + (w - img_w) / 2.0, y, img_w);

    // Page 2: inputs.
    d.new_page();
    let y = heading(&mut d, 20.0, "Inputs");
    let mut y = input_lines(&mut d, y, &inp.input_lines, w);
    y += 2.0;
    let mut rows = vec![
        (
            "Clearance",
            format!(
                "{:.2} m to every obstacle; hook and load over the landing zones {:.2} m",
                task.clearance_m, plan.landing_clearance_m
            ),
        ),
        if task.resumes() {
            (
                "Set-down",
                format!(
                    "{:.2} m, vertical; contact allowed only with the support under the load (no lift-off: the load hangs where the lift resumes)",
                    task.liftoff_m
                ),
            )
        } else {
            (
                "Lift-off / set-down",
                format!("{:.2} m, vertical; contact allowed only with the support under the load", task.liftoff_m),
            )
        },
        // One row for both ways the chart is read less than printed.
        (
            "Capacity reduction",
            format!(
                "{:.1} % of the chart value; {}",
                task.capacity_reduction_pct,
                if task.radius_allowance_m > 0.0 {
                    format!("read {:.2} m farther out than planned (radius_allowance_m)", task.radius_allowance_m)
                } else {
                    "read at the radius planned (no radius_allowance_m)".to_string()
                }
            ),
        ),
        (
            "Pick (load underside)",
            format!(
                "({:.2}, {:.2}, {:.2}) m, yaw {:.1}°",
                task.pick_pose.x_m,
                task.pick_pose.y_m,
                task.pick_pose.z_m,
                task.pick_pose.yaw_rad.to_degrees()
            ),
        ),
        (
            "Set (load underside)",
            format!(
                "({:.2}, {:.2}, {:.2}) m, yaw {:.1}°",
                task.set_pose.x_m,
                task.set_pose.y_m,
                task.set_pose.z_m,
                task.set_pose.yaw_rad.to_degrees()
            ),
        ),
    ];
    // The first few areas by name and extent: a row must fit its page.
    let areas_said = |areas: Vec<(&str, &[[f64; 2]], &str)>| {
        const NAMED: usize = 10;
        let mut said: Vec<String> = areas
            .iter()
            .take(NAMED)
            .map(|(name, corners, more)| {
                let extent = match liftplan_core::obb::plan_bounds(*corners) {
                    Some((lo, hi)) => format!(" (x {:.1} to {:.1} m, y {:.1} to {:.1} m)", lo[0], hi[0], lo[1], hi[1]),
                    None => String::new(),
                };
                format!("{name}{extent}{more}")
            })
            .collect();
        if areas.len() > NAMED {
            said.push(format!("and {} more", areas.len() - NAMED));
        }
        said
    };
    if !task.crane_stands_in.is_empty() {
        let areas = areas_said(task.crane_stands_in.iter().map(|a| (a.name.as_str(), &a.corners_m[..], "")).collect());
        rows.push((
            "Crane stands in",
            format!(
                "{} (crane_stands_in): its {} within one of these, as the lift sets it up and wherever another position is suggested",
                areas.join("; "),
                match (task.crane.model.is_tower(), task.ground.is_some()) {
                    (true, _) => "mast stands",
                    (false, true) => "carrier and outriggers, with their pads' mats, stand",
                    (false, false) => "carrier and outriggers stand",
                }
            ),
        ));
    }
    if !task.not_over.is_empty() {
        let areas = areas_said(
            task.not_over
                .iter()
                .map(|a| (a.name.as_str(), &a.corners_m[..], if a.crane_too { ", nor the crane" } else { "" }))
                .collect(),
        );
        let crane_too = task.not_over.iter().any(|a| a.crane_too);
        rows.push((
            "Never over",
            format!(
                "{} (not_over): the planner keeps the load, its hook block and rope {:.2} m off each in plan{}{}; the validator checks they never come over one{}{}",
                areas.join("; "),
                liftplan_core::lift::NOT_OVER_MARGIN_M + task.fall_zone_m,
                if task.fall_zone_m > 0.0 {
                    format!(
                        " (their fall zone, fall_zone_m {:.1} m, and {:.2} m more)",
                        task.fall_zone_m,
                        liftplan_core::lift::NOT_OVER_MARGIN_M
                    )
                } else {
                    String::new()
                },
                if crane_too { ", and every other part of the crane that swings (boom or jib, counterweight) off those marked 'nor the crane' (crane_too)" } else { "" },
                if task.fall_zone_m > 0.0 { format!(" nor within {:.1} m of one", task.fall_zone_m) } else { String::new() },
                if crane_too { ", nor the crane over those marked so" } else { "" }
            ),
        ));
    }
    if !plan.summary.power_lines.is_empty() {
        rows.push((
            "Power lines",
            format!(
                "{} ([[power_line]]): every part of the crane, its rope and its load is kept that far off each conductor (planned and checked against boxes round it, grown by that distance: away from the lift-off and set-down the clearance is kept beyond it, and a clearance shown to one is beyond the distance); each conductor is kept off wherever it may hang, from its least sag to its most and swung as far as its line says either way (a line whose swing is not given is taken as hanging plumb, its approach distance the only margin for the wind)",
                plan.summary.power_lines.join("; ")
            ),
        ));
    }
    if !obstacles.is_empty() {
        const NAMED: usize = 10;
        let mut said: Vec<String> = obstacles.iter().take(NAMED).map(|o| o.said()).collect();
        if obstacles.len() > NAMED {
            said.push(format!("and {} more", obstacles.len() - NAMED));
        }
        rows.push((
            "Placed by hand",
            format!(
                "{} ([[obstacle]]: on site, not in the scans or the model): the planner and the validator keep the crane and the load {:.2} m off each, as they do the scans; check on site that each stands where given",
                said.join("; "),
                task.clearance_m
            ),
        ));
    }
    let need_mm = key_values_height(&d, 15.0, &rows, 42.0);
    y = inputs_room(&mut d, y, need_mm);
    y = key_values_on_pages(&mut d, 15.0, y, &rows, 42.0, "Inputs (continued)");
    y += 3.0;
    let chart_img = chart.map(|c| pictures::chart_plot(c, task, plan, px(1200), px(600)));
    // The load chart keeps its place on this page where it can: the input
    // rows take the room left above it, and every input is on the last
    // pages when some are not here.
    let chart_mm = chart_img.as_ref().map_or(0.0, |ci| 7.0 + w * ci.height as f32 / ci.width as f32);
    let rows_fit = ((d.size.h - FOOT_MM - chart_mm - (y + 5.0)) / 4.2).floor().max(0.0) as usize;
    let rows_here = INPUT_ROWS_HERE.min(rows_fit).max(MIN_INPUT_ROWS_HERE);
    let appendix = inp.input_hashes.len() > rows_here;
    let here = if appendix { rows_here - 1 } else { rows_here };
    y = inputs_room(&mut d, y, 5.0 + 4.2 * (here.min(3) + appendix as usize) as f32);
    d.text(15.0, y, "Inputs and liftplan's code (blake3, first 16 hex digits)", 9.0, true, GREY);
    y += 5.0;
    for (f, h) in inp.input_hashes.iter().take(here) {
        y = input_row(&mut d, y, f, h, "Inputs (continued)");
    }
    if appendix {
        let more = inp.input_hashes.len() - here;
        let line = format!("... and {more} more: all {} are listed on the last pages", inp.input_hashes.len());
        y = inputs_room(&mut d, y, 4.2);
        d.text(50.0, y, &line, 8.0, false, INK);
        y += 4.2;
    }
    if let Some(ci) = &chart_img {
        y += 4.0;
        let caption = if task.radius_allowance_m > 0.0 {
            format!(
                "Load chart: capacity after the reduction against radius (steps), gross load (red line), radii read (dots: each step's plus the {:.2} m allowance).",
                task.radius_allowance_m
            )
        } else {
            "Load chart: capacity after the reduction against radius (steps), gross load (red line), radii used (dots)."
                .to_string()
        };
        // The image below the caption's last line.
        let lines = crate::pdf::wrap(&caption, w, 8.5);
        let more = (lines.len().max(1) - 1) as f32 * crate::pdf::line_height_mm(8.5);
        y = inputs_room(&mut d, y, chart_mm - 4.0 + more);
        for line in lines {
            d.text(15.0, y, &line, 8.5, false, GREY);
            y += crate::pdf::line_height_mm(8.5);
        }
        d.image(ci, 15.0, y + 3.0 - crate::pdf::line_height_mm(8.5), w);
    }

    // Page 3: the steps.
    d.new_page();
    let mut y = heading(&mut d, 20.0, "Steps");
    let (header, widths, right) = steps_columns(w);
    let rows: Vec<Vec<String>> = plan
        .steps
        .iter()
        .map(|st| {
            let amount = if st.unit == "°" { format!("{:+.1}°", st.amount) } else { format!("{:+.2} m", st.amount) };
            vec![
                st.n.to_string(),
                st.operation.clone(),
                amount,
                format!("{:.2}", st.radius_m),
                opt(st.capacity_kg.map(|c| c / 1000.0), 1),
                opt(st.utilisation_pct, 1),
                clearance_cell(st.min_clearance_m),
                format!("{} – {}", st.clearance_part, st.clearance_to),
            ]
        })
        .collect();
    y = steps_table(&mut d, y, &widths, &right, &header, &rows);
    // Where the table ran long (a step's amounts of hundreds of digits,
    // from a damaged plan.json), the words under it go on the next page.
    let under_table = format!(
        "{ends}Capacity is the chart value (before the reduction) at the largest radius of the step{allowance}; utilisation is the gross load over the reduced capacity; clearance is a distance that no crane part, rope, hook or load comes closer than to {against} at any moment of the step{swung}, between the validator's samples too: the smallest distance measured at samples no more than [plan] validator_sample_m of movement apart (0.05 m by default), less what the motion between two samples leaves room for (at most half that spacing), so the closest approach may be up to that much more than shown, never less. Wherever the motion between samples could take a part closer than its required clearance, the validator samples more finely, down to 2 mm of movement, so the required clearance holds along the whole motion, not only at the samples, to within 2 mm. Swing and load rotation angles are counter-clockwise positive seen from above. Swing is measured from {heading}, load yaw from the site's +X axis; each step's page also gives the {arm}'s grid bearing (clockwise from the site's north, +Y, as the overview is drawn).{pads}",
        heading = words.heading,
        arm = words.arm,
        pads = if plan.summary.highest_pad.is_some() {
            " Each step's page gives the most an outrigger pad carries during the step, an estimate from the crane file's masses: the weight of crane and load shared among the four pads as by a rigid frame (a quarter each, plus each pad's share of the moment about their centre; where that would pull a pad, it lifts and the other three carry it all), each mass at its part's centre and the gross load under the rope's sheave (where the chart deducts weights, with them there or without them, whichever weighs more on the pad), at both ends of the step and every half degree of swing and luff between; wind, the load swinging and dynamic factors are not in it, and the crane manufacturer's outrigger loads govern."
        } else {
            ""
        },
        swung = hanging_swept_said(task, plan).map(|s| format!(" ({s})")).unwrap_or_default(),
        against = if !obstacles.is_empty() {
            "the plant model, the scanned points or the obstacles placed by hand"
        } else {
            "the plant model or the scanned points"
        },
        ends = if task.resumes() {
            "The first step starts where the load hangs when the lift resumes (resume_from); the last is the vertical set-down. "
        } else {
            "The first and the last steps are the vertical lift-off and set-down. "
        },
        allowance = if task.radius_allowance_m > 0.0 {
            format!(" plus the radius allowance ({:.2} m)", task.radius_allowance_m)
        } else {
            String::new()
        }
    );
    y = room_on_page(
        &mut d,
        y + 4.0,
        wrap(&under_table, w, 8.5).len() as f32 * line_height_mm(8.5),
        "Steps (continued)",
    );
    y = d.paragraph(15.0, y, w, &under_table, 8.5);
    if let Some(cs) = cspace {
        y += 3.0;
        let img_w = w.min((size.h - 25.0 - y) * cs.width as f32 / cs.height as f32);
        if img_w > 60.0 {
            let caption = format!(
                "C-space of the crane at its position: swing across, {} up. Red: {} comes closer than the clearance to something; orange: {} does; grey hatching: outside the load chart for this load{}. The blue line is the planned path of {}.",
                words.radial_axis,
                words.body,
                words.radial_part,
                if task.swing_range_rad.is_some() {
                    "; dark hatching: outside the lift's permitted swing range"
                } else {
                    ""
                },
                words.radial_part
            );
            let y2 = d.paragraph(15.0, y, w, &caption, 8.0);
            d.image(cs, 15.0, y2, img_w.min(w * (size.h - 25.0 - y2) / (size.h - 25.0 - y)));
        }
    }

    // The rigging, where the lift gives its legs.
    if let (Some(slings), Some(check)) = (&task.slings, &plan.summary.slings) {
        d.new_page();
        let y = heading(&mut d, 20.0, "Rigging");
        crate::rigging::page(&mut d, y, w, slings, &task.load, check);
    }

    // One page per step.
    if s.step_pictures {
        let warned = chart_warnings(inp, task).unwrap_or_default();
        for st in &plan.steps {
            d.new_page();
            let mut y = heading(&mut d, 20.0, &format!("Step {} of {}: {}", st.n, plan.steps.len(), st.text));
            // Each warning once, however many of the cells it names the
            // step reads.
            let read_here: Vec<&str> = warned_read
                .iter()
                .flatten()
                .filter(|(_, steps)| steps.contains(&st.n))
                .map(|(cell, _)| cell.as_str())
                .collect();
            let chart_warned: Vec<&str> = warned
                .iter()
                .filter(|w| read_here.iter().any(|cell| warning_names(w, cell)))
                .map(String::as_str)
                .collect();
            let chart_warning = (!chart_warned.is_empty()).then(|| {
                (
                    "Chart warning",
                    format!(
                        "THIS STEP READS A CELL THE CHART WARNED OF: {}: CHECK IT against the chart the crane's owner issued",
                        chart_warned.join("; ")
                    ),
                )
            });
            let continued = format!("Step {} of {} (continued)", st.n, plan.steps.len());
            y = key_values_on_pages(
                &mut d,
                15.0,
                y,
                &[
                    (
                        "Crane at the end",
                        format!(
                            "swing {:.1}° ({} toward grid bearing {:.1}°), {}, rope {:.2} m, load yaw {:.1}°",
                            st.end.swing_rad.to_degrees(),
                            words.arm,
                            grid_bearing_deg(task.crane.placement.heading_rad + st.end.swing_rad),
                            radial_said(task, st.end.radial),
                            st.end.hoist_m,
                            st.end.load_yaw_rad.to_degrees()
                        ),
                    ),
                    ("Radius / load height", format!("{:.2} m / underside at {:.2} m", st.radius_m, st.load_height_m)),
                    (
                        "Capacity",
                        format!(
                            "{} t ({}), utilisation {} %",
                            opt(st.capacity_kg.map(|c| c / 1000.0), 1),
                            st.chart_cell.clone().unwrap_or_default(),
                            opt(st.utilisation_pct, 1)
                        ),
                    ),
                    (
                        "Min clearance",
                        if st.min_clearance_m.is_finite() {
                            format!(
                                "{:.2} m, {} to {} (required {:.2} m){}",
                                st.min_clearance_m,
                                st.clearance_part,
                                st.clearance_to,
                                st.required_clearance_m,
                                if st.clearance_at.is_some() { "; red flag in the picture" } else { "" }
                            )
                        } else {
                            format!(
                                "nothing within the validator's search ({:.2} m; required {:.2} m)",
                                liftplan_plan::validate::search_cutoff_m(plan.clearance_m),
                                st.required_clearance_m
                            )
                        },
                    ),
                ]
                .into_iter()
                .chain(st.pads.map(|p| ("Outrigger pads", format!("the most: {}", p.said(task.ground.as_ref())))))
                .chain(chart_warning)
                .collect::<Vec<_>>(),
                40.0,
                &continued,
            );
            let img = pictures::step_view(site, task, plan, &others, st.n, px(1300), px(950));
            // Below the table where it fits, else on the next page: a
            // step whose words run long (numbers of a plan.json damaged
            // in the cache ran it past the footer) keeps its picture whole.
            let img_h = w * img.height as f32 / img.width as f32;
            let y = room_on_page(&mut d, y + 2.0, img_h, &continued);
            d.image(&img, 15.0, y, w);
        }
    }

    // Sign-off.
    d.new_page();
    let mut y = heading(&mut d, 20.0, "Review and sign-off");
    y = sign_off_paragraph(
        &mut d,
        y,
        w,
        &format!(
            "This plan was generated by liftplan from the inputs listed on the inputs page and checked by its independent validator. It does not replace the lift engineer's review: check the crane set-up ({}) on site{}, confirm the load's mass and centre of gravity, and confirm that nothing on site has changed since the scans were taken (their dates, as the scan files give them, are on the inputs page).",
            words.set_up,
            match &wind {
                _ if task.crane.model.is_tower() => String::new(),
                Ok((w, other)) if !other.is_empty() => {
                    format!(
                        " and the wind ({:.1} m/s for this load, FROM A SPEED THE CHART'S SHEET DOES NOT STATE: cover)",
                        w.permissible_ms
                    )
                }
                Ok((w, _)) if w.reduced() =>
                    format!(" and the wind (AT MOST {:.1} m/s FOR THIS LOAD: cover)", w.permissible_ms),
                Ok((w, _)) => format!(" and the wind (at most the chart's {:.1} m/s: cover)", w.permissible_ms),
                Err(_) => " and the wind (the speed this load may be lifted in is not worked out: cover)".to_string(),
            }
        ),
    );
    y += 4.0;
    let support_loads = match (plan.summary.highest_pad, task.ground) {
        (None, _) => words.support_loads.to_string(),
        (Some(_), Some(_)) => {
            "outrigger loads (estimated only)".to_string()
        }
        (Some(_), None) => "outrigger loads (estimated only) and ground bearing pressure (the lift gives no mats: ground = { mat_m, allowable_kpa })".to_string(),
    };
    y = sign_off_paragraph(
        &mut d,
        y,
        w,
        &format!(
            "What this plan does not model: the {arm} bending under load (the crane is taken as rigid, so the loaded radius is longer than planned{}), {wind} ({}), the load swinging on its rope when slewing, {} or hoisting starts or stops (the clearance kept around every part, {:.2} m and less over the landing zones, is the only margin for it), and {}.",
            if task.radius_allowance_m > 0.0 {
                format!("; the chart is read {:.2} m farther out for it, as this lift asks", task.radius_allowance_m)
            } else {
                "; no radius allowance is taken for it, radius_allowance_m".to_string()
            },
            if task.capacity_reduction_pct > 0.0 {
                format!("chart values are reduced by {} % as this lift asks, nothing more", task.capacity_reduction_pct)
            } else {
                "chart values are used as printed".to_string()
            },
            words.radial_motion,
            task.clearance_m,
            support_loads,
            arm = words.arm,
            wind = if plan.gust_swing_per_m > 0.0 {
                format!("wind on the {} and the load, but for a gust's swing", words.arm)
            } else {
                format!("wind on the load and the {}", words.arm)
            }
        ),
    );
    y += 4.0;
    let cut = &plan.load_cutout;
    let cut_text = match &cut.set_by {
        Some(earlier) if cut.points > 0 => format!(
            "The load is picked up where lift {earlier} sets it down, so it was not there when the scans were taken: the {} scan points within {:.2} m of its box there ({:.2} m above it) are the top of what it stands on, and were left out of every check with it. Anything else standing that close to the load is not seen: check it on site.",
            cut.points, cut.grow_m, cut.above_m
        ),
        Some(earlier) => format!(
            "The load is picked up where lift {earlier} sets it down, so it was not there when the scans were taken; no scan point lay within {:.2} m of its box there ({:.2} m above it).",
            cut.grow_m, cut.above_m
        ),
        None if cut.points > 0 => format!(
            "The load as scanned at its pick position is not an obstacle to its own lift: the {} scan points within {:.2} m of its box there ({:.2} m above it, where slings lie) were taken for the load and left out of every check. Anything else standing that close to the load at pick is not seen: check it on site.",
            cut.points, cut.grow_m, cut.above_m
        ),
        None => format!(
            "No scan point lay within {:.2} m of the load's box at its pick position ({:.2} m above it), so none was left out as the load. If the load was on site when the scans were taken, check its pick position.",
            cut.grow_m, cut.above_m
        ),
    };
    y = sign_off_paragraph(&mut d, y, w, &cut_text);
    if let Some(l) = plan.summary.load_as_scanned.as_ref().filter(|_| cut.points > 0) {
        y += 4.0;
        y = sign_off_paragraph(&mut d, y, w, &sentence(&l.said()));
    }
    y += 4.0;
    let level = task.crane.placement.z_m;
    let set_up_text = match &plan.validator.set_up_ground {
        Some(g) if task.crane.model.is_tower() => {
            let flag = match tower_base_off_ground_m(task, plan) {
                Some(off) => format!(
                    " THE BASE IS {:.2} m {} THE GROUND AROUND THE MAST: check that its foundation stands so, or set ground_z_m.",
                    off.abs(),
                    if off > 0.0 { "ABOVE" } else { "BELOW" }
                ),
                None => String::new(),
            };
            format!(
                "The tower crane's base is at z = {level:.2} m as the lift gives it: the {} scanned ground points within {:.0} m of its mast lie at {:.2} to {:.2} m (median {:.2} m).{flag} Check the base on site.",
                g.points,
                liftplan_plan::validate::TOWER_GROUND_AROUND_M,
                g.lowest_m,
                g.highest_m,
                g.median_m
            )
        }
        Some(g) => format!(
            "The crane is set up at z = {level:.2} m: the {} scanned ground points under its carrier and outriggers lie at {:.2} to {:.2} m (median {:.2} m).",
            g.points, g.lowest_m, g.highest_m, g.median_m
        ),
        None if task.crane.model.is_tower() => {
            format!("The tower crane's base is at z = {level:.2} m as the lift gives it. Check it on site.")
        }
        None => format!(
            "The crane is set up at z = {level:.2} m as the lift gives it: no ground was scanned under its carrier and outriggers to check that level against. Check it on site."
        ),
    };
    // The pads' loads and what lies under them, with the set-up.
    let set_up_text = std::iter::once(set_up_text)
        .chain(plan.summary.pads_said_briefly().into_iter().chain(plan.summary.under_pads_said()).map(|s| sentence(&s)))
        .collect::<Vec<_>>()
        .join(" ");
    y = sign_off_paragraph(&mut d, y, w, &set_up_text);
    y += 4.0;
    let set_text = match plan.summary.set_down() {
        SetDown::Rests(g) if plan.summary.set_in_cutout_m > 0.0 => format!(
            "At its set position the load rests on {} (found {:.2} m under its underside, where the scans' top {:.2} m went with the load's cut-out at pick).",
            g.object, g.gap_m, plan.summary.set_in_cutout_m
        ),
        SetDown::Rests(g) => format!(
            "At its set position the load rests on {} (within {:.2} m under its underside).",
            g.object, plan.summary.support_m
        ),
        SetDown::Above(g) => format!(
            "At its set position the load hangs {:.2} m above {}, the nearest thing under it: the set-down ends there, and lowering it further is not part of this plan.",
            g.gap_m, g.object
        ),
        SetDown::OverNothing => format!(
            "Nothing in the plant model or the scans lies within {:.0} m under the load at its set position: what it is set down on is not part of this plan. Check it on site.",
            liftplan_plan::validate::SUPPORT_SEARCH_M
        ),
    };
    // Whether what holds it is under its centre of gravity; where the plant
    // model draws the load, how the lift's positions stand against it. What
    // is as it should be in one sentence, for the signatures to stay on
    // the page; what is not, each in its own.
    let on = plan.summary.set_on.as_ref();
    let fine: Vec<String> = on
        .and_then(|s| s.cog_inside_said())
        .into_iter()
        .chain(plan.summary.against_model.iter().filter(|a| a.agrees()).map(|a| a.agrees_clause()))
        .collect();
    let flagged = on
        .filter(|s| s.tips())
        .and_then(|s| s.cog_said())
        .into_iter()
        .chain(plan.summary.against_model.iter().filter(|a| !a.agrees()).map(|a| a.said()));
    let set_text = std::iter::once(set_text)
        .chain((!fine.is_empty()).then(|| sentence(&fine.join(", and "))))
        .chain(flagged.map(|f| sentence(&f)))
        .collect::<Vec<_>>()
        .join(" ");
    y = sign_off_paragraph(&mut d, y, w, &set_text);
    y += 4.0;
    let model_text = match &plan.model_vs_scans {
        Some(a) => {
            sentence(&a.line())
        }
        None if model_unchecked(inp, plan) => "THE PLANT MODEL AND THE SCANS BARELY MEET, so where the model stands in the site was not checked against the scans: CHECK [plant] translate_m and rotate_z_deg (a model off by a height datum, or beside the scanned area, meets none of the scans).".to_string(),
        None => "There is no plant model or no scans, so where the model stands in the site was not checked against the scans.".to_string(),
    };
    y = sign_off_paragraph(&mut d, y, w, &model_text);
    if let Some(said) =
        liftplan_plan::model_copy::PassesLeftOut::said(&plan.summary.passes_left_out, plan.summary.clearance_m)
    {
        y += 4.0;
        y = sign_off_paragraph(&mut d, y, w, &sentence(&said));
    }
    if let Some(warned) = chart_warnings(inp, task) {
        y += 4.0;
        y = sign_off_paragraph(
            &mut d,
            y,
            w,
            &format!(
                "READING THE LOAD CHART'S CONFIGURATION '{}' WARNED: {}. The capacities this plan checks were read so: CHECK THOSE CELLS against the chart the crane's owner issued (a footnote may restrict the value it marks){}.",
                task.chart_config,
                warned.join("; "),
                warned_read.as_deref().map(warned_cells_said).unwrap_or_default()
            ),
        );
    }
    let (left_out, scans) = &inp.scans_left_out;
    if !left_out.is_empty() {
        y += 4.0;
        y = sign_off_paragraph(
            &mut d,
            y,
            w,
            &format!(
                "{} of the {scans} scans DID NOT REGISTER AND WERE LEFT OUT, as [scans] on_unregistered = \"exclude\" asks: {}. Whatever only they saw is not an obstacle in this plan: CHECK ON SITE what stands where they looked, or have them registered.",
                left_out.len(),
                left_out.join(", ")
            ),
        );
    }
    if let Some(said) = scans_warned_paragraph(&inp.scans_warned) {
        y += 4.0;
        y = sign_off_paragraph(&mut d, y, w, &said);
    }
    // Files that may hold what the plan lacks: passed by as no scan, or
    // not read at all.
    let files_said = [
        (!inp.scans_passed_by.is_empty()).then(|| format!(
            "FILES AMONG THE SCANS WERE PASSED BY AS HOLDING NO SCAN: {}. Where one is a scan whose export failed, whatever only it saw is not an obstacle in this plan: CHECK that none is, or have it exported again.",
            inp.scans_passed_by.join("; ")
        )),
        (!inp.inputs_not_read.is_empty()).then(|| format!(
            "FILES IN THE INPUT FOLDERS WERE NOT READ: {}. Whatever only a scan or plant model among them shows is not an obstacle in this plan: CHECK that none is one, or have it exported in a format liftplan reads.",
            inp.inputs_not_read.join("; ")
        )),
    ];
    for said in files_said.into_iter().flatten() {
        y += 4.0;
        y = sign_off_paragraph(&mut d, y, w, &said);
    }
    if let Some((reference, how)) = &inp.site_level_unconfirmed {
        y += 4.0;
        y = sign_off_paragraph(
            &mut d,
            y,
            w,
            &format!(
                "THE SITE'S LEVEL IS NOT CONFIRMED: the scanner did not level itself ([scans.registration] leveled = false) and the reference scan '{reference}', which fixes the site frame, is {}. Every height in this plan, and so every clearance, rests on that frame: CHECK THE LEVEL, or give the reference's surveyed pose in a station file and scan with walls or columns in view.",
                how.strip_prefix("reference, ").unwrap_or(how)
            ),
        );
    }
    for said in [plan.summary.other_loads_said(), plan.summary.other_cranes_said()].into_iter().flatten() {
        y += 4.0;
        y = sign_off_paragraph(&mut d, y, w, &sentence(&said));
    }
    if task.resumes() {
        y += 4.0;
        y = sign_off_paragraph(
            &mut d,
            y,
            w,
            &format!(
                "This plan resumes a lift stopped part way (resume_from): it starts where the load hangs, with no lift-off, and holds the full clearance from its first step. The part of the lift already made, from the pick to there, is not in it: the plan it was made by was signed for that. CHECK that the crane shows the configuration on the cover before step 1.{}",
                resume_check(inp, task).map(|a| format!(" {}.", resume_check_said(a))).unwrap_or_default()
            ),
        );
    }
    if let Some(said) = plan.summary.obstacles_said() {
        y += 4.0;
        y = sign_off_paragraph(
            &mut d,
            y,
            w,
            &sentence(&format!("{said}: CHECK ON SITE that each stands where given, and that nothing else new does")),
        );
    }
    if let Some(c) = &plan.summary.coverage {
        y += 4.0;
        y = sign_off_paragraph(&mut d, y, w, &sentence(&c.line()));
    }
    if let Some(said) = plan.summary.line_like_said() {
        y += 4.0;
        y = sign_off_paragraph(&mut d, y, w, &sentence(&said));
    }
    y += 8.0;
    for role in [
        "Lift engineer (prepared / checked)",
        "Appointed person (approved)",
        "Crane operator (briefed)",
        "Rigging supervisor (briefed)",
    ] {
        y = room_on_page(&mut d, y, 16.0, "Review and sign-off (continued)");
        d.text(15.0, y, role, 10.0, true, INK);
        d.text(15.0, y + 12.0, "Name:", 9.0, false, GREY);
        d.line(27.0, y + 12.5, 95.0, y + 12.5, 0.5, GREY);
        d.text(100.0, y + 12.0, "Signature:", 9.0, false, GREY);
        d.line(118.0, y + 12.5, 160.0, y + 12.5, 0.5, GREY);
        d.text(163.0, y + 12.0, "Date:", 9.0, false, GREY);
        d.line(172.0, y + 12.5, size.w - 15.0, y + 12.5, 0.5, GREY);
        y += 24.0;
    }
    if appendix {
        d.new_page();
        let mut y = heading(&mut d, 20.0, "Inputs and liftplan's code");
        d.text(15.0, y, "blake3 of each input file, of each stage's settings and of the code that ran each stage, first 16 hex digits", 9.0, false, GREY);
        y += 6.0;
        for (f, h) in &inp.input_hashes {
            y = input_row(&mut d, y, f, h, "Inputs and liftplan's code (continued)");
        }
    }
    let pages = d.text.len();
    let bytes = d.finish(&footer(size.w, &inp.project, &task.id, &sm.revision, &inp.date), &inp.date);
    Ok((bytes, pages, overview, chart_img))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A chart warning names the cell it opens with, or every cell of the
    /// range it opens with, on its own sheet only.
    #[test]
    fn a_chart_warning_names_its_cell_or_range() {
        let one = "Main boom 360!H28: footnote mark dropped from '41.5 (1)'";
        assert!(warning_names(one, "Main boom 360!H28"));
        assert!(!warning_names(one, "Main boom 360!H29"));
        let range = "Main boom 360!A6:M44: 281 numbers written as text with decimal commas, read as decimals";
        for inside in ["A6", "M44", "H28", "B44"] {
            assert!(warning_names(range, &format!("Main boom 360!{inside}")), "{inside}");
        }
        for outside in ["Main boom 360!N28", "Main boom 360!H45", "Main boom 360 CW 70t!H28", "H28"] {
            assert!(!warning_names(range, outside), "{outside}");
        }
    }

    #[test]
    fn scans_merged_with_a_warning_are_a_check_before_signing() {
        let warned = |names: &[&str]| -> Vec<(String, String)> {
            names
                .iter()
                .map(|n| (n.to_string(), format!("scan '{n}' was placed with its station's help: ...")))
                .collect()
        };
        assert_eq!(scans_warned_said(&[]), None);
        assert_eq!(
            scans_warned_said(&warned(&["scan-2"])).as_deref(),
            Some("what registration warned of one scan merged (scan-2; inputs page)")
        );
        assert_eq!(
            scans_warned_said(&warned(&["s1", "s4"])).as_deref(),
            Some("what registration warned of 2 scans merged (s1, s4; inputs page)")
        );
        // The sign-off page gives the warnings' words.
        assert_eq!(scans_warned_paragraph(&[]), None);
        assert_eq!(
            scans_warned_paragraph(&warned(&["scan-2"])).as_deref(),
            Some(
                "SCAN 'scan-2' WAS MERGED WITH A WARNING from registration: scan 'scan-2' was placed with its station's help: ... Every obstacle it shows stands where it was placed: CHECK WHAT THE WARNING ASKS before signing, or have the scans registered without it."
            )
        );
        let two = scans_warned_paragraph(&warned(&["s1", "s4"])).unwrap();
        assert!(
            two.starts_with("2 SCANS WERE MERGED WITH A WARNING from registration: scan 's1' was placed")
                && two.contains("... scan 's4' was placed")
                && two.contains("Every obstacle they show stands where they were placed: CHECK WHAT THE WARNINGS ASK"),
            "{two}"
        );
    }

    #[test]
    fn step_numbers_are_said_as_runs() {
        assert_eq!(runs(&[3]), "3");
        assert_eq!(runs(&[3, 4]), "3, 4");
        assert_eq!(runs(&[2, 3, 4, 5, 8, 10, 11]), "2 to 5, 8, 10, 11");
        assert_eq!(runs(&[]), "");
    }

    /// A long lift id, description, project name and input file name stay on
    /// the sheet: the
    /// title and the description wrap (they ran off its right edge, which
    /// `Doc::text` asserts against in tests), and the footer shortens the
    /// project's name, keeping the lift and the date.
    #[test]
    fn a_long_id_description_and_project_name_stay_on_the_sheet() {
        let mut d = Doc::new("t", A4).unwrap();
        d.new_page();
        let w = A4.w - 30.0;
        assert_eq!(cover_heading(&mut d, w, "V-101", "Vessel V-101 onto its foundation"), 40.0);
        let id = "V-101-horizontal-separator-from-trailer-to-foundation-east-of-rack";
        let description = "Vessel V-101 from the low-loader trailer parked on the north access road, over pipe rack PR-3 and the cable tray, onto its foundation FDN-V101 east of the rack";
        let mut d = Doc::new("t", A4).unwrap();
        d.new_page();
        let y = cover_heading(&mut d, w, id, description);
        assert!(y > 40.0 + 2.0 * line_height_mm(11.0), "{y}");
        let text = d.text[0].replace('\n', "");
        assert!(text.contains("cable tray") && text.contains("east-of-rack"), "{text}");
        let project = "Raffinerie Nord — Erweiterung der Destillationsanlage Block 7, Los 3: Montage der Behälter";
        let f = footer(A4.w, project, "V-101", "3f9a2c1b", "2026-12-03");
        assert!(f.starts_with("liftplan ") && f.ends_with(" — lift V-101, plan 3f9a2c1b — issued 2026-12-03"), "{f}");
        assert!(f.contains("Raffinerie Nord") && f.contains("..."), "{f}");
        assert!(text_width_mm(&f, 8.0) <= A4.w - 30.0 - text_width_mm("page 99 of 99", 8.0) - 6.0 + 1e-3, "{f}");
        // An input's file name is listed whole, wrapped.
        let chart = "file:charts/Terex Demag AC700 Lastmomenttabelle Hauptausleger 360 Grad Abstützbasis 13,0 x 13,0 m (gültig ab 2019).xlsx";
        let below = input_row(&mut d, 100.0, chart, "0123456789abcdef", "Inputs (continued)");
        assert!((below - 100.0 - 2.0 * 4.2).abs() < 1e-3, "{below}");
        assert!(d.text[0].replace('\n', "").contains("(gültig ab 2019).xlsx"));
        assert_eq!(
            footer(A4.w, "demo", "V-101", "3f9a2c1b", "2026-12-03"),
            format!("liftplan {} — demo — lift V-101, plan 3f9a2c1b — issued 2026-12-03", env!("CARGO_PKG_VERSION"))
        );
    }

    /// More summary rows than the cover holds under its heading: the rest
    /// in a box of their own on the next page, every row drawn once, none
    /// below the footer (which the drawing asserts in a debug build).
    #[test]
    fn summary_rows_past_the_cover_go_on_the_next_page() {
        let mut d = Doc::new("t", A4).unwrap();
        d.new_page();
        let long = "a row that wraps onto a second and a third line of the summary box, as a lift's wind, its slings or the things to check first before signing do ".repeat(2);
        let rows: Vec<(&str, String)> = (0..30).map(|k| ("Row", format!("row {k:02}: {long}"))).collect();
        let y = summary_box(&mut d, 40.0, &rows, ("VALIDATED", true));
        assert!(d.text.len() >= 2 && d.text[1].starts_with("Summary (continued from the cover)"), "{:?}", d.text);
        assert!(d.text[0].contains("VALIDATED") && !d.text[1].contains("VALIDATED"));
        let all: String = d.text.concat();
        for k in 0..30 {
            assert_eq!(all.matches(&format!("row {k:02}:")).count(), 1, "row {k}");
        }
        assert!(y < A4.h - crate::pdf::FOOTER_FROM_FOOT_MM, "{y}");
        // Rows that fit stay on the cover.
        let mut d = Doc::new("t", A4).unwrap();
        d.new_page();
        summary_box(&mut d, 40.0, &rows[..3], ("VALIDATED", true));
        assert_eq!(d.text.len(), 1);
        // Rows that fit on the cover only in smaller type stay on it, set
        // in that type, above the footer.
        let room = A4.h - FOOT_MM - 40.0 - 14.0 - 2.0;
        let height = |n: usize, pt: f32| key_values_height_at(&d, 19.0, &rows[..n], 34.0, pt);
        let n = (1..rows.len()).find(|&n| height(n, ROW_PT) > room).expect("rows past the cover at 9 pt");
        assert!(height(n, COVER_SUMMARY_MIN_PT) <= room, "{n} rows");
        let mut d = Doc::new("t", A4).unwrap();
        d.new_page();
        let y = summary_box(&mut d, 40.0, &rows[..n], ("VALIDATED", true));
        assert_eq!(d.text.len(), 1, "{n} rows: {:?}", d.text);
        for k in 0..n {
            assert_eq!(d.text[0].matches(&format!("row {k:02}:")).count(), 1, "row {k}");
        }
        assert!(d.lowest_mm[0] < A4.h - FOOT_MM && y < A4.h, "{:?} {y}", d.lowest_mm);
    }

    /// A row longer than a page (what registration warned of, for a survey
    /// of sixty scans) goes on over further pages' boxes, its key once; one
    /// that does not fit under the verdict leaves the verdict alone on the
    /// cover; no line below a page's foot.
    #[test]
    fn a_summary_row_longer_than_a_page_runs_on() {
        let warnings: Vec<String> =
            (0..60).map(|k| format!("scan-{k:02} was placed along a way that holds loosely; ")).collect();
        let long = warnings.concat().repeat(3);
        for (at, rows) in [
            (40.0, vec![("Short", "one line".to_string()), ("CHECK FIRST", long.clone()), ("After", "it".into())]),
            (200.0, vec![("CHECK FIRST", long.clone())]),
        ] {
            let mut d = Doc::new("t", A4).unwrap();
            d.new_page();
            summary_box(&mut d, at, &rows, ("VALIDATED", true));
            assert!(d.text.len() >= 3, "{} pages", d.text.len());
            for (page, low) in d.lowest_mm.iter().enumerate() {
                assert!(*low <= A4.h - FOOT_MM, "page {page}: text at {low} mm");
            }
            let all: String = d.text.concat();
            for k in 0..60 {
                assert_eq!(all.matches(&format!("scan-{k:02}")).count(), 3, "scan-{k}");
            }
            assert_eq!(all.matches("CHECK FIRST").count(), 1);
            assert!(d.text[0].contains("VALIDATED"));
            if at == 200.0 {
                assert!(!d.text[0].contains("CHECK FIRST"), "{}", d.text[0]);
            }
        }
    }

    /// Sign-off paragraphs that do not fit go on to a further page, none
    /// drawn below a page's foot.
    #[test]
    fn the_sign_off_page_runs_on_to_a_further_page() {
        let mut d = Doc::new("t", A4).unwrap();
        d.new_page();
        let mut y = 20.0;
        for k in 0..50 {
            y = sign_off_paragraph(
                &mut d,
                y,
                A4.w - 30.0,
                &format!("check {k}: {}", "what the lift passes over ".repeat(12)),
            );
        }
        assert!(d.text.len() >= 3 && d.text[1].starts_with("Review and sign-off (continued)"), "{:?}", d.text);
        assert!(d.lowest_mm.iter().all(|&low| low <= A4.h - FOOT_MM), "{:?}", d.lowest_mm);
        assert!(d.text.concat().contains("check 49:"));
    }

    /// A value or a table cell too long for the sheet (a plant model's group
    /// path) wraps within it, broken after its slashes, and all of it is on
    /// the page; the steps table's rows grow to hold it.
    #[test]
    fn long_values_and_cells_wrap_within_the_sheet() {
        let mut d = Doc::new("t", A4).unwrap();
        d.new_page();
        let path = "/SITE/ZONE-A/PIPE-RACK-2/BEAM-17".repeat(5);
        let y = key_values(
            &mut d,
            15.0,
            30.0,
            &[("Min clearance", format!("0.12 m, load to {path} (required 1.00 m)"))],
            42.0,
        );
        assert!(y > 30.0 + 5.0 + 2.0 * crate::pdf::line_height_mm(9.0) - 1e-3, "not wrapped: {y}");
        let rows = vec![vec!["1".to_string(), format!("load – {path}")]];
        let widths = [20.0, 60.0];
        let heights = Doc::table_row_heights(&widths, &rows, 8.0);
        assert!(heights[0] > 3.0 * crate::pdf::line_height_mm(8.0), "{heights:?}");
        let below = d.table(15.0, y, &widths, &[true, false], &["Step", "Closest obstacle"], &rows, 8.0);
        assert!((below - y - crate::pdf::table_row_mm(8.0) - heights[0]).abs() < 1e-3);
        let text = d.text[0].replace('\n', "");
        assert_eq!(text.matches("/SITE/ZONE-A/PIPE-RACK-2/BEAM-17").count(), 10, "{text}");
    }

    /// A step's row taller than a page (what it comes closest to named in
    /// the longest words a plan.json may hold, of the widest letter) is
    /// split over pages, every letter of it drawn once and none lower than
    /// the table's margin at the foot; the rows before and after it are
    /// whole.
    #[test]
    fn a_steps_row_taller_than_a_page_is_split_over_pages() {
        let mut d = Doc::new("t", A4).unwrap();
        d.new_page();
        let (header, widths, right) = steps_columns(A4.w - 30.0);
        let name = "W".repeat(liftplan_plan::MAX_STEP_NAME_CHARS);
        let row = |n: usize, closest: String| {
            [
                n.to_string(),
                "Swing".into(),
                "+12.0°".into(),
                "20.00".into(),
                "40.0".into(),
                "30.0".into(),
                "2.50".into(),
                closest,
            ]
            .to_vec()
        };
        let rows =
            vec![row(1, "boom – PIPE-RACK-2".into()), row(2, format!("{name} – {name}")), row(3, "load – V-1".into())];
        let tallest = Doc::table_row_heights(&widths, &rows, 8.0)[1];
        assert!(tallest > A4.h, "not a row taller than a page: {tallest} mm");
        let y = steps_table(&mut d, 150.0, &widths, &right, &header, &rows);
        assert!(d.text.len() >= 3, "{} pages", d.text.len());
        assert!(y <= A4.h - 40.0 + 1e-3, "{y}");
        for (page, low) in d.lowest_mm.iter().enumerate() {
            assert!(*low <= A4.h - 40.0 + 1e-3, "page {page}: drawn at {low} mm");
        }
        let all = d.text.concat();
        assert_eq!(all.matches('W').count(), 2 * liftplan_plan::MAX_STEP_NAME_CHARS);
        assert!(all.contains("PIPE-RACK-2") && all.contains("V-1"), "{all}");
        assert!(d.text[1].starts_with("Steps (continued)"), "{}", d.text[1]);
        assert!(d.text.last().unwrap().contains("load – V-1"), "{:?}", d.text.last());
    }

    /// Text that would run past the sheet's right edge is refused (in
    /// debug builds, as every test's PDF is made).
    #[test]
    #[cfg(debug_assertions)]
    #[should_panic(expected = "runs past the sheet's right edge")]
    fn text_past_the_right_edge_is_refused() {
        let mut d = Doc::new("t", A4).unwrap();
        d.new_page();
        d.text(15.0, 30.0, &"wide ".repeat(80), 9.0, false, INK);
    }

    /// East is 90°, north 0°, south-west 225°; never 360.
    #[test]
    fn grid_bearings_turn_clockwise_from_north() {
        for (ccw_from_x, bearing) in
            [(0.0, 90.0), (90.0, 0.0), (180.0, 270.0), (-135.0, 225.0), (90.01, 0.0), (450.0, 0.0)]
        {
            assert!((grid_bearing_deg(f64::to_radians(ccw_from_x)) - bearing).abs() < 1e-9, "{ccw_from_x}");
        }
    }

    /// A survey of many scans has more input lines than one page holds: they
    /// go on to further pages, none drawn below a page's foot (where the
    /// signer would never see it), and every one is there.
    #[test]
    fn input_lines_run_on_to_further_pages() {
        let mut d = Doc::new("t", A4).unwrap();
        d.new_page();
        let lines: Vec<String> = (0..120)
            .map(|k| {
                let long =
                    if k % 7 == 0 { " and a note long enough to wrap onto a second line of the page" } else { "" };
                format!("scans: scan-{k}: 289094 points read, 112054 kept, fitness 100 %{long}")
            })
            .collect();
        let y = input_lines(&mut d, 29.0, &lines, A4.w - 30.0);
        assert!(d.text.len() >= 3, "{} pages", d.text.len());
        assert!(y <= A4.h - FOOT_MM, "{y}");
        for (page, low) in d.lowest_mm.iter().enumerate() {
            assert!(*low <= A4.h - FOOT_MM, "page {page}: text at {low} mm");
        }
        let all = d.text.concat();
        for k in 0..120 {
            assert!(all.contains(&format!("scan-{k}:")), "scan-{k}");
        }
        assert!(d.text[1].starts_with("Inputs (continued)"), "{}", d.text[1]);
    }

    /// A paragraph longer than a page (thirty of a plant model's longest
    /// names where the load rests against its model copy) runs on over the
    /// pages, each line once, none below the foot.
    #[test]
    fn a_paragraph_longer_than_a_page_runs_on() {
        let mut d = Doc::new("t", A4).unwrap();
        d.new_page();
        let names: Vec<String> = (0..30).map(|k| format!("/P{k:02}-{}", "A".repeat(196))).collect();
        let text = format!("The load agrees with {}.", names.join(", and with "));
        let y = sign_off_paragraph(&mut d, 200.0, A4.w - 30.0, &text);
        assert!(d.text.len() >= 3, "{} pages", d.text.len());
        assert!(y <= A4.h - FOOT_MM, "{y}");
        for (page, low) in d.lowest_mm.iter().enumerate() {
            assert!(*low <= A4.h - FOOT_MM, "page {page}: text at {low} mm");
        }
        let all: String = d.text.concat();
        for name in &names {
            assert_eq!(all.matches(&name[..4]).count(), 1, "{name}");
        }
        assert!(d.text[2].starts_with("Review and sign-off (continued)"), "{}", d.text[2]);
    }

    /// The inputs page's rows likewise: a row that does not fit goes on
    /// the next page, one longer than a page (forty power lines' words)
    /// runs on over pages, and the rows after it follow.
    #[test]
    fn key_values_longer_than_a_page_run_on() {
        let mut d = Doc::new("t", A4).unwrap();
        d.new_page();
        let lines: Vec<String> =
            (0..40).map(|k| format!("line {k:02}: {}", "conductor kept off ".repeat(12))).collect();
        let rows = [("Clearance", "1.00 m".to_string()), ("Power lines", lines.join("; ")), ("After", "them".into())];
        let y = key_values_on_pages(&mut d, 15.0, 250.0, &rows, 42.0, "Inputs (continued)");
        assert!(d.text.len() >= 3, "{} pages", d.text.len());
        assert!(y <= A4.h - FOOT_MM + row_step_mm(ROW_PT), "{y}");
        for (page, low) in d.lowest_mm.iter().enumerate() {
            assert!(*low <= A4.h - FOOT_MM, "page {page}: text at {low} mm");
        }
        let all: String = d.text.concat();
        for k in 0..40 {
            assert_eq!(all.matches(&format!("line {k:02}:")).count(), 1, "line {k}");
        }
        assert!(d.text[0].contains("Clearance") && !d.text[0].contains("Power lines"), "{}", d.text[0]);
        assert!(d.text[1].starts_with("Inputs (continued)\nPower lines"), "{}", d.text[1]);
        assert!(d.text.last().unwrap().contains("After\nthem"), "{:?}", d.text.last());
    }
}
