// Shared by the depth map's shaders (prepended to each when compiled):
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

