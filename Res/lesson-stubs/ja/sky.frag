#version 450

layout(location=1) in vec2 inTexcoord;

layout(location=110) uniform mat4 matInverseViewProjection;
layout(location=101) uniform vec3 lightDirection;

out vec4 outColor;

void main()
{
  // ピクセルごとの視線: ニア平面とファー平面の上の2点から作ります。
  vec2 ndc = inTexcoord * 2 - 1;
  vec4 p0 = matInverseViewProjection * vec4(ndc, -1, 1);
  vec4 p1 = matInverseViewProjection * vec4(ndc, 1, 1);
  vec3 d = p1.xyz / p1.w - p0.xyz / p0.w;
  float len2 = dot(d, d);
  d = len2 > 0 ? d * inversesqrt(len2) : vec3(0, 0, -1);
  float up = clamp(d.y, -1, 1);
  vec3 horizon = vec3(0.80, 0.86, 0.95);
  vec3 zenith = vec3(0.25, 0.45, 0.85);
  vec3 ground = vec3(0.35, 0.33, 0.30);
  vec3 color = up >= 0 ? mix(horizon, zenith, pow(up, 0.6)) : mix(horizon, ground, pow(-up, 0.4));
  // ライトの方向に、太陽のやわらかな光を足します。
  float sun = max(dot(d, normalize(lightDirection)), 0);
  color += vec3(1.0, 0.9, 0.7) * pow(sun, 200.0) * 4.0;
  outColor = vec4(color, 1);
}
