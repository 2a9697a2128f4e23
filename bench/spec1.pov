// The course scene spec1 (../shared/course-scenes/spec1.txt) for POV-Ray 3.7, for
// bench/compare.sh: the same two spheres, two tiled planes, four point lights, camera
// and window. POV-Ray is left-handed, so every z is negated (the picture is the same).
//
// Differences that remain (compare work, not colours):
// - Lighting: POV-Ray's ambient/diffuse/reflection finish, not the course's
//   ambient-over-distance model (spec §4); intensities and falloff differ.
// - Reflection depth: POV-Ray's max_trace_level 5, not the course's MAX_DIST of 32.
// - The checker is POV-Ray's, turned 45 degrees to the course grid direction; its phase
//   may differ.
// - POV-Ray samples pixel centres; the course puts the first and last pixel on the
//   window's edges, a difference of half a pixel.
#version 3.7;
global_settings { assumed_gamma 1.0 max_trace_level 5 }

camera {
  perspective
  location <0, 0, -3>
  direction <0, 0, 3>   // the window z = 0 is 3 in front of the eye
  right <8, 0, 0>       // world window 8 x 6
  up <0, 6, 0>
}

#declare Mirror = finish { ambient 0.1 diffuse 0.6 reflection 0.5 }
sphere { <2, 0, 3>, 2 pigment { rgb <0.2, 0.3, 1> } finish { Mirror } }
sphere { <-2, 0, 3>, 2 pigment { rgb <1, 0.3, 0.3> } finish { Mirror } }

plane { y, -4
  pigment { checker rgb <0.5, 0.5, 1> rgb <1, 0.3, 0.3> rotate y*45 }
  finish { ambient 0.1 diffuse 0.7 }
}
plane { <0, 0, -1>, -8
  pigment { checker rgb <1, 0.5, 0.3> rgb <0.5, 0.5, 1> rotate z*45 }
  finish { ambient 0.1 diffuse 0.7 }
}

light_source { <0, 0, -5> rgb 0.4 }
light_source { <0, 5, 3> rgb 0.6 }
light_source { <0, 11, 3> rgb <0, 0, 0.6> }
light_source { <0, 11, -3> rgb <0.6, 0, 0> }
