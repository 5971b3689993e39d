#version 450

// 課題のステップ6～9(lessons/ja/06-view-position-and-normal.md～09-2x2-smoothing.md):
// このピクセルの遮蔽率をSAOで計算します。書き上げるまで、このスタブは遮蔽なし(0)を書き込みます。

layout(location=1) in vec2 inTexcoord;

out float outColor;

layout(binding=0) uniform sampler2D texDepth;

layout(location=200) uniform vec4 saoInfo;
layout(location=201) uniform vec2 ndcToView;

void main()
{
  outColor = 0;
}
