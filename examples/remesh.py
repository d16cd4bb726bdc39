"""Remesh a mesh to exactly 516 vertices and print the report's verdict and quality; the remesh is
written to OUT_DIR/remesh.off and drawn to OUT_DIR/remesh.png.
Usage: python3 examples/remesh.py MESH [OUT_DIR]"""
import os
import sys

import lrvd

out = sys.argv[2] if len(sys.argv) > 2 else "."
V, F = lrvd.read_mesh(sys.argv[1])
V2, F2, report = lrvd.remesh(V, F, 516, seed=1)
q = report["quality"]
print(f"{len(V2)} vertices, {len(F2)} triangles, verification "
      f"{'passed' if report['verification']['passed'] else 'FAILED'}")
print(f"Qmin {q['Qmin']:.3f}, Qavg {q['Qavg']:.3f}, smallest angle {q['theta_min']:.1f} deg, "
      f"Hausdorff {q['hausdorff_pct']:.3f} % of the diagonal, {report['time_s']:.2f} s")
lrvd.write_mesh(os.path.join(out, "remesh.off"), V2, F2)
image = lrvd.render(V2, F2, edges=True, size=(600, 450))
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
plt.imsave(os.path.join(out, "remesh.png"), image)
sys.exit(0 if report["verification"]["passed"] and len(V2) == 516 else 1)
