#version 450

layout(location=1) in vec2 inTexcoord;

layout(binding=0) uniform sampler2D texColor;

out vec4 outColor;

void main()
{
  // R32F の距離を灰色で見たくて、赤チャンネルを全チャンネルに広げた
  outColor = vec4(texture(texColor, inTexcoord).r);
}
