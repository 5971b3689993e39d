#version 450

// Lesson step 2 (lessons/02-restore-pass.md): write the linear distance (metres) of the nearest of
// the 2x2 depth texels under this half-size pixel. Until then this stub writes 0 everywhere.

out float outColor;

layout(binding=0) uniform sampler2D texDepth;

void main()
{
  outColor = 0;
}
