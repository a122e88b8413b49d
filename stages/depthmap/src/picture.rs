//! Top view of a depth map: each cell coloured by the height of its highest
//! obstacle, empty cells white, with a height legend.

use crate::mdm::Mdm;
use liftplan_core::image::{Image, ramp};

pub fn top_view(m: &Mdm, max_px: u32) -> Image {
    let s = &m.spec;
    let scale = (max_px as f64 / s.nx.max(s.ny) as f64).clamp(0.05, 8.0);
    let w = ((s.nx as f64 * scale).ceil() as u32).max(1);
    let h = ((s.ny as f64 * scale).ceil() as u32).max(1);
    let mut im = Image::new(w + 80, h, [255, 255, 255]);
    let tops = &m.pyramid[0].2;
    let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
    for &t in tops.iter().filter(|t| t.is_finite()) {
        lo = lo.min(t);
        hi = hi.max(t);
    }
    let span = (hi - lo).max(0.1);
    for y in 0..h {
        let j = (((h - 1 - y) as f64 + 0.5) / scale) as u32;
        for x in 0..w {
            let i = ((x as f64 + 0.5) / scale) as u32;
            if i >= s.nx || j >= s.ny {
                continue;
            }
            let t = tops[(j * s.nx + i) as usize];
            if t.is_finite() {
                im.set(x as i64, y as i64, ramp(((t - lo) / span) as f64));
            }
        }
    }
    for k in 0..h.saturating_sub(40) {
        let f = 1.0 - k as f64 / (h.saturating_sub(40).max(1)) as f64;
        im.fill_rect(w as i64 + 10, 20 + k as i64, w as i64 + 30, 21 + k as i64, ramp(f));
    }
    im.text(w as i64 + 34, 16, &format!("{hi:.0} M"), 1, [0, 0, 0]);
    im.text(w as i64 + 34, h as i64 - 24, &format!("{lo:.0} M"), 1, [0, 0, 0]);
    im
}
