#!/usr/bin/env python3
"""`lrvd remesh` against geogram's vorpalite, side by side, in fresh processes on the same inputs.

For each row (an input and a vertex count N) the two tools run alternately, K times each, each run
a fresh process; the time is the CPU time of the whole process (user + sys of the child, from
os.wait4), so loading, checks and metrics count, as a user sees them. Per row: min / median / max
of each tool, the ratio of the medians (lrvd / vorpalite), and each output's vertex count and
validity from `lrvd quality REFERENCE OUTPUT --report` (closed 2-manifold, oriented, genus kept, no
degenerate or crossing triangle; Hausdorff distance and Qmin) for both tools. lrvd's own report adds
its loop's diagrams, repair rounds and runs.

    LRVD_PEER_VORPALITE=/path/to/vorpalite bench/peer_remesh.py --rows fast
    LRVD_PEER_VORPALITE=/path/to/vorpalite bench/peer_remesh.py --rows slow --runs 1
    LRVD_PEER_VORPALITE=/path/to/vorpalite bench/peer_remesh.py --rows fast --threads default

One thread (default): `lrvd --threads 1 remesh IN -n N` against `vorpalite IN OUT remesh:nb_pts=N
remesh:anisotropy=0 sys:multithread=false`; --threads default drops both limits. Without
LRVD_PEER_VORPALITE (or --peer) the script says so and measures lrvd alone. The rows measured
replace the same rows of the JSON file (--json); the markdown table, rendered from every row of that
file, replaces the one between the markers of --results. A benchmark, never a test. Standard
library only.
"""

import argparse
import hashlib
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

from mesh_sources import source_path

BEGIN_MARK = "<!-- peer_remesh.py table: begin -->"
END_MARK = "<!-- peer_remesh.py table: end -->"

# (row id, label, group, source kind, file or stress name, N). Groups: fast (CGAL's elk and
# armadillo), stress (stress meshes that need repair rounds), slow (shared meshes with many rounds).
ROWS = [
    ("elk-516", "CGAL elk", "fast", "cgal", "elk.off", 516),
    ("elk-1000", "CGAL elk", "fast", "cgal", "elk.off", 1000),
    ("armadillo-2000", "CGAL armadillo", "fast", "cgal", "armadillo.off", 2000),
    ("armadillo-4000", "CGAL armadillo", "fast", "cgal", "armadillo.off", 4000),
    ("folded_sheet-100", "stress folded_sheet", "stress", "stress", "folded_sheet", 100),
    ("folded_sheet-300", "stress folded_sheet", "stress", "stress", "folded_sheet", 300),
    ("thin_plate-100", "stress thin_plate", "stress", "stress", "thin_plate", 100),
    ("thin_plate-300", "stress thin_plate", "stress", "stress", "thin_plate", 300),
    ("feline-200", "feline (shared data)", "slow", "shared", "feline.off", 200),
    ("happy_buddha-300", "Happy Buddha (shared data)", "slow", "shared", "happy_buddha_51k.off", 300),
]
ROW_ORDER = {row[0]: i for i, row in enumerate(ROWS)}


def timed_run(argv, log_path):
    """Runs argv as a fresh process; returns (CPU s of that process, exit code)."""
    with open(log_path, "w") as log:
        child = subprocess.Popen(argv, stdout=log, stderr=subprocess.STDOUT)
        _, status, usage = os.wait4(child.pid, 0)
    child.returncode = os.waitstatus_to_exitcode(status)
    return usage.ru_utime + usage.ru_stime, child.returncode


def last_line(path):
    with open(path) as f:
        lines = [line.strip() for line in f if line.strip()]
    return lines[-1] if lines else ""


