//! Top view of the registered scans, coloured by scan, shaded by height, with a
//! scale bar: the first thing a survey lead looks at to see that scans line up.

use liftplan_core::cloud::PointCloud;
use liftplan_core::image::{Image, category};

pub fn top_view(cloud: &PointCloud, names: &[String], max_px: u32) -> Image {
    let bb = cloud.bbox();
    let (w, h) =
        if bb.is_empty() { (1.0, 1.0) } else { ((bb.max[0] - bb.min[0]).max(1e-3), (bb.max[1] - bb.min[1]).max(1e-3)) };
    let scale = (max_px as f64 - 40.0) / w.max(h);
    let iw = (w * scale) as u32 + 40;
    let ih = (h * scale) as u32 + 60;
    let mut im = Image::new(iw, ih, [255, 255, 255]);
    if bb.is_empty() {
        return im;
    }
    let zr = (bb.max[2] - bb.min[2]).max(1e-3);
    // Draw low points first so roofs stay on top.
    let mut idx: Vec<usize> = (0..cloud.len()).collect();
    idx.sort_by(|&a, &b| cloud.xyz[a][2].total_cmp(&cloud.xyz[b][2]));
    for i in idx {
        let p = cloud.xyz[i];
        let x = 20.0 + (p[0] - bb.min[0]) * scale;
        let y = 20.0 + (bb.max[1] - p[1]) * scale;
        let c = category(cloud.scan.get(i).copied().unwrap_or(0) as usize);
        let shade = 0.55 + 0.45 * (p[2] - bb.min[2]) / zr;
        let col = [(c[0] as f64 * shade) as u8, (c[1] as f64 * shade) as u8, (c[2] as f64 * shade) as u8];
        im.set(x as i64, y as i64, col);
    }
    // Scale bar: a round number of metres about a fifth of the width.
    let target = w / 5.0;
    let mag = 10f64.powf(target.log10().floor());
    let bar = [1.0, 2.0, 5.0, 10.0].iter().map(|m| m * mag).filter(|b| *b <= target).fold(mag, f64::max);
    let y = ih as f64 - 25.0;
    im.line(20.0, y, 20.0 + bar * scale, y, 3.0, [0, 0, 0]);
    im.text(20, (y + 6.0) as i64, &format!("{bar} M"), 1, [0, 0, 0]);
    let mut x = 40 + (bar * scale) as i64 + Image::text_width(&format!("{bar} M"), 1);
    for (k, n) in names.iter().enumerate().take(10) {
        im.fill_rect(x, (y - 3.0) as i64, x + 8, (y + 5.0) as i64, category(k));
        im.text(x + 11, (y - 3.0) as i64, n, 1, [0, 0, 0]);
        x += Image::text_width(n, 1) + 25;
    }
    im
}
