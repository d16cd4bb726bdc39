#!/usr/bin/env python3
"""`lrvd remesh` on the hard rows, seeds 1-3: which runs end valid, with what triangles and distance.

The rows are the meshes that need repair rounds: the shared benchmark meshes at 200 and 1000
vertices, CGAL's elk, armadillo and knot at 300-1000, the stress meshes at few vertices and eleven of
CGAL's meshes at 200. Each run is `lrvd --threads 1 remesh MESH -n N --seed S` as a fresh process;
its report gives validity (exit 0), Qmin, the Hausdorff distance and the repair rounds, and os.wait4
its CPU seconds. --jobs runs at a time (the times are then upper bounds). The runs are kept in the
JSON file (--json) and only the missing ones run, so an interrupted sweep resumes; the markdown
table, rendered from that file, replaces the one between the markers of --results.

    bench/hard_rows.py --jobs 2
    bench/hard_rows.py --rows comb-100,thin_tube-30 --json /tmp/h.json --results ''

A benchmark, never a test. Standard library only.
"""

import argparse
import concurrent.futures
import json
import os
import subprocess
import tempfile

from mesh_sources import source_path

BEGIN_MARK = "<!-- hard_rows.py table: begin -->"
END_MARK = "<!-- hard_rows.py table: end -->"

# (label, source kind, file or stress name, N); kinds: shared (--shared), cgal (--cgal), stress
# (made by `lrvd stress NAME` at its default scale).
SHARED = ["feline.off", "dragon_100k.off", "happy_buddha_51k.off", "horse_97k.ply", "stanford_bunny_bun_zipper.ply",
          "gargoyle_100k.off"]
ROWS = (
    [(f"{os.path.splitext(f)[0].replace('_bun_zipper', '')} 200", "shared", f, 200) for f in SHARED]
    + [(f"{os.path.splitext(f)[0].replace('_bun_zipper', '')} 1000", "shared", f, 1000) for f in SHARED if f != "gargoyle_100k.off"]
    + [(f"{m} {n}", "cgal", f"{m}.off", n) for m in ("elk", "armadillo", "knot")
       for n in (300, 516, 1000)]
    + [(f"{m} {n}", "stress", m, n) for m, counts in (("comb", (80, 100, 140)), ("thin_plate", (50, 100)),
                                                      ("folded_sheet", (100, 200)), ("open_cup", (100, 200)),
                                                      ("knot_tube", (200,)), ("thin_tube", (30, 60)))
       for n in counts]
    + [(f"CGAL {m} 200", "cgal", f"{m}.off", 200) for m in ("bones", "diplodocus", "fold", "holes", "lion", "man", "mpi",
                                                          "pig", "triceratops", "ChineseDragon-10kv", "bunny00")]
)
SEEDS = (1, 2, 3)


def row_id(row):
    return row[0].replace("CGAL ", "").replace(" ", "-")


def run_one(lrvd, path, n, seed):
    with tempfile.TemporaryDirectory() as d:
        report = os.path.join(d, "r.json")
        child = subprocess.Popen([lrvd, "--threads", "1", "remesh", path, "-n", str(n), "--seed", str(seed), "-o",
                                  os.path.join(d, "o.off"), "--report", report],
                                 stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        _, status, usage = os.wait4(child.pid, 0)
        r = json.load(open(report)) if os.path.exists(report) else {}
    q = r.get("quality", {})
    return {"exit": os.waitstatus_to_exitcode(status), "cpu_s": usage.ru_utime + usage.ru_stime,
            "triangles": r.get("input", {}).get("triangles"), "qmin": q.get("Qmin"), "hausdorff_pct": q.get("hausdorff_pct"),
            "rounds": r.get("repair_rounds"), "diagrams": r.get("diagram_evaluations"), "lloyd_rounds": r.get("lloyd_rounds"),
            "defects": r.get("defects_left", {}).get("summary")}


def span(values, fmt):
    values = [v for v in values if v is not None]
    return f"{fmt(min(values))}–{fmt(max(values))}" if values else "–"


def render(runs):
    lines = ["| row | input triangles | valid, seeds 1–3 | Qmin | Hausdorff % | rounds | s |",
             "|---|---:|---|---|---|---|---|"]
    valid = total = 0
    for row in ROWS:
        got = [runs.get(f"{row_id(row)}:{s}") for s in SEEDS]
        if any(g is None for g in got):
            continue
        marks = "".join("✓" if g["exit"] == 0 else "✗" for g in got)
        valid += marks.count("✓")
        total += len(got)
        lines.append(f"| {row[0]} | {got[0]['triangles']:,} | {marks.count('✓')} ({marks}) | "
                     f"{span([g['qmin'] for g in got], lambda v: f'{v:.3f}')} | "
                     f"{span([g['hausdorff_pct'] for g in got], lambda v: f'{v:.2f}')} | "
                     f"{span([g['rounds'] for g in got], str)} | {span([g['cpu_s'] for g in got], lambda v: f'{v:.1f}')} |")
    return lines, valid, total


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--lrvd", default="build/lrvd")
    parser.add_argument("--cgal", default="build/cgal-data", help="folder of CGAL's data-set meshes")
    parser.add_argument("--shared", default="/work/shared/data/meshes", help="folder of the shared benchmark meshes")
    parser.add_argument("--rows", default="all", help="all, or row ids (e.g. comb-100,bones-200), comma-separated")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--json", default="bench/hard_rows.json", help="JSON file of the runs (merged)")
    parser.add_argument("--results", default="docs/results.md", help="where the table goes ('' for none)")
    args = parser.parse_args()
    rows = ROWS if args.rows == "all" else [r for r in ROWS if row_id(r) in args.rows.split(",")]
    runs = json.load(open(args.json)) if os.path.exists(args.json) else {}
    with tempfile.TemporaryDirectory() as workdir:
        todo = [(row, s) for row in rows for s in SEEDS if f"{row_id(row)}:{s}" not in runs]
        paths = {row_id(row): source_path(args, row[1], row[2], workdir, row[0]) for row, _ in todo}
        with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
            futures = {pool.submit(run_one, args.lrvd, paths[row_id(row)], row[3], s): (row, s) for row, s in todo}
            for future in concurrent.futures.as_completed(futures):
                row, s = futures[future]
                runs[f"{row_id(row)}:{s}"] = future.result()
                print(f"{row[0]} seed {s}: {runs[f'{row_id(row)}:{s}']}", flush=True)
                json.dump(runs, open(args.json, "w"), indent=1, sort_keys=True)
    lines, valid, total = render(runs)
    print("\n".join(lines))
    print(f"{valid} of {total} runs valid")
    if args.results:
        text = open(args.results).read()
        begin, end = text.index(BEGIN_MARK) + len(BEGIN_MARK), text.index(END_MARK)
        table = "\n".join(lines) + f"\n\n{valid} of the {total} runs are valid.\n"
        open(args.results, "w").write(text[:begin] + "\n" + table + text[end:])


if __name__ == "__main__":
    main()