def digest(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def measure_output(lrvd, reference, output, workdir, tag):
    """`lrvd quality REFERENCE OUTPUT --report`: vertices, validity, genus, Hausdorff %, Qmin."""
    report = os.path.join(workdir, f"{tag}_quality.json")
    done = subprocess.run([lrvd, "quality", reference, output, "--report", report],
                          stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    # Exit 3: measured, and a check failed (the verdict is in the report).
    if done.returncode not in (0, 3) or not os.path.exists(report):
        return {"error": (done.stderr.strip().splitlines() or ["lrvd quality failed"])[-1]}
    with open(report) as f:
        r = json.load(f)
    check = r["verification"]
    q = r["quality"] or {}
    return {"vertices": q.get("vertices", 0), "valid": check["passed"], "genus": check["genus"],
            "failed": [name for name, p in check["properties"].items() if not p["passed"]],
            "hausdorff_pct": q.get("hausdorff_pct"), "q_min": q.get("Qmin")}


def tool_commands(args, source, n, output, report):
    """The two commands of one row: lrvd's (with --report) and vorpalite's."""
    lrvd = [args.lrvd] + (["--threads", "1"] if args.threads == "one" else [])
    lrvd += ["remesh", source, "-n", str(n), "-o", output["lrvd"], "--report", report]
    peer = [args.peer, source, output["peer"], f"remesh:nb_pts={n}", "remesh:anisotropy=0"]
    if args.threads == "one":
        peer.append("sys:multithread=false")
    return {"lrvd": lrvd, "peer": peer}


def spread(times):
    return {"min": min(times), "median": statistics.median(times), "max": max(times), "runs": times}


def measure_row(args, row, source, workdir):
    row_id, _, _, _, _, n = row
    tools = ["lrvd", "peer"] if args.peer else ["lrvd"]
    times = {tool: [] for tool in tools}
    digests = {tool: set() for tool in tools}
    errors = {}
    load_before = os.getloadavg()[0]
    outputs = {}
    lrvd_report = None
    for i in range(args.runs):
        output = {"lrvd": os.path.join(workdir, f"{row_id}_lrvd_{i}.off"),
                  "peer": os.path.join(workdir, f"{row_id}_peer_{i}.obj")}
        report = os.path.join(workdir, f"{row_id}_lrvd_{i}.json")
        commands = tool_commands(args, source, n, output, report)
        # The first tool alternates, so a drift of the machine's speed falls on both alike.
        for tool in (tools if i % 2 == 0 else tools[::-1]):
            log = os.path.join(workdir, f"{row_id}_{tool}_{i}.log")
            seconds, code = timed_run(commands[tool], log)
            # lrvd: exit 3 is an output written that failed a check (timed and measured).
            if code not in ((0, 3) if tool == "lrvd" else (0,)) or not os.path.exists(output[tool]):
                errors[tool] = f"exit {code}: {last_line(log)}"
                continue
            times[tool].append(seconds)
            digests[tool].add(digest(output[tool]))
            outputs.setdefault(tool, output[tool])
            if tool == "lrvd" and lrvd_report is None:
                with open(report) as f:
                    lrvd_report = json.load(f)
            print(f"  {row_id} {tool} run {i + 1}/{args.runs}: {seconds:.2f} s CPU (exit {code})", flush=True)
    result = {"id": row_id, "n": n, "threads": args.threads, "runs": args.runs,
              "date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
              "load": [round(load_before, 2), round(os.getloadavg()[0], 2)]}
    for tool in tools:
        entry = {"error": errors[tool]} if tool in errors else {}
        if times[tool]:
            entry.update(spread(times[tool]))
            entry["identical_outputs"] = len(digests[tool]) == 1
            entry["output"] = measure_output(args.lrvd, source, outputs[tool], workdir, f"{row_id}_{tool}")
        result[tool] = entry
    if times["lrvd"]:
        result["lrvd"]["loop"] = {key: lrvd_report.get(key) for key in
                                  ("diagram_evaluations", "repair_rounds", "runs", "iterations", "time_s")}
    if args.peer and times["lrvd"] and times["peer"]:
        result["ratio"] = result["lrvd"]["median"] / result["peer"]["median"]
    return result


def output_cell(entry, n):
    if "output" not in entry:
        return entry.get("error", "–")
    o = entry["output"]
    if "error" in o:
        return f"quality failed: {o['error']}"
    count = f"{o['vertices']} vertices" + ("" if o["vertices"] == n else " (**not N**)")
    verdict = "valid" if o["valid"] else "**invalid**: " + ", ".join(o["failed"])
    if "topology" in o["failed"]:
        verdict += f" (genus {o['genus']})"
    metrics = "" if o["hausdorff_pct"] is None else f", Hausdorff {o['hausdorff_pct']:.2f} %, Qmin {o['q_min']:.3f}"
    differ = "" if entry.get("identical_outputs", True) else " (outputs differ between runs: the first judged)"
    return f"{count}, {verdict}{metrics}{differ}"


def time_cell(entry):
    if "median" not in entry:
        return "–"
    return f"{entry['min']:.2f} / **{entry['median']:.2f}** / {entry['max']:.2f}"


def render_table(rows, peer_label):
    labels = {row[0]: row[1] for row in ROWS}
    lines = [f"| input | N | threads | K | lrvd CPU s (min / median / max) | {peer_label} CPU s | ratio | "
             f"lrvd output | lrvd loop: diagrams, repair rounds, runs | {peer_label} output | load |",
             "|---|---:|---|---:|---|---|---:|---|---|---|---|"]
    for r in sorted(rows, key=lambda r: (r["threads"] != "one", ROW_ORDER.get(r["id"], 99))):
        lrvd, peer = r.get("lrvd", {}), r.get("peer", {})
        loop = lrvd.get("loop") or {}
        loop_cell = (f"{loop['diagram_evaluations']}, {loop['repair_rounds']}, {loop['runs']}"
                     if loop else "–")
        ratio = f"{r['ratio']:.1f}" if "ratio" in r else "–"
        threads = "1" if r["threads"] == "one" else "default"
        lines.append(f"| {labels.get(r['id'], r['id'])} | {r['n']} | {threads} | {r['runs']} | {time_cell(lrvd)} | "
                     f"{time_cell(peer)} | {ratio} | {output_cell(lrvd, r['n'])} | {loop_cell} | "
                     f"{output_cell(peer, r['n'])} | {r['load'][0]:.1f}–{r['load'][1]:.1f} |")
    return "\n".join(lines)


def write_results(path, table, peer_note):
    with open(path) as f:
        text = f.read()
    if text.count(BEGIN_MARK) != 1 or text.count(END_MARK) != 1 or text.index(BEGIN_MARK) > text.index(END_MARK):
        sys.exit(f"{path} needs one '{BEGIN_MARK}' line and one '{END_MARK}' line after it")
    head, rest = text.split(BEGIN_MARK)
    _, tail = rest.split(END_MARK)
    body = (f"{BEGIN_MARK}\n"
            "Regenerate with `LRVD_PEER_VORPALITE=/path/to/vorpalite bench/peer_remesh.py --rows all` "
            "(`--rows fast|stress|slow`, `--runs K`, `--threads default`; bench/README.md). Whole process, "
            "CPU s (user + sys), K fresh runs of each tool alternated; ratio = lrvd median / peer median; "
            "outputs judged by `lrvd quality REFERENCE OUTPUT` (every check but the vertex count, which the "
            "vertices column shows); load = 1-minute load average before and after the row. "
            f"Peer: {peer_note}.\n\n{table}\n{END_MARK}")
    with open(path, "w") as f:
        f.write(head + body + tail)


def select_rows(spec):
    names = [s for s in spec.split(",") if s]
    groups = {row[2] for row in ROWS}
    chosen = [row for row in ROWS if "all" in names or row[2] in names or row[0] in names]
    unknown = [s for s in names if s != "all" and s not in groups and s not in ROW_ORDER]
    if unknown or not chosen:
        sys.exit(f"unknown rows {unknown}: give all, {', '.join(sorted(groups))} or row ids "
                 f"({', '.join(ROW_ORDER)})")
    return chosen


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--lrvd", default="build/lrvd", help="the lrvd binary (default build/lrvd)")
    parser.add_argument("--peer", default=os.environ.get("LRVD_PEER_VORPALITE", ""),
                        help="vorpalite binary (default: $LRVD_PEER_VORPALITE)")
    parser.add_argument("--peer-label", default="vorpalite", help="the peer's column name")
    parser.add_argument("--peer-note", default="",
                        help="how the peer was built (version, options), written above the table")
    parser.add_argument("--runs", type=int, default=3, help="runs of each tool per row, alternated (default 3)")
    parser.add_argument("--rows", default="all", help="all, fast, stress, slow or row ids, comma-separated")
    parser.add_argument("--threads", choices=["one", "default"], default="one",
                        help="one: lrvd --threads 1 and vorpalite sys:multithread=false; default: neither")
    parser.add_argument("--cgal", default="build/cgal-data", help="folder of CGAL's data-set meshes")
    parser.add_argument("--shared", default="/work/shared/data/meshes", help="folder of the shared benchmark meshes")
    parser.add_argument("--json", default="bench/peer_remesh.json", help="JSON file of the rows (merged)")
    parser.add_argument("--results", default="docs/results.md", help="markdown file with the table's markers")
    parser.add_argument("--no-write", action="store_true", help="print the table; write neither file")
    parser.add_argument("--render-only", action="store_true", help="measure nothing: rewrite the table from --json")
    args = parser.parse_args()
    if args.runs < 1:
        parser.error("--runs must be at least 1")
    if not os.access(args.lrvd, os.X_OK):
        parser.error(f"{args.lrvd} is not an executable file (build lrvd, or give --lrvd)")
    if not args.peer:
        print("vorpalite not given (set LRVD_PEER_VORPALITE or --peer): measuring lrvd alone", flush=True)
    elif not os.access(args.peer, os.X_OK):
        parser.error(f"{args.peer} is not an executable file (LRVD_PEER_VORPALITE / --peer)")
    measured = []
    if args.render_only:
        args.rows = ""
    with tempfile.TemporaryDirectory(prefix="peer_remesh_") as workdir:
        for row in select_rows(args.rows) if args.rows else []:
            print(f"{row[0]} (threads {args.threads}, load {os.getloadavg()[0]:.1f})", flush=True)
            measured.append(measure_row(args, row, source_path(args, row[3], row[4], workdir, row[0]), workdir))
            if "ratio" in measured[-1]:
                print(f"  ratio of medians (lrvd / vorpalite): {measured[-1]['ratio']:.2f}", flush=True)
    previous = {"rows": []}
    if os.path.exists(args.json):
        with open(args.json) as f:
            previous = json.load(f)
    rows = previous["rows"]
    keys = {(r["id"], r["threads"]) for r in measured}
    rows = [r for r in rows if (r["id"], r["threads"]) not in keys] + measured
    table = render_table(rows, args.peer_label)
    print(table)
    if args.no_write:
        return 0
    peer_note = args.peer_note or previous.get("peer_note") or "not described (give --peer-note)"
    with open(args.json, "w") as f:
        json.dump({"peer": args.peer_label, "peer_note": peer_note, "rows": rows}, f, indent=1)
        f.write("\n")
    write_results(args.results, table, peer_note)
    return 0


if __name__ == "__main__":
    sys.exit(main())
