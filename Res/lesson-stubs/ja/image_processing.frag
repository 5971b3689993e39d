#version 450

layout(location=1) in vec2 inTexcoord;

layout(binding=0) uniform sampler2D texColor; // メインの画像(線形のHDR)
layout(binding=1) uniform sampler2D texBloom; // ブルーム(ブルームのテクスチャのミップレベル0)

layout(location=120) uniform mat3 colorMatrix;
layout(location=121) uniform float bloomStrength;

out vec4 outColor;

void main()
{
  vec3 c = texture(texColor, inTexcoord).rgb;
  c += texture(texBloom, inTexcoord).rgb * bloomStrength;
  c = colorMatrix * c;
  // Reinhard風の肩で抑え、ガンマ2.2は手で掛けます(フレームバッファはsRGBではないため)。
  c = c / (1.0 + max(c.r, max(c.g, c.b)) * 0.15);
  c = pow(clamp(c, 0, 1), vec3(1.0 / 2.2));
  outColor = vec4(c, 1);
}
