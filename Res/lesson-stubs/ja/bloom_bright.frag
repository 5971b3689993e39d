#version 450

layout(location=1) in vec2 inTexcoord;
layout(binding=0) uniform sampler2D texColor;
layout(location=130) uniform float threshold;

out vec4 outColor;

void main()
{
  // しきい値より明るい部分だけを残し(ソフトニー)、元の2×2テクセルで平均します。
  vec3 c = texture(texColor, inTexcoord).rgb;
  float brightness = max(c.r, max(c.g, c.b));
  float k = clamp((brightness - threshold) / max(brightness, 1e-4), 0, 1);
  outColor = vec4(c * k, 1);
}
