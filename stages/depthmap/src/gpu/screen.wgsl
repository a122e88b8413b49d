// The GPU twin of the box queries: see the module doc of `gpu/screen.rs`,
// which prepares the boxes (grid-local f32, with outer and inner half sizes)
// and says why an answer this shader gives is the CPU's answer.

struct Params {
    n: u32,        // boxes of this dispatch
    nx: u32,
    ny: u32,
    budget: u32,   // loop iterations one invocation may run before it gives up
    cell: f32,
    margin: f32,   // how far inside a cell the inner test's lines stand (m)
    way: u32,      // clearances: DOWN or UP
    pad1: u32,
}
@group(0) @binding(0) var<uniform> P: Params;
// Per box, BOX_WORDS words (BOX_WORDS in screen.rs):
//  0..3  centre, left-out object (u32::MAX: none)
//  4..15 per axis k: its xyz and outer half size
// 16..19 the outer box's cells i0, i1, j0, j1 (inclusive)
// 20..21 the outer box's z range
// 22     the CPU walk's start level
// 23     inner radius
// 24..26 inner half sizes
// 27..30 the CPU walk's start tiles ti0, ti1, tj0, tj1 (inclusive)
// 31     UPRIGHT or 0
// 32     the height at or below which the left-out object's intervals are
//        left out (their top; f32::MAX: all of them)
@group(0) @binding(1) var<storage, read> boxes: array<u32>;
@group(0) @binding(2) var<storage, read> offsets: array<u32>;
// Per interval: bottom, top (f32 bits), object.
@group(0) @binding(3) var<storage, read> intervals: array<u32>;
// All pyramid levels, one after the other (empty cells hold -f32::MAX).
@group(0) @binding(4) var<storage, read> tops: array<f32>;
// Per level: first index in tops, width, height.
@group(0) @binding(5) var<storage, read> levels: array<vec4<u32>>;
// Per box: verdict, cell, interval.
@group(0) @binding(6) var<storage, read_write> verdict: array<vec4<u32>>;
// Clearances, per box: its heights as the CPU rounds them (for an upright
// box, the same over every column it reaches).
@group(0) @binding(7) var<storage, read> exact: array<vec2<f32>>;
// Clearances, per box, CLEAR_WORDS: verdict, n, n cells.
@group(0) @binding(8) var<storage, read_write> narrowed: array<u32>;

const MAX_DIM: u32 = 65535u;
const GROUP: u32 = 64u;
const FREE: u32 = 0u;
const HIT: u32 = 1u;
const GAVE_UP: u32 = 2u;
const STACK: u32 = 80u;
const EMPTY: vec2<f32> = vec2<f32>(1.0, -1.0);
// Word 31's flag for a box whose third axis is exactly up.
const UPRIGHT: u32 = 0x100u;
const BOX_WORDS: u32 = 33u;

fn word(b: u32, k: u32) -> f32 { return bitcast<f32>(boxes[BOX_WORDS * b + k]); }
fn centre(b: u32) -> vec3<f32> { return vec3<f32>(word(b, 0u), word(b, 1u), word(b, 2u)); }
fn axis(b: u32, k: u32) -> vec3<f32> { return vec3<f32>(word(b, 4u + 4u * k), word(b, 5u + 4u * k), word(b, 6u + 4u * k)); }

// A device may end loops silently after a number of iterations in all
// (Mesa's lavapipe: 65535), and a walk cut short would read as "free". So
// each walk counts its iterations against a budget (half such a cap), and,
// as the count cannot be exact (lavapipe runs eight invocations in
// lockstep on one count, counts the iteration in which a loop ends too, and
// once the cap is spent still runs each later loop once), every loop shows
// that it ended where it ends by itself: the start tiles all pushed, the
// walk with nothing left to walk (`done`), a cell's intervals at their end
// or past the box, the answer's cells all written. An answer goes out only
// then; a loop cut short ends anywhere else, and its box goes to the CPU.

