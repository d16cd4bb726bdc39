#!/usr/bin/env python3
"""The judge's cost against the diagram's on bench_fig9's spheres: verify_diagram vs compute_lrvd.

Each (case, thread count, binary) is one fresh `bench_verify --row N T --threads K` process under
/usr/bin/time -v (for its peak memory); with --base, a second bench_verify (built from other code)
runs each case right after the first, so both see the same load. Times are CPU seconds of the
process (user + sys, all threads) spent in each call; `ratio` = verification / diagram. Prints a
Markdown table; exits 1 if a verification failed or a run did not finish.

    bench/verify_sphere.py --bench build/bench_verify                        # every case, 1 and 2 threads
    bench/verify_sphere.py --bench build/bench_verify --base ../main-build/bench_verify --cases big
    bench/verify_sphere.py --bench build/bench_verify --cases 20000:80000 --threads 1

Cases, comma-separated: `big` (100k samples on 327,680 triangles, 1M on 1,310,720), `fig9` (the
14 rows of bench_fig9), `all` (both), SAMPLES:TRIANGLES. Standard library only.
"""

import argparse
import json
import os
import re
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


def cells(row):
    if row is None:
        return "| | | | did not finish "
    ratio = row["verify_cpu_s"] / max(row["diagram_cpu_s"], 1e-9)
    wall = row["verify_wall_s"] / max(row["diagram_wall_s"], 1e-9)
    mark = "" if row["passed"] else " FAIL"
    return (f"| {row['diagram_cpu_s']:.2f} | {row['verify_cpu_s']:.2f}{mark} | {ratio:.2f} ({wall:.2f}) "
            f"| {row['peak_mb']:.0f} MB ")


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--bench", default=os.path.join(here, "..", "build", "bench_verify"))
    parser.add_argument("--base", help="a second bench_verify, run alternately with the first")
    parser.add_argument("--cases", default="all", help="comma-separated: big, fig9, all, SAMPLES:TRIANGLES")
    parser.add_argument("--threads", default="1,2", help="thread counts, comma-separated")
    parser.add_argument("--runs", type=int, default=1, help="runs per process, minimum kept")
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
            for b in binaries:
                row = run(b, n, m, t, args.runs)
                failed = failed or row is None or not row["passed"]
                line += cells(row)
            print(line + "|", flush=True)
    print("\nCPU seconds (user + sys, all threads) in compute_lrvd and verify_diagram; ratio = verification /"
          " diagram, in parentheses the same in wall seconds; peak = the process's maximum resident set.")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
