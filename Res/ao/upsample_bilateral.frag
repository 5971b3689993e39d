#version 450

// Joint bilateral up-sampling of half-size AO to the main size: each pixel takes the four nearest
// half-size texels with their bilinear weights, each scaled down as its depth departs from the
// pixel's own (from the main depth buffer). A linear filter would mix a foreground object's AO into
// the background at every silhouette (a blocky halo two pixels wide).

layout(location=1) in vec2 inTexcoord;

layout(binding=0) uniform sampler2D texOcclusion; // half size
layout(binding=1) uniform sampler2D texDepth;     // half-size linear depth (m), level 0
layout(binding=2) uniform sampler2D texMainDepth; // main depth buffer (window depth)

layout(location=230) uniform vec3 depthPlanes; // near, far, 1 for reversed-Z (else 0)

out float outColor;

// 5 % of the distance, as the blur's depth test (blur_edge.glsl).
const float RELATIVE_TOLERANCE = 0.05;

float LinearDepth(float d) {
  float n = depthPlanes.x, f = depthPlanes.y;
  if (depthPlanes.z > 0.5) {
    return d <= 0.0 ? f : min(n * f / (d * (f - n) + n), f);
  }
  if (d >= 1.0) {
    return f;
  }
  float a = -2.0 * f * n / (f - n);
  float b = (f + n) / (f - n);
  return min(a / (2.0 * d - 1.0 - b), f);
}

void main()
{
  ivec2 pix = ivec2(gl_FragCoord.xy);
  float z = LinearDepth(texelFetch(texMainDepth, pix, 0).x);
  if (z >= depthPlanes.y) {
    outColor = texture(texOcclusion, inTexcoord).x; // sky: nothing to keep apart
    return;
  }
  ivec2 halfSize = textureSize(texOcclusion, 0);
  // Position in half-size texels, relative to the texel centres.
  vec2 h = inTexcoord * vec2(halfSize) - 0.5;
  ivec2 base = ivec2(floor(h));
  vec2 f = h - vec2(base);
  float sum = 0;
  float total = 0;
  float nearestGap = 1e30;
  float nearestValue = 0;
  for (int i = 0; i < 4; ++i) {
    ivec2 o = ivec2(i & 1, i >> 1);
    ivec2 q = clamp(base + o, ivec2(0), halfSize - 1);
    float value = texelFetch(texOcclusion, q, 0).x;
    float gap = abs(texelFetch(texDepth, q, 0).x - z) / z;
    float bilinear = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
    float w = bilinear * max(0.0, 1.0 - gap / RELATIVE_TOLERANCE);
    sum += value * w;
    total += w;
    if (gap < nearestGap) {
      nearestGap = gap;
      nearestValue = value;
    }
  }
  // No texel on the pixel's surface (a feature thinner than a half-size texel): the closest in depth.
  outColor = total > 1e-4 ? sum / total : nearestValue;
}
