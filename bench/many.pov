// The generated 1 000-object scene of tests/support/generated.rs for POV-Ray 3.7, for
// bench/compare.sh: the same grid of spheres, open cylinders, open cones, paraboloids
// and hyperboloids (in turn), with the same positions, sizes and axes, computed by the
// same formulas in POV-Ray's scene language; a floor plane and one light. z is negated
// (POV-Ray is left-handed).
//
// Differences that remain (compare work, not colours): the lighting model, as in
// spec1.pov; the paraboloids and hyperboloids are quadrics clipped by a box in their
// local frame. POV-Ray builds its own bounding hierarchy for these objects.
#version 3.7;
#include "transforms.inc"
global_settings { assumed_gamma 1.0 max_trace_level 5 }

camera {
  perspective
  location <0, 0, -3>
  direction <0, 0, 3>
  right <8, 0, 0>
  up <0, 6, 0>
}

plane { y, -4 pigment { rgb 0.5 } finish { ambient 0.1 diffuse 0.7 } }
light_source { <-5, 8, -2> rgb 1 }

#declare Count = 1000;
#declare Side = ceil(pow(Count, 1/3) - 1e-9);
#declare Axes = array[6] { <0, 1, 0>, <1, 0, 0>, <0, 0, -1>, <1, 1, 0>, <0, 1, -1>, <-1, 1, -1> };
#declare Colours = array[5] { <1, 0.5, 0.5>, <0.5, 1, 0.5>, <0.5, 0.5, 1>, <1, 1, 0.5>, <0.5, 1, 1> };
#declare I = 0;
#while (I < Count)
  #declare IX = mod(I, Side);
  #declare IY = mod(div(I, Side), Side);
  #declare IZ = div(I, Side * Side);
  #declare Z = -6 - 24 * (IZ + 0.5) / Side;
  #declare Spread = (3 - Z) / 3;
  #declare X = (2 * (IX + 0.5) / Side - 1) * 4 * Spread * 0.9;
  #declare Y = (2 * (IY + 0.5) / Side - 1) * 3 * Spread * 0.9;
  #declare Size = 8 * Spread / Side * 0.3;
  #declare C = <X, Y, -Z>;
  #declare A = vnormalize(Axes[mod(I, 6)]);
  #declare R = 0.6 * Size;
  #declare Kind = mod(I, 5);
  #declare Look = texture { pigment { rgb Colours[Kind] } finish { ambient 0.1 diffuse 0.7 } }
  #switch (Kind)
    #case (0) sphere { C, Size texture { Look } } #break
    #case (1) cylinder { C, C + Size * A, R open texture { Look } } #break
    #case (2) cone { C, 0, C + Size * A, R open texture { Look } } #break
    #case (3)
      // x² + z² = k y with k = r² / h.
      quadric { <1, 0, 1>, <0, 0, 0>, <0, -R * R / Size, 0>, 0
        clipped_by { box { <-R, 0, -R> * 1.01, <R, Size, R> * 1.01 } }
        Reorient_Trans(y, A) translate C texture { Look } }
      #break
    #else
      // x² + z² = k y² + rc², rc = 0.3 Size, radius R at y = ±Size.
      #declare W = 0.3 * Size;
      quadric { <1, -(R * R - W * W) / (Size * Size), 1>, <0, 0, 0>, <0, 0, 0>, -W * W
        clipped_by { box { <-R, -Size, -R> * 1.01, <R, Size, R> * 1.01 } }
        Reorient_Trans(y, A) translate C texture { Look } }
  #end
  #declare I = I + 1;
#end
