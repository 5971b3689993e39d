#version 450

// Angle-based SSAO (Unreal Engine 4; Mittring 2012): pairs of samples at equal distance on opposite sides of
// the pixel; the angles the two make above the surface (behind the normal's hemisphere clamped to 0,
// beyond the radius faded out) say how much of the half-circle they close off.

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
  int pairs = max(aoCounts.x, 1);
  float rot = NoiseAngle(pix);
  float sum = 0;
  for (int i = 0; i < pairs; ++i) {
    // Stratified angles and lengths (each pair in its own sector and length band).
    float ang = (float(i) + 0.5) / float(pairs) * PI + rot;
    float len = mix(0.1, 1.0, (float(i) + 0.5) / float(pairs));
    vec2 o = vec2(cos(ang), sin(ang)) * len * ssR;
    float pairOcclusion = 0;
    for (int side = -1; side <= 1; side += 2) {
      ivec2 q = pix + ivec2(round(o * float(side)));
      if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(DepthSize())))) {
        continue; // off screen: unknown, not the border texel repeated (which fakes occluders)
      }
      vec3 D = TexelPos(q) - P;
      float dist = length(D);
      if (dist < 1e-6) {
        continue;
      }
      // Elevation above the tangent plane, clamped at 0 (behind the normal's hemisphere).
      float elevation = asin(clamp(dot(D / dist, n), 0.0, 1.0));
      float fade = clamp(2.0 - 2.0 * dist / AO_RADIUS, 0.0, 1.0);
      pairOcclusion += elevation * fade;
    }
    sum += pairOcclusion / PI;
  }
  WriteOcclusion(ApplyIntensity(clamp(sum / float(pairs), 0.0, 1.0)), z);
}
