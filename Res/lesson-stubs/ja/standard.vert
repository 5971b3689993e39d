#version 450

layout(location=0) in vec3 inPosition;
layout(location=1) in vec2 inTexcoord;
layout(location=2) in vec3 inNormal;

layout(location=0) uniform mat4 matModel;
layout(location=1) uniform mat4 matViewProjection;
layout(location=2) uniform mat4 matShadow;

layout(location=0) out vec3 outPosition;
layout(location=1) out vec2 outTexcoord;
layout(location=2) out vec3 outNormal;
layout(location=3) out vec3 outShadowTexcoord;

void main()
{
  vec4 worldPosition = matModel * vec4(inPosition, 1);
  // 法線は逆行列の転置で変換するので、拡大率が軸ごとに違っても面に垂直なままです。
  mat3 matNormal = transpose(inverse(mat3(matModel)));
  outPosition = worldPosition.xyz;
  outTexcoord = inTexcoord;
  outNormal = matNormal * inNormal;
  vec4 shadowPosition = matShadow * worldPosition;
  outShadowTexcoord = shadowPosition.xyz / shadowPosition.w * 0.5 + 0.5;
  // 射影行列は通常のOpenGLの透視投影です。sao_restore_depth.fragがこれを逆に使います。
  gl_Position = matViewProjection * worldPosition;
}
