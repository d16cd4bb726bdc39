"""Where a benchmark row's input is: a stress mesh made by `lrvd stress NAME` into a work folder, or
a file of CGAL's data set (--cgal) or of the shared benchmark meshes (--shared)."""

import os
import subprocess
import sys


def source_path(args, kind, name, workdir, row_label):
    """The input's path; kind is "stress", "cgal" or "shared". Exits with a one-line reason when a
    file is missing."""
    if kind == "stress":
        path = os.path.join(workdir, name + ".off")
        if not os.path.exists(path):
            subprocess.run([args.lrvd, "stress", name, "-o", path], check=True, stdout=subprocess.DEVNULL)
        return path
    path = os.path.join(args.cgal if kind == "cgal" else args.shared, name)
    if not os.path.exists(path):
        sys.exit(f"{path} not found: give --cgal or --shared (row {row_label})")
    return path
