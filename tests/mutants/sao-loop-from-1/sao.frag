#version 450

// The SAO pass (third of four): Scalable Ambient Obscurance (McGuire et al. 2012) on the linear-depth mip chain.
// Output: occlusion in [0,1] (0 = open, 1 = fully occluded).

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
  vec3 c = cross(dpdx, dpdy);
  float len2 = dot(c, c);
  // Guard normalize(0): where the quad has no area (flat depth, sky) there is no usable normal.
  // A quad straddling a depth edge has a meaningless normal too (it would draw dark outlines).
  bool onEdge = max(abs(dpdx.z), abs(dpdy.z)) > 0.1 * depth;
  bool hasNormal = len2 > 1e-30 && !onEdge;
  vec3 normalVS = hasNormal ? c * inversesqrt(len2) : vec3(0, 0, 1);
  bool isSky = depth >= CAMERA_FAR;

  const ivec2 iuv = ivec2(gl_FragCoord.xy);
  const float startAngle = mod(float((3 * iuv.x ^ iuv.y + iuv.x * iuv.y) * 10), twoPi);

  // Radius in texture coordinates (vertical) and in pixels at this depth.
  vec2 size = vec2(textureSize(texDepth, 0));
  float radiusTS = RADIUS_IN_TEXCOORDS / depth;
  float pixelsSS = radiusTS * size.y;
  // The disc is round on screen: texture coordinates are stretched by the aspect ratio horizontally.
  vec2 aspectFix = vec2(size.y / size.x, 1);

  // How much the depth changes per level-0 texel here, and the distance of this surface's plane
  // from the camera (both for the mip bias below).
  float slopePerTexel = abs(dpdx.z) + abs(dpdy.z);
  float planeDistance = abs(dot(positionVS, normalVS));

  float occlusion = 0;
  if (!isSky && hasNormal) {
    for (int i = 1; i < int(samplingCount); ++i) {
      float ratio = (float(i) + 0.5) * (1.0 / samplingCount);
      float angle = ratio * (spiralTurns * twoPi) + startAngle;
      vec2 unitOffset = vec2(cos(angle), sin(angle));
      vec2 uv = inTexcoord + ratio * radiusTS * unitOffset * aspectFix;
      // Rebuild the sample at the centre of the texel whose depth is read: off-centre, a sloped
      // surface would look up to half a texel's slope above itself.
      uv = (floor(clamp(uv, vec2(0), vec2(1)) * size) + 0.5) / size;

      // Farther samples read coarser levels (fewer cache misses). The level must really exist and
      // the sampler must use a mipmap filter, or every level reads level 0.
      int mipLevel = clamp(findMSB(int(ratio * pixelsSS)) - logMipOffset, 0, maxMipLevel);
      float sampleDepth = textureLod(texDepth, uv, float(mipLevel)).x;
      vec3 samplePositionVS = GetViewSpacePosition(uv, sampleDepth);

      vec3 v = samplePositionVS - positionVS;
      float vn = dot(v, normalVS);
      float vv = dot(v, v);
      float f = max(RADIUS2 - vv, 0);
      // A level-L texel holds the nearest depth of its 2^L x 2^L block, up to (2^L - 1) texels of
      // slope closer than the surface at uv; along the normal that fakes a height of
      // depthError * planeDistance / sampleDepth. Raise the bias by it so slopes don't self-occlude.
      float depthError = float((1 << mipLevel) - 1) * slopePerTexel;
      float mipBias = depthError * planeDistance / max(sampleDepth, 1e-6);
      occlusion += f * f * f * max((vn - BIAS - mipBias) / (vv + 0.001), 0);
    }
  }
  occlusion = min(1.0, occlusion / samplingCount * INTENSITY);

  // Average with the neighbours on near-flat surfaces (cheap 2x2 smoothing): first along x, then
  // along y of the row-averaged value, which gives the mean of the quad. Each derivative is taken
  // after the branches have joined again, never inside one.
  float dOccX = dFdx(occlusion);
  if (abs(dpdx.z) < 0.02) {
    occlusion -= dOccX * (float(iuv.x & 1) - 0.5);
  }
  float dOccY = dFdy(occlusion);
  if (abs(dpdy.z) < 0.02) {
    occlusion -= dOccY * (float(iuv.y & 1) - 0.5);
  }

  outColor = clamp(occlusion, 0.0, 1.0);
}
