#version 450

// The blur pass (fourth of four): depth-aware (bilateral) 9x9 blur of the SAO buffer.

layout(binding=0) uniform sampler2D texColor; // occlusion
layout(binding=1) uniform sampler2D texDepth; // linear depth

out vec4 outColor;

// The Gaussian of SAO_blur.pix, centre first ("stddev = 2" there; its ratios are exp(-k^2/18), a
// sigma = 3 Gaussian cut at +-4 taps). SAO_blur.pix and the course add 0.3 to every tap but the
// centre; this port leaves the 0.3 out, for a narrower kernel.
const float gaussian[5] =
  { 0.153170, 0.144893, 0.122649, 0.092902, 0.062970 };

#ifndef CAMERA_FAR
#define CAMERA_FAR 1000.0
#endif

const int blurRadius = 4;        // taps each side
const int blurScale = 2;         // texels between taps
const float edgeDistance = 0.15; // depth difference (m) treated as a different surface
const float edgeSharpness = 1 / edgeDistance;
const float farPlaneZ = CAMERA_FAR; // the restore pass writes exactly this for sky

void main()
{
  ivec2 uv = ivec2(gl_FragCoord.xy);
  ivec2 maxUV = textureSize(texColor, 0) - 1;
  outColor = texelFetch(texColor, uv, 0);
  float depth = texelFetch(texDepth, uv, 0).x;

  // Sky is not blurred.
  if (depth > farPlaneZ) {
    return;
  }

  outColor *= gaussian[0] * gaussian[0];
  float totalWeight = gaussian[0] * gaussian[0];
  for (int y = -blurRadius; y <= blurRadius; ++y) {
    for (int x = -blurRadius; x <= blurRadius; ++x) {
      if (y == 0 && x == 0) {
        continue;
      }
      float weight = gaussian[abs(x)] * gaussian[abs(y)];

      // Clamp: reads outside the texture are undefined.
      ivec2 sampleUV = clamp(uv + ivec2(x, y) * blurScale, ivec2(0), maxUV);
      float sampleDepth = texelFetch(texDepth, sampleUV, 0).x;
      weight *= max(0.0, 1.0 - edgeSharpness * abs(sampleDepth - depth));

      outColor += texelFetch(texColor, sampleUV, 0) * weight;
      totalWeight += weight;
    }
  }

  outColor /= totalWeight;
}
