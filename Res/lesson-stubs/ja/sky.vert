#version 450

layout(location=0) in vec3 inPosition;
layout(location=1) in vec2 inTexcoord;

layout(location=1) out vec2 outTexcoord;

void main()
{
  outTexcoord = inTexcoord;
  // z = wで、この四角形はちょうどファー平面(ウィンドウの深度1.0)に載ります。GL_LEQUALなので、
  // どのジオメトリも書かなかったピクセルだけを覆います。
  gl_Position = vec4(inPosition.xy, 1, 1);
}
