# The module against the lrvd command of the same build: the same inputs give the same outputs and
# the same reports (but for times and file paths); remesh and MPS keep their promises.
import json
import os

import numpy as np
import pytest

import lrvd
from conftest import without_times_and_paths


def read_cells_ply(path):
    """The binary PLY `lrvd compute -o` writes: vertices (double x, y, z); faces (uchar count, int
    indices, int cell, uchar r, g, b)."""
    data = open(path, "rb").read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode().split("\n")
    nv = next(int(l.split()[2]) for l in header if l.startswith("element vertex"))
    nf = next(int(l.split()[2]) for l in header if l.startswith("element face"))
    vertices = np.frombuffer(data, dtype="<f8", count=3 * nv, offset=end).reshape(nv, 3)
    at = end + 24 * nv
    faces, cells = [], []
    for _ in range(nf):
        k = data[at]
        faces.append(np.frombuffer(data, dtype="<i4", count=k, offset=at + 1))
        cells.append(int(np.frombuffer(data, dtype="<i4", count=1, offset=at + 1 + 4 * k)[0]))
        at += 1 + 4 * k + 4 + 3
    return vertices, faces, cells


def test_compute_points_as_the_command(elk, data_dir, cli, tmp_path):
    V, F = elk
    rng = np.random.default_rng(7)
    t = rng.choice(len(F), 150, replace=False)
    b = rng.dirichlet([1, 1, 1], 150)
    points = np.einsum("ki,kij->kj", b, V[F[t]])
    xyz = tmp_path / "points.xyz"
    np.savetxt(xyz, points, fmt="%.17g")
    cli("compute", os.path.join(data_dir, "elk.off"), "--points", xyz, "-o", tmp_path / "cells.ply",
        "--report", tmp_path / "report.json")
    d = lrvd.compute(V, F, points=np.loadtxt(xyz))
    expected = json.load(open(tmp_path / "report.json"))
    assert without_times_and_paths(d.report) == without_times_and_paths(expected)
    assert d.report["verification"]["passed"]
    vertices, faces, cells = read_cells_ply(tmp_path / "cells.ply")
    c = d.cells
    assert np.array_equal(vertices, c["vertices"])
    assert cells == c["polygon_cell"].tolist()
    assert all(np.array_equal(f, c["polygon_vertices"][c["polygon_offsets"][p]:c["polygon_offsets"][p + 1]])
               for p, f in enumerate(faces))


def test_compute_random_and_weighted_as_the_command(cli, tmp_path):
    V, F = lrvd.stress("comb")
    lrvd.write_mesh(str(tmp_path / "comb.off"), V, F)
    weights = np.linspace(0, 1e-4, 80)
    np.savetxt(tmp_path / "w.txt", weights, fmt="%.17g")
    cli("compute", tmp_path / "comb.off", "-n", 80, "--seed", 5, "--diagram", "lrpd", "--weights", tmp_path / "w.txt",
        "--report", tmp_path / "report.json")
    d = lrvd.compute(V, F, n=80, seed=5, diagram="lrpd", weights=weights)
    assert without_times_and_paths(d.report) == without_times_and_paths(json.load(open(tmp_path / "report.json")))


def test_remesh_elk_516_as_make_demo(elk, data_dir, cli, tmp_path):
    V, F = elk
    V2, F2, report = lrvd.remesh(V, F, 516, seed=1)
    assert V2.shape == (516, 3) and report["output"]["vertices"] == 516
    assert report["verification"]["passed"] and report["quality"]["closed_manifold"]
    assert report["quality"]["genus_preserved"] and report["quality"]["self_intersections"] == 0
    out = tmp_path / "elk_516.off"
    cli("remesh", os.path.join(data_dir, "elk.off"), "-n", 516, "--seed", 1, "-o", out, "--report", tmp_path / "r.json")
    expected = json.load(open(tmp_path / "r.json"))
    assert without_times_and_paths(report) == without_times_and_paths(expected)
    V3, F3 = lrvd.read_mesh(str(out))
    assert np.array_equal(V2, V3) and np.array_equal(F2, F3)
    # quality() measures what `lrvd quality` measures.
    q = lrvd.quality(V, F, V2, F2)
    cli("quality", os.path.join(data_dir, "elk.off"), out, "--report", tmp_path / "q.json")
    assert without_times_and_paths(q) == without_times_and_paths(json.load(open(tmp_path / "q.json")))
    assert q["verification"]["passed"]


