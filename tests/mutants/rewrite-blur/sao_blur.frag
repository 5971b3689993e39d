#version 450
// A correct bilateral blur written differently: x loop outside, the centre handled inside the
// loop (its depth difference is 0, so its weight is the plain gaussian), reads clamped.

layout(binding=0) uniform sampler2D texColor;
layout(binding=1) uniform sampler2D texDepth;
out vec4 outColor;

const float w[5] = float[](0.153170, 0.144893, 0.122649, 0.092902, 0.062970);

void main()
{
  ivec2 c = ivec2(gl_FragCoord.xy);
  float d0 = texelFetch(texDepth, c, 0).r;
  vec4 centre = texelFetch(texColor, c, 0);
  if (d0 >= 1000.0) {
    outColor = centre;
    return;
  }
  ivec2 last = textureSize(texColor, 0) - 1;
  vec4 sum = vec4(0);
  float wsum = 0;
  for (int x = 4; x >= -4; --x) {
    for (int y = -4; y <= 4; ++y) {
      ivec2 p = clamp(c + 2 * ivec2(x, y), ivec2(0), last);
      float d = texelFetch(texDepth, p, 0).r;
      float k = w[abs(x)] * w[abs(y)] * clamp(1.0 - abs(d - d0) / 0.15, 0.0, 1.0);
      sum += k * texelFetch(texColor, p, 0);
      wsum += k;
    }
  }
  outColor = sum / wsum;
}
