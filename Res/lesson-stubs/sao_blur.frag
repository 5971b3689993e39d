#version 450

// Lesson step 11 (lessons/11-bilateral-blur.md): blur the occlusion, keeping depth edges.
// Until then this stub passes the occlusion through unchanged.

layout(binding=0) uniform sampler2D texColor;
layout(binding=1) uniform sampler2D texDepth;

out vec4 outColor;

// The engine injects the far plane; this default lets the file compile on its own.
#ifndef CAMERA_FAR
#define CAMERA_FAR 1000.0
#endif

void main()
{
  outColor = texelFetch(texColor, ivec2(gl_FragCoord.xy), 0);
}
