#version 450

// 課題のステップ2(lessons/ja/02-restore-pass.md): この1/2サイズのピクセルの下にある2×2の深度テクセルのうち、
// 最も近いものの線形距離(メートル)を書き込みます。書き上げるまで、このスタブはどのピクセルにも0を書き込みます。

out float outColor;

layout(binding=0) uniform sampler2D texDepth;

// カメラのニア平面とファー平面はエンジンが注入します。この既定値があれば、ファイル単体でもコンパイルできます。
#ifndef CAMERA_NEAR
#define CAMERA_NEAR 0.35
#endif
#ifndef CAMERA_FAR
#define CAMERA_FAR 1000.0
#endif

void main()
{
  outColor = 0;
}
