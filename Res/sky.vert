#version 450

layout(location=0) in vec3 inPosition;
layout(location=1) in vec2 inTexcoord;

layout(location=1) out vec2 outTexcoord;

void main()
{
  outTexcoord = inTexcoord;
  // z = w puts the quad exactly on the far plane (window depth 1.0): with GL_LEQUAL it only covers
  // pixels that no geometry wrote.
  gl_Position = vec4(inPosition.xy, 1, 1);
}
