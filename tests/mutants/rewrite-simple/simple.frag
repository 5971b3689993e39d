#version 450

// テクスチャを表示するだけのシェーダ（書き方を変えたもの）
layout(location=1) in vec2 inTexcoord;
layout(binding=0) uniform sampler2D image;
layout(location=0) out vec4 fragColor;

void main()
{
  vec4 c = textureLod(image, inTexcoord, 0.0);
  fragColor = vec4(c.rgb, c.a);
}
