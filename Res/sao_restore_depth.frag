#version 450

// The restore pass (first of the AO lesson's four): turn the depth buffer back into view distance (metres),
// at half size, keeping the nearest of each 2x2 block.

out float outColor;

layout(binding=0) uniform sampler2D texDepth;

// The engine injects the camera's planes; the defaults are the course's.
#ifndef CAMERA_NEAR
#define CAMERA_NEAR 0.35
#endif
#ifndef CAMERA_FAR
#define CAMERA_FAR 1000.0
#endif

void main()
{
  // Nearest of the 2x2 texels (depth is not linear, so it must not be averaged).
  // Clamp: a full-size side of 1 pixel would read past the last texel.
  ivec2 maxUV = textureSize(texDepth, 0) - 1;
  ivec2 uv = ivec2(gl_FragCoord.xy) * 2;
  float d1 = texelFetch(texDepth, min(uv + ivec2(0, 0), maxUV), 0).x;
  float d2 = texelFetch(texDepth, min(uv + ivec2(0, 1), maxUV), 0).x;
  float d3 = texelFetch(texDepth, min(uv + ivec2(1, 1), maxUV), 0).x;
  float d4 = texelFetch(texDepth, min(uv + ivec2(1, 0), maxUV), 0).x;
  float depth = min(min(d1, d2), min(d3, d4));

  // Invert the projection: D' = 2D - 1, distance = A / (D' - B) (positive, i.e. -z_view).
  const float near = CAMERA_NEAR;
  const float far = CAMERA_FAR;
  const float A = -2 * far * near / (far - near);
  const float B = (far + near) / (far - near);
  // Sky (depth 1.0 exactly: the cleared value) is written as exactly 'far', so that later passes can
  // test 'depth >= far' without relying on how the division rounds.
  if (depth >= 1.0) {
    outColor = far;
    return;
  }
  depth = 2 * depth - 1;
  outColor = min(A / (depth - B), far);
}
