//! The GPU twin of the picture renderer draws what the CPU rasteriser draws.
//!
//! Runs on every backend where wgpu finds an adapter (Mesa's lavapipe through
//! Vulkan and llvmpipe through OpenGL count, so CI exercises both); without
//! one it prints why and passes, since the CPU path is the one every machine
//! has and its own tests cover it.

use liftplan_core::image::Image;
use liftplan_docs::render::{Camera, PointBatch, Polyline, Projection, Scene, TriangleBatch, obb_batch, render_cpu};

fn scene() -> Scene {
    let ground = TriangleBatch {
        positions: vec![[-30.0, -30.0, 0.0], [30.0, -30.0, 0.0], [30.0, 30.0, 0.0], [-30.0, 30.0, 0.0]],
        triangles: vec![[0, 1, 2], [0, 2, 3]],
        color: [128, 128, 128],
    };
    let tank = obb_batch(
        &liftplan_core::obb::Obb::axis_aligned(
            nalgebra::Point3::new(-6.0, 4.0, 4.0),
            nalgebra::Vector3::new(3.0, 3.0, 4.0),
        ),
        [150, 160, 175],
    );
    let load = obb_batch(
        &liftplan_core::obb::Obb::axis_aligned(
            nalgebra::Point3::new(5.0, -3.0, 6.0),
            nalgebra::Vector3::new(2.0, 1.0, 1.0),
        ),
        [40, 110, 200],
    );
    // A ring of scan points of varying colour, some hidden behind the tank.
    let (mut positions, mut colors) = (vec![], vec![]);
    for i in 0..4000 {
        let a = i as f32 * 0.0157;
        let r = 10.0 + (i % 7) as f32;
        positions.push([r * a.cos(), r * a.sin(), 0.5 + (i % 13) as f32 * 0.3]);
        colors.push([(i % 251) as u8, (i * 7 % 253) as u8, 90]);
    }
    let points = PointBatch { positions, colors, color: [0; 3], size_px: 2.0 };
    let path: Vec<[f32; 3]> = (0..40)
        .map(|i| {
            let t = i as f32 / 39.0;
            [-12.0 + 20.0 * t, -8.0 + 10.0 * t, 3.0 + 8.0 * (t * 3.1).sin()]
        })
        .collect();
    Scene {
        triangles: vec![ground, tank, load],
        points: vec![points],
        lines: vec![
            Polyline { points: path.clone(), color: [230, 170, 180], width_px: 2.0, on_top: false },
            Polyline { points: path, color: [200, 30, 60], width_px: 3.5, on_top: true },
        ],
    }
}

fn compare(a: &Image, b: &Image) -> (f64, f64) {
    let (mut sum, mut far, n) = (0.0, 0usize, (a.width * a.height) as usize);
    for y in 0..a.height {
        for x in 0..a.width {
            let (p, q) = (a.get(x, y), b.get(x, y));
            let d = (0..3).map(|k| (p[k] as i32 - q[k] as i32).unsigned_abs()).max().unwrap_or(0);
            sum += (0..3).map(|k| (p[k] as f64 - q[k] as f64).abs()).sum::<f64>() / 3.0;
            if d > 24 {
                far += 1;
            }
        }
    }
    (sum / n as f64, far as f64 / n as f64)
}

#[test]
fn gpu_and_cpu_pictures_agree() {
    let devices = liftplan_docs::gpu::open_each_backend(true);
    if devices.is_empty() {
        eprintln!("SKIPPED: no GPU adapter for the twin test");
    }
    for (backend, opened) in devices {
        let g = opened.unwrap_or_else(|e| panic!("{backend:?} has an adapter, but: {e}"));
        check_pictures(&g);
    }
}

fn check_pictures(g: &liftplan_docs::gpu::GpuRenderer) {
    let s = scene();
    let (lo, hi) = s.bounds();
    let cams = [
        Camera::framing(lo, hi, -60.0, 30.0, 40.0, 4.0 / 3.0),
        Camera::top(lo, hi, 4.0 / 3.0),
        Camera {
            eye: [25.0, -25.0, 12.0],
            target: [0.0, 0.0, 3.0],
            up: [0.0, 0.0, 1.0],
            projection: Projection::Perspective { fov_y_deg: 55.0 },
            near: 1.0,
            far: 120.0,
        },
    ];
    for (i, cam) in cams.iter().enumerate() {
        for ss in [1, 2] {
            let cpu = render_cpu(&s, cam, 320, 240, ss);
            let gpu = g.render(&s, cam, 320, 240, ss).expect("GPU render");
            let (mean, far) = compare(&cpu, &gpu);
            eprintln!(
                "camera {i}, {ss}x{ss} samples on {}: mean difference {mean:.3}, pixels off by > 24: {:.3} %",
                g.name(),
                far * 100.0
            );
            // Edge samples may fall differently under the two rasterisers' rules;
            // nothing else may differ.
            assert!(mean < 0.5 && far < 0.005, "camera {i}, ss {ss}: mean {mean}, far {far}");
        }
    }
}
