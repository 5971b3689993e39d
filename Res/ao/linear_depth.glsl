// Window depth -> linear view distance (m) for either depth convention, with the planes passed as a
// uniform (the engine's passes that read a depth buffer directly: the bilateral up-sampling and the
// back-face restore). Sky (the cleared value) comes out exactly 'far'.

layout(location=230) uniform vec3 depthPlanes; // near, far, 1 for reversed-Z (else 0)

float LinearDepth(float d) {
  float n = depthPlanes.x, f = depthPlanes.y;
  if (depthPlanes.z > 0.5) {
    // Reversed-Z: depth = n (f - z) / (z (f - n)); every term positive, no cancellation.
    return d <= 0.0 ? f : min(n * f / (d * (f - n) + n), f);
  }
  if (d >= 1.0) {
    return f;
  }
  float a = -2.0 * f * n / (f - n);
  float b = (f + n) / (f - n);
  return min(a / (2.0 * d - 1.0 - b), f);
}
