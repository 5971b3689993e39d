#version 450

// The second depth layer (after Mara, McGuire, Nowrouzezahrai and Luebke 2016, "Deep G-Buffers for
// Stable Global Illumination Approximation"): a depth pass of the front faces that discards every
// fragment less than a minimum separation behind the first layer (the main depth buffer), so the
// depth test keeps, per pixel, the nearest surface hidden behind the visible one. vbao marches it as a
// second slab per tap: an occluder behind a thin foreground object is no longer lost.

layout(binding=0) uniform sampler2D texFrontDepth; // main depth buffer (window depth), same size

#include "linear_depth.glsl"
layout(location=232) uniform float layerSeparation; // metres behind the first layer

void main()
{
  float front = LinearDepth(texelFetch(texFrontDepth, ivec2(gl_FragCoord.xy), 0).x);
  if (LinearDepth(gl_FragCoord.z) <= front + layerSeparation) {
    discard;
  }
}
