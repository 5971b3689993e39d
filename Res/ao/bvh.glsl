// The scene's BVH in shader storage buffers, std430 (src/scene/bvh.rs writes it and documents the
// layout; tests/gl/rtao.rs reads every field back through this declaration).

struct BvhNode {
  vec3 lo;
  uint count; // triangles in a leaf; 0: inner node
  vec3 hi;
  uint first; // inner: first child (the second is first + 1); leaf: first triangle
};

struct BvhTriangle {
  vec4 v0;
  vec4 e1; // v1 - v0
  vec4 e2; // v2 - v0
};

layout(std430, binding=0) readonly buffer BvhNodes { BvhNode nodes[]; };
layout(std430, binding=1) readonly buffer BvhTriangles { BvhTriangle triangles[]; };
