#version 450

// Visibility-bitmask AO (after Therrien et al. 2023): per slice, a 32-bit mask of occluded sectors.
// Each depth sample is a slab from its surface to aoThickness behind it along its camera ray, clipped
// to the radius sphere around the pixel (the reference counts a ray as blocked by a hit within the
// radius). The sectors have equal cosine-weighted measure in the slice, so the set bits are the
// occluded fraction of the quantity the ray tracer measures. With two depth layers a second march (the
// first's steps up to 8; beyond, half of them but never fewer than 8) adds at each of its taps the
// slab of the nearest surface hidden there (the second_layer pass), reaching that surface's own back
// face when the back faces are drawn for it too.

#include "common.glsl"

layout(location=204) uniform float aoThickness; // metres behind each depth sample
layout(location=205) uniform int aoBackFaces;   // 1: each tap's thickness from texBackDepth
layout(location=207) uniform int aoLayers;      // 2: each tap also marches texSecondDepth
layout(location=208) uniform int aoLayerBackFaces; // 1: the second layer's thickness from texSecondBackDepth
layout(binding=1) uniform sampler2D texBackDepth; // linear depth of the back faces (m), AO size
layout(binding=3) uniform sampler2D texSecondDepth; // linear depth of the second layer (m), AO size
layout(binding=4) uniform sampler2D texSecondBackDepth; // its back faces' linear depth (m), AO size
layout(location=209) uniform int aoSlabLevels;  // >0: taps read texSlabs' levels, 0: texDepth
// Per level, the nearest slab under each texel: (front, back) in metres and its own texel
// (ao/slab_hierarchy.frag).
layout(binding=5) uniform sampler2D texSlabs;

// Which of the inputs above a frame reads, fixed at compile time by the engine from its settings
// (ao/method/vbao.rs): a software rasteriser runs the code of every branch, taken or not, so leaving
// the unused paths in cost the plain configuration twice its time on llvmpipe. VBAO_SLABS: 1 = the
// taps read texSlabs, 0 = texDepth, 2 = aoSlabLevels decides; the others 0 = left out, 1 = compiled
// (their uniform decides). Without the defines every path is compiled and the uniforms decide.
#ifndef VBAO_SLABS
#define VBAO_SLABS 2
#endif
#ifndef VBAO_BACK_FACES
#define VBAO_BACK_FACES 1
#endif
#ifndef VBAO_SECOND_LAYER
#define VBAO_SECOND_LAYER 1
#endif
#ifndef VBAO_SECOND_LAYER_BACK_FACES
#define VBAO_SECOND_LAYER_BACK_FACES 1
#endif

const int SECTORS = 32;
// The second layer's slab reaches its back face but is never thinner than this fraction of the set
// thickness (R/2, so R/8): exact slabs of a hidden 2 cm board leave gaps between the taps that let
// light through, R/2 makes it a wall. Chosen on the bench's training cameras
// (docs/bench/vbao/layer2-backfaces.md).
// (The screen-space reference applies the same floor: LAYER2_MIN_THICKNESS_OF_SET in
// src/ao/settings.rs, which a test holds equal to this.)
const float LAYER2_MIN_THICKNESS = 0.25;
// With the slab hierarchy, a tap reads the level whose texels are half the gap to the previous
// tap (rounded down to a power of two), and widens each slab to SLAB_SPACING_K spacings of the taps
// (in metres at its depth, at most aoThickness): a surface crossed by consecutive taps, each a slab
// as thin as the object, would leave the sectors between them open. A texel as wide as the whole
// gap reaches as far sideways, off the slice, where a block's nearest slab is more often a near
// surface beside the slice. Chosen on the bench's training cameras (960x540, high, R = 1 m, back
// faces) over biases 0, -1, -2 and K = 2, 3, 4: -1 and 3 had the best sum of the pairs that left
// no camera of the three scenes below the hierarchy off.
const int SLAB_LEVEL_BIAS = -1;
const float SLAB_SPACING_K = 3.0;

