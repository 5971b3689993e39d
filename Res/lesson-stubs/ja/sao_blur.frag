#version 450

// 課題のステップ11(lessons/ja/11-bilateral-blur.md): 深度の境界を保ったまま遮蔽率をぼかします。
// 書き上げるまで、このスタブは遮蔽率をそのまま書き写します。

layout(binding=0) uniform sampler2D texColor;
layout(binding=1) uniform sampler2D texDepth;

out vec4 outColor;

// ファー平面はエンジンが注入します。この既定値があれば、ファイル単体でもコンパイルできます。
#ifndef CAMERA_FAR
#define CAMERA_FAR 1000.0
#endif

void main()
{
  outColor = texelFetch(texColor, ivec2(gl_FragCoord.xy), 0);
}
