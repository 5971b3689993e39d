#version 450

// Normal-oriented hemisphere SSAO (Filion and McNaughton 2008; the LearnOpenGL SSAO chapter): a kernel in the hemisphere
// around the normal, concentrated toward the point, rotated by a 4x4 noise, with a range check.

#include "common.glsl"

void main()
{
  ivec2 pix = ivec2(gl_FragCoord.xy);
  vec3 P = TexelPos(pix);
  WriteOcclusion(0.0, -P.z);
  if (IsSky(-P.z)) {
    return;
  }
  vec3 n = SurfaceNormal(pix, P);
  // Tangent frame rotated by the noise angle around the normal (Gram-Schmidt).
  float a = NoiseAngle(pix);
  vec3 rnd = vec3(cos(a), sin(a), 0.0);
  vec3 t = rnd - n * dot(rnd, n);
  t = dot(t, t) > 1e-8 ? normalize(t) : normalize(cross(n, vec3(0, 1, 0.01)));
  vec3 b = cross(n, t);
  int count = max(aoCounts.x, 1);
  float sum = 0;
  for (int i = 0; i < count; ++i) {
    float u = (float(i) + 0.5) / float(count);
    float cz = sqrt(1.0 - u);                 // cosine-distributed elevation
    float sr = sqrt(max(0.0, 1.0 - cz * cz));
    float phi = float(i) * 2.39996323;
    vec3 k = vec3(sr * cos(phi), sr * sin(phi), cz);
    float s = u;
    k *= mix(0.1, 1.0, s * s);                // more samples near the point
    vec3 S = P + (t * k.x + b * k.y + n * k.z) * AO_RADIUS;
    vec2 uv = ProjectToUv(S);
    if (any(lessThan(uv, vec2(0))) || any(greaterThan(uv, vec2(1)))) {
      continue;
    }
    float zs = TexelDepth(ivec2(uv * DepthSize()));
    float rangeCheck = smoothstep(0.0, 1.0, AO_RADIUS / max(abs(-P.z - zs), 1e-6));
    sum += (zs <= -S.z - AO_BIAS ? 1.0 : 0.0) * rangeCheck;
  }
  WriteOcclusion(ApplyIntensity(sum / float(count)), -P.z);
}
