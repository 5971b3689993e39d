// Unit vectors in two numbers (octahedral mapping: the sphere folded onto the square [-1, 1]^2). At
// 16-bit float the round trip is within 1e-3 rad. The AO methods decode in common.glsl
// (DecodeOctahedral); src/math/octahedral.rs is the CPU side.

vec2 EncodeOctahedral(vec3 n) {
  n /= abs(n.x) + abs(n.y) + abs(n.z);
  if (n.z >= 0.0) {
    return n.xy;
  }
  return (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
}
