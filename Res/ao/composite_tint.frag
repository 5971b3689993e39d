#version 450

// Composite with a tint and a power: blended with SRC_ALPHA / ONE_MINUS_SRC_ALPHA,
// occluded areas move toward `tint` by 1 - visibility^power.

layout(location=1) in vec2 inTexcoord;

layout(binding=0) uniform sampler2D texOcclusion;

layout(location=220) uniform vec3 tint;
layout(location=221) uniform float power;

out vec4 outColor;

void main()
{
  float visibility = clamp(1.0 - texture(texOcclusion, inTexcoord).x, 0.0, 1.0);
  outColor = vec4(tint, 1.0 - pow(visibility, power));
}
