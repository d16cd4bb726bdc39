"""The stress table as a chart: on every stress mesh, the cells in pieces of the RVD and of the
LRVD of 100 samples (the RVD's cells reach across thin walls and gaps; the LRVD's do not).
Writes OUT_DIR/stress_table.png. Usage: python3 examples/stress_table.py [MESH] [OUT_DIR]
(MESH is not used: the stress meshes are built in.)"""
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import lrvd

out = sys.argv[2] if len(sys.argv) > 2 else "."
names = lrvd.stress_names()
pieces = {"rvd": [], "lrvd": []}
for name in names:
    V, F = lrvd.stress(name)
    for kind in pieces:
        d = lrvd.compute(V, F, n=100, seed=1, diagram=kind, verify=kind == "lrvd")
        pieces[kind].append(d.cells_in_pieces)
        if kind == "lrvd":
            assert d.passed, f"{name}: the LRVD failed its verification"
    print(f"{name:28s} RVD {pieces['rvd'][-1]:4d}  LRVD {pieces['lrvd'][-1]:4d} cells in pieces")

x = np.arange(len(names))
fig, ax = plt.subplots(figsize=(9, 4))
ax.bar(x - 0.2, pieces["rvd"], 0.4, label="RVD")
ax.bar(x + 0.2, pieces["lrvd"], 0.4, label="LRVD")
ax.set_xticks(x, names, rotation=30, ha="right")
ax.set_ylabel("cells in pieces (of 100)")
ax.set_title("Stress meshes, 100 samples, seed 1")
ax.legend()
fig.tight_layout()
fig.savefig(os.path.join(out, "stress_table.png"), dpi=100)
