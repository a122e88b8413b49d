//! A static 3D k-d tree for nearest-neighbour queries with a distance bound:
//! ICP's correspondence search, where point density varies by orders of
//! magnitude between the area next to a scanner and 60 m away (a fixed-cell grid
//! is either too coarse near the scanner or too fine far from it).

pub struct KdTree {
    pts: Vec<[f64; 3]>,
    /// Point indices, arranged so each node's points are contiguous.
    idx: Vec<u32>,
    nodes: Vec<Node>,
}

#[derive(Clone, Copy)]
struct Node {
    /// For an inner node: split axis (0..3) and value; children at `left`, `left + 1`.
    axis: u8,
    split: f64,
    left: u32,
    /// Range of `idx` for a leaf (start, end); `left == u32::MAX` marks a leaf.
    start: u32,
    end: u32,
}

const LEAF: usize = 12;

impl KdTree {
    pub fn new(pts: &[[f64; 3]]) -> KdTree {
        let mut t = KdTree { pts: pts.to_vec(), idx: (0..pts.len() as u32).collect(), nodes: Vec::new() };
        if !pts.is_empty() {
            t.nodes.push(Node { axis: 0, split: 0.0, left: u32::MAX, start: 0, end: pts.len() as u32 });
            t.build(0);
        }
        t
    }

    fn build(&mut self, node: usize) {
        let Node { start, end, .. } = self.nodes[node];
        let (s, e) = (start as usize, end as usize);
        if e - s <= LEAF {
            return;
        }
        // Split the widest axis at the median.
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for &i in &self.idx[s..e] {
            let p = self.pts[i as usize];
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let axis = (0..3).max_by(|&a, &b| (hi[a] - lo[a]).total_cmp(&(hi[b] - lo[b]))).unwrap_or(0);
        if hi[axis] - lo[axis] <= 0.0 {
            return; // all points coincide: keep as a leaf
        }
        let mid = s + (e - s) / 2;
        let pts = &self.pts;
        self.idx[s..e].select_nth_unstable_by(mid - s, |&a, &b| {
            pts[a as usize][axis].total_cmp(&pts[b as usize][axis]).then(a.cmp(&b))
        });
        let split = self.pts[self.idx[mid] as usize][axis];
        let left = self.nodes.len() as u32;
        self.nodes.push(Node { axis: 0, split: 0.0, left: u32::MAX, start, end: mid as u32 });
        self.nodes.push(Node { axis: 0, split: 0.0, left: u32::MAX, start: mid as u32, end });
        self.nodes[node] = Node { axis: axis as u8, split, left, start, end };
        self.build(left as usize);
        self.build(left as usize + 1);
    }

    pub fn points(&self) -> &[[f64; 3]] {
        &self.pts
    }

    /// The nearest point within `max_radius`, as (index, squared distance); ties go
    /// to the lower index.
    pub fn nearest(&self, q: &[f64; 3], max_radius: f64) -> Option<(u32, f64)> {
        if self.nodes.is_empty() {
            return None;
        }
        let mut best: (u32, f64) = (u32::MAX, max_radius * max_radius);
        let mut stack: [(u32, f64); 64] = [(0, 0.0); 64];
        let mut top = 1;
        stack[0] = (0, 0.0);
        while top > 0 {
            top -= 1;
            let (ni, d2) = stack[top];
            if d2 > best.1 {
                continue;
            }
            let n = self.nodes[ni as usize];
            if n.left == u32::MAX {
                for &i in &self.idx[n.start as usize..n.end as usize] {
                    let p = self.pts[i as usize];
                    let d = (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2);
                    if d < best.1 || (d == best.1 && i < best.0) {
                        best = (i, d);
                    }
                }
                continue;
            }
            let diff = q[n.axis as usize] - n.split;
            let (near, far) = if diff < 0.0 { (n.left, n.left + 1) } else { (n.left + 1, n.left) };
            if top + 2 <= stack.len() {
                stack[top] = (far, diff * diff);
                stack[top + 1] = (near, 0.0);
                top += 2;
            }
        }
        (best.0 != u32::MAX).then_some(best)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_brute_force() {
        let pts: Vec<[f64; 3]> = (0..3000)
            .map(|i| {
                let t = i as f64;
                [(t * 0.37).sin() * 20.0 * (t * 0.001).cos(), (t * 0.71).cos() * 5.0, (t * 0.13).sin()]
            })
            .collect();
        let t = KdTree::new(&pts);
        for k in 0..200 {
            let q = [(k as f64 * 1.3).sin() * 22.0, (k as f64 * 0.7).cos() * 6.0, (k as f64).sin()];
            for r in [0.05, 0.5, 100.0] {
                let want = pts
                    .iter()
                    .enumerate()
                    .map(|(i, p)| (i as u32, (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)))
                    .filter(|x| x.1 <= r * r)
                    .min_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
                assert_eq!(t.nearest(&q, r), want);
            }
        }
    }
}
