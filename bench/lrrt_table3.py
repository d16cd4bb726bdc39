#!/usr/bin/env python3
"""`lrvd mps --remesh` on the paper's Table 3 models: is the LRRT valid, at the one radius and with
the rounds of smaller disks round its defects?

    bench/lrrt_table3.py                                  # r = 0.005 and 0.01, uniform and adaptive, seeds 1-3
    bench/lrrt_table3.py --models feline --radii 0.005 --seeds 1

For each model, radius, mode and seed, two fresh processes: `lrvd --threads 1 mps MODEL --radius R
[--adaptive] --seed S --remesh OUT --keep-radius` (the LRRT of the one radius) and the same without
--keep-radius (the default: up to 8 rounds that halve the radius round the LRRT's defects and
sample again there). Per row (model, radius, mode): the runs whose LRRT passed its checks each way,
the rounds taken, the smallest radius reached, and the default's whole-process CPU seconds; the
rows with an LRRT still refused are listed under the table with the seeds and the first one's
one-line reason. The models and folders are
bench/mps_table3.py's. The JSON file (--json) keeps every run; the markdown table replaces the one
between the markers of --results. A benchmark, never a test. Standard library only.
"""

import argparse
import importlib.util
import json
import os
import statistics
import subprocess
import sys
import tempfile

BEGIN_MARK = "<!-- lrrt_table3.py table: begin -->"
END_MARK = "<!-- lrrt_table3.py table: end -->"


