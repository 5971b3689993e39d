#version 450

// 課題のステップ4(lessons/ja/04-down-sampling.md): レベルmipLevelの2×2テクセルの最小値を書き込みます。
// 書き上げるまで、このスタブは0を書き込みます。

layout(binding=0) uniform sampler2D texDepth;

out float outColor;

layout(location=200) uniform int mipLevel;

void main()
{
  outColor = 0;
}
