#version 450

// Ray-traced AO: from the surface each pixel sees (position from the linear depth, normal from the
// surface-normal pass), a few cosine-weighted rays of length R are traced against the scene's real
// triangles in a binary BVH (src/scene/bvh.rs documents the std430 layout). A ray blocked within R
// counts as fully occluded, an open one as fully open: the visibility the CPU reference computes, so
// occluders off screen and behind other surfaces count as they do there.
//
// Each frame takes the next rays of a low-discrepancy sequence (the R2 sequence, Roberts 2018, shifted
// per pixel by a hash: Cranley-Patterson rotation); with accumulation the frames are averaged by the
// temporal pass that follows (temporal_accumulate.frag), through the camera's motion.

#include "common.glsl"

#include "bvh.glsl"

layout(location=240) uniform mat4 viewToWorld;
// (rays this frame, index of the frame's first sample, unused,
// sequence: 0 = R2 over the frames, n > 0 = points first .. first + rays of one stratified lattice of
// n points (the GPU reference, which may split a pixel's lattice over several passes))
layout(location=241) uniform ivec4 rtaoFrame;
// Nodes in the BVH (0: no triangles, every ray is open).
layout(location=243) uniform int rtaoNodeCount;
// Pixels whose rays were not all traced to the end (zeroed before each pass, read back after it).
// A driver may end long loops early: Mesa's llvmpipe stops every loop of a shader invocation once
// all of them together have run 65535 iterations (LP_MAX_TGSI_LOOP_ITERATIONS), and a traversal cut
// short would read as "no hit". Such pixels keep the mean of the rays that did finish and are
// counted here, so the pass can be split or refused instead of being silently too bright.
layout(std430, binding=2) buffer RtaoStatus { uint rtaoCutPixels; };

// The shader's stack; src/scene/bvh.rs refuses deeper trees (MAX_STACK).
#define BVH_STACK 64
#define STRATIFIED_BLOCK 4

vec3 SafeRecip(vec3 d) {
  // Zero components become a tiny value of their sign, so the slab test never meets 0 * inf.
  vec3 tiny = mix(vec3(-1e-20), vec3(1e-20), greaterThanEqual(d, vec3(0.0)));
  return 1.0 / mix(d, tiny, lessThan(abs(d), vec3(1e-20)));
}

bool BoxHit(uint i, vec3 o, vec3 invD, float tMax) {
  vec3 t0 = (nodes[i].lo - o) * invD;
  vec3 t1 = (nodes[i].hi - o) * invD;
  vec3 tNear = min(t0, t1);
  vec3 tFar = max(t0, t1);
  float near = max(max(tNear.x, tNear.y), max(tNear.z, 0.0));
  float far = min(min(tFar.x, tFar.y), min(tFar.z, tMax));
  return near <= far;
}

// Moller-Trumbore with a small edge tolerance, so rays cannot slip between two triangles that share an
// edge.
bool TriangleHit(uint i, vec3 o, vec3 d, float tMax) {
  vec3 v0 = triangles[i].v0.xyz;
  vec3 e1 = triangles[i].e1.xyz;
  vec3 e2 = triangles[i].e2.xyz;
  vec3 p = cross(d, e2);
  float det = dot(e1, p);
  if (det == 0.0) {
    return false;
  }
  float inv = 1.0 / det;
  vec3 s = o - v0;
  float u = dot(s, p) * inv;
  vec3 q = cross(s, e1);
  float v = dot(d, q) * inv;
  float t = dot(e2, q) * inv;
  const float EPS = 1e-6;
  return u >= -EPS && v >= -EPS && u + v <= 1.0 + EPS && t >= 0.0 && t <= tMax;
}

// Any hit within tMax along unit d: AO needs only "blocked or not", so the first triangle hit ends
// the walk. Both children are tested before descending; the far one waits on the stack. The walk
// visits each node at most once, so its bound is never met by a walk that runs its course: leaving
// the loop through it (`cut`) means the driver ended the loop, and the answer is unknown.
bool Occluded(vec3 o, vec3 d, float tMax, uint start, inout bool cut) {
  if (rtaoNodeCount <= 0) {
    return false;
  }
  vec3 invD = SafeRecip(d);
  if (!BoxHit(start, o, invD, tMax)) {
    return false;
  }
  uint stack[BVH_STACK];
  int top = 0;
  uint node = start;
  for (int step = 0; step <= rtaoNodeCount; ++step) {
    uint count = nodes[node].count;
    uint first = nodes[node].first;
    if (count == 0u) {
      bool hitA = BoxHit(first, o, invD, tMax);
      bool hitB = BoxHit(first + 1u, o, invD, tMax);
      if (hitA && hitB) {
        stack[top++] = first + 1u;
        node = first;
        continue;
      }
      if (hitA || hitB) {
        node = hitA ? first : first + 1u;
        continue;
      }
    } else {
      uint t = first;
      for (; t < first + count; ++t) {
        if (TriangleHit(t, o, d, tMax)) {
          return true;
        }
      }
      if (t < first + count) {
        break; // this loop, too, can be ended early
      }
    }
    if (top == 0) {
      return false;
    }
    node = stack[--top];
  }
  cut = true;
  return false;
}

