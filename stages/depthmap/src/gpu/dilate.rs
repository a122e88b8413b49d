//! The GPU twin of the grey-scale dilation ([`crate::dilate::window_max`]):
//! the largest value in the `(2w + 1) x (2w + 1)` window around every cell.
//!
//! Two passes, along rows and then along columns, one invocation per cell,
//! each reading its whole window (the CPU's van Herk scheme saves
//! comparisons; on a device the reads are the cost either way). Values are
//! compared as their IEEE total-order keys, NaN read as `-inf`, as the CPU
//! compares them: a maximum in total order is one bit pattern whatever the
//! order of comparisons, so the result is the CPU's bit for bit (the tests
//! compare them). What this must not do: round anything (it only compares).

use super::{Gpu, words_from_bytes, words_to_bytes};

pub(super) const SHADER: &str = concat!(include_str!("../common.wgsl"), include_str!("dilate.wgsl"));

impl Gpu {
    /// [`crate::dilate::window_max`] on the device: the same bits.
    ///
    /// Refused with an error (never a wrong answer) where the grid does not
    /// fit one buffer or a window is longer than the loops this device runs
    /// to their end ([`Gpu::loop_cap`]); the caller then uses the CPU.
    pub fn window_max(&self, grid: &[f32], nx: usize, ny: usize, w: usize) -> Result<Vec<f32>, String> {
        if grid.len() != nx * ny || nx == 0 || ny == 0 {
            return Ok(grid.to_vec());
        }
        let bytes = 4 * grid.len() as u64;
        if bytes > self.buffer_limit || grid.len() > u32::MAX as usize {
            return Err(format!(
                "a {nx} x {ny} grid takes {bytes} bytes, more than one GPU buffer holds ({} bytes)",
                self.buffer_limit
            ));
        }
        // Reads per invocation: at most the window, and no more than the grid.
        let reads = (2 * w as u64 + 1).min(nx.max(ny) as u64);
        if let Some(cap) = self.loop_cap.filter(|&cap| reads > cap as u64) {
            return Err(format!(
                "a window of {reads} cells is longer than the loops {} runs to their end ({cap})",
                self.name()
            ));
        }
        // A window wider than the grid covers no more of it; so w fits a u32.
        let w = w.min(nx.max(ny)) as u32;
        let words: Vec<u32> = grid.iter().map(|v| v.to_bits()).collect();
        let n = grid.len() as u32;
        liftplan_core::gpu::catching_errors(&self.dev, || {
            let usage = wgpu::BufferUsages::STORAGE;
            let src = self.upload("dilation grid", &words_to_bytes(&words), usage);
            let rows = self.storage("dilation rows", bytes);
            let out = self.storage("dilation", bytes);
            let params = |along_y: u32| {
                let p = [nx as u32, ny as u32, w, along_y];
                self.upload("dilation params", &words_to_bytes(&p), wgpu::BufferUsages::UNIFORM)
            };
            let (along_x, along_y) = (params(0), params(1));
            let mut enc = self.dev.device.create_command_encoder(&Default::default());
            self.pass(&mut enc, &self.window_max, &[(0, &along_x), (1, &src), (2, &rows)], n, super::GROUP);
            self.pass(&mut enc, &self.window_max, &[(0, &along_y), (1, &rows), (2, &out)], n, super::GROUP);
            self.submit(enc);
            let data = liftplan_core::gpu::read_back(&self.dev, &out, 0, bytes)?;
            Ok(words_from_bytes(&data).into_iter().map(f32::from_bits).collect())
        })
    }
}
