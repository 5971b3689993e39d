#version 450

// Joint bilateral up-sampling of half-size AO to the main size: each pixel takes the four nearest
// half-size texels with their bilinear weights, each scaled down as its depth departs from the
// pixel's own (from the main depth buffer). A linear filter would mix a foreground object's AO into
// the background at every silhouette (a blocky halo two pixels wide).

layout(location=1) in vec2 inTexcoord;

layout(binding=0) uniform sampler2D texOcclusion; // half size
layout(binding=1) uniform sampler2D texDepth;     // half-size linear depth (m), level 0
layout(binding=2) uniform sampler2D texMainDepth; // main depth buffer (window depth)

#include "linear_depth.glsl"

out float outColor;

// 5 % of the distance, as the blur's depth test (blur_edge.glsl).
const float RELATIVE_TOLERANCE = 0.05;

void main()
{
  ivec2 pix = ivec2(gl_FragCoord.xy);
  float z = LinearDepth(texelFetch(texMainDepth, pix, 0).x);
  if (z >= depthPlanes.y) {
    outColor = texture(texOcclusion, inTexcoord).x; // sky: nothing to keep apart
    return;
  }
  vec2 halfSize = vec2(textureSize(texOcclusion, 0));
  // Position in half-size texels, relative to the texel centres; the 2x2 texels around it are
  // gathered in one fetch per texture (textureGather's order: (0,1), (1,1), (1,0), (0,0)).
  vec2 h = inTexcoord * halfSize - 0.5;
  vec2 base = floor(h);
  vec2 f = h - base;
  vec2 gatherUv = (base + 1.0) / halfSize;
  vec4 values = textureGather(texOcclusion, gatherUv, 0);
  vec4 depths = textureGather(texDepth, gatherUv, 0);
  vec4 bilinear = vec4((1.0 - f.x) * f.y, f.x * f.y, f.x * (1.0 - f.y), (1.0 - f.x) * (1.0 - f.y));
  vec4 gaps = abs(depths - z) / z;
  vec4 w = bilinear * max(vec4(0.0), 1.0 - gaps / RELATIVE_TOLERANCE);
  float total = dot(w, vec4(1.0));
  float sum = dot(w, values);
  float nearestGap = min(min(gaps.x, gaps.y), min(gaps.z, gaps.w));
  float nearestValue = gaps.x == nearestGap ? values.x
                     : gaps.y == nearestGap ? values.y
                     : gaps.z == nearestGap ? values.z : values.w;
  // No texel on the pixel's surface (a feature thinner than a half-size texel): the closest in depth.
  outColor = total > 1e-4 ? sum / total : nearestValue;
}
