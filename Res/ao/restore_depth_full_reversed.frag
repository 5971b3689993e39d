#version 450

// The engine's linear-depth restore for a reversed-Z depth buffer (near -> 1, far -> 0, cleared to 0),
// at full resolution (`--ao-resolution full`): one main texel per output texel.
// See restore_depth_reversed.frag for the formula.

out float outColor;

layout(binding=0) uniform sampler2D texDepth;

void main()
{
  ivec2 maxUV = textureSize(texDepth, 0) - 1;
  float depth = texelFetch(texDepth, min(ivec2(gl_FragCoord.xy), maxUV), 0).x;

  const float near = CAMERA_NEAR;
  const float far = CAMERA_FAR;
  // Sky (the cleared 0) is exactly 'far', as in the lesson's restore.
  if (depth <= 0.0) {
    outColor = far;
    return;
  }
  // Inverse of depth = n (f - z) / (z (f - n)): z = n f / (depth (f - n) + n). Every term is positive,
  // so there is no cancellation: the relative error stays a few f32 ulps at any distance.
  outColor = min(near * far / (depth * (far - near) + near), far);
}
