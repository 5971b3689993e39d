#version 450

// The composite of the engine's half-size AO, up-sampling as it blends: the occlusion of
// bilateral_upsample.glsl, then the tinted blend of composite_tint.frag (the lesson's blend is tint 0,
// power 1: colour x (1 - occlusion)). Drawn over the main framebuffer with a depth test that lets only
// pixels with a surface through (depth writes off; this shader reads that depth buffer too). Sky
// pixels never get here; should one, it is left alone (alpha 0): the sky pass draws it after.

layout(location=1) in vec2 inTexcoord;

layout(binding=0) uniform sampler2D texOcclusion; // half size
layout(binding=1) uniform sampler2D texDepth;     // half-size linear depth (m), level 0
layout(binding=2) uniform sampler2D texMainDepth; // main depth buffer (window depth)

layout(location=220) uniform vec3 tint;
layout(location=221) uniform float power;

#include "linear_depth.glsl"
#include "bilateral_upsample.glsl"

out vec4 outColor;

void main()
{
  bool sky;
  float occlusion = UpsampledOcclusion(inTexcoord, ivec2(gl_FragCoord.xy), sky);
  float visibility = clamp(1.0 - occlusion, 0.0, 1.0);
  // Power 1 without pow(): exactly the lesson's blend (a program of its own, AO_POWER_ONE: a
  // software rasteriser evaluates both sides of a branch).
#ifdef AO_POWER_ONE
  float alpha = 1.0 - visibility;
#else
  float alpha = 1.0 - pow(visibility, power);
#endif
  outColor = vec4(tint, sky ? 0.0 : alpha);
}
