#!/usr/bin/env python3
"""Time two builds of `lrvd` against each other, alternately, on one command.

On a shared VM the speed drifts by tens of percent within an hour, so two timings taken minutes
apart say little; runs of the two builds interleaved, one after the other, can be compared. Each
run is a fresh process (as a user runs it). For each build the script reports the median and
minimum of the command's own `time_s` (from its --report JSON: the remesh, the MPS sampler's
total, or compute's diagram), the ratio of the medians, and the process's minor page faults and kernel time (fresh
pages cost about 1.7 us each on this project's VM). With
--same-output it also checks that both builds wrote byte-identical outputs.

    bench/ab_compare.py --base /tmp/lrvd_old --new build/lrvd --runs 5 -- \\
        remesh build/cgal-data/elk.off -n 516 --threads 1
    bench/ab_compare.py --base /tmp/lrvd_old --new build/lrvd --runs 3 --same-output -- \\
        mps build/cgal-data/ChineseDragon-10kv.off --radius 0.005 --threads 1

The command is given without -o and --report: the script adds both (a temporary file each).
Standard library only.
"""

import argparse
import filecmp
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile

OUTPUT_SUFFIX = {"remesh": ".off", "mps": ".xyz", "compute": ".ply"}


def run_once(binary, command, workdir, tag, index):
    """Runs `binary command -o OUT --report R`; returns (time_s, minor faults, kernel s, OUT)."""
    suffix = OUTPUT_SUFFIX.get(command[0], ".out")
    output = os.path.join(workdir, f"{tag}_{index}{suffix}")
    report = os.path.join(workdir, f"{tag}_{index}.json")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    done = subprocess.run([binary] + command + ["-o", output, "--report", report],
                          stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    # Exit 3 is a written output that failed a check (reported, still timed); anything else failed.
    if done.returncode not in (0, 3):
        sys.exit(f"{binary} exited with {done.returncode}: {done.stderr.strip().splitlines()[-1:]}")
    with open(report) as f:
        r = json.load(f)
    t = r["time_s"] if "time_s" in r else r["diagram"]["time_s"]  # compute: the diagram's time
    seconds = t["total"] if isinstance(t, dict) else t
    return seconds, after.ru_minflt - before.ru_minflt, after.ru_stime - before.ru_stime, output


def summary(name, runs):
    times = [r[0] for r in runs]
    faults = [r[1] for r in runs]
    kernel = [r[2] for r in runs]
    print(f"{name}: median {statistics.median(times):.3f} s, min {min(times):.3f} s "
          f"({' '.join(f'{x:.3f}' for x in times)}); minor faults {statistics.median(faults):.0f}; "
          f"kernel {min(kernel):.2f}-{max(kernel):.2f} s")
    return statistics.median(times)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--base", required=True, help="the build to compare against (an lrvd binary)")
    parser.add_argument("--new", required=True, help="the build measured (an lrvd binary)")
    parser.add_argument("--runs", type=int, default=5, help="runs of each build, interleaved (default 5)")
    parser.add_argument("--same-output", action="store_true", help="also require byte-identical outputs")
    parser.add_argument("command", nargs=argparse.REMAINDER, help="-- then the lrvd command, without -o/--report")
    args = parser.parse_args()
    command = args.command[1:] if args.command[:1] == ["--"] else args.command
    if not command:
        parser.error("no command given (put it after --)")
    if args.runs < 1:
        parser.error("--runs must be at least 1")
    for binary in (args.base, args.new):
        if not os.access(binary, os.X_OK):
            parser.error(f"{binary} is not an executable file")
    results = {"base": [], "new": []}
    with tempfile.TemporaryDirectory(prefix="ab_compare_") as workdir:
        for i in range(args.runs):
            for tag, binary in (("base", args.base), ("new", args.new)):
                results[tag].append(run_once(binary, command, workdir, tag, i))
        if args.same_output:
            different = [i for i in range(args.runs)
                         if not filecmp.cmp(results["base"][i][3], results["new"][i][3], shallow=False)]
            print("outputs: " + ("identical" if not different else f"DIFFERENT in runs {different}"))
        base = summary("base", results["base"])
        new = summary("new ", results["new"])
    print(f"ratio of medians (new / base): {new / base:.3f}")
    return 1 if args.same_output and different else 0


if __name__ == "__main__":
    sys.exit(main())
