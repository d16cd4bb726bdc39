# Shapes, dtypes and contents of what the lrvd module takes and returns.
import os
import threading

import numpy as np

import lrvd


def test_version_is_the_commands(cli):
    assert cli("--version").stdout.strip() == "lrvd " + lrvd.__version__


def test_read_and_write_mesh(elk, tmp_path):
    V, F = elk
    assert V.dtype == np.float64 and V.shape == (1645, 3)  # genus 1: V = F / 2
    assert F.dtype == np.int32 and F.shape == (3290, 3)
    assert V.flags.c_contiguous and F.flags.c_contiguous
    assert F.min() == 0 and F.max() == len(V) - 1
    path = str(tmp_path / "elk.obj")
    lrvd.write_mesh(path, V, F)
    V2, F2 = lrvd.read_mesh(path)
    assert np.array_equal(V, V2) and np.array_equal(F, F2)


def test_stress_meshes():
    names = lrvd.stress_names()
    assert "comb" in names and len(names) == len(set(names)) >= 8
    V, F = lrvd.stress("comb")
    Vf, Ff = lrvd.stress("comb", scale=2.0)
    assert V.dtype == np.float64 and F.dtype == np.int32
    assert len(Ff) > 3 * len(F)  # twice the subdivisions each way


def test_compute_cells(elk):
    V, F = elk
    d = lrvd.compute(V, F, n=100, seed=3)
    assert d.kind == "lrvd" and d.passed is True
    c = d.cells
    polygons = len(c["polygon_cell"])
    assert polygons == d.report["diagram"]["polygons"]
    assert c["vertices"].dtype == np.float64 and c["vertices"].shape[1] == 3
    assert c["polygon_offsets"].shape == (polygons + 1,) and c["polygon_offsets"][-1] == len(c["polygon_vertices"])
    assert np.all(np.diff(c["polygon_offsets"]) >= 3)
    assert c["polygon_vertices"].max() == len(c["vertices"]) - 1
    assert set(np.unique(c["polygon_cell"])) == set(range(100))
    MV, MF = d.mesh
    assert c["polygon_triangle"].min() >= 0 and c["polygon_triangle"].max() < len(MF)
    # An LRVD's cells are one piece each (the paper's promise, checked by the verification).
    assert np.all(c["cell_components"] == 1) and d.cells_in_pieces == 0
    assert d.samples.shape == (100, 3)
    # The polygons' areas add up to the surface's.
    area = 0.0
    for p in range(polygons):
        corners = c["vertices"][c["polygon_vertices"][c["polygon_offsets"][p]:c["polygon_offsets"][p + 1]]]
        for k in range(1, len(corners) - 1):
            area += 0.5 * np.linalg.norm(np.cross(corners[k] - corners[0], corners[k + 1] - corners[0]))
    assert abs(area - d.report["input"]["area"]) < 1e-9 * d.report["input"]["area"]


def test_rvd_cells_in_pieces_lrvd_not():
    V, F = lrvd.stress("comb")
    rvd = lrvd.compute(V, F, n=100, diagram="rvd")
    lrvd_ = lrvd.compute(V, F, n=100, diagram="lrvd")
    assert rvd.cells_in_pieces > 0 and lrvd_.cells_in_pieces == 0
    assert rvd.report["diagram"]["cells_with_multiple_components"] == rvd.cells_in_pieces
    assert lrvd_.passed and lrvd_.report["verification"]["passed"]


def test_verify_later(elk):
    V, F = elk
    d = lrvd.compute(V, F, n=50, verify=False)
    assert d.passed is None and d.report["verification"] is None
    v = d.verify()
    assert v["passed"] is True and d.passed is True and d.report["verification"] == v


def test_inputs_of_other_dtypes_and_orders(elk):
    V, F = elk
    a = lrvd.compute(V, F, n=60, verify=False)
    b = lrvd.compute(np.asfortranarray(V), F.astype(np.int64), n=60, verify=False)
    c = lrvd.compute(V.tolist(), F.astype(np.uint32).tolist(), n=60, verify=False)
    for other in (b, c):
        assert np.array_equal(a.cells["vertices"], other.cells["vertices"])


def test_outputs_are_views_of_the_library_data(elk):
    V, F = elk
    V2, F2, report = lrvd.remesh(V, F, 60)
    # The arrays own no copy: their memory is the library's vector, kept alive by a capsule.
    assert not V2.flags.owndata and not F2.flags.owndata
    assert V2.shape == (60, 3) and F2.dtype == np.int32


def test_render_is_the_commands_picture(elk, data_dir, cli, tmp_path):
    import matplotlib.image
    V, F = elk
    image = lrvd.render(V, F, n=40, size=(160, 120), view=(40, 10))
    assert image.shape == (120, 160, 3) and image.dtype == np.uint8
    png = tmp_path / "elk.png"
    cli("render", os.path.join(data_dir, "elk.off"), "-n", 40, "--size", "160x120", "--view", "40,10", "-o", png)
    from_file = np.round(matplotlib.image.imread(str(png))[:, :, :3] * 255).astype(np.uint8)
    assert np.array_equal(image, from_file)
    plain = lrvd.render(V, F, size=(64, 48), color="quality")
    assert plain.shape == (48, 64, 3) and len(np.unique(plain.reshape(-1, 3), axis=0)) > 2


def test_the_gil_is_released_during_the_work(elk):
    V, F = elk
    counter = [0]
    worker = threading.Thread(target=lambda: lrvd.remesh(V, F, 300, threads=1))
    worker.start()
    while worker.is_alive():
        counter[0] += 1
    worker.join()
    # Held for the remesh (about a second), it would leave this loop a few switch intervals.
    assert counter[0] > 100000
