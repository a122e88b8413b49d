//! Square-window maximum filter over a row-major grid (a grey-scale dilation),
//! used to turn the map's cell tops into "highest obstacle within w cells".
//!
//! Separable (rows, then columns), each pass the van Herk / Gil-Werman scheme:
//! three comparisons per cell whatever the window. Cells outside the grid count
//! as empty (`-inf`). Exact: every output is the maximum of its window.
//!
//! The maximum is taken in IEEE total order (`f32::total_cmp`) with NaN read
//! as empty (`-inf`): so `+0.0` beats `-0.0` wherever both are in a window,
//! and the result is one bit pattern whatever the order of comparisons. The
//! GPU twin ([`crate::gpu::Gpu::window_max`]) compares in another order and
//! gives the same bits.

use rayon::prelude::*;

/// The value a cell counts as: NaN is empty.
fn canonical(v: f32) -> f32 {
    if v.is_nan() { f32::NEG_INFINITY } else { v }
}

/// The larger in IEEE total order (`-0.0` below `+0.0`).
fn total_max(a: f32, b: f32) -> f32 {
    if b.total_cmp(&a).is_gt() { b } else { a }
}

/// `out[i] = max(src[i - w ..= i + w])`, indices outside `src` ignored.
pub fn window_max_1d(src: &[f32], w: usize, out: &mut [f32]) {
    let n = src.len();
    // A window wider than the row covers no more of it, and padding for one
    // would be allocated (and `2w + 1` overflow) for nothing.
    let w = w.min(n);
    let b = 2 * w + 1;
    // Padded so that every window is exactly b long and starts at padded i.
    let len = n + 2 * w;
    let at = |p: usize| if p >= w && p < w + n { canonical(src[p - w]) } else { f32::NEG_INFINITY };
    let mut g = vec![f32::NEG_INFINITY; len];
    let mut h = vec![f32::NEG_INFINITY; len];
    for p in 0..len {
        g[p] = if p % b == 0 { at(p) } else { total_max(g[p - 1], at(p)) };
    }
    for p in (0..len).rev() {
        h[p] = if p % b == b - 1 || p == len - 1 { at(p) } else { total_max(h[p + 1], at(p)) };
    }
    for (i, o) in out.iter_mut().enumerate().take(n) {
        *o = total_max(h[i], g[i + 2 * w]);
    }
}

/// Maximum over the `(2w + 1) x (2w + 1)` window around every cell of an
/// `nx x ny` row-major grid.
pub fn window_max(grid: &[f32], nx: usize, ny: usize, w: usize) -> Vec<f32> {
    if grid.len() != nx * ny || nx == 0 || ny == 0 {
        return grid.to_vec();
    }
    let mut rows = vec![f32::NEG_INFINITY; nx * ny];
    rows.par_chunks_mut(nx).zip(grid.par_chunks(nx)).for_each(|(out, src)| window_max_1d(src, w, out));
    let cols: Vec<Vec<f32>> = (0..nx)
        .into_par_iter()
        .map(|i| {
            let src: Vec<f32> = (0..ny).map(|j| rows[j * nx + i]).collect();
            let mut out = vec![f32::NEG_INFINITY; ny];
            window_max_1d(&src, w, &mut out);
            out
        })
        .collect();
    let mut out = vec![f32::NEG_INFINITY; nx * ny];
    for (i, col) in cols.iter().enumerate() {
        for (j, v) in col.iter().enumerate() {
            out[j * nx + i] = *v;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #[test]
        fn equals_brute_force(
            nx in 1usize..20,
            ny in 1usize..20,
            // Windows past the grid's sides too, to the widest there is.
            w in prop_oneof![0usize..6, 18usize..40, Just(usize::MAX)],
            seed in any::<u64>(),
        ) {
            let mut s = seed;
            let grid: Vec<f32> = (0..nx * ny)
                .map(|_| {
                    s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
                    match s >> 60 {
                        0..=3 => f32::NEG_INFINITY,
                        4 => f32::NAN,
                        5 => -0.0,
                        6 => 0.0,
                        _ => ((s >> 40) & 0xfffff) as f32 / 1000.0 - 500.0,
                    }
                })
                .collect();
            let got = window_max(&grid, nx, ny, w);
            for j in 0..ny {
                for i in 0..nx {
                    // Naively, in the order of the window: NaN empty, +0 over -0.
                    let mut m = f32::NEG_INFINITY;
                    for jj in j.saturating_sub(w)..=j.saturating_add(w).min(ny - 1) {
                        for ii in i.saturating_sub(w)..=i.saturating_add(w).min(nx - 1) {
                            let v = grid[jj * nx + ii];
                            if !v.is_nan() && (v > m || (v == 0.0 && m == 0.0 && v.is_sign_positive())) {
                                m = v;
                            }
                        }
                    }
                    prop_assert_eq!(got[j * nx + i].to_bits(), m.to_bits());
                }
            }
        }
    }
}
