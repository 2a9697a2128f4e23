// examples/quadrics_gallery.txt for POV-Ray 3.7, for bench/compare.sh: a chequered
// floor, an open cylinder, an open cone, a paraboloid on its side, a hyperboloid, a
// mirror ball (the QUADRIC record), a point light and a spotlight. z is negated
// (POV-Ray is left-handed).
//
// Differences that remain (compare work, not colours):
// - Lighting model, reflection depth and pixel sampling, as in spec1.pov.
// - The paraboloid and hyperboloid are POV-Ray quadrics cut to their y range by a box
//   in the local frame (clipped_by), as the course's bounds test does; POV-Ray tests
//   the box as well as the surface.
// - The spotlight's edge: POV-Ray's falloff equals its radius here, a hard edge as in
//   spec §5.7.
#version 3.7;
#include "transforms.inc"
global_settings { assumed_gamma 1.0 max_trace_level 5 }

camera {
  perspective
  location <0, 1, -4>
  direction <0, -1, 4>  // to the window's centre, the origin: the same off-axis
                        // projection as the course's (the eye is above the centre)
  right <8, 0, 0>
  up <0, 6, 0>
}

#declare Matte = finish { ambient 0.1 diffuse 0.7 }

plane { y, -2.5
  pigment { checker rgb 0.8 rgb <0.2, 0.2, 0.6> rotate y*45 }
  finish { ambient 0.1 diffuse 0.7 reflection 0.05 }
}

// 22: base centre (-3, -2.5, -7), upright, radius 0.8, height 2.5.
cylinder { <-3, -2.5, 7>, <-3, 0, 7>, 0.8 open pigment { rgb <0.3, 0.6, 1> } finish { Matte } }

// 23: apex (3, -2.5, -7), widening upward to radius 1.2 at height 2.5.
cone { <3, -2.5, 7>, 0, <3, 0, 7>, 1.2 open pigment { rgb <1, 0.4, 0.3> } finish { Matte } }

// 21: vertex (-1, -1.5, -9), axis (0.5, 0.2, 1), radius 1 at height 2: x² + z² = k y,
// k = r²/h = 0.5. POV-Ray's quadric is A x² + B y² + C z² + ... + G x + H y + I z + J.
quadric { <1, 0, 1>, <0, 0, 0>, <0, -0.5, 0>, 0
  clipped_by { box { <-1.01, 0, -1.01>, <1.01, 2, 1.01> } }
  Reorient_Trans(y, <0.5, 0.2, -1>)
  translate <-1, -1.5, 9>
  pigment { rgb <0.5, 1, 0.3> } finish { Matte }
}

// 24: waist centre (1.2, -0.9, -10), upright, end radius 1, half-height 1.6, waist
// 0.45: x² + z² = k y² + rc², k = (1 - 0.2025) / 2.56.
#declare K = (1 - 0.45 * 0.45) / (1.6 * 1.6);
quadric { <1, -K, 1>, <0, 0, 0>, <0, 0, 0>, -0.45 * 0.45
  clipped_by { box { <-1.01, -1.6, -1.01>, <1.01, 1.6, 1.01> } }
  translate <1.2, -0.9, 10>
  pigment { rgb <0.6, 0.6, 1> } finish { Matte }
}

// QUADRIC 4 0 0 0 4 0 0 4 16 63: radius 0.5 at (0, 0, -4), a mirror.
sphere { <0, 0, 4>, 0.5 pigment { rgb 0.2 } finish { ambient 0.05 diffuse 0.3 reflection 0.7 } }

light_source { <-5, 6, 2> rgb 1 }
light_source { <6, 5, 3> rgb <1, 0.5, 0.25>
  spotlight point_at <3, -1, 7> radius 15 falloff 15
}