// Outer: a range of heights that holds every height of the outer box over
// the column above [x0, x1] x [y0, y1], or EMPTY when that box stays out of
// the column. Each box axis k bounds a_k . (p - c) to [-h_k, h_k]; with
// (x, y) anywhere in the rectangle, the horizontal part of that product lies
// in [ulo, uhi], which leaves a_k.z (z - c.z) in [-h_k - uhi, h_k - ulo].
// Each axis alone is a relaxation of the box, so their intersection holds it.
fn outer_range(b: u32, x0: f32, x1: f32, y0: f32, y1: f32) -> vec2<f32> {
    let c = centre(b);
    let d = vec4<f32>(x0 - c.x, x1 - c.x, y0 - c.y, y1 - c.y);
    var r = vec2<f32>(word(b, 20u), word(b, 21u));
    r = outer_axis(axis(b, 0u), word(b, 7u), d, c.z, r);
    r = outer_axis(axis(b, 1u), word(b, 11u), d, c.z, r);
    r = outer_axis(axis(b, 2u), word(b, 15u), d, c.z, r);
    return r;
}

// The outer box's exact height range over the column above [x0, x1] x
// [y0, y1], intersected with `r` (a range already known to hold it), or
// EMPTY when the box stays out of the column; for a cell the walk cannot
// decide with `outer_range`, which relaxes the box axis by axis.
//
// By duality, not by its vertices, so that rounding can only widen it. A
// point of the box is c + sum_k s_k a_k with |s_k| <= h_k; over the column
// its x - c.x = sum_k s_k a_k.x lies in [dx0, dx1], and likewise y. For
// any multipliers (lx, ly) its height is therefore
//   z = c.z + lx (x - c.x) + ly (y - c.y) + sum_k s_k (a_k.z - lx a_k.x - ly a_k.y)
// and lies between c.z + min(lx dx) + min(ly dy) - sum_k h_k |g_k| and
// c.z + max(lx dx) + max(ly dy) + sum_k h_k |g_k|. Both bounds hold for
// every choice of (lx, ly), however it was computed, so only their own few
// roundings need room: `dual_bounds` widens them by 2^-19 of the sum of
// their terms' magnitudes, four times what those operations can err by.
// The bounds are piecewise linear in (lx, ly), bent on the lines g_k = 0,
// lx = 0 and ly = 0; linear programming duality makes their best values
// the exact range, reached where two of those lines cross: the origin, a
// face's slope (g_j = g_k = 0, so (lx, ly, -1) is along the third axis),
// and each g_k = 0 on an axis. A crossing that would divide by nearly zero
// is left out, which only loosens the range. If the bounds cross, no point
// of the box lies over the column (for one that did, every upper bound is
// at least its height and every lower bound at most).
//
// The f32 box as the host wrote it (centre, axes within rounding of unit
// and square, half sizes grown by the margin) holds the queried box over
// the cell: the margin absorbs the axes' rounding and the column's.
fn outer_exact(b: u32, x0: f32, x1: f32, y0: f32, y1: f32, r: vec2<f32>) -> vec2<f32> {
    let c = centre(b);
    let a0 = axis(b, 0u);
    let a1 = axis(b, 1u);
    let a2 = axis(b, 2u);
    let ax = vec3<f32>(a0.x, a1.x, a2.x);
    let ay = vec3<f32>(a0.y, a1.y, a2.y);
    let az = vec3<f32>(a0.z, a1.z, a2.z);
    let h = vec3<f32>(word(b, 7u), word(b, 11u), word(b, 15u));
    let d = vec4<f32>(x0 - c.x, x1 - c.x, y0 - c.y, y1 - c.y);
    var o = r;
    o = narrow(o, dual_bounds(vec2<f32>(0.0, 0.0), c.z, d, ax, ay, az, h));
    // Unrolled: no loop here, so no loop count a device could cut short.
    o = crossing_bounds(o, ax.x, ay.x, az.x, c.z, d, ax, ay, az, h);
    o = crossing_bounds(o, ax.y, ay.y, az.y, c.z, d, ax, ay, az, h);
    o = crossing_bounds(o, ax.z, ay.z, az.z, c.z, d, ax, ay, az, h);
    if (o.x > o.y) { return EMPTY; }
    return o;
}

