#version 450

// One direction of the separable bilateral blur (as in SAO_blur.pix: 2 passes x 9 taps, radius 4,
// its Gaussian table, a sigma = 3 Gaussian in taps, without the 0.3 it adds off the centre; taps off
// the centre's plane lose their weight: blur_edge.glsl). Taps are 1 texel apart, not 2:
// the methods rotate their samples with a 4x4 tile, and taps 2 apart would only ever see 2 of its 4
// phases per axis, leaving the tile's pattern in the picture.

layout(binding=0) uniform sampler2D texColor; // occlusion
layout(binding=1) uniform sampler2D texDepth; // linear depth

layout(location=210) uniform ivec2 axis;      // (1,0) then (0,1)

// CAMERA_FAR and BLUR_REACH (texels read on either side) are injected by the engine
// (`ao::method_pass::method_defines`); the Gaussian table holds BLUR_REACH + 1 weights.
#include "blur_edge.glsl"

out float outColor;

// A method's own Gaussian, as blur_packed.frag takes it.
#ifndef BLUR_WEIGHTS
#define BLUR_WEIGHTS 0.153170, 0.144893, 0.122649, 0.092902, 0.062970
#endif
const float gaussian[BLUR_REACH + 1] = float[](BLUR_WEIGHTS);

void main()
{
  ivec2 uv = ivec2(gl_FragCoord.xy);
  ivec2 maxUV = textureSize(texColor, 0) - 1;
  float center = texelFetch(texColor, uv, 0).x;
  float depth = texelFetch(texDepth, uv, 0).x;
  outColor = center;
  if (depth >= CAMERA_FAR) {
    return;
  }
  float slope = InverseDepthSlope(texelFetch(texDepth, clamp(uv - axis, ivec2(0), maxUV), 0).x, depth,
                                  texelFetch(texDepth, clamp(uv + axis, ivec2(0), maxUV), 0).x);
  float sum = center * gaussian[0];
  float total = gaussian[0];
  for (int r = -BLUR_REACH; r <= BLUR_REACH; ++r) {
    if (r == 0) {
      continue;
    }
    ivec2 q = clamp(uv + axis * r, ivec2(0), maxUV);
    float w = gaussian[abs(r)] * EdgeWeight(depth, slope, r, texelFetch(texDepth, q, 0).x);
    sum += texelFetch(texColor, q, 0).x * w;
    total += w;
  }
  outColor = sum / total;
}
