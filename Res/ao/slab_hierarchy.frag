#version 450

// One level of vbao's slab hierarchy (Hi-Z style, after Greene, Kass and Miller, "Hierarchical
// Z-buffer visibility", 1993): per texel, (nearest front, back) of the slabs under it, linear metres.
// Level 0 holds each AO texel's own slab: its depth to depth + aoThickness, or to the back face
// behind it (never thinner than aoThickness, vbao's rule). A coarser texel keeps the nearest front of
// its 2x2 children and, as back, the back of that nearest child, extended towards the farthest back
// of the children by at most slabReach metres. Sky is (CAMERA_FAR, 0): an empty slab that neither
// min nor max picks.

layout(binding=0) uniform sampler2D texDepth;     // linear depth (m), AO size
layout(binding=1) uniform sampler2D texBackDepth; // back-face linear depth (m), AO size
layout(binding=2) uniform sampler2D texSlabs;     // this hierarchy, levels up to mipLevel

layout(location=200) uniform int mipLevel;       // level read; -1: level 0 from the depths
layout(location=204) uniform float aoThickness;  // metres behind each depth sample
layout(location=205) uniform int aoBackFaces;    // 1: each slab reaches texBackDepth
layout(location=209) uniform float slabReach;    // metres a coarse slab may reach past its nearest

out vec2 outSlab;

const vec2 EMPTY = vec2(CAMERA_FAR, 0.0);

vec2 OwnSlab(ivec2 p) {
  float z = texelFetch(texDepth, p, 0).x;
  if (z >= CAMERA_FAR) {
    return EMPTY;
  }
  float back = z + aoThickness;
  if (aoBackFaces != 0) {
    float b = texelFetch(texBackDepth, p, 0).x;
    back = b > z && b < CAMERA_FAR ? max(b, back) : back;
  }
  return vec2(z, back);
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
  vec2 nearest = EMPTY;
  float farthest = 0.0;
  for (int y = 0; y < count.y; ++y) {
    for (int x = 0; x < count.x; ++x) {
      vec2 c = texelFetch(texSlabs, min(2 * p + ivec2(x, y), src - 1), mipLevel).xy;
      nearest = c.x < nearest.x ? c : nearest;
      farthest = max(farthest, c.y);
    }
  }
  outSlab = vec2(nearest.x, max(nearest.y, min(farthest, nearest.x + slabReach)));
}
