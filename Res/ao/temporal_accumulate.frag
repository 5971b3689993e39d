#version 450

// Temporal accumulation of a screen-space method's occlusion (src/ao/temporal.rs). Each frame the
// method draws its samples rotated by another point of a low-discrepancy sequence; this pass
// follows every pixel back into the previous frame through the two cameras, keeps that history only
// where the previous frame saw the same surface there (its depth and normal agree), clamps it to the
// range of the current occlusion around the pixel (so a shadow that moved does not linger), and
// blends it with the current value as a running mean that stops growing at a set length. For rtao
// the clamp is opened wide (its occlusion belongs to the surface point, not to the view, and one
// frame's few rays say little about the range).
//
// The history keeps, per AO texel: (occlusion, frames in the mean, linear depth, world normal code).

layout(location=1) in vec2 inTexcoord;

layout(binding=0) uniform sampler2D texCurrent; // this frame's occlusion (blurred when the blur runs)
layout(binding=1) uniform sampler2D texDepth;   // linear depth (m) at the AO size, level 0
layout(binding=2) uniform sampler2D texHistory; // the previous frame's history (RGBA32F)
layout(binding=3) uniform sampler2D texRaw;     // this frame's occlusion before the blur

layout(location=250) uniform mat4 currentToPrevious; // view space now -> view space of the last frame
layout(location=254) uniform mat3 viewToWorld;       // normals: view space now -> world
layout(location=257) uniform vec2 ndcToView;         // this frame's NDC -> view space at 1 m
layout(location=258) uniform vec2 previousNdcToView; // the last frame's
// (frames the mean stops at, depth tolerance as a fraction of depth, least cosine between the
// normals, how far (in occlusion) the history may lie outside the neighbourhood's range)
layout(location=259) uniform vec4 temporalInfo;
layout(location=260) uniform int historyValid;  // 0: no usable history (first frame, resize, restart)
// rtao: the exponent its intensity applied (intensity / 5), undone for the mean so that the frames
// average the traced occlusion; 1: the values are averaged as they are.
layout(location=261) uniform float temporalCurve;
// rtao: frames of history from which the raw occlusion is blended instead of the blurred (a texel
// that came into view starts from the blurred frame, as a single frame of few rays is); 0: never.
layout(location=262) uniform float blurredFrames;

layout(location=0) out vec4 outHistory;

#ifndef CAMERA_FAR
#define CAMERA_FAR 1000.0
#endif

vec2 Size() { return vec2(textureSize(texDepth, 0)); }

float DepthAt(ivec2 p) {
  return texelFetch(texDepth, clamp(p, ivec2(0), ivec2(Size()) - 1), 0).x;
}

vec3 ViewPos(vec2 uv, float z) { return vec3((uv * 2 - 1) * ndcToView * z, -z); }

vec3 PosAt(ivec2 p) { return ViewPos((vec2(p) + 0.5) / Size(), DepthAt(p)); }

// The normal from the neighbours with the smaller depth step on each axis (as common.glsl's
// ReconstructNormal), and the largest depth step to a neighbour (the depth test's slack on slopes).
vec3 NormalAndSlope(ivec2 p, vec3 c, out float slope) {
  vec3 l = PosAt(p - ivec2(1, 0)), r = PosAt(p + ivec2(1, 0));
  vec3 d = PosAt(p - ivec2(0, 1)), u = PosAt(p + ivec2(0, 1));
  bool useRight = abs(r.z - c.z) < abs(c.z - l.z);
  bool useUp = abs(u.z - c.z) < abs(c.z - d.z);
  vec3 dx = useRight ? r - c : c - l;
  vec3 dy = useUp ? u - c : c - d;
  slope = max(abs(dx.z), abs(dy.z));
  vec3 n = cross(dx, dy);
  float len2 = dot(n, n);
  return len2 > 1e-30 ? n * inversesqrt(len2) : vec3(0, 0, 1);
}

