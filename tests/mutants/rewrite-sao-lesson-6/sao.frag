#version 450

// レッスン6: 視点座標と法線（書き方を変えたもの）
layout(location=1) in vec2 inTexcoord;
layout(location=0) out float outColor;

layout(binding=0) uniform sampler2D texDepth;
layout(location=200) uniform vec4 saoInfo;
layout(location=201) uniform vec2 ndcToView;


vec3 viewPosition(vec2 uv, float d)
{
  return vec3((uv * 2.0 - 1.0) * ndcToView * d, -d);
}

void main()
{
  float d = texture(texDepth, inTexcoord, -16.0).r;
  vec3 p = viewPosition(inTexcoord, d);
  vec3 right = dFdx(p);
  vec3 up = dFdy(p);
  vec3 n = cross(right, up);
  bool edge = abs(right.z) > 0.1 * d || abs(up.z) > 0.1 * d;
  bool ok = dot(n, n) > 1e-30 && !edge;
  float ny = ok ? normalize(n).y : 0.0;
  outColor = ny;
}
