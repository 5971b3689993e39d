#version 450

// The surface-normal pass: the scene's geometry with its view-space position passed on, so that the
// fragment shader can take the triangle's own plane from the position's screen derivatives.

layout(location=0) in vec3 inPosition;

layout(location=0) uniform mat4 matModel;
layout(location=1) uniform mat4 matViewProjection;
layout(location=3) uniform mat4 matView;

layout(location=0) out vec3 outViewPosition;

void main()
{
  vec4 worldPosition = matModel * vec4(inPosition, 1);
  outViewPosition = (matView * worldPosition).xyz;
  gl_Position = matViewProjection * worldPosition;
}
