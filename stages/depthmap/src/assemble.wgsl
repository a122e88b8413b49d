// The depth-map assembly on the GPU: see the module doc of `gpu.rs`, which
// compiles this with the LARGE placeholder below replaced by its constant.

struct Params {
    n: u32,          // items of this dispatch: points, raws or cells
    nx: u32,
    row0: u32,       // first row of the slab
    rows: u32,       // rows in the slab
    inv_cell: f32,
    radius: f32,
    gap: f32,
    single: u32,
}
@group(0) @binding(0) var<uniform> P: Params;
@group(0) @binding(1) var<storage, read> pts: array<vec4<u32>>;
@group(0) @binding(2) var<storage, read> mesh: array<u32>;
@group(0) @binding(3) var<storage, read_write> tally: array<atomic<u32>>;
@group(0) @binding(4) var<storage, read_write> keys: array<vec4<u32>>;
@group(0) @binding(5) var<storage, read_write> data: array<u32>;
@group(0) @binding(6) var<storage, read_write> sums: array<u32>;
@group(0) @binding(7) var<storage, read> starts: array<u32>;
@group(0) @binding(8) var<storage, read_write> merged: array<u32>;
@group(0) @binding(9) var<storage, read_write> tops: array<u32>;
@group(0) @binding(10) var<storage, read_write> intervals: array<u32>;
@group(0) @binding(11) var<storage, read_write> large: array<u32>;

// GROUP, MAX_DIM, item, key_of and bits_of (mdm::f32_key and its inverse)
// come from common.wgsl.

// mdm::raster::floor_index: floor(x) clamped to [-1, 2^30] first, so a point
// far off the grid (a configured extent) converts the same way on both paths.
fn floor_index(x: f32) -> i32 {
    return i32(floor(min(max(x, -1.0), 1073741824.0)));
}

// The slab-local cells of a point: columns x..y, rows z..w (empty when y < x or w < z).
fn span(q: vec3<f32>) -> vec4<i32> {
    let i0 = max(floor_index((q.x - P.radius) * P.inv_cell), 0);
    let i1 = min(floor_index((q.x + P.radius) * P.inv_cell), i32(P.nx) - 1);
    let j0 = max(floor_index((q.y - P.radius) * P.inv_cell), i32(P.row0));
    let j1 = min(floor_index((q.y + P.radius) * P.inv_cell), i32(P.row0 + P.rows) - 1);
    return vec4<i32>(i0, i1, j0 - i32(P.row0), j1 - i32(P.row0));
}

// A triangle raw's slab-local cell, or 0xffffffff outside the slab.
fn mesh_cell(r: u32) -> u32 {
    let c = mesh[5u * r];
    let first = P.row0 * P.nx;
    if (c < first || c - first >= P.rows * P.nx) { return 0xffffffffu; }
    return c - first;
}

@compute @workgroup_size(256)
fn count_points(@builtin(global_invocation_id) g: vec3<u32>) {
    let p = item(g);
    if (p >= P.n) { return; }
    let s = span(bitcast<vec3<f32>>(pts[p].xyz));
    for (var j = s.z; j <= s.w; j++) {
        for (var i = s.x; i <= s.y; i++) {
            atomicAdd(&tally[u32(j) * P.nx + u32(i)], 1u);
        }
    }
}

@compute @workgroup_size(256)
fn count_mesh(@builtin(global_invocation_id) g: vec3<u32>) {
    let r = item(g);
    if (r >= P.n) { return; }
    let c = mesh_cell(r);
    if (c != 0xffffffffu) { atomicAdd(&tally[c], 1u); }
}