def test_mps_maximal_on_a_stress_mesh(cli, tmp_path):
    V, F = lrvd.stress("folded_sheet")
    points, report = lrvd.mps(V, F, 0.05)
    assert report["maximal"] and report["min_distance_ok"] and report["mps_verification"]["passed"]
    assert points.shape == (report["samples"], 3)
    assert report["conflict"]["rule"] == "reach" and report["mps_verification"]["conflict"] == "reach"
    _, cut = lrvd.mps(V, F, 0.05, conflict="close-across-turns")
    assert cut["conflict"]["rule"] == "close-across-turns" and cut["conflict"]["close_pairs_let_through"] >= 0
    with pytest.raises(ValueError, match="--conflict is reach or close-across-turns"):
        lrvd.mps(V, F, 0.05, conflict="paper")
    lrvd.write_mesh(str(tmp_path / "s.off"), V, F)
    cli("mps", tmp_path / "s.off", "--radius", 0.05, "-o", tmp_path / "s.xyz", "--report", tmp_path / "m.json")
    assert without_times_and_paths(report) == without_times_and_paths(json.load(open(tmp_path / "m.json")))
    assert np.array_equal(points, np.loadtxt(tmp_path / "s.xyz")[:, :3])
    points2, report2, V2, F2 = lrvd.mps(V, F, 0.05, lrrt=True, keep_radius=True)
    assert np.array_equal(points, points2) and report2["remesh"]["vertices"] == len(V2) == len(points)
    assert F2.shape == (report2["remesh"]["triangles"], 3)
    assert report2["remesh"]["smaller_disks"]["rounds"] == 0
    # Without keep_radius an LRRT that fails takes smaller disks round its defects.
    points3, report3, V3, F3 = lrvd.mps(V, F, 0.05, lrrt=True)
    assert report3["remesh"]["vertices"] == len(V3) == len(points3) and report3["maximal"]
    assert (report3["remesh"]["smaller_disks"]["rounds"] > 0) == (not report2["remesh"]["valid"])
    with pytest.raises(ValueError, match="keep_radius applies to lrrt=True"):
        lrvd.mps(V, F, 0.05, keep_radius=True)


def test_mps_samples_the_features_first_by_default(cli, tmp_path):
    # A cube: its 12 edges and 8 corners are sampled first unless features=False (--no-features).
    V = np.array([[x, y, z] for z in (0, 1) for y in (0, 1) for x in (0, 1)], dtype=float)
    F = np.array([[0, 3, 1], [0, 2, 3], [4, 5, 7], [4, 7, 6], [0, 1, 5], [0, 5, 4],
                  [1, 3, 7], [1, 7, 5], [3, 2, 6], [3, 6, 7], [2, 0, 4], [2, 4, 6]], dtype=np.int32)
    points, report = lrvd.mps(V, F, 0.1)
    features = report["features"]
    assert features["on"] and features["sampled"] and features["edges"] == 12 and features["corners"] == 8
    assert features["samples"] > 8 and report["mps_verification"]["passed"]
    _, off = lrvd.mps(V, F, 0.1, features=False)
    assert not off["features"]["on"] and not off["features"]["sampled"] and off["features"]["samples"] == 0
    with pytest.raises(ValueError, match="--no-features"):
        lrvd.mps(V, F, 0.1, features=False, feature_angle=45)
    lrvd.write_mesh(str(tmp_path / "cube.off"), V, F)
    cli("mps", tmp_path / "cube.off", "--radius", 0.1, "-o", tmp_path / "c.xyz", "--report", tmp_path / "c.json")
    assert without_times_and_paths(report) == without_times_and_paths(json.load(open(tmp_path / "c.json")))


def test_threads_do_not_change_the_output(elk):
    V, F = elk
    a = lrvd.compute(V, F, n=300, threads=1)
    b = lrvd.compute(V, F, n=300)
    assert without_times_and_paths(a.report) == without_times_and_paths(b.report)
    for key in a.cells:
        assert np.array_equal(a.cells[key], b.cells[key])
    V1, F1, r1 = lrvd.remesh(V, F, 200, threads=1)
    V2, F2, r2 = lrvd.remesh(V, F, 200)
    assert np.array_equal(V1, V2) and np.array_equal(F1, F2)
    assert without_times_and_paths(r1) == without_times_and_paths(r2)
