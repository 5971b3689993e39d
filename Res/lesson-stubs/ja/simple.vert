#version 450

// 画面全体のパスはplane_xyメッシュを描きます。このメッシュは最初からNDCの[-1,1]を覆っています。
layout(location=0) in vec3 inPosition;
layout(location=1) in vec2 inTexcoord;

layout(location=1) out vec2 outTexcoord;

void main()
{
  outTexcoord = inTexcoord;
  gl_Position = vec4(inPosition, 1);
}