// `o` narrowed by the bounds at the crossings that axis k = (kx, ky, kz)
// makes: its face's slope, and g_k = 0 on each axis of (lx, ly).
fn crossing_bounds(o: vec2<f32>, kx: f32, ky: f32, kz: f32, cz: f32, d: vec4<f32>, ax: vec3<f32>, ay: vec3<f32>, az: vec3<f32>, h: vec3<f32>) -> vec2<f32> {
    var r = o;
    if (abs(kz) > 1e-6) {
        r = narrow(r, dual_bounds(vec2<f32>(-kx / kz, -ky / kz), cz, d, ax, ay, az, h));
    }
    if (abs(kx) > 1e-6) {
        r = narrow(r, dual_bounds(vec2<f32>(kz / kx, 0.0), cz, d, ax, ay, az, h));
    }
    if (abs(ky) > 1e-6) {
        r = narrow(r, dual_bounds(vec2<f32>(0.0, kz / ky), cz, d, ax, ay, az, h));
    }
    return r;
}

// The two bounds of `outer_exact` for the multipliers `l`, widened by room
// for their rounding (and a little for a device that flushes tiny numbers).
fn dual_bounds(l: vec2<f32>, cz: f32, d: vec4<f32>, ax: vec3<f32>, ay: vec3<f32>, az: vec3<f32>, h: vec3<f32>) -> vec2<f32> {
    let sx = l.x * d.xy;
    let sy = l.y * d.zw;
    let lx = l.x * ax;
    let ly = l.y * ay;
    let spread = dot(h, abs(az - lx - ly));
    let up = cz + max(sx.x, sx.y) + max(sy.x, sy.y) + spread;
    let lo = cz + min(sx.x, sx.y) + min(sy.x, sy.y) - spread;
    let size = abs(cz) + max(abs(sx.x), abs(sx.y)) + max(abs(sy.x), abs(sy.y)) + dot(h, abs(az) + abs(lx) + abs(ly));
    let room = size * 1.9073486328125e-6 + 1e-30;
    return vec2<f32>(lo - room, up + room);
}

// The intersection of two height ranges that both hold the same heights.
fn narrow(r: vec2<f32>, s: vec2<f32>) -> vec2<f32> {
    return vec2<f32>(max(r.x, s.x), min(r.y, s.y));
}

// `r` cut by one axis' bound (a: the axis, h: its half size, d: the
// rectangle's sides relative to the centre, cz: the centre's height).
fn outer_axis(a: vec3<f32>, h: f32, d: vec4<f32>, cz: f32, r: vec2<f32>) -> vec2<f32> {
    let ulo = min(a.x * d.x, a.x * d.y) + min(a.y * d.z, a.y * d.w);
    let uhi = max(a.x * d.x, a.x * d.y) + max(a.y * d.z, a.y * d.w);
    let nlo = -h - uhi;
    let nhi = h - ulo;
    if (a.z == 0.0) {
        if (nlo > 0.0 || nhi < 0.0) { return EMPTY; }
        return r;
    }
    if (abs(a.z) < 1e-6) {
        // A nearly level axis bounds z only loosely; it is left out (fewer
        // constraints: still a relaxation) rather than divided by.
        return r;
    }
    var zl = nlo / a.z;
    var zh = nhi / a.z;
    if (a.z < 0.0) {
        let t = zl;
        zl = zh;
        zh = t;
    }
    return vec2<f32>(max(r.x, cz + zl), min(r.y, cz + zh));
}

// Inner: the heights of the inner box on the vertical line through (x, y),
// or EMPTY. The inner box lies inside the queried one, so these heights are
// heights of the queried box in any column the line stands in.
fn segment(b: u32, x: f32, y: f32) -> vec2<f32> {
    let c = centre(b);
    let d = vec2<f32>(x - c.x, y - c.y);
    let radius = word(b, 23u);
    var t = vec2<f32>(-radius, radius);
    t = segment_axis(axis(b, 0u), word(b, 24u), d, radius, t);
    t = segment_axis(axis(b, 1u), word(b, 25u), d, radius, t);
    t = segment_axis(axis(b, 2u), word(b, 26u), d, radius, t);
    if (t.x > t.y) { return EMPTY; }
    return vec2<f32>(c.z + t.x, c.z + t.y);
}

