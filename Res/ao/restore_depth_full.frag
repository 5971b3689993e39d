#version 450

// The engine's linear-depth restore at full resolution (`--ao-resolution full`): one texel of the
// main depth buffer per output texel, so every AO pixel has its own exact depth. Same interface and
// formula as the lesson's sao_restore_depth.frag without its nearest-of-2x2.

out float outColor;

layout(binding=0) uniform sampler2D texDepth;

void main()
{
  ivec2 maxUV = textureSize(texDepth, 0) - 1;
  float depth = texelFetch(texDepth, min(ivec2(gl_FragCoord.xy), maxUV), 0).x;
  const float near = CAMERA_NEAR;
  const float far = CAMERA_FAR;
  const float A = -2 * far * near / (far - near);
  const float B = (far + near) / (far - near);
  // Sky (the cleared 1.0) is exactly 'far', so later passes can test 'depth >= far'.
  if (depth >= 1.0) {
    outColor = far;
    return;
  }
  outColor = min(A / (2 * depth - 1 - B), far);
}
