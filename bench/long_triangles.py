#!/usr/bin/env python3
"""Writes two meshes made of long, thin triangles, each of which many cells cross.

CAD exports tessellate a cylinder's side with triangles that run its whole length, and a cone
with triangles from apex to base; when the mesh also has enough small triangles elsewhere
(2 n or more, so that `lrvd` does not refine it first), each long triangle holds dozens of
candidate cells: the clipper's many-candidate path (src/diagram/clip.cpp, `clip_many`).

    bench/long_triangles.py OUTDIR
    bench/ab_compare.py --base OLD --new build/lrvd --runs 3 --same-output -- \\
        compute OUTDIR/cylinder_fine_caps.off -n 1000 --threads 1
    bench/ab_compare.py --base OLD --new build/lrvd --runs 3 --same-output -- \\
        remesh OUTDIR/cylinder_fine_caps.off -n 1000 --threads 1
    bench/ab_compare.py --base OLD --new build/lrvd --runs 2 --same-output -- \\
        compute OUTDIR/needle_cone.off -n 300 --threads 1

- cylinder_fine_caps.off: radius 1, length 20, 64 side segments (128 triangles 20 long), each
  cap a polar grid of 40 rings (10,240 triangles in all).
- needle_cone.off: a cone of 1 degree apex angle and height 1 whose 1,200 side triangles each
  run from apex to base, closed by a fan (2,400 triangles).

What they show: a triangle that many cells cross costs about m^2 clips for m candidates, which the
clipper's many-candidate path prunes (docs/algorithms/predicates.md, "Skipping a clip that cannot
cut"). Standard library only.
"""

import math
import os
import sys


def write_off(path, vertices, triangles):
    with open(path, "w") as f:
        f.write(f"OFF\n{len(vertices)} {len(triangles)} 0\n")
        for v in vertices:
            f.write("%.17g %.17g %.17g\n" % v)
        for t in triangles:
            f.write("3 %d %d %d\n" % t)


def cylinder_fine_caps(segments=64, length=20.0, radius=1.0, rings=40):
    vertices, triangles, index = [], [], {}
    for cap, z in ((0, 0.0), (1, length)):
        index[cap, 0, 0] = len(vertices)
        vertices.append((0.0, 0.0, z))
        for i in range(1, rings + 1):
            r = radius * i / rings
            for k in range(segments):
                a = 2 * math.pi * k / segments
                index[cap, i, k] = len(vertices)
                vertices.append((r * math.cos(a), r * math.sin(a), z))
    for cap in (0, 1):
        fan = []
        for k in range(segments):
            k1 = (k + 1) % segments
            fan.append((index[cap, 0, 0], index[cap, 1, k], index[cap, 1, k1]))
            for i in range(1, rings):
                a0, a1 = index[cap, i, k], index[cap, i, k1]
                b0, b1 = index[cap, i + 1, k], index[cap, i + 1, k1]
                fan += [(a0, b0, b1), (a0, b1, a1)]
        # The top cap faces +z as built; the bottom one is turned over to face -z.
        triangles += fan if cap == 1 else [(a, c, b) for a, b, c in fan]
    for k in range(segments):
        k1 = (k + 1) % segments
        b0, b1 = index[0, rings, k], index[0, rings, k1]
        t0, t1 = index[1, rings, k], index[1, rings, k1]
        triangles += [(b0, b1, t1), (b0, t1, t0)]
    return vertices, triangles


def needle_cone(segments=1200, apex_degrees=1.0, height=1.0):
    r = height * math.tan(math.radians(apex_degrees / 2))
    vertices = [(0.0, 0.0, height), (0.0, 0.0, 0.0)]
    for k in range(segments):
        a = 2 * math.pi * k / segments
        vertices.append((r * math.cos(a), r * math.sin(a), 0.0))
    triangles = []
    for k in range(segments):
        a, b = 2 + k, 2 + (k + 1) % segments
        triangles += [(0, a, b), (1, b, a)]
    return vertices, triangles


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    write_off(os.path.join(out, "cylinder_fine_caps.off"), *cylinder_fine_caps())
    write_off(os.path.join(out, "needle_cone.off"), *needle_cone())


if __name__ == "__main__":
    main()
