#version 450

// Horizon-based AO (seed 000 §3, Bavoil et al. 2008): for each screen direction, march in pixel
// steps (snapped to texel centres) and raise the horizon angle; occlusion is the rise of sin(horizon)
// above the tangent plane, weighted by W(r) = 1 - r^2/R^2.

#include "common.glsl"

const float tangentBias = 0.1745; // 10 degrees: hides tessellation creases

void main()
{
  ivec2 pix = ivec2(gl_FragCoord.xy);
  vec3 P = TexelPos(pix);
  float z = -P.z;
  outColor = 0;
  if (IsSky(z)) {
    return;
  }
  float ssR = min(AO_PROJ_SCALE * AO_RADIUS / z, maxRadiusPixels);
  if (ssR < 1.0) {
    return;
  }
  vec3 n = ReconstructNormal(pix, P);
  int dirs = max(aoCounts.x, 1);
  int steps = max(aoCounts.y, 1);
  float stepPx = ssR / float(steps + 1);
  float jitter = NoiseAngle(pix);
  float r2 = AO_RADIUS * AO_RADIUS;
  float sum = 0;
  for (int d = 0; d < dirs; ++d) {
    float ang = 2.0 * PI * float(d) / float(dirs) + jitter;
    vec2 dir = vec2(cos(ang), sin(ang));
    // Tangent of the surface along this screen direction, perspective-correct: the samples follow
    // the surface where the plane through the eye, P and the screen direction cuts it, so the tangent
    // is the line where that plane meets the tangent plane. (The view-space direction (dir, 0)
    // projected onto the tangent plane is another line: a floor seen in perspective then rises
    // above it, a false occlusion of 10 % on an open floor.)
    vec3 sliceNormal = cross(P, vec3(dir, 0.0));
    vec3 t = cross(n, sliceNormal);
    // Orient it so that it moves on screen along +dir (d(xy / -z) = t.xy * -P.z + P.xy * t.z).
    if (dot(t.xy * -P.z + P.xy * t.z, dir) < 0.0) {
      t = -t;
    }
    float tanAngle = atan(t.z, max(length(t.xy), 1e-6)) + tangentBias;
    float sinPrev = sin(tanAngle);
    float horizon = tanAngle;
    for (int s = 1; s <= steps; ++s) {
      // Start half a step out with a per-pixel offset, snapped to the texel centre.
      float dist = (float(s) - 0.5 + fract(jitter * 0.159)) * stepPx + 1.0;
      ivec2 q = pix + ivec2(round(dir * dist));
      vec3 D = TexelPos(q) - P;
      float dd = dot(D, D);
      if (dd > r2 || dd < 1e-12) {
        continue;
      }
      float h = atan(D.z, length(D.xy));
      if (h > horizon) {
        float sinH = sin(h);
        sum += (1.0 - dd / r2) * (sinH - sinPrev);
        sinPrev = sinH;
        horizon = h;
      }
    }
  }
  outColor = ApplyIntensity(clamp(sum / float(dirs), 0.0, 1.0));
}
