#version 450

layout(location=1) in vec2 inTexcoord;
layout(binding=0) uniform sampler2D texColor;
layout(location=130) uniform float threshold;

out vec4 outColor;

void main()
{
  // Keep only what is brighter than the threshold (soft knee), averaged over the 2x2 source texels.
  vec3 c = texture(texColor, inTexcoord).rgb;
  float brightness = max(c.r, max(c.g, c.b));
  float k = clamp((brightness - threshold) / max(brightness, 1e-4), 0, 1);
  outColor = vec4(c * k, 1);
}