// Cosine-weighted measure of the slice from angle 0 (the view vector) to g + b, signed, for the normal
// at angle g from V and a direction at angle b from the normal: the integral of cos(t - g) * |sin t|
// (the |sin t| is the slice parametrisation's Jacobian, as in GTAO's closed form), i.e.
// 0.25 * (-cos(2t - g) + cos g + 2t sin g) with t = g + b. cos(2t - g) = cos(2b + g) comes from
// cos 2b and sin 2b, which the caller has without trigonometry.
float SliceMeasure(float b, float cos2b, float sin2b, float cosG, float sinG, float g) {
  float t = g + b;
  float m = 0.25 * (-(cos2b * cosG - sin2b * sinG) + cosG + 2.0 * t * sinG);
  return t >= 0.0 ? m : -m;
}

// atan(y / x) for x > 0 (a direction above the tangent plane), within 1e-5 rad: a minimax polynomial
// on [-1, 1] and the complement beyond. The sectors are pi/32 wide at most, so the error is 1/3000 of
// one; the hardware atan costs several times more on a software rasteriser.
float AtanRight(float y, float x) {
  float ay = abs(y);
  float r = min(ay, x) / max(max(ay, x), 1e-30);
  float r2 = r * r;
  float a = r * (0.99997726 + r2 * (-0.33262347 + r2 * (0.19354346 + r2 * (-0.11643287
          + r2 * (0.05265332 + r2 * -0.01172120)))));
  a = ay > x ? 0.5 * PI - a : a;
  return y < 0.0 ? -a : a;
}

// Bits [first, last) set (none when last <= first).
uint SectorBits(int first, int last) {
  int count = last - first;
  uint bits = count >= SECTORS ? 0xffffffffu : ((1u << uint(max(count, 0))) - 1u) << uint(first);
  return count > 0 ? bits : 0u;
}

// One slice of one pixel: what every slab of its taps is measured against.
struct Slice {
  vec3 origin;   // the pixel's point lifted by the bias
  float outside; // |origin|^2 - radius^2: the ray-sphere test's constant
  vec3 n;        // surface normal divided by the length of its projection into the slice plane
  vec3 tSlice;   // the slice's tangent
  float cosG, sinG, g; // angle of the projected normal from V
  float measureLo, toSector; // slice measure at -pi/2, and measure -> sectors
};

// A direction (u along the normal, v along the slice's tangent, u >= 0) as (angle from the normal,
// cos 2b, sin 2b), what SliceMeasure takes.
vec3 SliceAngle(float u, float v) {
  float inv = 1.0 / max(u * u + v * v, 1e-30);
  return vec3(AtanRight(v, u), (u * u - v * v) * inv, 2.0 * u * v * inv);
}

// Sectors of the slice occluded by the slab on the camera ray X(d) = e * d from depth 'front' to
// 'front + thickness', clipped to the radius sphere around the origin. Written without early
// returns: a software rasteriser runs every branch for a group of pixels anyway, so the cases that
// occlude nothing are masked out at the end instead of skipped.
uint SlabBits(Slice sl, vec3 e, float front, float thickness) {
  // Part of the ray within the radius of the origin: |e d - origin|^2 <= r^2.
  float ee = dot(e, e);
  float eo = dot(e, sl.origin);
  float disc = eo * eo - ee * sl.outside;
  float root = sqrt(max(disc, 0.0));
  float invEE = 1.0 / ee;
  float d0 = max(front, (eo - root) * invEE);
  float d1 = min(front + thickness, (eo + root) * invEE);
  // Angles from the projected normal (towards ortho): the hemisphere is (-pi/2, pi/2) and
  // atan never wraps there. Measured from V instead, a floor seen at a grazing angle puts its
  // far points near -V, where the angle jumps from pi to -pi and one slab would fill the mask.
  vec3 a = e * d0 - sl.origin;
  vec3 b = e * d1 - sl.origin;
  // Heights use the full normal: a tap rounded to a texel lies up to half a texel off the
  // slice plane, and its height along the projected normal alone would lift a flat floor's
  // neighbours above the tangent plane. Divided by the projection's length (in sl.n) they equal
  // the in-slice heights for points in the plane.
  float ua = dot(a, sl.n), va = dot(a, sl.tSlice);
  float ub = dot(b, sl.n), vb = dot(b, sl.tSlice);
  // An end below the tangent plane is replaced by the point where the slab crosses it, on the side
  // where it crosses (b = +-pi/2: the direction (0, +-1)); the side is the sign of the crossing's
  // tangent coordinate (ua vb - ub va) / (ua - ub).
  float side = (ua * vb - ub * va) * (ua - ub) >= 0.0 ? 1.0 : -1.0;
  vec3 endA = SliceAngle(max(ua, 0.0), ua > 0.0 ? va : side);
  vec3 endB = SliceAngle(max(ub, 0.0), ub > 0.0 ? vb : side);
  bool swap = endA.x > endB.x;
  vec3 lo = swap ? endB : endA;
  vec3 hi = swap ? endA : endB;
  float from = SliceMeasure(lo.x, lo.y, lo.z, sl.cosG, sl.sinG, sl.g);
  float to = SliceMeasure(hi.x, hi.y, hi.z, sl.cosG, sl.sinG, sl.g);
  int first = clamp(int(round((from - sl.measureLo) * sl.toSector)), 0, SECTORS);
  int last = clamp(int(round((to - sl.measureLo) * sl.toSector)), 0, SECTORS);
  // Nothing: the ray misses the sphere, the slab ends before the sphere begins (or the reverse),
  // or the whole slab is below the tangent plane (a segment between two points below it).
  bool occludes = disc > 0.0 && d1 > d0 && (ua > 0.0 || ub > 0.0);
  return occludes ? SectorBits(first, last) : 0u;
}

