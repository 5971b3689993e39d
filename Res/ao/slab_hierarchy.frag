#version 450

// One level of vbao's slab hierarchy (a depth pyramid after Greene, Kass and Miller, "Hierarchical
// Z-buffer visibility", 1993): per texel, the nearest slab under it as (front, back) in linear
// metres and the level-0 texel it belongs to. Level 0 holds each AO texel's own slab: its depth to
// the back face behind it, or to depth + aoThickness where there is none (open planes) or back faces
// are off. A coarser texel keeps its nearest child's slab whole. Keeping the union of the children
// instead (nearest front to farthest back) turns a block of a near board and a far wall into one
// slab from board to wall: it lost up to 8 dB on the bench's training cameras
// (docs/bench/vbao/slab-hierarchy.md). The coordinates let vbao put the
// slab on its own camera ray: a block's nearest depth moved onto another texel's ray lies off its
// surface (on a receding floor, above it: the raised horizons of a min-depth chain).
// Sky is (CAMERA_FAR, 0): never the nearest while a surface is under the texel.

layout(binding=0) uniform sampler2D texDepth;     // linear depth (m), AO size
layout(binding=1) uniform sampler2D texBackDepth; // back-face linear depth (m), AO size
layout(binding=2) uniform sampler2D texSlabs;     // this hierarchy, levels up to mipLevel

layout(location=200) uniform int mipLevel;       // level read; -1: level 0 from the depths
layout(location=204) uniform float aoThickness;  // metres behind each depth sample
layout(location=205) uniform int aoBackFaces;    // 1: each slab reaches texBackDepth

out vec4 outSlab; // (front, back, texel x, texel y)

vec4 OwnSlab(ivec2 p) {
  float z = texelFetch(texDepth, p, 0).x;
  if (z >= CAMERA_FAR) {
    return vec4(CAMERA_FAR, 0.0, vec2(p));
  }
  float back = z + aoThickness;
  if (aoBackFaces != 0) {
    // The back face itself, however thin: vbao widens each slab to the spacing of the taps that
    // read it, which it knows and this pass does not.
    float b = texelFetch(texBackDepth, p, 0).x;
    back = b > z && b < CAMERA_FAR ? b : back;
  }
  return vec4(z, back, vec2(p));
}

void main()
{
  ivec2 p = ivec2(gl_FragCoord.xy);
  if (mipLevel < 0) {
    outSlab = OwnSlab(p);
    return;
  }
  ivec2 src = textureSize(texSlabs, mipLevel);
  ivec2 dst = max(src / 2, ivec2(1));
  // An odd source's last column (row) has no parent of its own: the last parent takes it too, so
  // every texel of the finer level lies under one of the coarser.
  ivec2 count = ivec2(2) + ivec2(equal(p, dst - 1)) * (src - 2 * dst);
  vec4 nearest = texelFetch(texSlabs, min(2 * p, src - 1), mipLevel);
  for (int y = 0; y < count.y; ++y) {
    for (int x = 0; x < count.x; ++x) {
      vec4 c = texelFetch(texSlabs, min(2 * p + ivec2(x, y), src - 1), mipLevel);
      nearest = c.x < nearest.x ? c : nearest;
    }
  }
  outSlab = nearest;
}
