#version 450

// Lesson steps 6-9 (lessons/06-...md to 09-...md): compute the occlusion of this pixel with SAO.
// Until then this stub reports no occlusion.

layout(location=1) in vec2 inTexcoord;

out float outColor;

layout(binding=0) uniform sampler2D texDepth;

layout(location=200) uniform vec4 saoInfo;
layout(location=201) uniform vec2 ndcToView;

void main()
{
  outColor = 0;
}
