// Shared by the AO methods in Res/ao/ (included with #include "common.glsl").
// Inputs: the half-size linear-depth mip chain the lesson's restore and down-sampling passes make.

layout(location=1) in vec2 inTexcoord;

layout(binding=0) uniform sampler2D texDepth; // linear view distance (m), mip chain of nearest depths

layout(location=200) uniform vec4 aoInfo;     // radius (m), bias (m), intensity, pixels per metre at 1 m
layout(location=201) uniform vec2 ndcToView;  // NDC -> view space at 1 m
layout(location=202) uniform ivec2 aoCounts;  // samples (or directions/slices), steps
layout(location=203) uniform float maxRadiusPixels;
// 1: each pixel's normal is the geometric one of the surface-normal pass (texNormal); 0: rebuilt from
// the depth buffer (ReconstructNormal). The engine also defines AO_SURFACE_NORMALS (0 or 1) from its
// settings so that only one path is compiled: a software rasteriser runs both sides of a branch, even
// one every pixel takes the same way. Without the define both paths stay and this uniform decides.
layout(location=206) uniform int aoSurfaceNormals;
layout(binding=2) uniform sampler2D texNormal; // octahedral view-space normals at the AO size
// This frame's (rotation, step offset) as fractions of their range: the next point of a
// low-discrepancy sequence while frames are accumulated (src/ao/temporal.rs), (0, 0) otherwise.
// NoiseAngle and StepNoise add it, so every pixel's pattern moves on from frame to frame.
layout(location=215) uniform vec2 aoFrameJitter;

// CAMERA_FAR, LOG_MAX_OFFSET and BLUR_REACH come from the engine (`ao::method_pass::method_defines`),
// without a fallback here: a program built without them fails to compile instead of disagreeing.

#define AO_RADIUS (aoInfo.x)
#define AO_BIAS (aoInfo.y)
#define AO_INTENSITY (aoInfo.z)
#define AO_PROJ_SCALE (aoInfo.w)

layout(location=0) out float outColor;
// (occlusion, linear depth) side by side for the packed blur (blur_packed.frag): one fetch per tap
// instead of two. Written through WriteOcclusion only.
layout(location=1) out vec2 outPacked;

// Every method's result goes out through here: the occlusion, and the pair the blur reads.
void WriteOcclusion(float occlusion, float z) {
  outColor = occlusion;
  outPacked = vec2(occlusion, z);
}

const float PI = 3.14159265;

vec2 DepthSize() { return vec2(textureSize(texDepth, 0)); }

bool IsSky(float z) { return z >= CAMERA_FAR; }

// View-space position of texture coordinate uv at linear distance z.
vec3 ViewPos(vec2 uv, float z) { return vec3((uv * 2 - 1) * ndcToView * z, -z); }

// Level-0 depth of a texel, clamped to the texture.
float TexelDepth(ivec2 p) {
  return texelFetch(texDepth, clamp(p, ivec2(0), ivec2(DepthSize()) - 1), 0).x;
}

// View-space position at the centre of texel p.
vec3 TexelPos(ivec2 p) {
  p = clamp(p, ivec2(0), ivec2(DepthSize()) - 1);
  return ViewPos((vec2(p) + 0.5) / DepthSize(), TexelDepth(p));
}

// Texture coordinate where view-space point p projects.
vec2 ProjectToUv(vec3 p) {
  vec2 ndc = p.xy / max(-p.z, 1e-6) / ndcToView;
  return ndc * 0.5 + 0.5;
}

// Normal from the neighbours with the smaller depth step on each axis (no derivatives, so no
// 2x2-quad artefacts at silhouettes); (0,0,1) where it cannot be built.
vec3 ReconstructNormal(ivec2 p, vec3 c) {
  vec3 l = TexelPos(p - ivec2(1, 0)), r = TexelPos(p + ivec2(1, 0));
  vec3 d = TexelPos(p - ivec2(0, 1)), u = TexelPos(p + ivec2(0, 1));
  // On the screen's border the outer neighbour is clamped onto the pixel itself (a zero step):
  // use the inner one there, or the normal degenerates to the view axis.
  ivec2 last = ivec2(DepthSize()) - 1;
  bool useRight = p.x <= 0 || (p.x < last.x && abs(r.z - c.z) < abs(c.z - l.z));
  bool useUp = p.y <= 0 || (p.y < last.y && abs(u.z - c.z) < abs(c.z - d.z));
  vec3 dx = useRight ? r - c : c - l;
  vec3 dy = useUp ? u - c : c - d;
  vec3 n = cross(dx, dy);
  float len2 = dot(n, n);
  return len2 > 1e-30 ? n * inversesqrt(len2) : vec3(0, 0, 1);
}

// The unit vector of an octahedral code (the surface-normal pass encodes with octahedral.glsl).
vec3 DecodeOctahedral(vec2 e) {
  vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
  float fold = clamp(-n.z, 0.0, 1.0);
  n.x += n.x >= 0.0 ? -fold : fold;
  n.y += n.y >= 0.0 ? -fold : fold;
  float len2 = dot(n, n);
  return len2 > 1e-20 ? n * inversesqrt(len2) : vec3(0, 0, 1);
}

// The normal a method uses at texel p (position c): the triangle's own when the surface-normal pass
// ran, else the one rebuilt from depth, which bends across creases and silhouettes.
vec3 SurfaceNormal(ivec2 p, vec3 c) {
#if !defined(AO_SURFACE_NORMALS)
  if (aoSurfaceNormals != 0) {
    return DecodeOctahedral(texelFetch(texNormal, p, 0).xy);
  }
  return ReconstructNormal(p, c);
#elif AO_SURFACE_NORMALS
  return DecodeOctahedral(texelFetch(texNormal, p, 0).xy);
#else
  return ReconstructNormal(p, c);
#endif
}

// A 4x4 tile of rotation angles (the "4x4 noise texture" of the seeds, as arithmetic).
float NoiseAngle(ivec2 p) {
  const float bayer[16] = float[16](0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5);
  return fract((bayer[(p.y & 3) * 4 + (p.x & 3)] + 0.5) / 16.0 + aoFrameJitter.x) * 2.0 * PI;
}

// A step offset in [0, 1) independent of NoiseAngle's 4x4 tile (interleaved gradient noise, Jimenez
// 2014): derived from the angle instead, the same rotation always comes with the same distances and
// the blur is left with a pattern of rows.
float StepNoise(ivec2 p) {
  return fract(52.9829189 * fract(dot(vec2(p), vec2(0.06711056, 0.00583715))) + aoFrameJitter.y);
}

// Intensity 5 (the lesson's default) leaves occlusion as computed; larger darkens, smaller lightens.
// pow(0, 0) is undefined in GLSL (it can come out NaN), so visibility is kept above 0 and an
// intensity of 0 returns no occlusion outright.
float ApplyIntensity(float occlusion) {
  if (AO_INTENSITY <= 0.0) {
    return 0.0;
  }
  return 1.0 - pow(clamp(1.0 - occlusion, 1e-6, 1.0), AO_INTENSITY / 5.0);
}
