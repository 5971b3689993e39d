#version 450

// sao.frag as a student has it at the end of lesson 8: positions and normal (lesson 6), the spiral
// of taps and their mip levels (lesson 7), the occlusion term and its scaling (lesson 8), written
// once, clamped. The 2x2 smoothing of lesson 9 is not there yet.

layout(location=1) in vec2 inTexcoord;
out float outColor;

layout(binding=0) uniform sampler2D texDepth;

layout(location=200) uniform vec4 saoInfo;
#define RADIUS2             (saoInfo.x)
#define RADIUS_IN_TEXCOORDS (saoInfo.y)
#define BIAS                (saoInfo.z)
#define INTENSITY           (saoInfo.w)

layout(location=201) uniform vec2 ndcToView;

#ifndef SAO_SAMPLE_COUNT
#define SAO_SAMPLE_COUNT 11
#endif
#ifndef SAO_SPIRAL_TURNS
#define SAO_SPIRAL_TURNS 3
#endif
#ifndef CAMERA_FAR
#define CAMERA_FAR 1000.0
#endif

const float twoPi = 6.28318531;
const float samplingCount = SAO_SAMPLE_COUNT;
const float spiralTurns = SAO_SPIRAL_TURNS;
const int maxMipLevel = 3;
const int logMipOffset = 3;

vec3 GetViewSpacePosition(vec2 uv, float linearDepth)
{
  return vec3((uv * 2.0 - 1.0) * ndcToView * linearDepth, -linearDepth);
}

void main()
{
  float depth = textureLod(texDepth, inTexcoord, 0.0).r;
  vec3 positionVS = GetViewSpacePosition(inTexcoord, depth);

  vec3 dpdx = dFdx(positionVS);
  vec3 dpdy = dFdy(positionVS);
  vec3 n = cross(dpdx, dpdy);
  bool onEdge = max(abs(dpdx.z), abs(dpdy.z)) > 0.1 * depth;
  bool hasNormal = dot(n, n) > 1e-30 && !onEdge;
  vec3 normalVS = hasNormal ? normalize(n) : vec3(0.0, 0.0, 1.0);
  bool isSky = depth >= CAMERA_FAR;

  ivec2 iuv = ivec2(gl_FragCoord.xy);
  float startAngle = mod(float((3 * iuv.x ^ iuv.y + iuv.x * iuv.y) * 10), twoPi);
  vec2 size = vec2(textureSize(texDepth, 0));
  float radiusTS = RADIUS_IN_TEXCOORDS / depth;
  float pixelsSS = radiusTS * size.y;
  vec2 aspectFix = vec2(size.y / size.x, 1.0);

  float slopePerTexel = abs(dpdx.z) + abs(dpdy.z);
  float planeDistance = abs(dot(positionVS, normalVS));

  float occlusion = 0.0;
  if (!isSky && hasNormal) {
    for (int i = 0; i < int(samplingCount); ++i) {
      float ratio = (float(i) + 0.5) / samplingCount;
      float angle = startAngle + ratio * spiralTurns * twoPi;
      vec2 uv = inTexcoord + ratio * radiusTS * vec2(cos(angle), sin(angle)) * aspectFix;
      uv = (floor(clamp(uv, 0.0, 1.0) * size) + 0.5) / size;
      int mipLevel = clamp(findMSB(int(ratio * pixelsSS)) - logMipOffset, 0, maxMipLevel);
      float sampleDepth = textureLod(texDepth, uv, float(mipLevel)).r;
      vec3 samplePositionVS = GetViewSpacePosition(uv, sampleDepth);

      vec3 v = samplePositionVS - positionVS;
      float vn = dot(v, normalVS);
      float vv = dot(v, v);
      float f = max(RADIUS2 - vv, 0.0);
      float mipBias = float((1 << mipLevel) - 1) * slopePerTexel * planeDistance
                    / max(sampleDepth, 1e-6);
      occlusion += f * f * f * max((vn - BIAS - mipBias) / (vv + 0.001), 0.0);
    }
  }
  occlusion = min(1.0, occlusion / samplingCount * INTENSITY);

  outColor = clamp(occlusion, 0.0, 1.0);
}