// The line's parameter range `t` cut by one axis' slab.
fn segment_axis(a: vec3<f32>, h: f32, d: vec2<f32>, radius: f32, t: vec2<f32>) -> vec2<f32> {
    let o = a.x * d.x + a.y * d.y;
    if (abs(a.z) < 1e-6) {
        // Level (or nearly): the line stays inside this slab over all of
        // [-radius, radius], or nothing is sure.
        if (abs(o) + abs(a.z) * radius > h) { return EMPTY; }
        return t;
    }
    let ta = (-h - o) / a.z;
    let tb = (h - o) / a.z;
    return vec2<f32>(max(t.x, min(ta, tb)), min(t.y, max(ta, tb)));
}

// The hull of two height ranges, either of which may be EMPTY.
fn hull(r: vec2<f32>, s: vec2<f32>) -> vec2<f32> {
    if (s.x > s.y) { return r; }
    if (r.x > r.y) { return s; }
    return vec2<f32>(min(r.x, s.x), max(r.y, s.y));
}

// Whether the interval [zlo, zhi] meets the height range r (not EMPTY).
fn meets(r: vec2<f32>, zlo: f32, zhi: f32) -> bool {
    return r.x <= r.y && zhi >= r.x && zlo <= r.y;
}

// Heights the queried box surely has over a cell: the inner box's height
// range over the column above the cell pulled in by the margin. That part
// of the inner box is convex, so its highest and lowest points are among its
// vertices: the inner segments on the column's four vertical edges, the
// box's corners inside the column, and where the box's edges cross the
// column's sides. Each is computed in `f32`, off by far less than the margin
// between the inner box and the queried one, and the cell by the margin
// between the pulled-in column and the cell, so each is a height the queried
// box has over the cell, and so is all between them. A point dropped (an
// edge nearly parallel to a side) only narrows the range.
fn inner_range(b: u32, x0: f32, x1: f32, y0: f32, y1: f32) -> vec2<f32> {
    if (P.margin < 0.0 || word(b, 23u) < 0.0) { return EMPTY; }
    let xa = x0 + P.margin;
    let xb = x1 - P.margin;
    let ya = y0 + P.margin;
    let yb = y1 - P.margin;
    if ((boxes[BOX_WORDS * b + 31u] & UPRIGHT) != 0u) {
        return upright_inner(b, xa, xb, ya, yb);
    }
    let q = vec4<f32>(xa, xb, ya, yb);
    var r = segment(b, xa, ya);
    r = hull(r, segment(b, xb, ya));
    r = hull(r, segment(b, xa, yb));
    r = hull(r, segment(b, xb, yb));
    let c = centre(b);
    let u = axis(b, 0u) * word(b, 24u);
    let v = axis(b, 1u) * word(b, 25u);
    let w = axis(b, 2u) * word(b, 26u);
    // The four edges along each axis, from their middles; their ends are
    // the box's corners.
    r = hull(r, edge(c + v + w, u, q));
    r = hull(r, edge(c + v - w, u, q));
    r = hull(r, edge(c - v + w, u, q));
    r = hull(r, edge(c - v - w, u, q));
    r = hull(r, edge(c + u + w, v, q));
    r = hull(r, edge(c + u - w, v, q));
    r = hull(r, edge(c - u + w, v, q));
    r = hull(r, edge(c - u - w, v, q));
    r = hull(r, edge(c + u + v, w, q));
    r = hull(r, edge(c + u - v, w, q));
    r = hull(r, edge(c - u + v, w, q));
    r = hull(r, edge(c - u - v, w, q));
    return r;
}

// The heights of the box edge m - e .. m + e where it lies in the column
// above q = (xa, xb, ya, yb): at its ends and where it crosses the sides.
fn edge(m: vec3<f32>, e: vec3<f32>, q: vec4<f32>) -> vec2<f32> {
    var r = corner(m - e, q);
    r = hull(r, corner(m + e, q));
    r = hull(r, crossing(m, e, q.x, q.zw));
    r = hull(r, crossing(m, e, q.y, q.zw));
    r = hull(r, crossing(m.yxz, e.yxz, q.z, q.xy));
    r = hull(r, crossing(m.yxz, e.yxz, q.w, q.xy));
    return r;
}

fn corner(p: vec3<f32>, q: vec4<f32>) -> vec2<f32> {
    if (p.x < q.x || p.x > q.y || p.y < q.z || p.y > q.w) { return EMPTY; }
    return vec2<f32>(p.z, p.z);
}

