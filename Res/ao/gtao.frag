#version 450

// Ground-truth-based AO (Jimenez et al. 2016): per slice, find the two horizons, then integrate the
// cosine-weighted visibility between them analytically around the normal projected into the slice.
// Converges to the ray-traced visibility of a heightfield.

#include "common.glsl"

void main()
{
  ivec2 pix = ivec2(gl_FragCoord.xy);
  vec3 P = TexelPos(pix);
  float z = -P.z;
  WriteOcclusion(0.0, z);
  if (IsSky(z)) {
    return;
  }
  float ssR = min(AO_PROJ_SCALE * AO_RADIUS / z, maxRadiusPixels);
  if (ssR < 1.0) {
    return;
  }
  vec3 n = SurfaceNormal(pix, P);
  vec3 V = normalize(-P);
  int slices = max(aoCounts.x, 1);
  int steps = max(aoCounts.y, 1);
  float noise = NoiseAngle(pix) / (2.0 * PI);
  float stepNoise = fract(noise * 7.0 + 0.37);
  float visibility = 0;
  float openSum = 0;
  for (int s = 0; s < slices; ++s) {
    float phi = PI * (float(s) + noise) / float(slices);
    vec3 dir = vec3(cos(phi), sin(phi), 0.0);
    vec3 ortho = dir - dot(dir, V) * V;
    vec3 axis = normalize(cross(dir, V));
    vec3 projN = n - axis * dot(n, axis);
    float projLen = length(projN);
    if (projLen < 1e-6) {
      continue;
    }
    float cosN = clamp(dot(projN, V) / projLen, -1.0, 1.0);
    float nAngle = sign(dot(ortho, projN)) * acos(cosN);
    float sinN = sin(nAngle);
    // The slice's tangent: the projected normal turned a quarter towards ortho.
    vec3 tSlice = cosN * normalize(ortho) - sinN * V;
    float hc[2];
    for (int side = 0; side < 2; ++side) {
      float sgn = side == 0 ? -1.0 : 1.0;
      // Lowest possible horizon: the tangent plane on this side.
      float lowCos = cos(nAngle + sgn * 0.5 * PI);
      float best = lowCos;
      for (int j = 0; j < steps; ++j) {
        float dist = (float(j) + stepNoise) / float(steps) * ssR + 1.0;
        ivec2 q = pix + ivec2(round(sgn * dir.xy * dist));
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(DepthSize())))) {
          break; // off screen: unknown, not the border texel repeated (which fakes occluders)
        }
        vec3 D = TexelPos(q) - P;
        float len = length(D);
        if (len < 1e-6) {
          continue;
        }
        // Cosine to V of the tap's direction in the slice, from its height over the tangent plane
        // (full normal) and its position along the slice's tangent: a tap rounded to a texel lies
        // off the slice plane, and dot(D, V) alone would lift a flat floor's taps above it (false
        // occlusion on an open floor). Equal to dot(D, V) / len for taps in the plane.
        float u = dot(D, n) / projLen;
        float v = dot(D, tSlice);
        float c = (cosN * u - sinN * v) * inversesqrt(max(u * u + v * v, 1e-30));
        // Fade occluders out between 0.6 R and R (no hard cut at the radius).
        float w = clamp((AO_RADIUS - len) / (0.4 * AO_RADIUS), 0.0, 1.0);
        best = max(best, mix(lowCos, c, w));
      }
      hc[side] = best;
    }
    float h0 = -acos(clamp(hc[0], -1.0, 1.0));
    float h1 = acos(clamp(hc[1], -1.0, 1.0));
    h0 = nAngle + max(h0 - nAngle, -0.5 * PI);
    h1 = nAngle + min(h1 - nAngle, 0.5 * PI);
    float a0 = -cos(2.0 * h0 - nAngle) + cosN + 2.0 * h0 * sinN;
    float a1 = -cos(2.0 * h1 - nAngle) + cosN + 2.0 * h1 * sinN;
    visibility += projLen * 0.25 * (a0 + a1);
    // The same slice with nothing above the tangent plane: cos(n) + n sin(n).
    openSum += projLen * (cosN + nAngle * sinN);
  }
  // Normalised by the open value of the same slices, not by the slice count: the slice average reaches
  // 1 on an open tilted surface only over many slice angles; per pixel it lands above or below, and
  // clamping the values above 1 left a floor 2.7 % occluded on average.
  visibility = openSum > 0.0 ? clamp(visibility / openSum, 0.0, 1.0) : 1.0;
  WriteOcclusion(ApplyIntensity(1.0 - visibility), z);
}
