#version 450

// 課題のステップ5(lessons/ja/05-linear-depth-view.md、講座の1.6節): テクスチャを出力に書き写して表示します。
// 書き上げるまで、このスタブは透明な黒を書き込むので、ステップ12の合成は何も暗くしません。

layout(location=1) in vec2 inTexcoord;

layout(binding=0) uniform sampler2D texColor;

out vec4 outColor;

void main()
{
  outColor = vec4(0);
}
