#version 450

// The geometric normal of the triangle each pixel sees, in view space, turned towards the camera
// (the ray-traced reference turns its hit triangle's normal the same way: open meshes show both
// sides). Within one triangle the view position is an affine function of the screen position, so its
// screen derivatives span the triangle's plane exactly, at silhouettes and creases too, where a
// normal rebuilt from the depth buffer mixes two surfaces.

#include "octahedral.glsl"

layout(location=0) in vec3 inViewPosition;

layout(location=0) out vec2 outNormal;

void main()
{
  vec3 n = cross(dFdx(inViewPosition), dFdy(inViewPosition));
  float len2 = dot(n, n);
  // A triangle seen exactly edge-on has no area on screen: its plane contains the view ray, so any
  // normal across the ray is as good; the view axis is the one that cannot be wrong in sign.
  n = len2 > 1e-30 ? n * inversesqrt(len2) : vec3(0, 0, 1);
  if (dot(n, -inViewPosition) < 0.0) {
    n = -n;
  }
  outNormal = EncodeOctahedral(n);
}
