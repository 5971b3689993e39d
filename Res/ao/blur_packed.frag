#version 450

// The separable bilateral blur of blur_separable.frag (same 9 taps, weights and depth test)
// for the engine's `sao`, whose AO pass also writes (occlusion, linear depth) into one RG texture:
// each tap is one fetch instead of two (McGuire packs the blur key next to the AO value the same
// way). The first pass writes the pair on for the second; the second writes occlusion into R8.

layout(binding=0) uniform sampler2D texPacked; // r = occlusion, g = linear depth (m)

layout(location=210) uniform ivec2 axis;       // (1,0) then (0,1)

// CAMERA_FAR and BLUR_REACH (texels read on either side) are injected by the engine
// (`ao::method_pass::method_defines`); the Gaussian table holds BLUR_REACH + 1 weights, the
// centre's first. A method whose noise wants a narrower Gaussian has the engine inject its own
// table as BLUR_WEIGHTS (`ao::blur::weights_define`).
#include "blur_edge.glsl"

layout(location=0) out vec2 outColor;

#ifndef BLUR_WEIGHTS
#define BLUR_WEIGHTS 0.153170, 0.144893, 0.122649, 0.092902, 0.062970
#endif
const float gaussian[BLUR_REACH + 1] = float[](BLUR_WEIGHTS);

void main()
{
  ivec2 uv = ivec2(gl_FragCoord.xy);
  ivec2 maxUV = textureSize(texPacked, 0) - 1;
  vec2 center = texelFetch(texPacked, uv, 0).xy;
  float depth = center.y;
  outColor = center;
  if (depth >= CAMERA_FAR) {
    return;
  }
  float slope = InverseDepthSlope(texelFetch(texPacked, clamp(uv - axis, ivec2(0), maxUV), 0).y, depth,
                                  texelFetch(texPacked, clamp(uv + axis, ivec2(0), maxUV), 0).y);
  float sum = center.x * gaussian[0];
  float total = gaussian[0];
  for (int r = -BLUR_REACH; r <= BLUR_REACH; ++r) {
    if (r == 0) {
      continue;
    }
    vec2 tap = texelFetch(texPacked, clamp(uv + axis * r, ivec2(0), maxUV), 0).xy;
    float w = gaussian[abs(r)] * EdgeWeight(depth, slope, r, tap.y);
    sum += tap.x * w;
    total += w;
  }
  outColor = vec2(sum / total, depth);
}
