#!/usr/bin/python3
"""Draws the build's layers (docs/architecture.md) from CMake's own dependency graph.

    /usr/bin/python3 scripts/layers_graph.py build docs/layers.svg   (Debian's python3-matplotlib)

Runs `cmake --graphviz` on the configured build folder, keeps lrvd's libraries and the two programs
on top of them (the lrvd command, the Python module), and draws each as a box, the layers it links
below it, one arrow per link. The boxes' places are set below (PLACES), so that no link passes over a box.
"""
import os
import re
import subprocess
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# Umbrella names for users (lrvd_core, lrvd_verification) are no layer; tests and benches sit on top.
SHOWN = re.compile(r"^lrvd(_[a-z]+)?$")
HIDDEN = {"lrvd_core", "lrvd_verification", "lrvd_tests", "lrvd_bench", "lrvd_fuzz_entry", "lrvd_fuzz_seeds"}
PROGRAMS = {"lrvd": "src/cli", "lrvd_python": "python/src"}


def read_graph(build):
    with tempfile.TemporaryDirectory() as tmp:
        dot = os.path.join(tmp, "lrvd.dot")
        subprocess.run(["cmake", f"--graphviz={dot}", build], check=True, stdout=subprocess.DEVNULL)
        text = open(dot).read()
    names = {n: label.split("\\n")[0] for n, label in re.findall(r'"(node\d+)" \[ label = "([^"]+)"', text)}
    edges = re.findall(r'"(node\d+)" -> "(node\d+)"', text)
    keep = {n for n, label in names.items() if SHOWN.match(label) and label not in HIDDEN}
    nodes = sorted(names[n] for n in keep)
    links = {name: set() for name in nodes}
    for a, b in edges:
        if a in keep and b in keep and names[a] != names[b]:
            links[names[a]].add(names[b])
    return nodes, links


def folder_of(build, name, source_dir):
    """The folder a layer's include root links to (build/layers/NAME/FOLDER), from the sources' root."""
    if name in PROGRAMS:
        return PROGRAMS[name]
    root = os.path.join(build, "layers", name)
    folders = os.listdir(root) if os.path.isdir(root) else []
    return os.path.relpath(os.path.realpath(os.path.join(root, folders[0])), source_dir) + "/" if folders else ""


# Where each box goes (x, tier), chosen so that no link passes over another box. The links are
# the build's; a layer this table does not know yet is put on the right, above what it links.
PLACES = {
    "lrvd": (-1, 6), "lrvd_python": (1, 6),
    "lrvd_report": (-1, 5), "lrvd_render": (2.5, 5),
    "lrvd_verify": (-2.5, 4), "lrvd_mps": (-1, 4), "lrvd_remesh": (0.5, 4),
    "lrvd_voronoi": (-1, 3), "lrvd_metrics": (1, 3),
    "lrvd_diagram": (-1, 2), "lrvd_samples": (0, 1), "lrvd_io": (0, 0), "lrvd_mesh": (0, -1),
    "lrvd_common": (-1, -2), "lrvd_predicates": (1, -2),
}


def place(nodes, links):
    x, tier = {}, {}
    right = max(p[0] for p in PLACES.values())

    def put(n):
        if n in x:
            return
        for d in links[n]:
            put(d)
        if n in PLACES:
            x[n], tier[n] = PLACES[n]
        else:
            right_now = max([right] + list(x.values()))
            x[n], tier[n] = right_now + 1.5, 1 + max((tier[d] for d in links[n]), default=-3)
            print(f"layers_graph.py: {n} is not in PLACES; put on the right", file=sys.stderr)

    for n in nodes:
        put(n)
    return x, tier


def draw(build, out):
    nodes, links = read_graph(build)
    cache = open(os.path.join(build, "CMakeCache.txt")).read()
    source_dir = re.search(r"^lrvd_SOURCE_DIR:STATIC=(.*)$", cache, re.M).group(1)
    x, tier = place(nodes, links)
    width = max(abs(v) for v in x.values()) + 0.6
    rows = sorted(set(tier.values()))
    fig, ax = plt.subplots(figsize=(2.3 * width + 1, 1.05 * len(rows) + 0.5))
    for n in nodes:
        for d in sorted(links[n]):
            ax.annotate("", xy=(x[d] * 2.3, tier[d] + 0.22), xytext=(x[n] * 2.3, tier[n] - 0.22),
                        arrowprops=dict(arrowstyle="-|>", color="#667", lw=0.9, shrinkA=0, shrinkB=0,
                                        ))
    for n in nodes:
        ax.text(x[n] * 2.3, tier[n], f"{n}\n{folder_of(build, n, source_dir)}", ha="center", va="center", fontsize=9,
                family="DejaVu Sans Mono",
                bbox=dict(boxstyle="round,pad=0.35", fc="#eef3fb" if n not in PROGRAMS else "#fdf3e3", ec="#445"))
    ax.set_xlim(-2.3 * width, 2.3 * width)
    ax.set_ylim(min(rows) - 0.6, max(rows) + 0.6)
    ax.axis("off")
    plt.rcParams["svg.hashsalt"] = "lrvd-layers"
    fig.savefig(out, bbox_inches="tight", metadata={"Date": None} if out.endswith(".svg") else None)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: layers_graph.py BUILD_DIR OUT.svg")
    draw(sys.argv[1], sys.argv[2])
