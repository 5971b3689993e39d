#version 450

// Half-size AO to the main size, depth-aware (bilateral_upsample.glsl), into a texture: for the AO
// views and the ambient-only lighting. The blended composites up-sample as they blend instead
// (composite_bilateral.frag), one pass fewer.

layout(location=1) in vec2 inTexcoord;

layout(binding=0) uniform sampler2D texOcclusion; // half size
layout(binding=1) uniform sampler2D texDepth;     // half-size linear depth (m), level 0
layout(binding=2) uniform sampler2D texMainDepth; // main depth buffer (window depth)

#include "linear_depth.glsl"
#include "bilateral_upsample.glsl"

out float outColor;

void main()
{
  bool sky;
  outColor = UpsampledOcclusion(inTexcoord, ivec2(gl_FragCoord.xy), sky);
}