// Where the edge m + s e, s in [-1, 1], crosses x = side with y in span.
fn crossing(m: vec3<f32>, e: vec3<f32>, side: f32, span: vec2<f32>) -> vec2<f32> {
    if (abs(e.x) < 1e-6) { return EMPTY; }
    let s = (side - m.x) / e.x;
    if (abs(s) > 1.0) { return EMPTY; }
    let y = m.y + s * e.y;
    if (y < span.x || y > span.y) { return EMPTY; }
    let z = m.z + s * e.z;
    return vec2<f32>(z, z);
}

// An upright box (turned about z only) has the same heights over every
// column it reaches, so the inner box's heights are sure wherever its
// footprint meets the (pulled-in) cell: a 2D separating-axis test of two
// rectangles, exact with their four axes. Only for a box with an inner box
// (`inner_range` checks).
fn upright_inner(b: u32, xa: f32, xb: f32, ya: f32, yb: f32) -> vec2<f32> {
    let c = centre(b);
    let u = axis(b, 0u).xy;
    let v = axis(b, 1u).xy;
    let hu = word(b, 24u);
    let hv = word(b, 25u);
    let e = vec2<f32>(0.5 * (xb - xa), 0.5 * (yb - ya));
    let d = vec2<f32>(0.5 * (xa + xb) - c.x, 0.5 * (ya + yb) - c.y);
    let apart = abs(d.x) > e.x + hu * abs(u.x) + hv * abs(v.x)
        || abs(d.y) > e.y + hu * abs(u.y) + hv * abs(v.y)
        || abs(dot(d, u)) > hu + e.x * abs(u.x) + e.y * abs(u.y)
        || abs(dot(d, v)) > hv + e.x * abs(v.x) + e.y * abs(v.y);
    if (apart) { return EMPTY; }
    return vec2<f32>(c.z - word(b, 26u), c.z + word(b, 26u));
}

// What a box's walk needs of its words (see the layout at the top).
struct Walk {
    left_obj: u32,
    left_to: f32,
    i0: u32, i1: u32, j0: u32, j1: u32,
    start: u32,
    ti0: u32, ti1: u32, tj0: u32, tj1: u32,
}

fn walk_of(b: u32) -> Walk {
    let o = BOX_WORDS * b;
    return Walk(
        boxes[o + 3u], word(b, 32u),
        boxes[o + 16u], boxes[o + 17u], boxes[o + 18u], boxes[o + 19u],
        boxes[o + 22u],
        boxes[o + 27u], boxes[o + 28u], boxes[o + 29u], boxes[o + 30u],
    );
}

// Whether interval `k`, whose top is `zhi`, is left out of box's walk `w`:
// the CPU's `LeaveOut::counts`, negated.
fn left_out(w: Walk, k: u32, zhi: f32) -> bool {
    return intervals[3u * k + 2u] == w.left_obj && zhi <= w.left_to;
}

