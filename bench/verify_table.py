#!/usr/bin/env python3
"""Times the exact diagram verification against the diagram it checks, as `lrvd compute` runs both.

For each sample count and thread count, one fresh `lrvd compute MESH -n N --threads T` process
(no cells written) reports the diagram's `time_s` and the verification's; the script adds the
process's peak memory and whether the verification passed, and prints a Markdown table. It exits
1 if any verification failed or any run did not finish. docs/reference/verification.md, "Cost",
holds its numbers.

    bench/verify_table.py --lrvd build/lrvd                       # the elk, 20k to 200k samples
    bench/verify_table.py --lrvd build/lrvd --mesh build/cgal-data/bones.off --counts 10000,50000 --threads 2

Standard library only.
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile


def run(lrvd, mesh, n, threads, report):
    """One `lrvd compute` process: (exit status, peak memory in MB)."""
    with open(os.devnull, "wb") as quiet:
        proc = subprocess.Popen([lrvd, "compute", mesh, "-n", str(n), "--threads", str(threads), "--report", report],
                                stdout=quiet, stderr=quiet)
        _, status, usage = os.wait4(proc.pid, 0)
    proc.returncode = os.waitstatus_to_exitcode(status)
    return proc.returncode, usage.ru_maxrss / 1024  # Linux: kilobytes


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--lrvd", default=os.path.join(here, "..", "build", "lrvd"), help="the lrvd binary")
    parser.add_argument("--mesh", default=os.path.join(here, "..", "build", "cgal-data", "elk.off"))
    parser.add_argument("--counts", default="20000,50000,200000", help="sample counts, comma-separated")
    parser.add_argument("--threads", default="1,2", help="thread counts, comma-separated")
    args = parser.parse_args()
    counts = [int(c) for c in args.counts.split(",")]
    threads = [int(t) for t in args.threads.split(",")]

    print(f"`lrvd compute {os.path.basename(args.mesh)} -n N --threads T`, one fresh process per row\n")
    print("| samples | threads | diagram | verification | ratio | peak memory | verified |")
    print("|---:|---:|---:|---:|---:|---:|---|")
    failed = False
    with tempfile.TemporaryDirectory() as work:
        for n in counts:
            for t in threads:
                report = os.path.join(work, f"{n}_{t}.json")
                status, peak_mb = run(args.lrvd, args.mesh, n, t, report)
                if status not in (0, 3) or not os.path.exists(report):
                    print(f"| {n} | {t} | | | | | exit {status} |")
                    failed = True
                    continue
                with open(report) as f:
                    r = json.load(f)
                diagram, verification = r["diagram"]["time_s"], r["verification"]
                passed = verification["passed"]
                failed = failed or not passed
                print(f"| {n} | {t} | {diagram:.3f} s | {verification['time_s']:.3f} s | "
                      f"{verification['time_s'] / diagram:.1f} | {peak_mb:.0f} MB | {'yes' if passed else 'NO'} |")
                sys.stdout.flush()
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