@compute @workgroup_size(256)
fn fill_points(@builtin(global_invocation_id) g: vec3<u32>) {
    let p = item(g);
    if (p >= P.n) { return; }
    let q = bitcast<vec3<f32>>(pts[p].xyz);
    let s = span(q);
    let k = vec4<u32>(pts[p].w, 0u, key_of(bitcast<u32>(q.z - P.radius)), key_of(bitcast<u32>(q.z + P.radius)));
    for (var j = s.z; j <= s.w; j++) {
        for (var i = s.x; i <= s.y; i++) {
            keys[atomicAdd(&tally[u32(j) * P.nx + u32(i)], 1u)] = k;
        }
    }
}

@compute @workgroup_size(256)
fn fill_mesh(@builtin(global_invocation_id) g: vec3<u32>) {
    let r = item(g);
    if (r >= P.n) { return; }
    let c = mesh_cell(r);
    if (c == 0xffffffffu) { return; }
    let b = 5u * r;
    let k = vec4<u32>(mesh[b + 3u], mesh[b + 4u], key_of(mesh[b + 1u]), key_of(mesh[b + 2u]));
    keys[atomicAdd(&tally[c], 1u)] = k;
}

// Sums that stop at 0xffffffff instead of wrapping, so an overfull slab shows.
fn add_sat(a: u32, b: u32) -> u32 {
    let s = a + b;
    if (s < a) { return 0xffffffffu; }
    return s;
}

var<workgroup> partial: array<u32, 256>;

// Exclusive prefix sum of each block of 256 of data[..n], in place; the
// block's total to sums[block].
@compute @workgroup_size(256)
fn scan_blocks(@builtin(workgroup_id) w: vec3<u32>, @builtin(local_invocation_id) l: vec3<u32>) {
    let b = w.x + w.y * MAX_DIM;
    let i = b * GROUP + l.x;
    var v = 0u;
    if (i < P.n) { v = data[i]; }
    partial[l.x] = v;
    workgroupBarrier();
    for (var off = 1u; off < GROUP; off = off * 2u) {
        var t = 0u;
        if (l.x >= off) { t = partial[l.x - off]; }
        workgroupBarrier();
        partial[l.x] = add_sat(partial[l.x], t);
        workgroupBarrier();
    }
    if (i < P.n) {
        var prior = 0u;
        if (l.x > 0u) { prior = partial[l.x - 1u]; }
        data[i] = prior;
    }
    if (l.x == GROUP - 1u && b * GROUP < P.n) { sums[b] = partial[GROUP - 1u]; }
}

// Adds each block's scanned total to its elements.
@compute @workgroup_size(256)
fn add_blocks(@builtin(global_invocation_id) g: vec3<u32>) {
    let i = item(g);
    if (i >= P.n) { return; }
    data[i] = add_sat(data[i], sums[i / GROUP]);
}

fn precedes(a: vec4<u32>, b: vec4<u32>) -> bool {
    if (a.x != b.x) { return a.x < b.x; }
    if (a.y != b.y) { return a.y < b.y; }
    if (a.z != b.z) { return a.z < b.z; }
    return a.w < b.w;
}

fn sift(base: u32, root: u32, n: u32) {
    var r = root;
    loop {
        let c = 2u * r + 1u;
        if (c >= n) { break; }
        var m = c;
        if (c + 1u < n && precedes(keys[base + c], keys[base + c + 1u])) { m = c + 1u; }
        let top = keys[base + r];
        let child = keys[base + m];
        if (!precedes(top, child)) { break; }
        keys[base + r] = child;
        keys[base + m] = top;
        r = m;
    }
}

fn sort_keys(base: u32, n: u32) {
    if (n <= 16u) {
        for (var i = 1u; i < n; i++) {
            let v = keys[base + i];
            var j = i;
            while (j > 0u && precedes(v, keys[base + j - 1u])) {
                keys[base + j] = keys[base + j - 1u];
                j--;
            }
            keys[base + j] = v;
        }
        return;
    }
    for (var s = n / 2u; s > 0u; s--) { sift(base, s - 1u, n); }
    for (var end = n - 1u; end > 0u; end--) {
        let t = keys[base];
        keys[base] = keys[base + end];
        keys[base + end] = t;
        sift(base, 0u, end);
    }
}