@compute @workgroup_size(64)
fn screen_boxes(@builtin(global_invocation_id) g: vec3<u32>) {
    let b = g.x + g.y * MAX_DIM * GROUP;
    if (b >= P.n) { return; }
    let w = walk_of(b);
    verdict[b] = vec4<u32>(GAVE_UP, 0u, 0u, 0u);
    // The CPU's walk (`Mdm::hit_where`): its start tiles row by row, each
    // tile's four children in the order (0,0), (1,0), (0,1), (1,1), so the
    // first contact found is the CPU's. The stack is filled in reverse.
    var stack: array<vec3<u32>, STACK>;
    var sp = 0u;
    let starts = (w.ti1 - w.ti0 + 1u) * (w.tj1 - w.tj0 + 1u);
    if (starts > 16u) { return; }
    var steps = 0u;
    for (var tj = w.tj1 + 1u; tj > w.tj0; tj--) {
        steps++;
        for (var ti = w.ti1 + 1u; ti > w.ti0; ti--) {
            steps++;
            stack[sp] = vec3<u32>(w.start, ti - 1u, tj - 1u);
            sp++;
        }
    }
    if (sp != starts) { return; }
    var done = false;
    loop {
        if (sp == 0u) {
            done = true;
            break;
        }
        steps++;
        if (steps > P.budget) { return; }
        sp--;
        let t = stack[sp];
        let lvl = t.x;
        // The tile's cells, cut to the outer box's (no others can be met).
        let ci0 = max(t.y << lvl, w.i0);
        let ci1 = min(((t.y + 1u) << lvl) - 1u, w.i1);
        let cj0 = max(t.z << lvl, w.j0);
        let cj1 = min(((t.z + 1u) << lvl) - 1u, w.j1);
        if (ci0 > ci1 || cj0 > cj1) { continue; }
        let info = levels[lvl];
        let top = tops[info.x + t.z * info.y + t.y];
        let x0 = f32(ci0) * P.cell;
        let x1 = f32(ci1 + 1u) * P.cell;
        let y0 = f32(cj0) * P.cell;
        let y1 = f32(cj1 + 1u) * P.cell;
        let r = outer_range(b, x0, x1, y0, y1);
        if (r.x > r.y || top < r.x) { continue; }
        if (lvl == 0u) {
            let cell = t.z * P.nx + t.y;
            var r = r;
            var inner = EMPTY;
            var inner_done = false;
            let end = offsets[cell + 1u];
            var k = offsets[cell];
            var higher = false;
            for (; k < end; k++) {
                steps++;
                if (steps > P.budget) { return; }
                let zlo = bitcast<f32>(intervals[3u * k]);
                if (zlo > r.y) {
                    higher = true;
                    break;
                }
                let zhi = bitcast<f32>(intervals[3u * k + 1u]);
                if (zhi < r.x || left_out(w, k, zhi)) { continue; }
                // It may meet the box: a hit if it meets what the box surely
                // has over the cell, else the CPU's exact test must decide.
                if (!inner_done) {
                    inner = inner_range(b, x0, x1, y0, y1);
                    inner_done = true;
                    if (!meets(inner, zlo, zhi)) {
                        // Undecided: once per cell, the exact outer range.
                        r = outer_exact(b, x0, x1, y0, y1, r);
                        if (zlo > r.y) {
                            higher = true;
                            break;
                        }
                        if (zhi < r.x) { continue; }
                    }
                }
                if (meets(inner, zlo, zhi)) {
                    verdict[b] = vec4<u32>(HIT, cell, k, 0u);
                }
                return;
            }
            // The cell's loop ended by itself: past its last interval, or at
            // one above the box (the rest are higher still).
            if (k < end && !higher) { return; }
            continue;
        }
        if (sp + 4u > STACK) { return; }
        stack[sp] = vec3<u32>(lvl - 1u, 2u * t.y + 1u, 2u * t.z + 1u);
        stack[sp + 1u] = vec3<u32>(lvl - 1u, 2u * t.y, 2u * t.z + 1u);
        stack[sp + 2u] = vec3<u32>(lvl - 1u, 2u * t.y + 1u, 2u * t.z);
        stack[sp + 3u] = vec3<u32>(lvl - 1u, 2u * t.y, 2u * t.z);
        sp += 4u;
    }
    // A device that cuts loops short (see the top of this file) ends this
    // loop without `done`: the walk is not finished, and the box goes to
    // the CPU.
    if (!done) { return; }
    verdict[b] = vec4<u32>(FREE, 0u, 0u, 0u);
}

// The clearance twin (`Gpu::clearances_where`): how far a box can move
// straight down or up before it meets the map (`Mdm::clearance_where`).
//
// The CPU's gap in a cell is an `f32` subtraction from the box's exact
// height range over the cell's column, which the device cannot compute. It
// can bound it: from below with the outer range (and a slack for the
// rounding of the subtractions, on either path), from above with the inner
// range, where that surely holds an interval. For an upright box the range
// is the CPU's own (`exact`), so the gap is exact where the box surely
// reaches the cell. The walk keeps the least upper bound U found so far,
// with its cell, and the cells whose lower bound L is not beyond it in the
// CPU's order (smaller gap, then lower cell index): L < U, or L = U and the
// cell comes first. Every other cell's gap is larger than the gap of U's
// cell, or equal and later, so the CPU's answer is in one of the cells
// kept, which it then measures exactly. Too many undecided cells, or a walk
// over its budget: the CPU answers the box.

const DOWN: u32 = 0u;
const CLEAR_WORDS: u32 = 12u;
const CELLS: u32 = 10u;
const NOTHING: u32 = 0u;
const NARROWED: u32 = 1u;
// Above every gap the walk can meet (the host keeps heights under 1e30 m).
const NO_BOUND: f32 = 3.0e38;
// Empty tiles hold -f32::MAX; no height comes near it.
const EMPTY_TOP: f32 = -1.0e38;

