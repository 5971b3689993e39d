// Joint bilateral up-sampling of half-size AO, shared by the up-sampling pass (upsample_bilateral.frag,
// for the AO views and the ambient-only lighting) and the composite that up-samples as it blends
// (composite_bilateral.frag): each main-size pixel takes the four nearest half-size texels with their
// bilinear weights, each scaled down as its depth departs from the pixel's own (from the main depth
// buffer). A linear filter would mix a foreground object's AO into the background at every silhouette
// (a blocky halo two pixels wide).
//
// The includer declares texOcclusion (half size), texDepth (half-size linear depth, m) and
// texMainDepth (the main depth buffer, window depth), and includes linear_depth.glsl first.

// 5 % of the distance, as the blur's depth test (blur_edge.glsl).
const float UPSAMPLE_RELATIVE_TOLERANCE = 0.05;

// The occlusion at main-size pixel `pix` (texture coordinate `uv`); `sky` is set where the main depth
// buffer holds no surface.
float UpsampledOcclusion(vec2 uv, ivec2 pix, out bool sky) {
  float z = LinearDepth(texelFetch(texMainDepth, pix, 0).x);
  sky = z >= depthPlanes.y;
  if (sky) {
    // Nothing there to occlude: the half-size texels beside a silhouette belong to the surface.
    return 0.0;
  }
  vec2 halfSize = vec2(textureSize(texOcclusion, 0));
  // Position in half-size texels, relative to the texel centres; the 2x2 texels around it are
  // gathered in one fetch per texture (textureGather's order: (0,1), (1,1), (1,0), (0,0)).
  vec2 h = uv * halfSize - 0.5;
  vec2 base = floor(h);
  vec2 f = h - base;
  vec2 gatherUv = (base + 1.0) / halfSize;
  vec4 values = textureGather(texOcclusion, gatherUv, 0);
  vec4 depths = textureGather(texDepth, gatherUv, 0);
  vec4 bilinear = vec4((1.0 - f.x) * f.y, f.x * f.y, f.x * (1.0 - f.y), (1.0 - f.x) * (1.0 - f.y));
  vec4 gaps = abs(depths - z) / z;
  vec4 w = bilinear * max(vec4(0.0), 1.0 - gaps / UPSAMPLE_RELATIVE_TOLERANCE);
  float total = dot(w, vec4(1.0));
  if (total > 1e-4) {
    return dot(w, values) / total;
  }
  // No texel on the pixel's surface (a feature thinner than a half-size texel): the closest in depth.
  float nearestGap = min(min(gaps.x, gaps.y), min(gaps.z, gaps.w));
  return gaps.x == nearestGap ? values.x
       : gaps.y == nearestGap ? values.y
       : gaps.z == nearestGap ? values.z : values.w;
}