// `a > b` on the floats of two keys: the key order, except that -0 == +0.
fn above(a: u32, b: u32) -> bool {
    return a > b && ((bits_of(a) | bits_of(b)) & 0x7fffffffu) != 0u;
}

// `lo <= hi + gap` on the floats of two keys.
fn within_gap(lo: u32, hi: u32) -> bool {
    return bitcast<f32>(bits_of(lo)) <= bitcast<f32>(bits_of(hi)) + P.gap;
}

// A sorted cell's raw keys merged in place (mdm::merge_sorted) into
// [key(bottom), key(top), object, 0]; returns how many.
fn merge_run(base: u32, n: u32) -> u32 {
    if (n == 0u) { return 0u; }
    var m = 0u;
    var cur = keys[base];
    var hi = cur.w;
    for (var k = 1u; k < n; k++) {
        let e = keys[base + k];
        if (e.x == cur.x && e.y == cur.y && (cur.y != 0u || within_gap(e.z, hi))) {
            if (above(e.w, hi)) { hi = e.w; }
        } else {
            keys[base + m] = vec4<u32>(cur.z, hi, cur.x, 0u);
            m++;
            cur = e;
            hi = e.w;
        }
    }
    keys[base + m] = vec4<u32>(cur.z, hi, cur.x, 0u);
    return m + 1u;
}

// The end of pass 4 for cell c, its m merged intervals sorted: one kept in
// single-level mode, the count to merged[c] and the top's bits to tops[c].
fn finish(c: u32, base: u32, merged_n: u32) {
    var m = merged_n;
    if (P.single != 0u && m > 0u) {
        var top = keys[base];
        for (var k = 1u; k < m; k++) {
            let e = keys[base + k];
            if (e.y > top.y) { top = e; }
        }
        keys[base] = vec4<u32>(keys[base].x, top.y, top.z, 0u);
        m = 1u;
    }
    var highest = 0u;
    for (var k = 0u; k < m; k++) { highest = max(highest, keys[base + k].y); }
    merged[c] = m;
    if (m == 0u) { tops[c] = 0xff800000u; } else { tops[c] = bits_of(highest); }
}

// Cells with more raw keys than this are sorted by a whole workgroup
// (large_cells); the others by one invocation each (merge_cells).
const LARGE: u32 = {LARGE}u;

// Pass 4 for every cell of at most LARGE keys, one invocation each.
@compute @workgroup_size(64)
fn merge_cells(@builtin(global_invocation_id) g: vec3<u32>) {
    let c = g.x + g.y * MAX_DIM * 64u;
    if (c >= P.n) { return; }
    let base = starts[c];
    let n = starts[c + 1u] - base;
    if (n > LARGE) { return; }
    sort_keys(base, n);
    let m = merge_run(base, n);
    sort_keys(base, m);
    finish(c, base, m);
}

var<workgroup> group_most: atomic<u32>;
var<workgroup> group_large: atomic<u32>;
var<workgroup> large_at: u32;

// Lists the cells of more than LARGE keys (large[0..stats[0]]) and the
// largest count (stats[1]). Each workgroup gathers its own first and takes
// its places in the list with one atomic: every cell on the same two words
// would queue hundreds of thousands of atomics on them.
@compute @workgroup_size(256)
fn find_large(@builtin(global_invocation_id) g: vec3<u32>, @builtin(local_invocation_index) lane: u32) {
    if (lane == 0u) {
        atomicStore(&group_most, 0u);
        atomicStore(&group_large, 0u);
    }
    workgroupBarrier();
    let c = item(g);
    var n = 0u;
    if (c < P.n) { n = starts[c + 1u] - starts[c]; }
    atomicMax(&group_most, n);
    let is_large = n > LARGE;
    var slot = 0u;
    if (is_large) { slot = atomicAdd(&group_large, 1u); }
    workgroupBarrier();
    if (lane == 0u) {
        atomicMax(&tally[1], atomicLoad(&group_most));
        large_at = atomicAdd(&tally[0], atomicLoad(&group_large));
    }
    workgroupBarrier();
    if (is_large) { large[large_at + slot] = c; }
}

