#version 450

// Horizon-based AO (Bavoil, Sainz and Dimitrov 2008): for each screen direction, march in pixel
// steps (snapped to texel centres) and raise the horizon; occlusion is the rise of sin(horizon) above
// the tangent plane, weighted by W(r) = 1 - r^2/R^2.

// The engine's header: inputs, uniforms, WriteOcclusion (found in the engine's Res/ao/ when it is
// not beside this file).
#include "common.glsl"

// SIN_BIAS comes from my_hbao.toml (0.1736 = sin 10 degrees): it hides tessellation creases.
const float sinBias = SIN_BIAS;

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
  int dirs = max(aoCounts.x, 1);
  int steps = max(aoCounts.y, 1);
  float stepPx = ssR / float(steps + 1);
  float jitter = NoiseAngle(pix);
  float stepNoise = StepNoise(pix);
  float r2 = AO_RADIUS * AO_RADIUS;
  float sum = 0;
  for (int d = 0; d < dirs; ++d) {
    float ang = 2.0 * PI * float(d) / float(dirs) + jitter;
    vec2 dir = vec2(cos(ang), sin(ang));
    // Horizons are measured as elevation above the tangent plane itself (sin = D.n / |D|, as HBAO+
    // does), which is perspective-correct by construction: a floor's taps lie on that plane whatever
    // screen direction or texel rounding brought them there. (The tangent taken as the view-space
    // direction (dir, 0) projected onto the plane made an open floor in perspective rise above it:
    // 10.6 % false occlusion.) The bias keeps tessellation creases below the first horizon.
    float sinPrev = sinBias;
    for (int s = 1; s <= steps; ++s) {
      // Start half a step out with a per-pixel offset, snapped to the texel centre.
      float dist = (float(s) - 0.5 + stepNoise) * stepPx + 1.0;
      ivec2 q = pix + ivec2(round(dir * dist));
      if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(DepthSize())))) {
        break; // off screen: unknown, not the border texel repeated (which fakes occluders)
      }
      vec3 D = TexelPos(q) - P;
      float dd = dot(D, D);
      if (dd > r2 || dd < 1e-12) {
        continue;
      }
      float sinH = dot(D, n) * inversesqrt(dd);
      if (sinH > sinPrev) {
        sum += (1.0 - dd / r2) * (sinH - sinPrev);
        sinPrev = sinH;
      }
    }
  }
  WriteOcclusion(ApplyIntensity(clamp(sum / float(dirs), 0.0, 1.0)), z);
}
