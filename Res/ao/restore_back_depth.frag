#version 450

// Linear depth of the back faces (a depth pass with front faces culled) at the AO buffers' size, for
// vbao's per-pixel thickness. At half size, the back face behind the texel of the 2x2 block whose
// FRONT is nearest: the texel the front restore keeps, so front and back belong to one ray. (The
// farthest back face of the block would give a plate's silhouette the thickness of the wall behind.)

layout(binding=0) uniform sampler2D texDepth;      // back-face depth buffer (window depth)
layout(binding=1) uniform sampler2D texFrontDepth; // main depth buffer (window depth)

#include "linear_depth.glsl"
layout(location=231) uniform int blockSize;    // main texels per AO texel along each axis: 1, 2 or 4

out float outColor;

void main()
{
#ifdef RESTORE_ONE_TEXEL
  // Drawn at the AO size (the engine's AO chain: a block of one texel), the texel's own depth. Built
  // apart (src/render/passes/ao_size_restore.rs): a software rasteriser pays for the general loop's
  // bookkeeping even when it runs once.
  outColor = LinearDepth(texelFetch(texDepth, ivec2(gl_FragCoord.xy), 0).x);
  return;
#endif
  ivec2 maxUV = textureSize(texDepth, 0) - 1;
  ivec2 base = ivec2(gl_FragCoord.xy) * blockSize;
  float nearestFront = 1e30;
  float back = depthPlanes.y;
  for (int y = 0; y < blockSize; ++y) {
    for (int x = 0; x < blockSize; ++x) {
      ivec2 p = min(base + ivec2(x, y), maxUV);
      float front = LinearDepth(texelFetch(texFrontDepth, p, 0).x);
      if (front < nearestFront) {
        nearestFront = front;
        back = LinearDepth(texelFetch(texDepth, p, 0).x);
      }
    }
  }
  // No back face behind it: 'far', which vbao reads as "use the set thickness".
  outColor = back;
}