// A unit vector as one float: octahedral coordinates, 11 bits each (exact in a float's mantissa).
float EncodeNormal(vec3 n) {
  n /= max(abs(n.x) + abs(n.y) + abs(n.z), 1e-20);
  vec2 e = n.z >= 0.0 ? n.xy : (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
  vec2 q = floor(clamp(e * 0.5 + 0.5, 0.0, 1.0) * 2047.0 + 0.5);
  return q.x * 2048.0 + q.y;
}

vec3 DecodeNormal(float code) {
  float qx = floor(code / 2048.0);
  vec2 e = vec2(qx, code - qx * 2048.0) / 2047.0 * 2.0 - 1.0;
  vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
  float fold = clamp(-n.z, 0.0, 1.0);
  n.x += n.x >= 0.0 ? -fold : fold;
  n.y += n.y >= 0.0 ? -fold : fold;
  float len2 = dot(n, n);
  return len2 > 1e-20 ? n * inversesqrt(len2) : vec3(0, 0, 1);
}

// The occlusion as traced from the value that went out, and back.
float Uncurved(float v) {
  return temporalCurve == 1.0 ? v : 1.0 - pow(clamp(1.0 - v, 1e-6, 1.0), 1.0 / temporalCurve);
}
float Curved(float v) {
  return temporalCurve == 1.0 ? v : 1.0 - pow(clamp(1.0 - v, 1e-6, 1.0), temporalCurve);
}

void main()
{
  ivec2 pix = ivec2(gl_FragCoord.xy);
  float z = DepthAt(pix);
  float current = texelFetch(texCurrent, pix, 0).x;
#ifdef TEMPORAL_SKY_PASS
  // The first of the two draws (src/ao/temporal.rs): sky texels only, which need no history; the
  // surface texels are left to the second draw, which the depth buffer this one leaves lets through.
  if (z < CAMERA_FAR) {
    discard;
  }
  outHistory = vec4(current, 0.0, z, 0.0);
  return;
#endif
  if (z >= CAMERA_FAR) {
    outHistory = vec4(current, 0.0, z, 0.0);
    return;
  }
  vec3 P = PosAt(pix);
  float slope;
  vec3 nView = NormalAndSlope(pix, P, slope);
  vec3 nWorld = normalize(viewToWorld * nView);

  // The range of this frame's occlusion around the pixel.
  float lo = current, hi = current;
  for (int y = -1; y <= 1; ++y) {
    for (int x = -1; x <= 1; ++x) {
      ivec2 q = clamp(pix + ivec2(x, y), ivec2(0), ivec2(Size()) - 1);
      float v = texelFetch(texCurrent, q, 0).x;
      lo = min(lo, v);
      hi = max(hi, v);
    }
  }

  // Where this surface point was on the last frame's screen, and how far from that camera.
  vec4 q = currentToPrevious * vec4(P, 1.0);
  float expected = -q.z;
  vec2 uv = q.xy / max(expected, 1e-6) / previousNdcToView * 0.5 + 0.5;
  bool inside = historyValid != 0 && expected > 0.0 && all(greaterThanEqual(uv, vec2(0.0)))
      && all(lessThan(uv, vec2(1.0)));
  // The history at uv, bilinear over the texels that hold the same surface: a texel counts when
  // the depth the last frame stored there is the one this point had (within a fraction of the
  // depth, and the depth step to a neighbour, which reprojection off a texel's centre can add on a
  // slope) and the normals agree. Nearest texels instead would shift the history by up to half a
  // texel every frame the camera moves, a blur that grows with the frames.
  vec2 st = uv * Size() - 0.5;
  ivec2 base = ivec2(floor(st));
  vec2 f = st - vec2(base);
  float weight = 0.0, sum = 0.0, frameSum = 0.0;
  for (int k = 0; k < 4; ++k) {
    ivec2 o = ivec2(k & 1, k >> 1);
    ivec2 hp = clamp(base + o, ivec2(0), ivec2(Size()) - 1);
    vec4 h = texelFetch(texHistory, hp, 0);
    float w = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
    bool sameDepth = abs(h.z - expected) <= temporalInfo.y * expected + 2.0 * slope;
    bool sameNormal = h.y > 0.0 && dot(DecodeNormal(h.w), nWorld) >= temporalInfo.z;
    if (inside && sameDepth && sameNormal) {
      weight += w;
      sum += w * h.x;
      frameSum += w * h.y;
    }
  }
  // Too little of the footprint holds the surface: start again from this frame.
  bool kept = weight > 0.25;
  float frames = kept ? frameSum / weight : 0.0;
  float previous = kept ? sum / weight : current;

  if (blurredFrames > 0.0 && frames >= blurredFrames) {
    current = texelFetch(texRaw, pix, 0).x;
  }
  float history = clamp(previous, lo - temporalInfo.w, hi + temporalInfo.w);
  float n = min(frames + 1.0, max(temporalInfo.x, 1.0));
  float blended = frames > 0.0 ? Curved(mix(Uncurved(history), Uncurved(current), 1.0 / n)) : current;
  // A history that went wrong (NaN never compares true) is dropped for the current value.
  blended = blended >= 0.0 && blended <= 1.0 ? blended : current;
  outHistory = vec4(blended, n, z, EncodeNormal(nWorld));
}
