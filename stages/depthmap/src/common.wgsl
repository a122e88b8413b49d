// What the assembly and dilation shaders share (prepended to each when
// compiled).

// A dispatch of 256-invocation workgroups, split over y past MAX_DIM groups
// as `Gpu::pass` splits it: the item an invocation handles.
const GROUP: u32 = 256u;
const MAX_DIM: u32 = 65535u;

fn item(g: vec3<u32>) -> u32 { return g.x + g.y * MAX_DIM * GROUP; }

// mdm::f32_key and its inverse, on bit patterns. The key orders f32 values
// as IEEE total order does, as unsigned integers.
fn key_of(bits: u32) -> u32 {
    if ((bits & 0x80000000u) != 0u) { return ~bits; }
    return bits | 0x80000000u;
}
fn bits_of(key: u32) -> u32 {
    if ((key & 0x80000000u) != 0u) { return key & 0x7fffffffu; }
    return ~key;
}

