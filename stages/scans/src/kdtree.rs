//! A static 3D k-d tree for nearest-neighbour queries with a distance bound:
//! ICP's correspondence search, where point density varies by orders of
//! magnitude between the area next to a scanner and 60 m away (a fixed-cell grid
//! is either too coarse near the scanner or too fine far from it).
//!
//! Registration spends most of its time here (half of a survey's, measured),
//! so the tree keeps its points in its own order, each leaf's points side by
//! side in memory, and skips a node whose box lies farther from the query
//! than the nearest point found so far. Its answers are exact and must not
//! depend on how the tree is laid out: the nearest point, ties to the lower
//! index of the points it was built from.

pub struct KdTree {
    /// The points in the tree's order: each node's points are contiguous.
    ordered: Vec<[f64; 3]>,
    /// Each of `ordered`'s index in the points the tree was built from.
    ids: Vec<u32>,
    nodes: Vec<Node>,
}

#[derive(Clone, Copy)]
struct Node {
    /// The box of the node's points.
    lo: [f64; 3],
    hi: [f64; 3],
    /// Children at `left` and `left + 1`; `u32::MAX` marks a leaf.
    left: u32,
    /// The node's range of `ordered`.
    start: u32,
    end: u32,
}

const LEAF: usize = 12;

impl KdTree {
    pub fn new(pts: &[[f64; 3]]) -> KdTree {
        let mut idx: Vec<u32> = (0..pts.len() as u32).collect();
        let mut nodes = Vec::new();
        if !pts.is_empty() {
            nodes.push(Node { lo: [0.0; 3], hi: [0.0; 3], left: u32::MAX, start: 0, end: pts.len() as u32 });
            build(pts, &mut idx, &mut nodes, 0);
        }
        let ordered = idx.iter().map(|&i| pts[i as usize]).collect();
        KdTree { ordered, ids: idx, nodes }
    }

    /// The nearest point within `max_radius`, as (index, squared distance); ties go
    /// to the lower index.
    pub fn nearest(&self, q: &[f64; 3], max_radius: f64) -> Option<(u32, f64)> {
        self.nearest_from(q, max_radius, None)
    }

    /// [`KdTree::nearest`], the search started from a point known to be
    /// near (`hint`: its index and [`distance2`] from `q`, as ICP has it
    /// from its last step): the same answer, with fewer nodes visited. A
    /// hint beyond `max_radius` is not used.
    pub fn nearest_from(&self, q: &[f64; 3], max_radius: f64, hint: Option<(u32, f64)>) -> Option<(u32, f64)> {
        if self.nodes.is_empty() {
            return None;
        }
        let r2 = max_radius * max_radius;
        let mut best: (u32, f64) = match hint {
            Some((i, d)) if d <= r2 => (i, d),
            _ => (u32::MAX, r2),
        };
        // Nodes to visit with a lower bound of their points' squared
        // distances; the nearer child is visited first. The stack holds at
        // most one entry per level and the tree's depth is under 40 for
        // 2^32 points.
        let mut stack: [(u32, f64); 64] = [(0, 0.0); 64];
        let mut top = 1;
        stack[0] = (0, box_distance2(&self.nodes[0], q));
        while top > 0 {
            top -= 1;
            let (ni, bound) = stack[top];
            // Not `>=`: a node as far as the best may hold a tie of lower index.
            if bound > best.1 {
                continue;
            }
            let n = &self.nodes[ni as usize];
            if n.left == u32::MAX {
                let range = n.start as usize..n.end as usize;
                for (p, &i) in self.ordered[range.clone()].iter().zip(&self.ids[range]) {
                    let d = distance2(p, q);
                    if d < best.1 || (d == best.1 && i < best.0) {
                        best = (i, d);
                    }
                }
                continue;
            }
            let (a, b) = (n.left, n.left + 1);
            let (da, db) = (box_distance2(&self.nodes[a as usize], q), box_distance2(&self.nodes[b as usize], q));
            let ((near, dn), (far, df)) = if da <= db { ((a, da), (b, db)) } else { ((b, db), (a, da)) };
            if top + 2 <= stack.len() {
                stack[top] = (far, df);
                stack[top + 1] = (near, dn);
                top += 2;
            }
        }
        (best.0 != u32::MAX).then_some(best)
    }
}

/// The squared distance between two points, summed in the order every
/// caller's bound must follow (see [`box_distance2`]); a hint to
/// [`KdTree::nearest_from`] must be measured with it.
#[inline]
pub fn distance2(p: &[f64; 3], q: &[f64; 3]) -> f64 {
    (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)
}

