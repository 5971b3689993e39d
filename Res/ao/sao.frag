#version 450

// The engine's own SAO: McGuire's estimator with a disc that is round in view space, texel-centred
// samples, the mip bias of the lesson port, sky and sub-3-pixel discs skipped, the screen radius
// clamped near the camera.

#include "common.glsl"

// Samples 2^LOG_MAX_OFFSET pixels apart share a texel of the level they read (McGuire). The engine
// injects it (`ao::method_pass::LOG_MAX_OFFSET`) and sizes the depth chain so that the largest
// (clamped) disc finds its level.

// (occlusion, linear depth) for the engine's packed blur (ao/blur_packed.frag): one fetch per blur tap.
// Ignored when the target has no second attachment.
void main()
{
  ivec2 pix = ivec2(gl_FragCoord.xy);
  vec3 P = TexelPos(pix);
  float z = -P.z;
  WriteOcclusion(0.0, z);
  if (IsSky(z)) {
    return;
  }
  float ssR = AO_PROJ_SCALE * AO_RADIUS / z; // disc radius in pixels
  if (ssR < 3.0) {
    return; // too small to see: skip the work
  }
  ssR = min(ssR, maxRadiusPixels);
  vec3 n = SurfaceNormal(pix, P);
  float slopePerTexel = abs(TexelDepth(pix + ivec2(1, 0)) - z) + abs(TexelDepth(pix + ivec2(0, 1)) - z);
  float planeDistance = abs(dot(P, n));
  int count = max(aoCounts.x, 1);
  float turns = float(max(aoCounts.y, 1));
  float startAngle = NoiseAngle(pix);
  int maxLevel = textureQueryLevels(texDepth) - 1;
  float r2 = AO_RADIUS * AO_RADIUS;
  float sum = 0;
  for (int i = 0; i < count; ++i) {
    float alpha = (float(i) + 0.5) / float(count);
    float angle = alpha * turns * 2.0 * PI + startAngle;
    float h = alpha * ssR;
    ivec2 q = pix + ivec2(h * vec2(cos(angle), sin(angle)));
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(DepthSize())))) {
      continue; // off screen: unknown, not the border texel repeated (which fakes occluders)
    }
    int level = clamp(findMSB(int(h)) - LOG_MAX_OFFSET, 0, maxLevel);
    float zq = texelFetch(texDepth, q >> level, level).x;
    vec3 Q = ViewPos((vec2(q) + 0.5) / DepthSize(), zq);
    vec3 v = Q - P;
    float vv = dot(v, v);
    float vn = dot(v, n);
    float mipBias = float((1 << level) - 1) * slopePerTexel * planeDistance / max(zq, 1e-6);
    float f = max(r2 - vv, 0.0);
    sum += f * f * f * max((vn - AO_BIAS - mipBias) / (vv + 0.001), 0.0);
  }
  // Same normalisation as the lesson: intensity / r^6 / N, with the lesson's intensity of 5.
  float occlusion = min(1.0, sum / float(count) * 5.0 / (r2 * r2 * r2));
  WriteOcclusion(ApplyIntensity(occlusion), z);
}
