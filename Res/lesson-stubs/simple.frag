#version 450

// Lesson step 5 (lessons/05-linear-depth-view.md, course section 1.6): show a texture, copying it to
// the output. Until then this stub draws transparent black, so the composite of step 12 darkens
// nothing.

layout(location=1) in vec2 inTexcoord;

layout(binding=0) uniform sampler2D texColor;

out vec4 outColor;

void main()
{
  outColor = vec4(0);
}
