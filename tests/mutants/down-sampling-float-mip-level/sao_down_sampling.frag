#version 450

layout(binding=0) uniform sampler2D texDepth;

out float outColor;

// The level read, declared float: the engine sets an int at location 200, which OpenGL refuses
// (GL_INVALID_OPERATION), so mipLevel stays 0.
layout(location=200) uniform float mipLevel;

void main()
{
  ivec2 uv = ivec2(gl_FragCoord.xy) * 2;
  int level = int(mipLevel);
  float d1 = texelFetch(texDepth, uv + ivec2(0, 0), level).x;
  float d2 = texelFetch(texDepth, uv + ivec2(0, 1), level).x;
  float d3 = texelFetch(texDepth, uv + ivec2(1, 1), level).x;
  float d4 = texelFetch(texDepth, uv + ivec2(1, 0), level).x;
  outColor = min(min(d1, d2), min(d3, d4));
}
