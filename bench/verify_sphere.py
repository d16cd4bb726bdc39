#!/usr/bin/env python3
"""The judge's cost against the diagram's on bench_fig9's spheres: verify_diagram vs compute_lrvd.

Each (case, thread count, binary) is --repeat fresh `bench_verify --row N T --threads K` processes
under /usr/bin/time -v (for its peak memory); with --base, a second bench_verify (built from other
code) runs each case right after the first, alternating, so both see the same load. Times are CPU
seconds of the process (user + sys, all threads) spent in each call, min / median / max over the
processes; `ratio` = median verification / median diagram. Prints a Markdown table; exits 1 if a
verification failed or a run did not finish.

    bench/verify_sphere.py --bench build/bench_verify                        # every case, 1 and 2 threads
    bench/verify_sphere.py --bench build/bench_verify --base ../main-build/bench_verify --cases big
    bench/verify_sphere.py --bench build/bench_verify --cases 20000:80000 --threads 1 --repeat 5

Cases, comma-separated: `big` (100k samples on 327,680 triangles, 1M on 1,310,720), `fig9` (the
14 rows of bench_fig9), `all` (both), SAMPLES:TRIANGLES. Standard library only.
"""

import argparse
import json
import os
import re
import statistics
import subprocess
import sys

BIG = [(100000, 327680), (1000000, 1310720)]
FIG9 = [(n, 20480) for n in (2000, 5000, 10000, 20000, 50000, 100000)] + \
       [(10000, m) for m in (500, 2000, 5000, 10000, 20000, 40000, 80000, 140000)]


def cases_of(spec):
    named = {"big": BIG, "fig9": FIG9, "all": BIG + FIG9}
    cases = []
    for item in spec.split(","):
        cases += named[item] if item in named else [tuple(int(x) for x in item.split(":"))]
    return cases


def run(bench, n, m, threads, runs):
    """One process: the JSON line of bench_verify plus `peak_mb`, or None if it did not finish."""
    cmd = ["/usr/bin/time", "-v", bench, "--row", str(n), str(m), "--threads", str(threads), "--runs", str(runs)]
    proc = subprocess.run(cmd, capture_output=True, text=True)
    peak = re.search(r"Maximum resident set size \(kbytes\): (\d+)", proc.stderr)
    lines = [l for l in proc.stdout.splitlines() if l.startswith("{")]
    if not lines or not peak:
        sys.stderr.write(proc.stderr[-2000:])
        return None
    row = json.loads(lines[-1])
    row["peak_mb"] = int(peak.group(1)) / 1024
    return row


def spread(rows, key):
    """min / median / max of rows[*][key], and the median."""
    values = sorted(r[key] for r in rows)
    median = statistics.median(values)
    if len(values) == 1:
        return f"{median:.2f}", median
    return f"{values[0]:.2f} / **{median:.2f}** / {values[-1]:.2f}", median


def cells(rows):
    if not rows or any(r is None for r in rows):
        return "| | | | did not finish "
    diagram, d = spread(rows, "diagram_cpu_s")
    verify, v = spread(rows, "verify_cpu_s")
    wall = statistics.median(r["verify_wall_s"] for r in rows) / max(statistics.median(r["diagram_wall_s"] for r in rows), 1e-9)
    mark = "" if all(r["passed"] for r in rows) else " FAIL"
    peak = max(r["peak_mb"] for r in rows)
    return f"| {diagram} | {verify}{mark} | {v / max(d, 1e-9):.2f} ({wall:.2f}) | {peak:.0f} MB "


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--bench", default=os.path.join(here, "..", "build", "bench_verify"))
    parser.add_argument("--base", help="a second bench_verify, run alternately with the first")
    parser.add_argument("--cases", default="all", help="comma-separated: big, fig9, all, SAMPLES:TRIANGLES")
    parser.add_argument("--threads", default="1,2", help="thread counts, comma-separated")
    parser.add_argument("--runs", type=int, default=1, help="runs per process, minimum kept")
    parser.add_argument("--repeat", type=int, default=1, help="fresh processes per row and binary, alternated")
    args = parser.parse_args()
    threads = [int(t) for t in args.threads.split(",")]
    binaries = [args.bench] + ([args.base] if args.base else [])
    names = ["this"] + (["base"] if args.base else [])

    head = "| samples | triangles | threads "
    for name in names:
        head += f"| {name}: diagram s | verification s | ratio (wall) | peak memory "
    print(head + "|")
    print("|---:" * (3 + 4 * len(binaries)) + "|")
    failed = False
    for n, m in cases_of(args.cases):
        for t in threads:
            line = f"| {n} | {m} | {t} "
            rows = [[] for _ in binaries]
            for _ in range(max(1, args.repeat)):
                for k, b in enumerate(binaries):
                    rows[k].append(run(b, n, m, t, args.runs))
            for k in range(len(binaries)):
                failed = failed or any(r is None or not r["passed"] for r in rows[k])
                line += cells(rows[k])
            print(line + "|", flush=True)
    print("\nCPU seconds (user + sys, all threads) in compute_lrvd and verify_diagram, min / median / max over"
          " the processes; ratio = median verification / median diagram, in parentheses the same in wall seconds;"
          " peak = the processes' largest maximum resident set.")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