// A slice at angle phi: its screen direction, the direction ortho to V in its plane, the normal
// projected into it (length and angle g from V, measured towards ortho) and its cosine-weighted
// measure from -pi/2 to pi/2 about the normal; projLen 0 when the normal is edge-on to the slice.
struct SliceSetup {
  vec2 dir;
  vec3 ortho;
  float projLen;
  float g;
  float cosG;
  float sinG;
  float measureLo;
  float total;
};

SliceSetup SetUpSlice(float phi, vec3 n, vec3 V) {
  SliceSetup st;
  st.dir = vec2(cos(phi), sin(phi));
  vec3 ortho = vec3(st.dir, 0.0) - st.dir.x * V.x * V - st.dir.y * V.y * V;
  st.ortho = ortho * inversesqrt(max(dot(ortho, ortho), 1e-12));
  vec3 axis = cross(st.ortho, V);
  vec3 projN = n - axis * dot(n, axis);
  st.projLen = length(projN);
  if (st.projLen < 1e-6) {
    // No weight: every field defined, so a caller's product stays 0.
    st.projLen = 0.0;
    st.g = 0.0;
    st.cosG = 1.0;
    st.sinG = 0.0;
    st.measureLo = 0.0;
    st.total = 0.0;
    return st;
  }
  st.g = atan(dot(projN, st.ortho), dot(projN, V));
  st.cosG = cos(st.g);
  st.sinG = sin(st.g);
  // The hemisphere: b from -pi/2 (cos 2b = -1, sin 2b = 0) to pi/2.
  st.measureLo = SliceMeasure(-0.5 * PI, -1.0, 0.0, st.cosG, st.sinG, st.g);
  st.total = SliceMeasure(0.5 * PI, -1.0, 0.0, st.cosG, st.sinG, st.g) - st.measureLo;
  return st;
}

// A tap's slab from the hierarchy: the level of texels about as wide as the gap to the previous tap
// (pixels), whose nearest slab stands for what the tap would skip, on that slab's own ray.
void TapFromSlabs(ivec2 q, float gap, out float zq, out float thickness, out vec2 ray) {
  int level = clamp(int(floor(log2(max(gap, 1.0)))) + SLAB_LEVEL_BIAS, 0, aoSlabLevels - 1);
  vec4 slab = texelFetch(texSlabs, q >> level, level);
  zq = slab.x;
  // Never thinner than the taps' spacing there (m): see SLAB_SPACING_K.
  float spacing = SLAB_SPACING_K * gap * zq / AO_PROJ_SCALE;
  thickness = max(slab.y - slab.x, min(spacing, aoThickness));
  ray = slab.zw;
}

