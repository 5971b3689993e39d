#version 450

layout(location=1) in vec2 inTexcoord;
layout(binding=0) uniform sampler2D texColor;

out vec4 outColor;

void main()
{
  // バイリニアで4回読む = 元のレベルの4×4の平均。
  vec2 t = 1.0 / vec2(textureSize(texColor, 0));
  vec3 c = texture(texColor, inTexcoord + vec2(-t.x, -t.y)).rgb
         + texture(texColor, inTexcoord + vec2( t.x, -t.y)).rgb
         + texture(texColor, inTexcoord + vec2(-t.x,  t.y)).rgb
         + texture(texColor, inTexcoord + vec2( t.x,  t.y)).rgb;
  outColor = vec4(c * 0.25, 1);
}
