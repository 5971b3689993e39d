#version 450

// Lesson step 4 (lessons/04-down-sampling.md): write the min of the 2x2 texels of level mipLevel.
// Until then this stub writes 0.

layout(binding=0) uniform sampler2D texDepth;

out float outColor;

layout(location=200) uniform int mipLevel;

void main()
{
  outColor = 0;
}
