//! The C-space picture: swing across (0° to 360° from the crane heading), radial
//! joint up; body and boom collisions, chart limits, and optionally a path.

use crate::CSpace;
use liftplan_core::image::{Image, Rgb};

const FREE: Rgb = [238, 244, 238];
const BODY: Rgb = [200, 60, 50];
const BOOM: Rgb = [235, 150, 60];
const CHART: Rgb = [150, 150, 160];
const OUT_OF_SWING_RANGE: Rgb = [70, 70, 80];

/// Whether `swing` (rad) lies in the permitted range `(a, b)` by some whole
/// number of turns.
fn in_swing_range(swing: f64, (a, b): (f64, f64)) -> bool {
    liftplan_core::units::swing_into_range(swing, a, b).is_some()
}

/// Draws the tables; `path` holds (swing rad, radial) points joined by lines,
/// `marks` labelled points (pick, set); swing outside `swing_range` (the
/// lift's permitted range, rad) is hatched dark.
pub fn draw(
    cs: &CSpace,
    gross_kg: f64,
    reduction_pct: f64,
    swing_range: Option<(f64, f64)>,
    path: &[(f64, f64)],
    marks: &[(&str, f64, f64)],
) -> Image {
    let (ml, mb, mt, mr) = (70i64, 50i64, 30i64, 20i64);
    let w = 1000i64;
    let h = 420i64;
    let mut img = Image::new((w + ml + mr) as u32, (h + mb + mt) as u32, [255, 255, 255]);
    let x_of = |swing: f64| ml as f64 + swing.rem_euclid(std::f64::consts::TAU) / std::f64::consts::TAU * w as f64;
    let y_of = |radial: f64| (mt + h) as f64 - (radial - cs.radial0) / (cs.nr as f64 * cs.radial_step) * h as f64;
    for py in 0..h {
        let k = (((h - 1 - py) as f64 / h as f64) * cs.nr as f64) as u32;
        let k = k.min(cs.nr - 1);
        let cap_ok = cs.row_capacity_kg[k as usize].is_some_and(|c| c * (1.0 - reduction_pct / 100.0) >= gross_kg);
        for px in 0..w {
            let i = ((px as f64 / w as f64) * cs.ns as f64) as u32;
            let i = i.min(cs.ns - 1);
            let idx = (k * cs.ns + i) as usize;
            let mut c = FREE;
            if !cs.cell_hits.is_empty() && cs.cell_hits[idx].is_some() {
                c = BOOM;
            }
            if !cs.swing_hits.is_empty() && cs.swing_hits[i as usize].is_some() {
                c = BODY;
            }
            if !cap_ok && (px + py) % 6 < 3 {
                c = CHART;
            }
            if swing_range.is_some_and(|r| !in_swing_range(cs.swing_center(i), r)) && (px - py).rem_euclid(6) < 3 {
                c = OUT_OF_SWING_RANGE;
            }
            img.set(ml + px, mt + py, c);
        }
    }
    img.rect_outline(ml as f64, mt as f64, (ml + w) as f64, (mt + h) as f64, 1.0, [60, 60, 60]);
    for deg in (0..=360).step_by(45) {
        let x = ml as f64 + deg as f64 / 360.0 * w as f64;
        img.line(x, (mt + h) as f64, x, (mt + h + 5) as f64, 1.0, [60, 60, 60]);
        let t = format!("{deg}");
        img.text(x as i64 - Image::text_width(&t, 2) / 2, mt + h + 10, &t, 2, [40, 40, 40]);
    }
    img.text(ml + w / 2 - 120, mt + h + 32, "SWING FROM HEADING (DEG)", 2, [40, 40, 40]);
    let span = cs.nr as f64 * cs.radial_step;
    for q in 0..=4 {
        let r = cs.radial0 + span * q as f64 / 4.0;
        let y = y_of(r);
        let t = if cs.radial_step < 0.2 { format!("{:.0}", r.to_degrees()) } else { format!("{r:.0}") };
        img.text(ml - 10 - Image::text_width(&t, 2), y as i64 - 7, &t, 2, [40, 40, 40]);
    }
    img.text(4, 8, if cs.radial_step < 0.2 { "LUFF (DEG)" } else { "TROLLEY (M)" }, 2, [40, 40, 40]);
    for win in path.windows(2) {
        let (a, b) = (win[0], win[1]);
        // Draw across the 0/360 seam as two pieces.
        let (xa, xb) = (x_of(a.0), x_of(b.0));
        let (ya, yb) = (y_of(a.1), y_of(b.1));
        if (xa - xb).abs() > w as f64 / 2.0 {
            // Crosses the 0°/360° seam: draw to the edge and on from the other edge.
            let (left, right) = (ml as f64, (ml + w) as f64);
            let (xa2, xb2) = if xa > xb { (xa - w as f64, xb) } else { (xa + w as f64, xb) };
            let edge = if xa > xb { left } else { right };
            let t = (edge - xa2) / (xb2 - xa2);
            let ym = ya + (yb - ya) * t;
            img.line(xa, ya, if xa > xb { right } else { left }, ym, 3.0, [20, 60, 160]);
            img.line(edge, ym, xb, yb, 3.0, [20, 60, 160]);
            continue;
        }
        img.line(xa, ya, xb, yb, 3.0, [20, 60, 160]);
    }
    for (label, s, r) in marks {
        let (x, y) = (x_of(*s), y_of(*r));
        img.disc(x, y, 6.0, [20, 60, 160]);
        img.text(x as i64 + 8, y as i64 - 16, label, 2, [20, 60, 160]);
    }
    img
}

#[cfg(test)]
mod tests {
    use super::in_swing_range;

    /// A permitted range across ±180° holds the swings behind the heading
    /// by whole turns, whichever way they are written.
    #[test]
    fn the_permitted_swing_range_holds_swings_by_whole_turns() {
        let r = |a: f64, b: f64| (a.to_radians(), b.to_radians());
        let behind = r(90.0, 270.0);
        assert!(in_swing_range(200f64.to_radians(), behind));
        assert!(in_swing_range((-160f64).to_radians(), behind));
        assert!(!in_swing_range(10f64.to_radians(), behind));
        let front = r(-60.0, 60.0);
        assert!(in_swing_range(350f64.to_radians(), front) && !in_swing_range(90f64.to_radians(), front));
    }
}
