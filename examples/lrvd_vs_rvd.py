"""An LRVD and an RVD of the same samples on a mesh: how many cells each has in pieces.
Usage: python3 examples/lrvd_vs_rvd.py MESH [OUT_DIR]"""
import sys

import lrvd

V, F = lrvd.read_mesh(sys.argv[1])
for kind in ("lrvd", "rvd"):
    d = lrvd.compute(V, F, n=300, seed=1, diagram=kind)
    print(f"{kind}: {len(d.cells['polygon_cell'])} polygons, {d.cells_in_pieces} cells in pieces, "
          f"verification {'passed' if d.report['verification']['passed'] else 'FAILED'}")
    assert d.report["verification"]["passed"] or kind == "rvd"
