// The GPU twin of dilate::window_max: see the module doc of `gpu/dilate.rs`.

struct Params {
    nx: u32,
    ny: u32,
    w: u32,
    // 0: the window runs along a row (x), 1: along a column (y).
    along_y: u32,
}
@group(0) @binding(0) var<uniform> P: Params;
@group(0) @binding(1) var<storage, read> src: array<u32>;
@group(0) @binding(2) var<storage, read_write> dst: array<u32>;

const NEG_INF: u32 = 0xff800000u;

// item, key_of and bits_of (IEEE total order as an unsigned order) come from
// common.wgsl.

// NaN counts as empty.
fn canonical(bits: u32) -> u32 {
    if ((bits & 0x7fffffffu) > 0x7f800000u) { return NEG_INF; }
    return bits;
}

// One output cell: the largest of its window along one axis, in total order.
@compute @workgroup_size(256)
fn window_max(@builtin(global_invocation_id) g: vec3<u32>) {
    let c = item(g);
    if (c >= P.nx * P.ny) { return; }
    let i = c % P.nx;
    let j = c / P.nx;
    var at = i;
    var n = P.nx;
    var stride = 1u;
    if (P.along_y != 0u) {
        at = j;
        n = P.ny;
        stride = P.nx;
    }
    var lo = 0u;
    if (at > P.w) { lo = at - P.w; }
    let hi = at + min(P.w, n - 1u - at);
    let base = c - at * stride;
    var best = key_of(NEG_INF);
    var k = lo;
    loop {
        if (k > hi) { break; }
        best = max(best, key_of(canonical(src[base + k * stride])));
        k = k + 1u;
    }
    dst[c] = bits_of(best);
}
