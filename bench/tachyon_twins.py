#!/usr/bin/env python3
"""Writes the Tachyon twins of issue 16: two scenes, each as a legacy scene file for
legacy-rt and as a Tachyon .dat file with the same geometry, into the folder given
(default target/bench):

  twin_small.txt / .dat   a floor, a wall, 3 spheres, 2 open cylinders, one light
  twin_many.txt  / .dat   a floor, 64 spheres and 48 open cylinders (113 objects), one light
  twin_grid.txt  / .dat   a floor, a wall and a regular 10 x 10 grid of small spheres
                          rising row by row from the floor towards the wall, one light:
                          the scene Tachyon's uniform grid favours (issue 47)

The cameras coincide: legacy-rt's eye at (0, 0, 3) looks through the 8 x 6 window at
z = 0, a horizontal half-angle of atan(4/3); Tachyon's camera at the same point with
ZOOM 0.5 sees the same field (checked by the centroid of a sphere in both images, within
a pixel at 320x240). Tachyon's frame is mirrored left to right against the course's, so
every x is negated in the .dat files. Both have shadows and no mirrors; the shading
models differ (Tachyon has no division by the distance), so the images share geometry,
not colours: the comparison is of work.
"""
import os, sys

def legacy_sphere(c, r, colour):
    return (f"13 sphere\n{colour[0]} {colour[1]} {colour[2]} ambient\n"
            f"{4 * colour[0]} {4 * colour[1]} {4 * colour[2]} diffuse\n0 0 0 specular\n"
            f"{c[0]} {c[1]} {c[2]} centre\n{r} radius\n")

def legacy_cylinder(base, height, r, colour):
    return (f"22 cylinder\n{colour[0]} {colour[1]} {colour[2]} ambient\n"
            f"{4 * colour[0]} {4 * colour[1]} {4 * colour[2]} diffuse\n0 0 0 specular\n"
            f"{base[0]} {base[1]} {base[2]} centre of base\n0 1 0 centre line\n"
            f"{r} {height} radius height\n")

def legacy_plane(normal, point, colour):
    return (f"14 plane\n{colour[0]} {colour[1]} {colour[2]} ambient\n"
            f"{4 * colour[0]} {4 * colour[1]} {4 * colour[2]} diffuse\n0 0 0 specular\n"
            f"{normal[0]} {normal[1]} {normal[2]} normal\n{point[0]} {point[1]} {point[2]} point\n")

def texture(colour):
    top = max(colour)
    r, g, b = (c / top for c in colour)
    return (f"TEXTURE AMBIENT 0.1 DIFFUSE 0.8 SPECULAR 0.0 OPACITY 1.0 "
            f"COLOR {r:.3f} {g:.3f} {b:.3f} TEXFUNC 0")

def write(folder, name, spheres, cylinders, planes):
    light = (0, 4, 2)
    legacy = ["8 6 world window\n0 0 3 viewpoint\n",
              f"10 light\n20 20 20 emissivity\n{light[0]} {light[1]} {light[2]} location\n"]
    dat = ["BEGIN_SCENE\nRESOLUTION 640 480\nCAMERA\n  ZOOM 0.5\n  ASPECTRATIO 1.0\n"
           "  ANTIALIASING 0\n  RAYDEPTH 6\n  CENTER 0 0 3\n  VIEWDIR 0 0 -1\n"
           "  UPDIR 0 1 0\nEND_CAMERA\n",
           f"LIGHT CENTER {-light[0]} {light[1]} {light[2]} RAD 0.01 COLOR 1 1 1\n"]
    for normal, point, colour in planes:
        legacy.append(legacy_plane(normal, point, colour))
        dat.append(f"PLANE CENTER {-point[0]} {point[1]} {point[2]} "
                   f"NORMAL {-normal[0]} {normal[1]} {normal[2]} {texture(colour)}\n")
    for c, r, colour in spheres:
        legacy.append(legacy_sphere(c, r, colour))
        dat.append(f"SPHERE CENTER {-c[0]} {c[1]} {c[2]} RAD {r} {texture(colour)}\n")
    for base, height, r, colour in cylinders:
        legacy.append(legacy_cylinder(base, height, r, colour))
        dat.append(f"FCYLINDER BASE {-base[0]} {base[1]} {base[2]} "
                   f"APEX {-base[0]} {base[1] + height} {base[2]} RAD {r} {texture(colour)}\n")
    dat.append("END_SCENE\n")
    with open(os.path.join(folder, name + ".txt"), "w") as f:
        f.write("".join(legacy))
    with open(os.path.join(folder, name + ".dat"), "w") as f:
        f.write("".join(dat))

def main():
    args = sys.argv[1:]
    # An option is never a folder: --help prints this, anything else is refused.
    if args[:1] in (["-h"], ["--help"]):
        print(__doc__)
        return
    if len(args) > 1 or (args and args[0].startswith("-")):
        sys.exit(__doc__)
    folder = args[0] if args else "target/bench"
    os.makedirs(folder, exist_ok=True)
    floor = ((0, 1, 0), (0, -3, 0), (0.6, 0.6, 0.6))
    wall = ((0, 0, 1), (0, 0, -14), (0.3, 0.3, 0.8))
    write(folder, "twin_small",
          spheres=[((-2, -1.5, -7), 1.5, (1, 0.2, 0.2)), ((1.5, -2, -6), 1, (0.2, 1, 0.2)),
                   ((0.5, 0.5, -10), 1.2, (0.2, 0.2, 1))],
          cylinders=[((3, -3, -9), 3, 0.6, (1, 1, 0.2)), ((-4, -3, -11), 4, 0.8, (1, 0.2, 1))],
          planes=[floor, wall])
    spheres = [((-7 + 2 * i, -2.4, -6 - 2 * j), 0.6, (1, 0.3 + 0.05 * i, 0.3))
               for i in range(8) for j in range(8)]
    cylinders = [((-6 + 2 * i, -3, -7 - 2 * j), 1.5, 0.3, (0.3, 1, 0.3 + 0.05 * j))
                 for i in range(7) for j in range(7)][:48]
    write(folder, "twin_many", spheres=spheres, cylinders=cylinders, planes=[floor])
    grid = [((-6.3 + 1.4 * i, -2.5 + 0.6 * j, -5 - j), 0.4, (0.3 + 0.07 * i, 0.3, 1 - 0.07 * j))
            for i in range(10) for j in range(10)]
    write(folder, "twin_grid", spheres=grid, cylinders=[], planes=[floor, wall])

if __name__ == "__main__":
    main()
