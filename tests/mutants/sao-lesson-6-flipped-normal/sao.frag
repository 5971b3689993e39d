#version 450

layout(location=1) in vec2 inTexcoord;

out float outColor;

layout(binding=0) uniform sampler2D texDepth; // linear depth (metres), 4 mip levels

layout(location=200) uniform vec4 saoInfo;
#define RADIUS2             (saoInfo.x) // sampling radius squared (m^2)
#define RADIUS_IN_TEXCOORDS (saoInfo.y) // sampling radius in texture coordinates at 1 m
#define BIAS                (saoInfo.z) // a distance in metres (not a cosine, whatever the course says)
#define INTENSITY           (saoInfo.w) // intensity / radius^6

// NDC -> view space at 1 m: (aspect / fovScale, 1 / fovScale)
layout(location=201) uniform vec2 ndcToView;

// The engine injects these; the defaults are the lesson's values (turns from McGuire's table for 11).
#ifndef SAO_SAMPLE_COUNT
#define SAO_SAMPLE_COUNT 11
#endif
#ifndef SAO_SPIRAL_TURNS
#define SAO_SPIRAL_TURNS 3
#endif
#ifndef CAMERA_FAR
#define CAMERA_FAR 1000.0
#endif

const float twoPi = 3.14159265 * 2;
const float samplingCount = SAO_SAMPLE_COUNT;
const float spiralTurns = SAO_SPIRAL_TURNS;
const int maxMipLevel = 3; // highest level index (the texture has 4 levels)

// Samples closer than 2^logMipOffset pixels read level 0.
const int logMipOffset = 3;

vec3 GetViewSpacePosition(vec2 uv, float linearDepth)
{
  vec2 ndc = uv * 2 - 1;
  vec2 viewOneMeter = ndc * ndcToView;
  return vec3(viewOneMeter * linearDepth, -linearDepth);
}

void main()
{
  float depth = textureLod(texDepth, inTexcoord, 0).x;
  vec3 positionVS = GetViewSpacePosition(inTexcoord, depth);

  // Derivatives first, while every pixel of the 2x2 quad is still running the same code.
  vec3 dpdx = dFdx(positionVS);
  vec3 dpdy = dFdy(positionVS);
  vec3 c = cross(dpdy, dpdx);
  float len2 = dot(c, c);
  // Guard normalize(0): where the quad has no area (flat depth, sky) there is no usable normal.
  // A quad straddling a depth edge has a meaningless normal too (it would draw dark outlines).
  bool onEdge = max(abs(dpdx.z), abs(dpdy.z)) > 0.1 * depth;
  bool hasNormal = len2 > 1e-30 && !onEdge;
  vec3 normalVS = hasNormal ? c * inversesqrt(len2) : vec3(0, 0, 1);
  bool isSky = depth >= CAMERA_FAR;

  // Lesson 6's checkpoint: the normal's y where there is one.
  outColor = hasNormal ? normalVS.y : 0.0;
}
