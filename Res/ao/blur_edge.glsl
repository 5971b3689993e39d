// The depth test of the engine's bilateral blurs (blur_separable.frag, blur_packed.frag), shared.
//
// A tap keeps its weight while its depth lies on the plane through the centre pixel and falls to 0
// when it leaves that plane by BLUR_EDGE_RELATIVE of the centre's distance. On a plane inverse depth is
// linear in screen space, so the plane's prediction at a tap r texels away is the centre's inverse
// depth plus r times its slope. An absolute threshold (the old 0.15 m) cut every vertical tap on a floor
// far away, where one row apart is more than 0.15 m deep, and left the methods' noise as stripes.

// 5 % of the distance: far above the f32 error of the restore (1e-5 relative), below the depth step at
// the silhouette of an object standing a hand's width in front of another at a few metres.
#define BLUR_EDGE_RELATIVE 0.05

// Slope of inverse depth along the axis at the centre: the one-sided difference with the smaller
// step, so that a silhouette beside the centre does not tilt its plane.
float InverseDepthSlope(float before, float center, float after) {
  float back = 1.0 / center - 1.0 / before;
  float ahead = 1.0 / after - 1.0 / center;
  return abs(back) < abs(ahead) ? back : ahead;
}

float EdgeWeight(float center, float slope, int r, float tapDepth) {
  float predicted = 1.0 / center + slope * float(r);
  return max(0.0, 1.0 - abs(1.0 / tapDepth - predicted) * center / BLUR_EDGE_RELATIVE);
}
