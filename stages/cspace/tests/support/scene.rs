//! Random plant sites around a crane at the origin, shared by the C-space tests.

use liftplan_core::mesh::TriMesh;
use liftplan_depthmap::mdm::Mdm;

/// Towers, overhead beams, low clutter near the crane and pipe-rack tiers.
pub fn site(seed: u64) -> TriMesh {
    let mut mesh = TriMesh::default();
    let mut s = seed;
    let mut next = || {
        s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (s >> 11) as f64 / (1u64 << 53) as f64
    };
    for k in 0..40 {
        let g = mesh.group_id(&format!("B{k}"));
        let (r, a) = (4.0 + next() * 44.0, next() * std::f64::consts::TAU);
        let (cx, cy) = (r * a.cos(), r * a.sin());
        let (hx, hy) = (0.2 + next() * 2.0, 0.2 + next() * 2.0);
        let (bottom, top) = match k % 4 {
            0 => (0.0, 2.0 + next() * 35.0), // tower
            1 => {
                let b = 6.0 + next() * 25.0; // overhead beam
                (b, b + 0.5 + next() * 2.0)
            }
            2 => (0.0, 0.5 + next() * 5.0), // low clutter
            _ => (next() * 10.0, 12.0 + next() * 20.0),
        };
        if r < 9.0 && top > 3.0 {
            continue; // not on the crane's own body
        }
        mesh.add_box(g, [cx - hx, cy - hy, bottom], [cx + hx, cy + hy, top]);
    }
    // Pipe-rack tiers: thin decks stacked with gaps from 0.2 to 6 m, some
    // narrower than the boom grown by the clearance, some wider.
    for k in 0..8 {
        let (r, a) = (12.0 + next() * 34.0, next() * std::f64::consts::TAU);
        let (cx, cy) = (r * a.cos(), r * a.sin());
        let (hx, hy) = (0.5 + next() * 3.0, 0.5 + next() * 3.0);
        let mut z = 2.0 + next() * 10.0;
        for tier in 0..3 {
            let g = mesh.group_id(&format!("RACK{k}-{tier}"));
            let deck = 0.2 + next() * 0.8;
            mesh.add_box(g, [cx - hx, cy - hy, z], [cx + hx, cy + hy, z + deck]);
            z += deck + 0.2 + next() * 5.8;
        }
    }
    mesh
}

/// The depth map of a site and of ground points, at 0.5 m cells.
pub fn depth_map(mesh: TriMesh, ground: &[[f64; 3]]) -> Mdm {
    let inp = liftplan_depthmap::Inputs { points: ground.to_vec(), ground: vec![true; ground.len()], mesh };
    liftplan_depthmap::build_cpu(&inp, &liftplan_depthmap::Settings { cell_m: 0.5, ..Default::default() }).unwrap().0
}