// A tap's slab from the texel itself: the set thickness, or down to the back face behind it where
// the back faces are drawn and there is one ('far' where none: open planes, sky).
void TapFromDepth(ivec2 q, out float zq, out float thickness) {
  zq = texelFetch(texDepth, q, 0).x;
  thickness = aoThickness;
#if VBAO_BACK_FACES
  if (aoBackFaces != 0) {
    float back = texelFetch(texBackDepth, q, 0).x;
    thickness = back > zq && back < CAMERA_FAR ? max(back - zq, aoThickness) : aoThickness;
  }
#endif
}

// Each pixel's slice angle, as a fraction of a half turn: interleaved gradient noise (Jimenez 2014)
// on the pixel shifted and with its axes swapped, so it does not follow StepNoise. With one slice per
// pixel the 4x4 tile of the other methods (NoiseAngle) repeats every 4 texels, and the blur left faint
// stripes that the up-sampling widens (16 output pixels apart at a quarter of the size); this noise
// has no period, and the training cameras scored the same (sums of six: 170.47 -> 170.63 dB at a
// quarter of the size, `high`, two layers; 121.28 -> 121.32 at `low`, the scenes' defaults).
float SliceAngleNoise(ivec2 p) {
  return fract(52.9829189 * fract(dot(vec2(p) + vec2(5.0, 11.0), vec2(0.00583715, 0.06711056)))
      + aoFrameJitter.x);
}

// Angles of the mean slice weight: the weight is a smooth function of the angle with period pi, for
// which evenly spaced points converge fast. On the training cameras 4 scored within 0.1 dB (sums of
// six) of 8 at `low` and `ultra`, 2 up to 1.3 dB off; each costs a slice's set-up (no taps).
const int WEIGHT_ANGLES = 4;

