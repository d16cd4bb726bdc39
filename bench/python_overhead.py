"""The Python call's cost over the library call: lrvd.remesh on CGAL's elk at 516 vertices, seed 1,
against bench_remesh_call (the same library calls from C++), in CPU seconds (user + sys of every
thread), the two alternating so that the machine's load falls on both alike.
Usage: PYTHONPATH=build/python /usr/bin/python3 bench/python_overhead.py [BUILD] [ROUNDS] [THREADS] [MESH]"""
import os
import statistics
import subprocess
import sys
import time

import lrvd

build = sys.argv[1] if len(sys.argv) > 1 else "build"
rounds = int(sys.argv[2]) if len(sys.argv) > 2 else 7
threads = int(sys.argv[3]) if len(sys.argv) > 3 else 1
mesh = sys.argv[4] if len(sys.argv) > 4 else os.path.join(build, "cgal-data", "elk.off")
V, F = lrvd.read_mesh(mesh)
lrvd.remesh(V, F, 516, seed=1, threads=threads)  # not timed: the first call's page faults and thread start
library, python = [], []
for r in range(rounds):
    # Two runs, the second timed: warm, as the Python calls after the first.
    out = subprocess.run([os.path.join(build, "bench_remesh_call"), mesh, "516", "1", "2", str(threads)],
                         capture_output=True, text=True, check=True).stdout.split("\n")[1].split()
    library.append(float(out[0]))
    assert out[2] == "1", "the library's remesh failed its check"
    start = time.process_time()
    V2, F2, report = lrvd.remesh(V, F, 516, seed=1, threads=threads)
    python.append(time.process_time() - start)
    assert report["verification"]["passed"] and len(V2) == 516


def line(name, times):
    return (f"{name:8s} min {min(times):.3f}  median {statistics.median(times):.3f}  max {max(times):.3f} s CPU")


print(f"elk 516, seed 1, {threads} thread(s), {rounds} alternating rounds")
print(line("library", library))
print(line("python", python))
print(f"overhead: {100 * (statistics.median(python) / statistics.median(library) - 1):+.1f} % (medians), "
      f"{100 * (min(python) / min(library) - 1):+.1f} % (minima)")
