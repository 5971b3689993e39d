#version 450

layout(location=1) in vec2 inTexcoord;

layout(binding=0) uniform sampler2D texColor;

out vec4 outColor;

void main()
{
  // 画像は上が v=0 だと思い込んで反転した
  outColor = texture(texColor, vec2(inTexcoord.x, 1.0 - inTexcoord.y));
}
