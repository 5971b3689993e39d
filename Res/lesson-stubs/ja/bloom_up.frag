#version 450

layout(location=1) in vec2 inTexcoord;
layout(binding=0) uniform sampler2D texColor;

out vec4 outColor;

void main()
{
  // 小さいレベルをテントフィルタで広げ、ブレンド(ONE, ONE)で大きいレベルに足します。
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
