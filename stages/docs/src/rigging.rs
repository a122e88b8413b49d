//! The rigging page: the load, its lift points, the sling legs, a spreader
//! and the hook block drawn to scale in two elevations, with a row per leg,
//! for the rigging crew to make the slings up to and the signer to see what
//! the Slings row on the cover says.
//!
//! [`sketch`] works the rigging out as plain data in the load's frame, as
//! the plan takes it (the load level, the hook block over the centre of
//! gravity, or over a spreader's joint one); [`page`] draws it.
//!
//! What this module must not do: check anything (core's `slings` checks the
//! legs, and the cover says it), or draw the rigging otherwise than as the
//! plan takes it.

use crate::pdf::Doc;
use liftplan_core::crane::LoadShape;
use liftplan_core::slings::{SlingCheck, Slings};

/// What a straight piece of the rigging is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PieceKind {
    /// A sling leg from a lift point, to the hook block or a spreader's pin.
    Leg,
    /// A spreader's top leg, from its pin to the hook block.
    TopLeg,
    /// A lifting beam's or frame's lug, from the spreader up to the hook.
    Lug,
    /// A spreader beam, or one side of a frame.
    Spreader,
}

/// A straight piece of the rigging, its ends in the load's frame (m from the
/// centre of its box).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Piece {
    pub from: [f64; 3],
    pub to: [f64; 3],
    pub kind: PieceKind,
}

impl Piece {
    /// Its length (m).
    pub fn length_m(&self) -> f64 {
        let d = [0, 1, 2].map(|a| self.to[a] - self.from[a]);
        (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
    }

    /// Its angle from the vertical (degrees).
    pub fn from_vertical_deg(&self) -> f64 {
        let d = [0, 1, 2].map(|a| self.to[a] - self.from[a]);
        d[0].hypot(d[1]).atan2(d[2].abs()).to_degrees()
    }
}

/// The rigging as the plan takes it, in the load's frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Sketch {
    /// The hook block's underside, where the legs (or a spreader's top legs
    /// or lug) meet.
    pub hook: [f64; 3],
    /// The legs first, one per lift point in their order, then a
    /// spreader's pieces.
    pub pieces: Vec<Piece>,
}

impl Sketch {
    /// The sling legs, in the order of the lift points.
    pub fn legs(&self) -> impl Iterator<Item = &Piece> {
        self.pieces.iter().filter(|p| p.kind == PieceKind::Leg)
    }
}

