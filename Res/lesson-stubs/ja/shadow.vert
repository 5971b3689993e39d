#version 450

layout(location=0) in vec3 inPosition;

layout(location=0) uniform mat4 matModel;
layout(location=1) uniform mat4 matViewProjection; // ライトのビュー・プロジェクション行列

void main()
{
  gl_Position = matViewProjection * matModel * vec4(inPosition, 1);
}
