#version 450

// The surface normals at the AO buffers' size. At half size each AO texel keeps the normal of the
// texel of its 2x2 block whose depth is nearest: the texel the depth restore keeps, so that a tap's
// position and its normal belong to the same surface.

#include "octahedral.glsl"

layout(binding=0) uniform sampler2D texNormal;     // main-size octahedral normals
layout(binding=1) uniform sampler2D texFrontDepth; // main depth buffer (window depth)

#include "linear_depth.glsl"
layout(location=231) uniform int blockSize;    // main texels per AO texel along each axis: 1, 2 or 4

layout(location=0) out vec2 outNormal;

void main()
{
  ivec2 maxUV = textureSize(texNormal, 0) - 1;
  ivec2 base = ivec2(gl_FragCoord.xy) * blockSize;
  float nearest = 1e30;
  vec2 code = EncodeOctahedral(vec3(0, 0, 1));
  for (int y = 0; y < blockSize; ++y) {
    for (int x = 0; x < blockSize; ++x) {
      ivec2 p = min(base + ivec2(x, y), maxUV);
      float z = LinearDepth(texelFetch(texFrontDepth, p, 0).x);
      if (z < nearest) {
        nearest = z;
        code = texelFetch(texNormal, p, 0).xy;
      }
    }
  }
  outNormal = code;
}