// keys[base + i] and keys[base + j] (i < j) in order.
fn order(i: u32, j: u32) {
    let a = keys[i];
    let b = keys[j];
    if (precedes(b, a)) {
        keys[i] = b;
        keys[j] = a;
    }
}

// A workgroup's bitonic sort of keys[base..base + n], n uniform: every
// comparator puts the smaller key first, so the network runs as if padded
// to a power of two with keys above all others, which never move.
fn sort_together(base: u32, n: u32, lane: u32) {
    var p = 1u;
    while (p < n) { p = p * 2u; }
    let pairs = p / 2u;
    for (var k = 2u; k <= p; k = k * 2u) {
        let half = k / 2u;
        for (var t = lane; t < pairs; t += GROUP) {
            let off = t % half;
            let i = (t / half) * k + off;
            let j = (t / half) * k + k - 1u - off;
            if (j < n) { order(base + i, base + j); }
        }
        storageBarrier();
        for (var d = k / 4u; d > 0u; d = d / 2u) {
            for (var t = lane; t < pairs; t += GROUP) {
                let i = (t / d) * 2u * d + t % d;
                if (i + d < n) { order(base + i, base + i + d); }
            }
            storageBarrier();
        }
    }
}

var<workgroup> cell_id: u32;
var<workgroup> cell_base: u32;
var<workgroup> cell_n: u32;
var<workgroup> cell_m: u32;

// Pass 4 for one listed cell of more than LARGE keys per workgroup: sorted
// together, merged by the first invocation, sorted together again, finished.
@compute @workgroup_size(256)
fn large_cells(@builtin(workgroup_id) w: vec3<u32>, @builtin(local_invocation_id) l: vec3<u32>) {
    let listed = w.x + w.y * MAX_DIM;
    if (l.x == 0u) {
        var c = 0xffffffffu;
        if (listed < P.n) { c = large[listed]; }
        cell_id = c;
        if (c != 0xffffffffu) {
            cell_base = starts[c];
            cell_n = starts[c + 1u] - starts[c];
        }
    }
    let c = workgroupUniformLoad(&cell_id);
    if (c == 0xffffffffu) { return; }
    let base = workgroupUniformLoad(&cell_base);
    let n = workgroupUniformLoad(&cell_n);
    sort_together(base, n, l.x);
    if (l.x == 0u) { cell_m = merge_run(base, n); }
    let m = workgroupUniformLoad(&cell_m);
    storageBarrier();
    sort_together(base, m, l.x);
    if (l.x == 0u) { finish(c, base, m); }
}

// How many loop iterations one invocation may run: Mesa's llvmpipe (lavapipe)
// silently leaves every loop of an invocation after 65535 in all, so the
// host checks its passes fit what this finds.
@compute @workgroup_size(1)
fn probe_loops() {
    var k = 0u;
    loop {
        if (k >= P.n) { break; }
        k = k + data[1] + 1u;
    }
    data[0] = k;
}

// Pass 5: each cell's merged intervals, [bottom, top, object] as f32 bits, to
// their place in intervals (merged[] is now their exclusive prefix sum).
@compute @workgroup_size(256)
fn compact(@builtin(global_invocation_id) g: vec3<u32>) {
    let c = item(g);
    if (c >= P.n) { return; }
    let src = starts[c];
    let dst = merged[c];
    let m = merged[c + 1u] - dst;
    for (var k = 0u; k < m; k++) {
        let e = keys[src + k];
        let o = 3u * (dst + k);
        intervals[o] = bits_of(e.x);
        intervals[o + 1u] = bits_of(e.y);
        intervals[o + 2u] = e.z;
    }
}
