#version 450

// Full-screen passes draw the plane_xy mesh, which already spans NDC [-1,1].
layout(location=0) in vec3 inPosition;
layout(location=1) in vec2 inTexcoord;

layout(location=1) out vec2 outTexcoord;

void main()
{
  outTexcoord = inTexcoord;
  gl_Position = vec4(inPosition, 1);
}