/// The rigging of `slings` on `load`, as `check` found it: legs from the
/// lift points up to the hook block's underside, `load.rigging_height_m`
/// over the load's top, over the centre of gravity (one leg hangs plumb
/// over its lift point: the load tilts until its centre of gravity is under
/// it); or plumb up to a spreader's pins, `below_hook_m` under the hook
/// block, whose top legs (or lug) meet over the joint centre of gravity of
/// the load and the spreader.
pub fn sketch(slings: &Slings, load: &LoadShape, check: &SlingCheck) -> Sketch {
    let pts = &slings.lift_points_m;
    let hook_z = load.size_m[2] / 2.0 + load.rigging_height_m;
    let leg = |from: [f64; 3], to: [f64; 3]| Piece { from, to, kind: PieceKind::Leg };
    let (Some(spreader), Some(spread)) = (&slings.spreader, &check.spreader) else {
        let hook = match pts[..] {
            [one] => [one[0], one[1], hook_z],
            _ => [load.cog_m[0], load.cog_m[1], hook_z],
        };
        return Sketch { hook, pieces: pts.iter().map(|p| leg(*p, hook)).collect() };
    };
    let pins_z = hook_z - spreader.below_hook_m;
    let pins: Vec<[f64; 3]> = pts.iter().map(|p| [p[0], p[1], pins_z]).collect();
    let mut pieces: Vec<Piece> = pts.iter().zip(&pins).map(|(p, pin)| leg(*p, *pin)).collect();
    let hook = match (spread.width_m, spread.hook_from_centre_m) {
        (Some(width_m), Some([dx, dy])) => {
            let n = pts.len() as f64;
            let centre = [0, 1].map(|a| pts.iter().map(|p| p[a]).sum::<f64>() / n);
            let (hx, hy) = (spreader.length_m / 2.0, width_m / 2.0);
            let corner = |sx: f64, sy: f64| [centre[0] + sx * hx, centre[1] + sy * hy, pins_z];
            let corners = [corner(-1.0, -1.0), corner(1.0, -1.0), corner(1.0, 1.0), corner(-1.0, 1.0)];
            for k in 0..4 {
                pieces.push(Piece { from: corners[k], to: corners[(k + 1) % 4], kind: PieceKind::Spreader });
            }
            [centre[0] + dx, centre[1] + dy, hook_z]
        }
        _ => {
            let (a, b) = (pts[0], pts[1]);
            let span = (b[0] - a[0]).hypot(b[1] - a[1]).max(1e-9);
            let dir = [(b[0] - a[0]) / span, (b[1] - a[1]) / span];
            let middle = [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
            let along = |t: f64| [middle[0] + dir[0] * t, middle[1] + dir[1] * t, pins_z];
            let half = spreader.length_m / 2.0;
            pieces.push(Piece { from: along(-half), to: along(half), kind: PieceKind::Spreader });
            let over = along(spread.hook_from_middle_m);
            [over[0], over[1], hook_z]
        }
    };
    if spreader.top_leg_wll_kg.is_some() {
        pieces.extend(pins.iter().map(|pin| Piece { from: *pin, to: hook, kind: PieceKind::TopLeg }));
    } else {
        pieces.push(Piece { from: [hook[0], hook[1], pins_z], to: hook, kind: PieceKind::Lug });
    }
    Sketch { hook, pieces }
}

/// A label on an elevation: the view (0: the side, along the load's x; 1:
/// the end, along its y), the pieces of the sketch it names (their
/// `pieces` indices) and what it says.
#[derive(Debug, Clone, PartialEq)]
pub struct Label {
    pub view: usize,
    pub pieces: Vec<usize>,
    pub text: String,
}

/// Each leg's and top leg's length and angle from the vertical, as the rows
/// give them, to write beside it: once, in the elevation that shows it
/// longer (the side where it runs as far along x as along y), and legs seen
/// there as one line with the same figures in one label ("1, 4: 6.12 m,
/// 48.2°"), so that no label is written over another.
pub fn labels(s: &Sketch, check: &SlingCheck) -> Vec<Label> {
    let top = check.spreader.as_ref().and_then(|sp| sp.top.as_ref());
    let (mut leg_n, mut top_n) = (0, 0);
    let mut named: Vec<(usize, String, String)> = Vec::new();
    for (i, p) in s.pieces.iter().enumerate() {
        let (name, length) = match p.kind {
            PieceKind::Leg => {
                leg_n += 1;
                (leg_n.to_string(), check.leg_lengths_m.get(leg_n - 1))
            }
            PieceKind::TopLeg => {
                top_n += 1;
                (format!("top {top_n}"), top.and_then(|t| t.leg_lengths_m.get(top_n - 1)))
            }
            PieceKind::Lug | PieceKind::Spreader => continue,
        };
        let figures =
            format!("{:.2} m, {:.1}°", length.copied().unwrap_or_else(|| p.length_m()), p.from_vertical_deg());
        named.push((i, name, figures));
    }
    let view_of = |p: &Piece| usize::from((p.to[1] - p.from[1]).abs() > (p.to[0] - p.from[0]).abs());
    let seen_as_one = |a: &Piece, b: &Piece, v: usize| {
        let near = |x: [f64; 3], y: [f64; 3]| (x[v] - y[v]).abs() < 0.01 && (x[2] - y[2]).abs() < 0.01;
        near(a.from, b.from) && near(a.to, b.to)
    };
    let mut out: Vec<(Label, Vec<String>)> = Vec::new();
    for (i, name, figures) in named {
        let p = &s.pieces[i];
        let v = view_of(p);
        let same = out
            .iter_mut()
            .find(|(l, _)| l.view == v && l.text.ends_with(&figures) && seen_as_one(&s.pieces[l.pieces[0]], p, v));
        match same {
            Some((l, names)) => {
                l.pieces.push(i);
                names.push(name);
                l.text = format!("{}: {figures}", names.join(", "));
            }
            None => out.push((Label { view: v, pieces: vec![i], text: format!("{name}: {figures}") }, vec![name])),
        }
    }
    out.into_iter().map(|(l, _)| l).collect()
}

/// The top view under the elevations, at their scale: the load's outline,
/// its centre of gravity and the square it may lie in (`cog_tolerance_m`),
/// the lift points, the legs and a spreader as seen from above, the hook
/// block, and each shackle's pin (orange, along its direction; a pin
/// standing more than 70° from level, as a small square); returns the y
/// below it.
#[allow(clippy::too_many_arguments)]
fn plan_view(
    d: &mut Doc,
    y: f32,
    w: f32,
    s: &Sketch,
    slings: &Slings,
    load: &LoadShape,
    cog_tolerance_m: f64,
    y_half: f64,
    scale: f32,
) -> f32 {
    d.text(15.0, y, "Top: the load's x across, its y up", 8.5, true, INK);
    let top = y + 3.0;
    let mid = 15.0 + w / 2.0;
    let height = (2.0 * y_half) as f32 * scale;
    let at = |p: [f64; 3]| (mid + p[0] as f32 * scale, top + (y_half - p[1]) as f32 * scale);
    let [hx, hy] = [load.size_m[0] / 2.0, load.size_m[1] / 2.0];
    let (bx, by) = at([-hx, hy, 0.0]);
    let (ex, ey) = at([hx, -hy, 0.0]);
    d.frame(bx, by, ex - bx, ey - by, 0.8, INK);
    let (cx, cy) = at(load.cog_m);
    cog_cross(d, cx, cy);
    // Where the centre of gravity may lie (load cog_tolerance_m).
    let tol = cog_tolerance_m as f32 * scale;
    if tol > 0.0 {
        d.frame(cx - tol, cy - tol, 2.0 * tol, 2.0 * tol, 0.5, COG);
    }
    for p in &s.pieces {
        let ((x1, y1), (x2, y2)) = (at(p.from), at(p.to));
        let (width, color) = stroke(p.kind);
        if (x1 - x2).hypot(y1 - y2) > 0.05 {
            d.line(x1, y1, x2, y2, width, color);
        }
    }
    for (n, p) in s.legs().enumerate() {
        let (px, py) = at(p.from);
        d.fill_rect(px - 0.7, py - 0.7, 1.4, 1.4, INK);
        d.text(px + 1.2, py + 3.2, &(n + 1).to_string(), 7.0, false, LEG);
        if let Some(a) = slings.pin_axes.as_ref().and_then(|axes| axes.get(n)) {
            let level = a[0].hypot(a[1]);
            if level > 20f64.to_radians().sin() {
                let half = 4.0 / level as f32;
                let (dx, dy) = (a[0] as f32 * half, -a[1] as f32 * half);
                d.line(px - dx, py - dy, px + dx, py + dy, 1.6, PIN);
            } else {
                d.frame(px - 1.5, py - 1.5, 3.0, 3.0, 0.8, PIN);
            }
        }
    }
    // The hook block in outline, over the centre of gravity's cross.
    let (kx, ky) = at(s.hook);
    d.frame(kx - 2.0, ky - 2.0, 4.0, 4.0, 0.8, INK);
    top + height + 6.0
}

/// How a piece of the rigging is drawn: its line's width (pt) and colour.
fn stroke(kind: PieceKind) -> (f32, [u8; 3]) {
    match kind {
        PieceKind::Leg | PieceKind::TopLeg => (0.9, LEG),
        PieceKind::Lug => (1.5, SPREADER),
        PieceKind::Spreader => (2.5, SPREADER),
    }
}

/// The centre of gravity's mark, a red cross at (`x`, `y`) mm.
fn cog_cross(d: &mut Doc, x: f32, y: f32) {
    d.line(x - 1.5, y, x + 1.5, y, 0.8, COG);
    d.line(x, y - 1.5, x, y + 1.5, 0.8, COG);
}

const PIN: [u8; 3] = [230, 120, 0];
const INK: [u8; 3] = [20, 20, 20];
const GREY: [u8; 3] = [110, 110, 110];
const LEG: [u8; 3] = [25, 80, 170];
const SPREADER: [u8; 3] = [90, 90, 90];
const COG: [u8; 3] = [200, 30, 30];

/// Draws the rigging page's body from `y` (mm from the top) in `w` mm:
/// the side and end elevations and the top view of [`sketch`], a row per
/// leg and per top leg, and what the lengths are for (the top view, the
/// rows and the words on a second page where the first has no room left
/// for them); returns the y below it.
pub fn page(d: &mut Doc, mut y: f32, w: f32, slings: &Slings, load: &LoadShape, check: &SlingCheck) -> f32 {
    let s = sketch(slings, load, check);
    let [hx, hy, hz] = load.size_m.map(|v| v / 2.0);
    // One scale for both views: each view's extent across, and the heights
    // from the load's underside to a little over the hook block.
    let across = |axis: usize, half: f64| {
        s.pieces.iter().flat_map(|p| [p.from[axis].abs(), p.to[axis].abs()]).fold(half, f64::max) + 0.5
    };
    let (side_half, end_half) = (across(0, hx), across(1, hy));
    let (z_lo, z_hi) = (-hz - 0.3, s.hook[2] + 1.2);
    let gap = 10.0f32;
    let panel_h = 95.0f32;
    let panel_w = (w - gap) / 2.0;
    let scale = (panel_w as f64 / (2.0 * side_half))
        .min(panel_w as f64 / (2.0 * end_half))
        .min(panel_h as f64 / (z_hi - z_lo)) as f32;
    y = d.paragraph(
        15.0,
        y,
        w,
        "Drawn to scale in the load's frame as the plan takes it: the load level, the hook block over its centre of gravity (red cross). Legs in blue, numbered as the lift points, each with its length and its angle from the vertical beside it in the elevation that shows it longer; a spreader in grey; in the top view, each shackle's pin in orange (rigging pin_axes) and the square its centre of gravity may lie in (load cog_tolerance_m) in red.",
        8.5,
    );
    y += 2.0;
    let labels = labels(&s, check);
    for (k, (axis, title)) in
        [(0usize, "Side: the load's x across, up"), (1usize, "End: the load's y across, up")].into_iter().enumerate()
    {
        let x0 = 15.0 + k as f32 * (panel_w + gap);
        d.text(x0, y, title, 8.5, true, INK);
        let top = y + 3.0;
        let mid = x0 + panel_w / 2.0;
        let at = |p: [f64; 3]| (mid + (p[axis] as f32) * scale, top + ((z_hi - p[2]) as f32) * scale);
        let half = [hx, hy][axis];
        let (bx, by) = at([-half, -half, hz]);
        let (ex, ey) = at([half, half, -hz]);
        d.frame(bx, by, ex - bx, ey - by, 0.8, INK);
        let (cx, cy) = at(load.cog_m);
        cog_cross(d, cx, cy);
        for p in &s.pieces {
            let ((x1, y1), (x2, y2)) = (at(p.from), at(p.to));
            let (width, color) = stroke(p.kind);
            d.line(x1, y1, x2, y2, width, color);
        }
        for (n, p) in s.legs().enumerate() {
            let (px, py) = at(p.from);
            d.fill_rect(px - 0.7, py - 0.7, 1.4, 1.4, INK);
            // Side by side in this view where two points are.
            let shift = s.legs().take(n).filter(|q| (q.from[axis] - p.from[axis]).abs() < 0.05).count() as f32;
            d.text(px + 1.0 + 2.5 * shift, py + 3.2, &(n + 1).to_string(), 7.0, false, LEG);
        }
        let (hook_x, _) = at(s.hook);
        for label in labels.iter().filter(|l| l.view == axis) {
            let p = &s.pieces[label.pieces[0]];
            let ((x1, y1), (x2, y2)) = (at(p.from), at(p.to));
            let (mx, my) = ((x1 + x2) / 2.0, (y1 + y2) / 2.0);
            let width = crate::pdf::text_width_mm(&label.text, 7.0);
            // Outside the legs, on the side of the hook block it lies, and
            // within the panel.
            let x = if mx < hook_x - 0.05 { mx - 1.5 - width } else { mx + 1.5 };
            let x = x.min(x0 + panel_w - width).max(x0);
            d.text(x, my, &label.text, 7.0, false, LEG);
        }
        let (kx, ky) = at(s.hook);
        d.fill_rect(kx - 1.5, ky - 3.0, 3.0, 3.0, INK);
        d.line(kx, ky - 3.0, kx, top, 0.6, GREY);
        d.text(kx + 2.0, ky - 1.0, "hook block", 7.0, false, GREY);
    }
    y += 3.0 + ((z_hi - z_lo) as f32) * scale + 6.0;
    let header = ["Leg", "From (x, y, z) m", "To", "Length m", "From vertical", "Most t", "Shackle pin", "Out of line"];
    let widths = [14.0, 36.0, 22.0, 17.0, 24.0, 14.0, 30.0, w - 157.0];
    let right = [false, false, false, true, true, true, false, true];
    let rows = leg_rows(&s, slings, check);
    let one = if s.legs().count() == 1 && slings.spreader.is_none() {
        " On one leg the load tilts until its centre of gravity hangs under its lift point."
    } else {
        ""
    };
    let words = format!(
        "Lengths are from each lift point to the hook block's underside ({:.2} m over the load's top, rigging height_m), or to a spreader's pin, for the load to hang level as planned with its centre of gravity at ({:.2}, {:.2}, {:.2}) m from its box's centre (load cog_m): make the slings up to them, shackles and fittings included, and check at the trial lift that the load hangs level. A shackle's pin is given in the load's frame (rigging pin_axes; a top leg's, at the spreader's lug, spreader top_pin_axes); out of line is how far its leg may pull from the plane square to the pin. Most: the most the leg carries, in the worst way the load may hang on the legs and, where its centre of gravity is known only to a tolerance, at the worst place within it for that leg; a top leg's, the most it carries with the spreader; the ratings are in the cover's Slings row.{one}",
        load.rigging_height_m, load.cog_m[0], load.cog_m[1], load.cog_m[2]
    );
    // The top view, the rows and the words together, on the next page
    // where this one has no room left for them.
    let rows_mm = Doc::table_row_heights(&widths, &rows, 8.0).iter().sum::<f32>() + crate::pdf::table_row_mm(8.0);
    let words_mm = crate::pdf::wrap(&words, w, 8.5).len() as f32 * crate::pdf::line_height_mm(8.5);
    let top_view_mm = 3.0 + (2.0 * end_half) as f32 * scale + 6.0;
    if y + top_view_mm + rows_mm + 4.0 + words_mm > d.size.h - BOTTOM_MM {
        d.new_page();
        y = crate::report::heading(d, 20.0, "Rigging (continued)");
    }
    y = plan_view(d, y, w, &s, slings, load, check.cog_tolerance_m, end_half, scale);
    y = d.table(15.0, y, &widths, &right, &header, &rows, 8.0);
    d.paragraph(15.0, y + 4.0, w, &words, 8.5)
}

/// Where the rigging pages' drawing stops, from the sheet's foot (mm): above
/// the footer.
const BOTTOM_MM: f32 = 15.0;

/// A row per leg of `s` (its lift point, where it ends, its length, its
/// angle from the vertical, the most it carries, its shackle's pin and how
/// far it pulls out of line), then per top leg.
fn leg_rows(s: &Sketch, slings: &Slings, check: &SlingCheck) -> Vec<Vec<String>> {
    let side = check.side_loading.as_ref();
    let at = |p: [f64; 3]| format!("({:.2}, {:.2}, {:.2})", p[0], p[1], p[2]);
    let mut rows: Vec<Vec<String>> = s
        .legs()
        .enumerate()
        .map(|(k, p)| {
            vec![
                (k + 1).to_string(),
                at(p.from),
                if slings.spreader.is_some() { "spreader pin".into() } else { "hook block".into() },
                check.leg_lengths_m.get(k).map_or_else(|| format!("{:.2}", p.length_m()), |l| format!("{l:.2}")),
                format!("{:.1}°", p.from_vertical_deg()),
                check.leg_most_kg.get(k).map_or_else(|| "—".into(), |kg| format!("{:.2}", kg / 1000.0)),
                slings
                    .pin_axes
                    .as_ref()
                    .and_then(|a| a.get(k))
                    .map_or_else(|| "—".into(), |a| format!("({:.2}, {:.2}, {:.2})", a[0], a[1], a[2])),
                side.and_then(|sl| sl.out_of_line_deg.get(k)).map_or_else(|| "—".into(), |deg| format!("{deg:.1}°")),
            ]
        })
        .collect();
    let top = check.spreader.as_ref().and_then(|sp| sp.top.as_ref());
    let top_pins = slings.spreader.as_ref().and_then(|sp| sp.top_shackles.as_ref()).and_then(|t| t.pin_axes.as_ref());
    for (k, p) in s.pieces.iter().filter(|p| p.kind == PieceKind::TopLeg).enumerate() {
        rows.push(vec![
            format!("top {}", k + 1),
            at(p.from),
            "hook block".into(),
            top.and_then(|t| t.leg_lengths_m.get(k))
                .map_or_else(|| format!("{:.2}", p.length_m()), |l| format!("{l:.2}")),
            format!("{:.1}°", p.from_vertical_deg()),
            top.and_then(|t| t.leg_most_kg.get(k)).map_or_else(|| "—".into(), |kg| format!("{:.2}", kg / 1000.0)),
            top_pins
                .and_then(|a| a.get(k))
                .map_or_else(|| "—".into(), |a| format!("({:.2}, {:.2}, {:.2})", a[0], a[1], a[2])),
            top.and_then(|t| t.out_of_line_deg.get(k)).map_or_else(|| "—".into(), |deg| format!("{deg:.1}°")),
        ]);
    }
    rows
}

#[cfg(test)]
mod tests {
    use super::*;
    use liftplan_core::slings::{Ratings, Spreader, check};

    fn load(size_m: [f64; 3], cog_m: [f64; 3]) -> LoadShape {
        LoadShape { size_m, cog_m, rigging_height_m: 4.0 }
    }

    /// Two legs to lift points 8 m apart on the load's top, 10 t each,
    /// the points given by the lift or not.
    fn two_legs(points_given: bool) -> Slings {
        Slings {
            lift_points_m: vec![[-4.0, 0.0, 1.5], [4.0, 0.0, 1.5]],
            points_given,
            ratings: Ratings::legs(10_000.0),
            spreader: None,
            pin_axes: None,
        }
    }

    /// Two legs 6 m apart hanging plumb from a 7 m spreader beam 3 m under
    /// the hook block, hung by two top legs, with `top_shackles`.
    fn spreader_beam(top_shackles: Option<liftplan_core::slings::TopShackles>) -> Slings {
        Slings {
            lift_points_m: vec![[-3.0, 0.0, 1.5], [3.0, 0.0, 1.5]],
            points_given: true,
            ratings: Ratings::legs(10_000.0),
            spreader: Some(Spreader {
                length_m: 7.0,
                below_hook_m: 3.0,
                wll_kg: 20_000.0,
                mass_kg: 300.0,
                top_leg_wll_kg: Some(12_000.0),
                width_m: None,
                top_shackles,
            }),
            pin_axes: None,
        }
    }

    /// Two legs to the hook over the centre of gravity; a beam's legs
    /// plumb to its pins, its top legs to the hook over the joint centre of
    /// gravity; a lifting frame's four legs plumb, its lug over that of the
    /// frame and the load. The legs' lengths are the check's.
    #[test]
    fn the_sketch_hangs_the_legs_where_the_check_does() {
        let l = load([8.0, 3.0, 3.0], [0.2, 0.0, -0.1]);
        let two = two_legs(false);
        let c = check(&two, 12_000.0, l.size_m, l.cog_m, l.rigging_height_m).unwrap();
        let s = sketch(&two, &l, &c);
        assert_eq!(s.hook, [0.2, 0.0, 5.5]);
        let lengths: Vec<f64> = s.legs().map(Piece::length_m).collect();
        assert!(lengths.iter().zip(&c.leg_lengths_m).all(|(a, b)| (a - b).abs() < 1e-12), "{lengths:?}");
        assert!((s.pieces[1].from_vertical_deg() - 3.8f64.atan2(4.0).to_degrees()).abs() < 1e-9);

        let beam = spreader_beam(None);
        let c = check(&beam, 12_000.0, l.size_m, l.cog_m, l.rigging_height_m).unwrap();
        let s = sketch(&beam, &l, &c);
        let legs: Vec<&Piece> = s.legs().collect();
        assert!(legs.iter().all(|p| p.from_vertical_deg() == 0.0 && p.to[2] == 2.5), "{legs:?}");
        assert!(legs.iter().zip(&c.leg_lengths_m).all(|(p, l)| (p.length_m() - l).abs() < 1e-12));
        // Over the joint centre of gravity: 12 t at 0.2 m, 0.3 t at 0.
        assert!((s.hook[0] - 0.2 * 12.0 / 12.3).abs() < 1e-9 && s.hook[2] == 5.5, "{:?}", s.hook);
        let beams: Vec<&Piece> = s.pieces.iter().filter(|p| p.kind == PieceKind::Spreader).collect();
        assert_eq!((beams.len(), beams[0].length_m()), (1, 7.0));
        assert_eq!(s.pieces.iter().filter(|p| p.kind == PieceKind::TopLeg && p.to == s.hook).count(), 2);

        let frame = Slings {
            lift_points_m: vec![[-3.0, -1.0, 1.5], [3.0, -1.0, 1.5], [3.0, 1.0, 1.5], [-3.0, 1.0, 1.5]],
            spreader: Some(Spreader {
                length_m: 6.0,
                width_m: Some(2.0),
                top_leg_wll_kg: None,
                ..beam.spreader.clone().unwrap()
            }),
            ..two.clone()
        };
        let c = check(&frame, 12_000.0, l.size_m, l.cog_m, l.rigging_height_m).unwrap();
        let s = sketch(&frame, &l, &c);
        assert_eq!(s.pieces.iter().filter(|p| p.kind == PieceKind::Spreader).count(), 4);
        let lug: Vec<&Piece> = s.pieces.iter().filter(|p| p.kind == PieceKind::Lug).collect();
        assert_eq!(lug.len(), 1);
        assert!((lug[0].length_m() - 3.0).abs() < 1e-12 && lug[0].from_vertical_deg() == 0.0);
        let [dx, dy] = c.spreader.as_ref().unwrap().hook_from_centre_m.unwrap();
        assert_eq!([s.hook[0], s.hook[1]], [dx, dy]);

        // One leg: plumb over its lift point.
        let one = Slings { lift_points_m: vec![[0.5, 0.0, 1.5]], ..two.clone() };
        let c = check(&one, 12_000.0, l.size_m, l.cog_m, l.rigging_height_m).unwrap();
        let s = sketch(&one, &l, &c);
        assert_eq!(s.hook, [0.5, 0.0, 5.5]);
        assert_eq!(s.pieces[0].from_vertical_deg(), 0.0);
    }

    /// Each leg and top leg is labelled once with the check's length and its
    /// angle from the vertical, in the elevation that shows it longer; legs
    /// seen there as one line with the same figures share a label, legs
    /// with other figures do not.
    #[test]
    fn each_leg_is_labelled_once_with_its_length_and_angle() {
        let texts = |slings: &Slings, l: &LoadShape| -> Vec<(usize, Vec<usize>, String)> {
            let c = check(slings, 12_000.0, l.size_m, l.cog_m, l.rigging_height_m).unwrap();
            labels(&sketch(slings, l, &c), &c).into_iter().map(|x| (x.view, x.pieces, x.text)).collect()
        };
        let two = two_legs(true);
        // The demo's legs, by hand: 4.2 and 3.8 m across, 4 m up.
        let l = load([8.0, 3.0, 3.0], [0.2, 0.0, -0.1]);
        let want = |dx: f64| format!("{:.2} m, {:.1}°", dx.hypot(4.0), dx.atan2(4.0).to_degrees());
        assert_eq!(
            texts(&two, &l),
            vec![(0, vec![0], format!("1: {}", want(4.2))), (0, vec![1], format!("2: {}", want(3.8)))]
        );
        assert_eq!(want(4.2), "5.80 m, 46.4°");
        // Along the load's y: the end view.
        let across = Slings { lift_points_m: vec![[0.0, -1.5, 1.5], [0.0, 1.5, 1.5]], ..two.clone() };
        assert!(texts(&across, &load([3.0, 8.0, 3.0], [0.0; 3])).iter().all(|t| t.0 == 1));
        // Four legs at a square's corners: 1 and 4 seen as one line in the
        // side view, 2 and 3 too.
        let corners = vec![[-4.0, -3.5, 1.5], [4.0, -3.5, 1.5], [4.0, 3.5, 1.5], [-4.0, 3.5, 1.5]];
        let four = Slings { lift_points_m: corners.clone(), ..two.clone() };
        let l = load([8.0, 7.0, 3.0], [0.0; 3]);
        let t = texts(&four, &l);
        assert_eq!(t.iter().map(|t| t.1.clone()).collect::<Vec<_>>(), vec![vec![0, 3], vec![1, 2]], "{t:?}");
        assert!(t[0].2.starts_with("1, 4: ") && t[1].2.starts_with("2, 3: "), "{t:?}");
        // With the centre of gravity off along y, legs 1 and 4 differ:
        // labelled apart.
        let t = texts(&four, &load([8.0, 7.0, 3.0], [0.0, 0.5, 0.0]));
        assert_eq!(t.len(), 4, "{t:?}");
        // A beam: its plumb legs and its top legs, each once.
        let beam = spreader_beam(None);
        let t = texts(&beam, &load([8.0, 3.0, 3.0], [0.0; 3]));
        let names: Vec<&str> = t.iter().map(|t| t.2.split(':').next().unwrap()).collect();
        assert_eq!(names, ["1", "2", "top 1", "top 2"], "{t:?}");
        assert_eq!(t[0].2, "1: 1.00 m, 0.0°");
    }

    /// A top leg's row gives its shackle's pin and how far it pulls out of
    /// line, where the spreader's top pins are given.
    #[test]
    fn a_top_leg_s_row_gives_its_shackle_s_pin() {
        use liftplan_core::slings::TopShackles;
        let l = load([8.0, 3.0, 3.0], [0.0; 3]);
        let beam = spreader_beam(Some(TopShackles {
            wll_kg: 12_000.0,
            pin_axes: Some(vec![[0.0, 1.0, 0.0], [1.0, 0.0, 0.0]]),
        }));
        let c = check(&beam, 12_000.0, l.size_m, l.cog_m, l.rigging_height_m).unwrap();
        let rows = leg_rows(&sketch(&beam, &l, &c), &beam, &c);
        let top: Vec<&Vec<String>> = rows.iter().filter(|r| r[0].starts_with("top ")).collect();
        assert_eq!((top[0][6].as_str(), top[0][7].as_str()), ("(0.00, 1.00, 0.00)", "0.0°"));
        // The second's pin along the beam: its leg, 3 m across and 3 m up,
        // pulls 45° out of line.
        assert_eq!((top[1][6].as_str(), top[1][7].as_str()), ("(1.00, 0.00, 0.00)", "45.0°"));
    }

    /// The page's drawing stays above the footer (drawing below it is the
    /// document's own debug assertion) on A4 and Letter, for loads long,
    /// square and tall, the top view, the rows and the words going on to a
    /// second page where the first has no room left for them.
    #[test]
    fn the_rigging_fits_its_pages() {
        let corners = |[x, y, z]: [f64; 3]| {
            let [hx, hy, hz] = [x / 2.0, y / 2.0, z / 2.0];
            vec![[-hx, -hy, hz], [hx, -hy, hz], [hx, hy, hz], [-hx, hy, hz]]
        };
        let legs = |points: Vec<[f64; 3]>| Slings {
            pin_axes: Some(vec![[0.0, 1.0, 0.0]; points.len()]),
            lift_points_m: points,
            points_given: true,
            ratings: Ratings { shackle_wll_kg: Some(50_000.0), ..Ratings::legs(50_000.0) },
            spreader: None,
        };
        let cases = [
            (legs(vec![[-4.0, 0.0, 1.5], [4.0, 0.0, 1.5]]), load([8.0, 3.0, 3.0], [0.2, 0.0, -0.1])),
            (legs(corners([8.0, 7.0, 3.0])), load([8.0, 7.0, 3.0], [0.0; 3])),
            (
                legs(corners([10.0, 10.0, 3.0])),
                LoadShape { rigging_height_m: 6.0, ..load([10.0, 10.0, 3.0], [0.0; 3]) },
            ),
            (legs(corners([3.0, 3.0, 10.0])), load([3.0, 3.0, 10.0], [0.0, 0.0, -1.0])),
            (legs(vec![[0.0, 0.0, 1.0]]), load([2.0, 2.0, 2.0], [0.1, 0.0, 0.0])),
        ];
        let mut went_on = 0;
        for size in [crate::pdf::A4, crate::pdf::LETTER] {
            for (slings, l) in &cases {
                let c = check(slings, 12_000.0, l.size_m, l.cog_m, l.rigging_height_m).unwrap();
                let mut d = Doc::new("rigging", size).unwrap();
                d.new_page();
                let y = crate::report::heading(&mut d, 20.0, "Rigging");
                page(&mut d, y, size.w - 30.0, slings, l, &c);
                let pdf = lopdf::Document::load_mem(&d.finish("footer", "2026-12-05")).unwrap();
                let pages: Vec<u32> = pdf.get_pages().keys().copied().collect();
                assert!(pages.len() <= 2, "{:?}: {} pages", l.size_m, pages.len());
                went_on += pages.len() - 1;
                let text = pdf.extract_text(&pages).unwrap().replace('\n', " ");
                assert!(
                    text.contains("Top: the load's x across, its y up")
                        && text.contains("Lengths are from each lift point"),
                    "{text}"
                );
                for (k, p) in slings.lift_points_m.iter().enumerate() {
                    let row = format!("{} ({:.2}, {:.2}, {:.2}) hook block ", k + 1, p[0], p[1], p[2]);
                    assert!(text.contains(&row), "{row}: {text}");
                }
                let s = sketch(slings, l, &c);
                for label in labels(&s, &c) {
                    assert!(text.contains(&label.text), "{}: {text}", label.text);
                }
            }
        }
        assert!(went_on > 0, "no case went on to a second page: that branch is not tested");
    }
}
