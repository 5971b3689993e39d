#version 450
// The rewrite of ../rewrite-sao with its helpers moved to a file of their own (#include): a
// student's folder may split a shader, and the grader must grade it with its includes.

layout(location=1) in vec2 inTexcoord;
layout(binding=0) uniform sampler2D texDepth;
layout(location=200) uniform vec4 saoInfo; // r^2, r in texcoords at 1 m, bias, intensity / r^6
layout(location=201) uniform vec2 ndcToView;
out float outColor;

const int SAMPLES = 11;
const float TURNS = 3.0;
const float PI = 3.14159265358979;

#include "sao_helpers.glsl"

void main()
{
  float z = textureLod(texDepth, inTexcoord, 0.0).r;
  vec3 p = ViewPos(inTexcoord, z);
  vec3 dx = dFdx(p);
  vec3 dy = dFdy(p);
  vec3 c = cross(dx, dy);
  vec3 n = length(c) > 0.0 ? c / length(c) : vec3(0.0, 0.0, 1.0);

  float rTex = saoInfo.y / z;
  float rPix = rTex * float(textureSize(texDepth, 0).y);
  // round on screen: one texture-coordinate unit is wider than high
  vec2 texels = vec2(textureSize(texDepth, 0));
  vec2 squash = vec2(texels.y / texels.x, 1.0);
  float a = 2.0 * PI * Hash(ivec2(gl_FragCoord.xy));
  float step = 2.0 * PI * TURNS / float(SAMPLES);
  mat2 rot = mat2(cos(step), sin(step), -sin(step), cos(step));
  vec2 dir = vec2(cos(a), sin(a));
  // the first sample is half a step along the spiral
  mat2 half_rot = mat2(cos(0.5 * step), sin(0.5 * step), -sin(0.5 * step), cos(0.5 * step));
  dir = half_rot * dir;

  float sum = 0.0;
  int i = 0;
  while (i < SAMPLES) {
    float t = (float(i) + 0.5) / float(SAMPLES);
    int level = clamp(findMSB(int(t * rPix)) - 3, 0, 3);
    sum += SampleAO(p, n, inTexcoord + t * rTex * dir * squash, float(level));
    dir = rot * dir;
    ++i;
  }
  float ao = min(1.0, sum * saoInfo.w / float(SAMPLES));

  // 2x2 smoothing on near-flat quads (derivatives taken outside branches)
  float ax = dFdx(ao);
  float ay = dFdy(ao);
  ivec2 q = ivec2(gl_FragCoord.xy) & 1;
  if (abs(dx.z) < 0.02) {
    ao -= ax * (float(q.x) - 0.5);
  }
  if (abs(dy.z) < 0.02) {
    ao -= ay * (float(q.y) - 0.5);
  }
  outColor = ao;
}
