#version 450

// The down-sampling pass (second of four): one level of the linear-depth mip chain = the nearest of the 2x2 texels of the level above.

layout(binding=0) uniform sampler2D texDepth;

out float outColor;

layout(location=200) uniform int mipLevel; // the level read (the one written is mipLevel + 1)

void main()
{
  // Clamp: a source level 1 texel wide or tall would read past its last texel.
  ivec2 maxUV = textureSize(texDepth, mipLevel) - 1;
  ivec2 uv = ivec2(gl_FragCoord.xy) * 2;
  float d1 = texelFetch(texDepth, min(uv + ivec2(0, 0), maxUV), mipLevel).x;
  float d2 = texelFetch(texDepth, min(uv + ivec2(0, 1), maxUV), mipLevel).x;
  float d3 = texelFetch(texDepth, min(uv + ivec2(1, 1), maxUV), mipLevel).x;
  float d4 = texelFetch(texDepth, min(uv + ivec2(1, 0), maxUV), mipLevel).x;
  outColor = min(min(d1, d2), min(d3, d4));
}