// Room for the rounding of one `f32` subtraction of `a` and `b` on the
// device and one on the CPU: each errs by at most 2^-24 of the operands
// (a few ulps on the device); this is 2^-20 of them.
fn slack(a: f32, b: f32) -> f32 {
    return (abs(a) + abs(b)) * 9.5367431640625e-7;
}

// Whether a cell of lower bound `l` at index `cell` may still hold the
// answer, against the best upper bound `u` at `u_cell`.
fn in_the_running(l: f32, cell: u32, u: f32, u_cell: u32) -> bool {
    return l < u || (l == u && cell <= u_cell);
}

@compute @workgroup_size(64)
fn clear_boxes(@builtin(global_invocation_id) g: vec3<u32>) {
    let b = g.x + g.y * MAX_DIM * GROUP;
    if (b >= P.n) { return; }
    let slot = CLEAR_WORDS * b;
    narrowed[slot] = GAVE_UP;
    let down = P.way == DOWN;
    let upright = (boxes[BOX_WORDS * b + 31u] & UPRIGHT) != 0u;
    let e = exact[b];
    // An upright box's heights are the CPU's own (`e`, the same over every
    // column it reaches): its gaps need no slack (rounding is monotone, and
    // x - 0 is x), a turned box's bounds do.
    var loose = 1.0;
    if (upright) { loose = 0.0; }
    let w = walk_of(b);
    // The CPU walk's start tiles, as in screen_boxes (the order does not
    // matter here, only which cells are walked). This start and the tile
    // step repeat screen_boxes' on purpose: as functions taking the stack by
    // pointer they doubled the twin tests' time on llvmpipe (naga's GLSL
    // passes the array by copy).
    var stack: array<vec3<u32>, STACK>;
    var sp = 0u;
    let starts = (w.ti1 - w.ti0 + 1u) * (w.tj1 - w.tj0 + 1u);
    if (starts > 16u) { return; }
    var steps = 0u;
    for (var tj = w.tj1 + 1u; tj > w.tj0; tj--) {
        steps++;
        for (var ti = w.ti1 + 1u; ti > w.ti0; ti--) {
            steps++;
            stack[sp] = vec3<u32>(w.start, ti - 1u, tj - 1u);
            sp++;
        }
    }
    if (sp != starts) { return; }
    var best_u = NO_BOUND;
    var best_cell = 0xffffffffu;
    var kept: array<u32, CELLS>;
    var kept_l: array<f32, CELLS>;
    var n = 0u;
    var done = false;
    loop {
        if (sp == 0u) {
            done = true;
            break;
        }
        steps++;
        if (steps > P.budget) { return; }
        sp--;
        let t = stack[sp];
        let lvl = t.x;
        let ci0 = max(t.y << lvl, w.i0);
        let ci1 = min(((t.y + 1u) << lvl) - 1u, w.i1);
        let cj0 = max(t.z << lvl, w.j0);
        let cj1 = min(((t.z + 1u) << lvl) - 1u, w.j1);
        if (ci0 > ci1 || cj0 > cj1) { continue; }
        let info = levels[lvl];
        let top = tops[info.x + t.z * info.y + t.y];
        if (top < EMPTY_TOP) { continue; }
        let x0 = f32(ci0) * P.cell;
        let x1 = f32(ci1 + 1u) * P.cell;
        let y0 = f32(cj0) * P.cell;
        let y1 = f32(cj1 + 1u) * P.cell;
        let r = outer_range(b, x0, x1, y0, y1);
        if (r.x > r.y) { continue; }
        if (down) {
            // Every gap in the tile is at least its lowest box height less
            // its top.
            var lo = r.x;
            if (upright) { lo = e.x; }
            let l = (lo - top) - loose * slack(lo, top);
            if (!in_the_running(l, cj0 * P.nx + ci0, best_u, best_cell)) { continue; }
        } else if (top < r.x) {
            // Nothing in the tile reaches the box's bottom.
            continue;
        }
        if (lvl > 0u) {
            if (sp + 4u > STACK) { return; }
            stack[sp] = vec3<u32>(lvl - 1u, 2u * t.y + 1u, 2u * t.z + 1u);
            stack[sp + 1u] = vec3<u32>(lvl - 1u, 2u * t.y, 2u * t.z + 1u);
            stack[sp + 2u] = vec3<u32>(lvl - 1u, 2u * t.y + 1u, 2u * t.z);
            stack[sp + 3u] = vec3<u32>(lvl - 1u, 2u * t.y, 2u * t.z);
            sp += 4u;
            continue;
        }
        // A cell: the box's heights over it, outer (all it may have there,
        // exact up to rounding) and inner (what it surely has there, or
        // EMPTY). An upright box has its exact heights, or none, over it.
        let cell = t.z * P.nx + t.y;
        var o = e;
        var inner = inner_range(b, x0, x1, y0, y1);
        if (upright) {
            if (inner.x <= inner.y) { inner = e; }
        } else {
            o = outer_exact(b, x0, x1, y0, y1, r);
            if (o.x > o.y) { continue; }
        }
        let sure = inner.x <= inner.y;
        var l_cell = NO_BOUND;
        var u_cell = NO_BOUND;
        let end = offsets[cell + 1u];
        var k = offsets[cell];
        var higher = false;
        for (; k < end; k++) {
            steps++;
            if (steps > P.budget) { return; }
            let zlo = bitcast<f32>(intervals[3u * k]);
            let zhi = bitcast<f32>(intervals[3u * k + 1u]);
            if (down && zlo > o.y) {
                higher = true;
                break;
            }
            if (left_out(w, k, zhi)) { continue; }
            // Down, the box meets the interval if it starts no higher than
            // the box's top, when the box's bottom reaches its top; up,
            // symmetrically. Surely met: it lies that way of what the box
            // surely has.
            if (down) {
                l_cell = min(l_cell, (o.x - zhi) - loose * slack(o.x, zhi));
                if (sure && zlo <= inner.y) {
                    u_cell = min(u_cell, (inner.x - zhi) + loose * slack(inner.x, zhi));
                }
            } else {
                if (zhi < o.x) { continue; }
                l_cell = min(l_cell, (zlo - o.y) - loose * slack(zlo, o.y));
                if (sure && zhi >= inner.x) {
                    u_cell = min(u_cell, (zlo - inner.y) + loose * slack(zlo, inner.y));
                }
            }
        }
        if (k < end && !higher) { return; }
        if (l_cell == NO_BOUND) { continue; }
        if (u_cell < NO_BOUND && (u_cell < best_u || (u_cell == best_u && cell < best_cell))) {
            best_u = u_cell;
            best_cell = cell;
            // keep_running's loop counts against the budget too.
            steps += n;
            n = keep_running(&kept, &kept_l, n, best_u, best_cell);
            if (n > CELLS) { return; }
        }
        if (!in_the_running(l_cell, cell, best_u, best_cell)) { continue; }
        if (n == CELLS) { return; }
        kept[n] = cell;
        kept_l[n] = l_cell;
        n++;
    }
    if (!done) { return; }
    // Every cell with an interval that way was kept, or lost to the cell of
    // the least upper bound, which is kept: none kept, no such cell.
    if (n == 0u) {
        narrowed[slot] = NOTHING;
        return;
    }
    narrowed[slot + 1u] = n;
    var written = 0u;
    for (; written < n; written++) {
        narrowed[slot + 2u + written] = kept[written];
    }
    // This loop too may be cut short (the eight invocations' other walks
    // count against the same cap): the cells go out only when all did.
    if (written == n) { narrowed[slot] = NARROWED; }
}

// Drops the kept cells that can no longer hold the answer; returns how
// many are left (packed at the front), or more than CELLS where its loop
// was cut short.
fn keep_running(
    kept: ptr<function, array<u32, CELLS>>,
    kept_l: ptr<function, array<f32, CELLS>>,
    n: u32,
    u: f32,
    u_cell: u32,
) -> u32 {
    var m = 0u;
    var k = 0u;
    for (; k < n; k++) {
        if (in_the_running((*kept_l)[k], (*kept)[k], u, u_cell)) {
            (*kept)[m] = (*kept)[k];
            (*kept_l)[m] = (*kept_l)[k];
            m++;
        }
    }
    if (k < n) { return CELLS + 1u; }
    return m;
}