void main()
{
  ivec2 pix = ivec2(gl_FragCoord.xy);
  ivec2 size = ivec2(DepthSize());
  float z = TexelDepth(pix);
  WriteOcclusion(0.0, z);
  if (IsSky(z)) {
    return;
  }
  vec3 P = TexelPos(pix);
  float ssR = min(AO_PROJ_SCALE * AO_RADIUS / z, maxRadiusPixels);
  if (ssR < 1.0) {
    return;
  }
  vec3 n = SurfaceNormal(pix, P);
  vec3 V = normalize(-P);
  // The bias lifts the origin off the surface, as the ray tracer's rays leave it (no self-hits from a
  // reconstructed normal that is slightly off).
  vec3 origin = P + n * AO_BIAS;
  float r2 = AO_RADIUS * AO_RADIUS;
  int slices = max(aoCounts.x, 1);
  int steps = max(aoCounts.y, 1);
  float angleNoise = SliceAngleNoise(pix);
  float stepNoise = StepNoise(pix);
  // Sum of each slice's weight, and of its open part: their ratio is exactly 1 on an open surface
  // whatever the slice count (averaging the open parts alone reaches 1 only over many slices).
  float weight = 0;
  float openPart = 0;
  for (int s = 0; s < slices; ++s) {
    SliceSetup st = SetUpSlice(PI * (float(s) + angleNoise) / float(slices), n, V);
    if (st.projLen == 0.0) {
      continue;
    }
    vec2 dir = st.dir;
    vec3 ortho = st.ortho;
    float projLen = st.projLen;
    float g = st.g;
    float cosG = st.cosG;
    float sinG = st.sinG;
    float measureLo = st.measureLo;
    float total = st.total;
    float toSector = float(SECTORS) / max(total, 1e-6);
    // The slice's tangent: the projected normal turned a quarter towards ortho.
    vec3 tSlice = cosG * ortho - sinG * V;
    Slice slice = Slice(origin, dot(origin, origin) - r2, n / projLen, tSlice, cosG, sinG, g,
        measureLo, toSector);
    uint mask = 0u;
    for (int side = 0; side < 2 && mask != 0xffffffffu; ++side) {
      vec2 sideDir = side == 0 ? -dir : dir;
      float previous = 0.0; // the previous tap's distance (pixels); the pixel itself first
      for (int j = 0; j < steps; ++j) {
        // Even spacing out to the radius: a slab covers its sectors only where a tap lands on it,
        // and far slabs are as likely to be thin as near ones. On the bench's training cameras
        // (1920x1080, R = 1 m, four presets x three configurations) even spacing scored above
        // quadratic spacing (more taps near the pixel) in every case, by up to 7 dB summed at `low`
        // (docs/bench/vbao/steps-or-slices.md).
        float t = (float(j) + stepNoise) / float(steps);
        float dist = t * ssR + 1.0;
        float gap = dist - previous;
        previous = dist;
        vec2 offset = sideDir * dist;
        ivec2 q = pix + ivec2(round(offset));
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) {
          break; // off screen: nothing is known there, and every farther step is off too
        }
        vec2 ray = vec2(q);
        float zq;
        float thickness;
#if VBAO_SLABS == 1
        TapFromSlabs(q, gap, zq, thickness, ray);
#elif VBAO_SLABS == 0
        TapFromDepth(q, zq, thickness);
#else
        if (aoSlabLevels > 0) {
          TapFromSlabs(q, gap, zq, thickness, ray);
        } else {
          TapFromDepth(q, zq, thickness);
        }
#endif
        if (IsSky(zq)) {
          continue;
        }
        // The sample's camera ray, parametrised by linear depth: X(d) = e * d.
        vec3 e = vec3(((ray + 0.5) / vec2(size) * 2.0 - 1.0) * ndcToView, -1.0);
        mask |= SlabBits(slice, e, zq, thickness);
      }
#if VBAO_SECOND_LAYER
      // The nearest surface hidden behind each tap ('far' where none), reaching its own back face
      // when the back faces are drawn (never thinner than LAYER2_MIN_THICKNESS of the set
      // thickness; the set thickness where none lies behind it), else the set thickness. A march of
      // its own: a software rasteriser pays for every slab of a group of pixels whether a second
      // layer is there or not, so past 8 steps it takes half the first march's. On the bench's
      // training cameras (quarter AO size, back faces, R = 1 m, sums over six cameras) half the
      // steps lost 3.1 dB at `low` and 1.6 at `medium`, but 0.6 at `high` for about a tenth of the
      // AO chain's time.
      int layerSteps = max(steps / 2, min(steps, 8));
      for (int j = 0; j < layerSteps && aoLayers > 1; ++j) {
        float t = (float(j) + stepNoise) / float(layerSteps);
        ivec2 q = pix + ivec2(round(sideDir * (t * ssR + 1.0)));
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) {
          break;
        }
        float hidden = texelFetch(texSecondDepth, q, 0).x;
        float thickness2 = aoThickness;
#if VBAO_SECOND_LAYER_BACK_FACES
        if (aoLayerBackFaces != 0) {
          float back2 = texelFetch(texSecondBackDepth, q, 0).x;
          thickness2 = back2 > hidden && back2 < CAMERA_FAR
              ? max(back2 - hidden, LAYER2_MIN_THICKNESS * aoThickness) : aoThickness;
        }
#endif
        // On the tap's own camera ray.
        vec3 eq = vec3(((vec2(q) + 0.5) / vec2(size) * 2.0 - 1.0) * ndcToView, -1.0);
        uint bits = SlabBits(slice, eq, hidden, thickness2);
        mask |= hidden < CAMERA_FAR ? bits : 0u;
      }
#endif
    }
    weight += projLen * total;
    openPart += projLen * total * (1.0 - float(bitCount(mask)) / float(SECTORS));
  }
  // Each slice's occluded weight against the mean slice weight over the angle: unbiased whatever
  // the slice count, where the ratio of the sums leaves a one-slice pixel unweighted (the blur then
  // averages light and heavy slices alike). On the bench's training cameras it scored 0.9-3.4 dB
  // (sums of six) above the ratio with every preset and configuration
  // (docs/bench/vbao/steps-or-slices.md); an open surface still comes out exactly 1.
  float meanWeight = 0.0;
  for (int k = 0; k < WEIGHT_ANGLES; ++k) {
    SliceSetup st = SetUpSlice(PI * (float(k) + 0.5) / float(WEIGHT_ANGLES), n, V);
    meanWeight += st.projLen * st.total;
  }
  meanWeight /= float(WEIGHT_ANGLES);
  float occludedPart = weight - openPart;
  float visibility = meanWeight > 0.0
      ? clamp(1.0 - occludedPart / (float(slices) * meanWeight), 0.0, 1.0) : 1.0;
  WriteOcclusion(ApplyIntensity(1.0 - visibility), z);
}
