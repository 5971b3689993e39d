#version 450

// Visibility-bitmask AO (after Therrien et al. 2023): per slice, a 32-bit mask of occluded sectors.
// Each depth sample is a slab from its surface to aoThickness behind it along its camera ray, clipped
// to the radius sphere around the pixel (the reference counts a ray as blocked by a hit within the
// radius). The sectors have equal cosine-weighted measure in the slice, so the set bits are the
// occluded fraction of the quantity the ray tracer measures.

#include "common.glsl"

layout(location=204) uniform float aoThickness; // metres behind each depth sample

const int SECTORS = 32;

// Cosine-weighted measure of the slice from angle 0 (the view vector) to h, signed, for the normal
// at angle g: the integral of cos(t - g) * |sin t| (the |sin t| is the slice parametrisation's
// Jacobian, as in GTAO's closed form).
float SliceMeasure(float h, float g) {
  float m = 0.25 * (-cos(2.0 * h - g) + cos(g) + 2.0 * h * sin(g));
  return h >= 0.0 ? m : -m;
}

// Bits [first, last) set.
uint SectorBits(int first, int last) {
  int count = last - first;
  if (count <= 0) {
    return 0u;
  }
  return count >= SECTORS ? 0xffffffffu : ((1u << uint(count)) - 1u) << uint(first);
}

// Independent of NoiseAngle's 4x4 tile (interleaved gradient noise, Jimenez 2014): the step offset
// must not correlate with the slice angle, or every slice of a pixel samples the same distances.
float StepNoise(ivec2 p) {
  return fract(52.9829189 * fract(dot(vec2(p), vec2(0.06711056, 0.00583715))));
}

void main()
{
  ivec2 pix = ivec2(gl_FragCoord.xy);
  ivec2 size = ivec2(DepthSize());
  float z = TexelDepth(pix);
  outColor = 0;
  if (IsSky(z)) {
    return;
  }
  vec3 P = TexelPos(pix);
  float ssR = min(AO_PROJ_SCALE * AO_RADIUS / z, maxRadiusPixels);
  if (ssR < 1.0) {
    return;
  }
  vec3 n = ReconstructNormal(pix, P);
  vec3 V = normalize(-P);
  // The bias lifts the origin off the surface, as the ray tracer's rays leave it (no self-hits from a
  // reconstructed normal that is slightly off).
  vec3 origin = P + n * AO_BIAS;
  float r2 = AO_RADIUS * AO_RADIUS;
  int slices = max(aoCounts.x, 1);
  int steps = max(aoCounts.y, 1);
  float angleNoise = NoiseAngle(pix) / (2.0 * PI);
  float stepNoise = StepNoise(pix);
  // Sum of each slice's weight, and of its open part: their ratio is exactly 1 on an open surface
  // whatever the slice count (averaging the open parts alone reaches 1 only over many slices).
  float weight = 0;
  float openPart = 0;
  for (int s = 0; s < slices; ++s) {
    float phi = PI * (float(s) + angleNoise) / float(slices);
    vec2 dir = vec2(cos(phi), sin(phi));
    vec3 ortho = vec3(dir, 0.0) - dir.x * V.x * V - dir.y * V.y * V;
    ortho *= inversesqrt(max(dot(ortho, ortho), 1e-12));
    vec3 axis = cross(ortho, V);
    vec3 projN = n - axis * dot(n, axis);
    float projLen = length(projN);
    if (projLen < 1e-6) {
      continue;
    }
    // Angles in the slice are measured from V towards ortho.
    float g = atan(dot(projN, ortho), dot(projN, V));
    float lo = g - 0.5 * PI;
    float hi = g + 0.5 * PI;
    float measureLo = SliceMeasure(lo, g);
    float total = SliceMeasure(hi, g) - measureLo;
    float toSector = float(SECTORS) / max(total, 1e-6);
    // The slice's tangent: the projected normal turned a quarter towards ortho.
    vec3 tSlice = cos(g) * ortho - sin(g) * V;
    uint mask = 0u;
    for (int side = 0; side < 2 && mask != 0xffffffffu; ++side) {
      vec2 sideDir = side == 0 ? -dir : dir;
      for (int j = 0; j < steps; ++j) {
        // Quadratic spacing: more taps near the pixel, where occluders subtend larger angles.
        float t = (float(j) + stepNoise) / float(steps);
        vec2 offset = sideDir * (t * t * ssR + 1.0);
        ivec2 q = pix + ivec2(round(offset));
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) {
          break; // off screen: nothing is known there, and every farther step is off too
        }
        float zq = texelFetch(texDepth, q, 0).x;
        if (IsSky(zq)) {
          continue;
        }
        // The sample's camera ray, parametrised by linear depth: X(d) = e * d.
        vec3 e = vec3(((vec2(q) + 0.5) / vec2(size) * 2.0 - 1.0) * ndcToView, -1.0);
        // Part of the ray within the radius of the origin: |e d - origin|^2 <= r^2.
        float ee = dot(e, e);
        float eo = dot(e, origin);
        float disc = eo * eo - ee * (dot(origin, origin) - r2);
        if (disc <= 0.0) {
          continue;
        }
        float root = sqrt(disc);
        float d0 = max(zq, (eo - root) / ee);
        float d1 = min(zq + aoThickness, (eo + root) / ee);
        if (d1 <= d0) {
          continue;
        }
        // Angles from the projected normal (towards ortho): the hemisphere is (-pi/2, pi/2) and
        // atan never wraps there. Measured from V instead, a floor seen at a grazing angle puts its
        // far points near -V, where the angle jumps from pi to -pi and one slab would fill the mask.
        vec3 a = e * d0 - origin;
        vec3 b = e * d1 - origin;
        // Heights use the full normal: a tap rounded to a texel lies up to half a texel off the
        // slice plane, and its height along the projected normal alone would lift a flat floor's
        // neighbours above the tangent plane. Divided by projLen they equal the in-slice heights for
        // points in the plane.
        float ua = dot(a, n) / projLen, va = dot(a, tSlice);
        float ub = dot(b, n) / projLen, vb = dot(b, tSlice);
        if (ua <= 0.0 && ub <= 0.0) {
          continue; // the whole slab is below the tangent plane (a segment between two points below it)
        }
        float ba, bb;
        if (ua > 0.0 && ub > 0.0) {
          ba = atan(va, ua);
          bb = atan(vb, ub);
        } else {
          // The slab crosses the tangent plane: it covers from its upper end down to the plane, on
          // the side where it crosses.
          float crossing = (ua * vb - ub * va) / (ua - ub);
          ba = ua > 0.0 ? atan(va, ua) : atan(vb, ub);
          bb = crossing >= 0.0 ? 0.5 * PI : -0.5 * PI;
        }
        float from = g + min(ba, bb);
        float to = g + max(ba, bb);
        int first = int(round((SliceMeasure(from, g) - measureLo) * toSector));
        int last = int(round((SliceMeasure(to, g) - measureLo) * toSector));
        mask |= SectorBits(clamp(first, 0, SECTORS), clamp(last, 0, SECTORS));
      }
    }
    weight += projLen * total;
    openPart += projLen * total * (1.0 - float(bitCount(mask)) / float(SECTORS));
  }
  float visibility = weight > 0.0 ? clamp(openPart / weight, 0.0, 1.0) : 1.0;
  outColor = ApplyIntensity(1.0 - visibility);
}
