#version 450

// Crytek-style SSAO (Mittring 2007): points in a sphere around the pixel, each compared
// with the depth buffer; a point behind the stored surface (within the range) is occluded.
// An open plane hides half the sphere, so the occluded fraction is rescaled: 0.5 -> 0, 1 -> 1.

#include "common.glsl"

void main()
{
  ivec2 pix = ivec2(gl_FragCoord.xy);
  vec3 P = TexelPos(pix);
  WriteOcclusion(0.0, -P.z);
  if (IsSky(-P.z)) {
    return;
  }
  int count = max(aoCounts.x, 1);
  float rot = NoiseAngle(pix);
  float occluded = 0;
  for (int i = 0; i < count; ++i) {
    // Fibonacci sphere directions, radii growing with i so that more samples lie near the centre.
    float t = (float(i) + 0.5) / float(count);
    float cz = 1.0 - 2.0 * t;
    float sr = sqrt(max(0.0, 1.0 - cz * cz));
    float phi = float(i) * 2.39996323 + rot;
    vec3 dir = vec3(sr * cos(phi), sr * sin(phi), cz);
    float scale = mix(0.1, 1.0, fract(float(i) * 0.618034 + 0.5));
    vec3 S = P + dir * scale * AO_RADIUS;
    vec2 uv = ProjectToUv(S);
    if (any(lessThan(uv, vec2(0))) || any(greaterThan(uv, vec2(1)))) {
      continue; // off screen: unknown, count as open
    }
    float zs = TexelDepth(ivec2(uv * DepthSize()));
    float behind = -S.z - zs; // > 0: the sample lies behind the visible surface
    // Range check (min/max distance): far-away occluders in front do not count.
    if (behind > AO_BIAS && behind < AO_RADIUS) {
      occluded += 1.0;
    }
  }
  float fraction = occluded / float(count);
  WriteOcclusion(ApplyIntensity(clamp(2.0 * fraction - 1.0, 0.0, 1.0)), -P.z);
}
