#version 450
// A correct restore pass written differently: a loop over the 2x2 block and the
// projection inverted as n*f / (f - D*(f - n)), without the NDC step.

layout(binding=0) uniform sampler2D texDepth;
out float outColor;

const float zNear = 0.35;
const float zFar = 1000.0;

float LinearDistance(float d)
{
  return zNear * zFar / (zFar - d * (zFar - zNear));
}

void main()
{
  ivec2 base = 2 * ivec2(gl_FragCoord.xy);
  float nearest = 1.0;
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 2; ++i) {
      nearest = min(nearest, texelFetch(texDepth, base + ivec2(i, j), 0).r);
    }
  }
  outColor = LinearDistance(nearest);
}
