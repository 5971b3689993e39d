#version 450
// A correct down-sampling pass written differently: texelFetchOffset and a running minimum.

layout(binding=0) uniform sampler2D texDepth;
layout(location=200) uniform int mipLevel;
out float outColor;

void main()
{
  ivec2 p = ivec2(gl_FragCoord.xy) << 1;
  float m = texelFetchOffset(texDepth, p, mipLevel, ivec2(1, 1)).r;
  m = min(m, texelFetchOffset(texDepth, p, mipLevel, ivec2(1, 0)).r);
  m = min(m, texelFetchOffset(texDepth, p, mipLevel, ivec2(0, 1)).r);
  m = min(m, texelFetch(texDepth, p, mipLevel).r);
  outColor = m;
}