/// The squared distance from `q` to a node's box: in floating point never more
/// than [`distance2`] gives for a point in the box, since each rounded step
/// (difference, square, sum in the same order) keeps the order of its
/// operands, and a point's difference along each axis is at least the box's.
#[inline]
fn box_distance2(n: &Node, q: &[f64; 3]) -> f64 {
    let gap = |k: usize| {
        if q[k] < n.lo[k] {
            n.lo[k] - q[k]
        } else if q[k] > n.hi[k] {
            q[k] - n.hi[k]
        } else {
            0.0
        }
    };
    gap(0).powi(2) + gap(1).powi(2) + gap(2).powi(2)
}

/// Splits `nodes[node]` (its range of `idx`) at the median of its box's widest
/// axis until a node holds no more than [`LEAF`] points, or its points
/// coincide; sets every node's box.
fn build(pts: &[[f64; 3]], idx: &mut [u32], nodes: &mut Vec<Node>, node: usize) {
    let Node { start, end, .. } = nodes[node];
    let (s, e) = (start as usize, end as usize);
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for &i in &idx[s..e] {
        let p = pts[i as usize];
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    nodes[node].lo = lo;
    nodes[node].hi = hi;
    if e - s <= LEAF {
        return;
    }
    let axis = (0..3).max_by(|&a, &b| (hi[a] - lo[a]).total_cmp(&(hi[b] - lo[b]))).unwrap_or(0);
    if hi[axis] - lo[axis] <= 0.0 {
        return; // all points coincide: keep as a leaf
    }
    let mid = s + (e - s) / 2;
    idx[s..e].select_nth_unstable_by(mid - s, |&a, &b| {
        pts[a as usize][axis].total_cmp(&pts[b as usize][axis]).then(a.cmp(&b))
    });
    let left = nodes.len() as u32;
    nodes.push(Node { lo, hi, left: u32::MAX, start, end: mid as u32 });
    nodes.push(Node { lo, hi, left: u32::MAX, start: mid as u32, end });
    nodes[node].left = left;
    build(pts, idx, nodes, left as usize);
    build(pts, idx, nodes, left as usize + 1);
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

    /// Ties (points repeated, or at one distance on a lattice) go to the lower
    /// index whatever leaf the tree puts them in, and a point exactly at the
    /// radius counts: registration's answers must not depend on the tree's
    /// layout.
    #[test]
    fn ties_go_to_the_lower_index_and_the_radius_is_inclusive() {
        let mut pts: Vec<[f64; 3]> = Vec::new();
        for x in 0..12 {
            for y in 0..12 {
                for z in 0..3 {
                    pts.push([x as f64 * 0.5, y as f64 * 0.5, z as f64 * 0.5]);
                }
            }
        }
        // The lattice again, in reverse, and a cluster of one point many times.
        let again: Vec<[f64; 3]> = pts.iter().rev().copied().collect();
        pts.extend(again);
        pts.extend(std::iter::repeat_n([2.0, 2.0, 0.5], 40));
        let t = KdTree::new(&pts);
        let brute = |q: &[f64; 3], r: f64| {
            pts.iter()
                .enumerate()
                .map(|(i, p)| (i as u32, (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)))
                .filter(|x| x.1 <= r * r)
                .min_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)))
        };
        let mut ties = 0;
        for k in 0..400 {
            // Queries on the lattice, half-way between its points and off it.
            let q = [(k % 23) as f64 * 0.25, (k / 23 % 23) as f64 * 0.25, (k % 5) as f64 * 0.25];
            for r in [0.0, 0.25, 0.5, 0.6, 3.0] {
                let want = brute(&q, r);
                assert_eq!(t.nearest(&q, r), want, "query {q:?} within {r}");
                if let Some((i, d)) = want {
                    let tied = pts
                        .iter()
                        .filter(|p| (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2) == d)
                        .count();
                    ties += usize::from(tied > 1 && (i as usize) < pts.len());
                }
            }
        }
        assert!(ties > 500, "the queries must meet ties: {ties}");
        // Started from any point, near or not, within the radius or not, the
        // search gives the same answer.
        for k in 0..400 {
            let q = [(k % 23) as f64 * 0.25, (k / 23 % 23) as f64 * 0.25, (k % 5) as f64 * 0.25];
            for r in [0.0, 0.25, 0.5, 0.6, 3.0] {
                for h in [0, k % pts.len(), pts.len() - 1, pts.len() - 41] {
                    let hint = Some((h as u32, distance2(&pts[h], &q)));
                    assert_eq!(t.nearest_from(&q, r, hint), brute(&q, r), "query {q:?} within {r} from {h}");
                }
            }
        }
        // At exactly the radius: the lattice's neighbour 0.5 m away.
        assert_eq!(t.nearest(&[0.0, 0.0, 0.25], 0.25), Some((0, 0.0625)));
        assert_eq!(KdTree::new(&[]).nearest(&[0.0; 3], 10.0), None);
    }
}