def mps_table3():
    """bench/mps_table3.py as a module (its model list and find_meshes)."""
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "mps_table3.py")
    spec = importlib.util.spec_from_file_location("mps_table3", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def run(binary, path, radius, mode, seed, keep, workdir):
    """One fresh `lrvd mps --remesh` process: (exit code, report or None, process CPU s)."""
    report = os.path.join(workdir, "report.json")
    if os.path.exists(report):
        os.remove(report)
    command = [binary, "--threads", "1", "mps", path, "--radius", str(radius), "--seed", str(seed),
               "-o", os.path.join(workdir, "samples.xyz"), "--remesh", os.path.join(workdir, "lrrt.obj"),
               "--report", report]
    if mode == "adaptive":
        command.append("--adaptive")
    if keep:
        command.append("--keep-radius")
    process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    _, status, usage = os.wait4(process.pid, 0)
    code = os.waitstatus_to_exitcode(status)
    result = None
    if os.path.exists(report):
        with open(report) as f:
            result = json.load(f)
    return code, result, usage.ru_utime + usage.ru_stime


def measure(args, meshes):
    runs = []
    with tempfile.TemporaryDirectory() as workdir:
        for name, path in meshes:
            for radius in args.radii:
                for mode in args.modes:
                    for seed in args.seeds:
                        entry = {"model": name, "radius": radius, "mode": mode, "seed": seed}
                        for keep in (True, False):
                            code, report, cpu = run(args.lrvd, path, radius, mode, seed, keep, workdir)
                            remesh = (report or {}).get("remesh") or {}
                            entry["keep" if keep else "default"] = {
                                "exit": code,
                                "valid": bool(remesh.get("valid")),
                                "maximal": bool(report and report.get("maximal") and report.get("min_distance_ok")),
                                "samples": (report or {}).get("samples"),
                                "rounds": (remesh.get("smaller_disks") or {}).get("rounds"),
                                "smallest_radius": (remesh.get("smaller_disks") or {}).get("smallest_radius"),
                                "refusal": remesh.get("refusal"),
                                "cpu_s": cpu,
                            }
                        d = entry["default"]
                        print(f"{name} r={radius} {mode} seed {seed}: one radius "
                              f"{'valid' if entry['keep']['valid'] else 'invalid'}, default "
                              f"{'valid' if d['valid'] else 'invalid'} after {d['rounds']} rounds, "
                              f"{d['cpu_s']:.1f} CPU s", flush=True)
                        runs.append(entry)
    return runs


def table(runs, args):
    rows = {}
    for entry in runs:
        rows.setdefault((entry["model"], entry["radius"], entry["mode"]), []).append(entry)
    lines = [
        "Regenerate with `bench/lrrt_table3.py` (one thread; the models of `bench/mps_table3.py`). Per model, "
        "radius and mode, over the seeds: the runs whose LRRT passed its checks at the one radius "
        "(`--keep-radius`) and by default (the rounds of smaller disks round its defects), the rounds taken "
        "(min–max), the smallest radius reached, and the default's whole-process CPU seconds (min / median / "
        "max, the sampling, its checks, the LRRT and the rounds). Every run is maximal with the minimum "
        "distance unless the table says otherwise.",
        "",
        "| model | radius | mode | seeds | valid, one radius | valid, default | rounds | smallest radius | CPU s, default |",
        "|---|---:|---|---|---:|---:|---|---:|---|",
    ]
    refused = []
    for (model, radius, mode), entries in rows.items():
        keep_valid = sum(e["keep"]["valid"] for e in entries)
        default_valid = sum(e["default"]["valid"] for e in entries)
        rounds = [e["default"]["rounds"] or 0 for e in entries]
        smallest = min(e["default"]["smallest_radius"] or radius for e in entries)
        cpu = [e["default"]["cpu_s"] for e in entries]
        maximal = all(e["default"]["maximal"] and e["keep"]["maximal"] for e in entries)
        seeds = ",".join(str(e["seed"]) for e in entries)
        lines.append(f"| {model} | {radius:g} | {mode} | {seeds} | {keep_valid} of {len(entries)} | "
                     f"{default_valid} of {len(entries)}{'' if maximal else ' (NOT all maximal)'} | "
                     f"{min(rounds)}–{max(rounds)} | {smallest:.3g} | "
                     f"{min(cpu):.1f} / **{statistics.median(cpu):.1f}** / {max(cpu):.1f} |")
        failed = [e for e in entries if not e["default"]["valid"]]
        if failed:
            seeds_failed = ", ".join(str(e["seed"]) for e in failed)
            first = failed[0]["default"]
            which = f"seeds {seeds_failed}; seed {failed[0]['seed']}" if len(failed) > 1 else f"seed {seeds_failed}"
            refused.append(f"- {model}, r = {radius:g} {mode}, {which}: {first['refusal'] or 'exit ' + str(first['exit'])}")
    keep_total = sum(e["keep"]["valid"] for e in runs)
    default_total = sum(e["default"]["valid"] for e in runs)
    lines += ["", f"In all: {keep_total} of {len(runs)} valid at the one radius, {default_total} of {len(runs)} "
                  "by default."]
    if refused:
        lines += ["", "Refused by default:", ""] + refused
    return "\n".join(lines) + "\n"


def write_results(path, text):
    with open(path) as f:
        content = f.read()
    begin, end = content.find(BEGIN_MARK), content.find(END_MARK)
    if begin < 0 or end < begin:
        sys.exit(f"lrrt_table3: {path} has no {BEGIN_MARK} ... {END_MARK} markers")
    content = content[:begin] + BEGIN_MARK + "\n" + text + END_MARK + content[end + len(END_MARK):]
    with open(path, "w") as f:
        f.write(content)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--lrvd", default="build/lrvd", help="the lrvd binary (default build/lrvd)")
    parser.add_argument("--cgal", default="build/cgal-data", help="folder of CGAL's data-set meshes")
    parser.add_argument("--shared", default="/work/shared/data/meshes", help="folder of the shared benchmark meshes")
    parser.add_argument("--models", default="", help="comma-separated model names (default: all found)")
    parser.add_argument("--radii", default="0.005,0.01", help="comma-separated radii (default 0.005,0.01)")
    parser.add_argument("--modes", default="uniform,adaptive", help="uniform, adaptive or both")
    parser.add_argument("--seeds", default="1,2,3", help="comma-separated seeds (default 1,2,3)")
    parser.add_argument("--json", default="bench/lrrt_table3.json", help="JSON file of every run")
    parser.add_argument("--results", default="docs/results.md", help="markdown file with the table's markers")
    parser.add_argument("--no-write", action="store_true", help="print the table; write neither file")
    parser.add_argument("--render-only", action="store_true", help="measure nothing: the table from --json")
    args = parser.parse_args()
    args.radii = [float(x) for x in args.radii.split(",")]
    args.modes = args.modes.split(",")
    args.seeds = [int(x) for x in args.seeds.split(",")]
    if not set(args.modes) <= {"uniform", "adaptive"}:
        sys.exit("lrrt_table3: --modes takes uniform and/or adaptive")
    if not (os.path.isfile(args.lrvd) and os.access(args.lrvd, os.X_OK)):
        sys.exit(f"lrrt_table3: {args.lrvd} is not an executable (build the project first)")
    if args.render_only:
        with open(args.json) as f:
            runs = json.load(f)
    else:
        runs = measure(args, mps_table3().find_meshes(args))
    text = table(runs, args)
    print(text)
    if args.no_write:
        return
    if not args.render_only:
        with open(args.json, "w") as f:
            json.dump(runs, f, indent=1)
    write_results(args.results, text)


if __name__ == "__main__":
    main()
