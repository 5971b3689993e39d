#version 450

layout(location=1) in vec2 inTexcoord;
layout(binding=0) uniform sampler2D texColor;

out vec4 outColor;

void main()
{
  // Tent filter of the smaller level, added onto the larger one by blending (ONE, ONE).
  vec2 t = 1.0 / vec2(textureSize(texColor, 0));
  vec3 c = texture(texColor, inTexcoord).rgb * 4
         + texture(texColor, inTexcoord + vec2(t.x, 0)).rgb * 2
         + texture(texColor, inTexcoord - vec2(t.x, 0)).rgb * 2
         + texture(texColor, inTexcoord + vec2(0, t.y)).rgb * 2
         + texture(texColor, inTexcoord - vec2(0, t.y)).rgb * 2
         + texture(texColor, inTexcoord + t).rgb
         + texture(texColor, inTexcoord - t).rgb
         + texture(texColor, inTexcoord + vec2(t.x, -t.y)).rgb
         + texture(texColor, inTexcoord + vec2(-t.x, t.y)).rgb;
  outColor = vec4(c / 16.0, 1);
}