bool SphereMeetsBox(uint i, vec3 c, float r) {
  vec3 d = clamp(c, nodes[i].lo, nodes[i].hi) - c;
  return dot(d, d) <= r * r;
}

// Where a pixel's rays start their walk: every ray stays within the radius of its origin, so it can
// only hit triangles in leaves whose boxes meet that sphere, and all of those lie under the deepest
// node reached by following, from the root, the one child that meets the sphere while only one
// does. Each ray then skips the levels above it: the same triangles, the same answer (the 640x360
// references at 256 rays of the three bench scenes, bit for bit, 5-7 % faster on llvmpipe).
uint EntryNode(vec3 c, float r) {
  uint node = 0u;
  while (rtaoNodeCount > 0 && nodes[node].count == 0u) {
    uint first = nodes[node].first;
    bool hitA = SphereMeetsBox(first, c, r);
    bool hitB = SphereMeetsBox(first + 1u, c, r);
    if (hitA == hitB) {
      break; // both: the rays may need either side; neither: the node's own box decides
    }
    node = hitA ? first : first + 1u;
  }
  return node;
}

// Orthonormal tangent frame of a unit normal (Duff et al. 2017), as the CPU reference builds it.
void TangentFrame(vec3 n, out vec3 t, out vec3 b) {
  float s = n.z >= 0.0 ? 1.0 : -1.0;
  float a = -1.0 / (s + n.z);
  float c = n.x * n.y * a;
  t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
  b = vec3(c, s + n.y * n.y * a, -n.y);
}

// A point of the unit square to a cosine-weighted direction (Malley's method), as the reference.
vec3 CosineDirection(vec3 n, vec3 t, vec3 b, vec2 uv) {
  float r = sqrt(uv.x);
  float phi = 2.0 * PI * uv.y;
  return t * (r * cos(phi)) + b * (r * sin(phi)) + n * sqrt(max(1.0 - uv.x, 0.0));
}

// A 32-bit integer hash (the PCG output permutation, Jarzynski and Olano 2020).
uint Hash(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

const float TO_UNIT = 1.0 / 4294967296.0;

// The i-th point: R2 (golden ratio of the plane) or the lattice of n points, shifted by `shift`
// (fixed point, so the fraction stays exact however far the sequence runs).
vec2 SamplePoint(uint i, uint n, uvec2 shift) {
  if (rtaoFrame.w > 0) {
    uint u = uint((float(i) + 0.5) / float(n) * 4294967296.0);
    return vec2(u + shift.x, i * 2654435769u + shift.y) * TO_UNIT;
  }
  return vec2(i * 3242174889u + shift.x, i * 2447445414u + shift.y) * TO_UNIT;
}

void main()
{
  ivec2 pix = ivec2(gl_FragCoord.xy);
  float z = TexelDepth(pix);
  if (IsSky(z)) {
    WriteOcclusion(0.0, z);
    return;
  }
  vec3 P = TexelPos(pix);
  vec3 n = SurfaceNormal(pix, P);
  // The reference's offset, 1e-4 of the distance (at least 1e-4 m): the engine draws the depth rtao
  // reads at the AO size itself (it always reads the surface normals), so each texel's point lies
  // on its triangle.
  float eps = 1e-4 * max(1.0, length(P));
  vec3 origin = (viewToWorld * vec4(P + n * eps, 1.0)).xyz;
  vec3 nWorld = normalize(mat3(viewToWorld) * n);
  vec3 t, b;
  TangentFrame(nWorld, t, b);

  uint rays = uint(max(rtaoFrame.x, 1));
  uint first = uint(max(rtaoFrame.y, 0));
  // The reference's lattice is shifted per block of STRATIFIED_BLOCK² pixels, not per pixel: the
  // pixels a SIMD lane group shades then trace parallel rays that walk the same BVH nodes (on
  // llvmpipe, where lanes wait for the slowest, the demo camera's 640x360 reference at 256 rays
  // went from 5.1 to 4.0 s; blocks of 8, 16 or the whole image gained nothing more). Each pixel's estimate stays
  // unbiased; neighbours' errors are correlated, which a reference's per-pixel error ignores.
  ivec2 cell = rtaoFrame.w > 0 ? pix / STRATIFIED_BLOCK : pix;
  uint h = Hash(uint(cell.x) + Hash(uint(cell.y)));
  uvec2 shift = uvec2(h, Hash(h));
  uint lattice = rtaoFrame.w > 0 ? uint(rtaoFrame.w) : rays;
  uint entry = EntryNode(origin, AO_RADIUS);
  int blocked = 0;
  int traced = 0;
  bool cut = false;
  for (uint k = 0u; k < rays && !cut; ++k) {
    vec2 uv = SamplePoint(first + k, lattice, shift);
    vec3 d = CosineDirection(nWorld, t, b, uv);
    bool hit = Occluded(origin, normalize(d), AO_RADIUS, entry, cut);
    if (!cut) {
      blocked += hit ? 1 : 0;
      traced += 1;
    }
  }
  if (traced < int(rays)) {
    atomicAdd(rtaoCutPixels, 1u);
  }
  float occlusion = traced > 0 ? float(blocked) / float(traced) : 0.0;
  WriteOcclusion(ApplyIntensity(occlusion), z);
}
