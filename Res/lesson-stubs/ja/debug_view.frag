#version 450

// エンジンの道具(課題の一部ではありません): 途中のバッファを1つグレーで表示するか、値をそのまま書き出します。

layout(location=1) in vec2 inTexcoord;

layout(binding=0) uniform sampler2D texValue;

layout(location=210) uniform int mode;    // 0 = 線形距離、1 = 遮蔽率を可視率として表示
layout(location=211) uniform float scale; // 値に掛ける数(そのまま書き出すときは1)

out vec4 outColor;

void main()
{
  float v;
  if (mode == 0) {
    // レベル0の最も近いテクセル: 深度を縁の向こうと補間してはいけません。
    ivec2 size = textureSize(texValue, 0);
    ivec2 p = clamp(ivec2(inTexcoord * vec2(size)), ivec2(0), size - 1);
    v = texelFetch(texValue, p, 0).x;
  } else {
    v = 1.0 - texture(texValue, inTexcoord).x;
  }
  v *= scale;
  outColor = vec4(v, v, v, 1);
}
