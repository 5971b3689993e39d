#version 450

// Lesson step 2 (lessons/02-restore-pass.md): write the linear distance (metres) of the nearest of
// the 2x2 depth texels under this half-size pixel. Until then this stub writes 0 everywhere.

out float outColor;

layout(binding=0) uniform sampler2D texDepth;

// The engine injects the camera's planes; these defaults let the file compile on its own.
#ifndef CAMERA_NEAR
#define CAMERA_NEAR 0.35
#endif
#ifndef CAMERA_FAR
#define CAMERA_FAR 1000.0
#endif

void main()
{
  outColor = 0;
}
