#!/usr/bin/env python3
"""Runs `lrvd remesh` on every mesh of CGAL's data set and tabulates what its checks say.

The 20 benchmark rows (bench_remesh) are four models; this sweep is the rest of the world: CAD
parts, scans, animals with thin legs and horns, open sheets with holes, many-component files.
Each run's exit status is 0 (valid), 2 (input refused, with its one-line reason) or 3 (a check
failed: the failed checks are listed); anything else is a crash and is listed first.

    bench/cgal_sweep.py --lrvd build/lrvd --counts 200 --jobs 2 --out sweep.md
    bench/cgal_sweep.py --lrvd build/lrvd --counts 500,1000 --only cow,bull,bones --out sweep.md

The meshes come from /usr/share/doc/libcgal-dev/data.tar.gz (package libcgal-demo), extracted
into --data (default: a temporary directory). Results: docs/results.md, "CGAL's data set".
"""
import argparse
import concurrent.futures
import glob
import json
import os
import shlex
import subprocess
import tarfile
import tempfile
import time

ARCHIVE = "/usr/share/doc/libcgal-dev/data.tar.gz"  # in package libcgal-demo
SUFFIXES = (".off", ".obj", ".ply", ".stl")


def extract(data_dir):
    if not glob.glob(os.path.join(data_dir, "**", "*.off"), recursive=True):
        with tarfile.open(ARCHIVE) as archive:
            members = [m for m in archive.getmembers() if m.isfile() and m.name.endswith(SUFFIXES) and m.size < 3_000_000]
            archive.extractall(data_dir, members=members)
    return sorted(p for p in glob.glob(os.path.join(data_dir, "**", "*"), recursive=True) if p.endswith(SUFFIXES))


def run(lrvd, mesh, n, work, timeout, extra):
    base = os.path.join(work, f"{os.path.basename(mesh)}_{n}")
    report = base + ".json"
    start = time.monotonic()
    try:
        proc = subprocess.run([lrvd, "remesh", mesh, "-n", str(n), "-o", base + ".off", "--report", report,
                               "--threads", "1"] + extra, capture_output=True, text=True, timeout=timeout)
        status = proc.returncode
        stderr = proc.stderr.strip().splitlines()
    except subprocess.TimeoutExpired:
        status, stderr = "timeout", []
    row = {"mesh": os.path.basename(mesh), "n": n, "exit": status, "seconds": round(time.monotonic() - start, 1)}
    if status in (0, 3) and os.path.exists(report):
        with open(report) as f:
            r = json.load(f)
        row.update(repair_rounds=r["repair_rounds"], second_run=r["kept_to_sheets"], q_min=r["quality"]["Qmin"],
                   hausdorff_pct=r["quality"]["hausdorff_pct"], components=r["input"]["components"],
                   closed=r["input"]["closed"],
                   failed={k: p["violations"] for k, p in r["verification"]["properties"].items() if not p["passed"]})
    elif stderr:
        row["message"] = stderr[-1]
    return row


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--lrvd", default="build/lrvd")
    parser.add_argument("--counts", default="200", help="comma-separated vertex counts")
    parser.add_argument("--only", default="", help="comma-separated mesh names without suffix")
    parser.add_argument("--data", default="", help="where the data set is (extracted there if empty)")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--timeout", type=float, default=900)
    parser.add_argument("--out", default="", help="markdown table; JSON rows go beside it")
    parser.add_argument("--remesh-args", default="", help="more lrvd remesh options, e.g. '--density curvature'")
    args = parser.parse_args()

    data = args.data or tempfile.mkdtemp(prefix="cgal_data_")
    meshes = extract(data)
    if args.only:
        wanted = set(args.only.split(","))
        meshes = [m for m in meshes if os.path.splitext(os.path.basename(m))[0] in wanted]
    counts = [int(c) for c in args.counts.split(",")]
    work = tempfile.mkdtemp(prefix="cgal_sweep_")
    jobs = [(m, n) for m in meshes for n in counts]
    with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        rows = list(pool.map(lambda job: run(args.lrvd, job[0], job[1], work, args.timeout, shlex.split(args.remesh_args)), jobs))

    tally = {}
    for row in rows:
        tally[str(row["exit"])] = tally.get(str(row["exit"]), 0) + 1
    lines = [f"{len(rows)} runs: " + ", ".join(f"exit {k}: {v}" for k, v in sorted(tally.items())), "",
             "| mesh | N | exit | s | components | closed | rounds | second run | Qmin | Hausdorff % | failed checks |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    order = {"0": 3, "2": 2, "3": 1}
    for row in sorted(rows, key=lambda r: (order.get(str(r["exit"]), 0), r["mesh"], r["n"])):
        if row["exit"] == 2:
            continue  # refused input: counted above
        failed = ", ".join(f"{k} {v}" for k, v in row.get("failed", {}).items()) or row.get("message", "")
        lines.append(f"| {row['mesh']} | {row['n']} | {row['exit']} | {row['seconds']} | {row.get('components', '')} | "
                     f"{row.get('closed', '')} | {row.get('repair_rounds', '')} | {row.get('second_run', '')} | "
                     f"{row.get('q_min', 0):.3f} | {row.get('hausdorff_pct', 0):.2f} | {failed} |")
    text = "\n".join(lines) + "\n"
    if args.out:
        with open(args.out, "w") as f:
            f.write(text)
        with open(os.path.splitext(args.out)[0] + ".json", "w") as f:
            json.dump(rows, f, indent=1)
    print(text)


if __name__ == "__main__":
    main()
