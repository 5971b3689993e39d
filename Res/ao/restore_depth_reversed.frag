#version 450

// The engine's linear-depth restore for a reversed-Z depth buffer (near -> 1, far -> 0, cleared to 0).
// Same interface as the lesson's sao_restore_depth.frag (binding 0, outColor, CAMERA_NEAR/FAR
// injected), which keeps the course's formula for students: the engine picks this file instead when
// the scene asks for `depth = "d32f-reversed"`.

out float outColor;

layout(binding=0) uniform sampler2D texDepth;

void main()
{
  // The nearest of the 2x2 texels is the LARGEST reversed depth.
  ivec2 maxUV = textureSize(texDepth, 0) - 1;
  ivec2 uv = ivec2(gl_FragCoord.xy) * 2;
  float d1 = texelFetch(texDepth, min(uv + ivec2(0, 0), maxUV), 0).x;
  float d2 = texelFetch(texDepth, min(uv + ivec2(0, 1), maxUV), 0).x;
  float d3 = texelFetch(texDepth, min(uv + ivec2(1, 1), maxUV), 0).x;
  float d4 = texelFetch(texDepth, min(uv + ivec2(1, 0), maxUV), 0).x;
  float depth = max(max(d1, d2), max(d3, d4));

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
