#version 450

// Engine tool (not part of the lesson): shows one intermediate buffer as grey, or writes raw values.

layout(location=1) in vec2 inTexcoord;

layout(binding=0) uniform sampler2D texValue;

layout(location=210) uniform int mode;    // 0 = linear depth, 1 = occlusion shown as visibility
layout(location=211) uniform float scale; // multiplies the value (1 for raw output)

out vec4 outColor;

void main()
{
  float v;
  if (mode == 0) {
    // Nearest texel of level 0: depth must not be interpolated across edges.
    ivec2 size = textureSize(texValue, 0);
    ivec2 p = clamp(ivec2(inTexcoord * vec2(size)), ivec2(0), size - 1);
    v = texelFetch(texValue, p, 0).x;
  } else {
    v = 1.0 - texture(texValue, inTexcoord).x;
  }
  v *= scale;
  outColor = vec4(v, v, v, 1);
}
