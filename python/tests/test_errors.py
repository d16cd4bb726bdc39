# Bad input: a ValueError (or a TypeError for an argument of the wrong type) with a one-line message,
# the command's where it has one; never a crash. A failed check is no exception.
import os

import numpy as np
import pytest

import lrvd


def cli_message(cli, *args):
    result = cli(*args, check=False)
    assert result.returncode == 2, result.stdout + result.stderr
    line = result.stderr.strip()
    assert line.startswith("lrvd: error: ") and "\n" not in line
    return line[len("lrvd: error: "):]


@pytest.fixture(scope="module")
def cube():
    V = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=float)
    F = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
                  [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]])
    return V, F


def test_the_cube_is_valid(cube):
    assert lrvd.compute(*cube, n=10).passed


@pytest.mark.parametrize("V, error, words", [
    (np.zeros((8, 2)), ValueError, "shape (n, 3)"),
    (np.zeros((8, 3, 1)), ValueError, "shape (n, 3)"),
    (np.array([["a", "b", "c"]] * 8), TypeError, "float64"),
    (None, TypeError, "not None"),
    ("mesh.off", TypeError, "float64"),
    (np.zeros((2, 3)), ValueError, "at least 3 rows"),
])
def test_bad_vertices(cube, V, error, words):
    with pytest.raises(error, match=words.replace("(", r"\(").replace(")", r"\)")):
        lrvd.compute(V, cube[1], n=10)


def test_nan_and_infinite_coordinates(cube):
    for bad in (np.nan, np.inf):
        V = cube[0].copy()
        V[5, 1] = bad
        with pytest.raises(ValueError, match="V row 5 is not finite"):
            lrvd.compute(V, cube[1], n=10)
        with pytest.raises(ValueError, match="points row 0 is not finite"):
            lrvd.compute(*cube, points=np.array([[bad, 0, 0]]))
        with pytest.raises(ValueError, match="not finite"):
            lrvd.compute(*cube, n=3, diagram="lrpd", weights=np.array([0, bad, 0]))


@pytest.mark.parametrize("F, error, words", [
    (np.zeros((12, 3)), TypeError, "integer"),
    (np.zeros((12, 4), dtype=int), ValueError, "shape"),
    (np.full((12, 3), 8), ValueError, "vertex index 8, outside 0..7"),
    (np.full((12, 3), -1), ValueError, "vertex index -1"),
    (np.full((12, 3), 2**40), ValueError, "outside 0..7"),
    (np.zeros((0, 3), dtype=int), ValueError, "no triangles"),
])
def test_bad_triangles(cube, F, error, words):
    with pytest.raises(error, match=words):
        lrvd.compute(cube[0], F, n=10)


def test_invalid_meshes(cube):
    V, F = cube
    with pytest.raises(ValueError):  # a triangle twice
        lrvd.compute(V, np.vstack([F, F[:1]]), n=10)
    with pytest.raises(ValueError):  # zero area
        lrvd.compute(V, np.vstack([F, [[0, 0, 1]]]), n=10)
    with pytest.raises(ValueError):  # an unused vertex
        lrvd.compute(np.vstack([V, [[5, 5, 5]]]), F, n=10)


def test_messages_are_the_commands(cube, cli, tmp_path, data_dir):
    V, F = cube
    lrvd.write_mesh(str(tmp_path / "cube.off"), V, F)
    mesh = str(tmp_path / "cube.off")
    cases = [
        (lambda: lrvd.compute(V, F, n=0), ("compute", mesh, "-n", 0)),
        (lambda: lrvd.compute(V, F, n=5, diagram="lrpd"), ("compute", mesh, "-n", 5, "--diagram", "lrpd")),
        (lambda: lrvd.remesh(V, F, 3), ("remesh", mesh, "-n", 3, "-o", tmp_path / "o.off")),
        (lambda: lrvd.mps(V, F, -1), ("mps", mesh, "--radius", -1, "-o", tmp_path / "o.xyz")),
        (lambda: lrvd.mps(V, F, 0.1, max_radius_ratio=3), ("mps", mesh, "--radius", 0.1, "--max-radius-ratio", 3,
                                                           "-o", tmp_path / "o.xyz")),
        (lambda: lrvd.read_mesh(str(tmp_path / "missing.off")), ("compute", tmp_path / "missing.off", "-n", 5)),
        (lambda: lrvd.compute(V, F, n=6000000), ("compute", mesh, "-n", 6000000)),
        (lambda: lrvd.compute(V, F, points=np.array([[9.0, 9, 9]])), None),
    ]
    for call, args in cases:
        with pytest.raises(ValueError) as raised:
            call()
        message = str(raised.value)
        assert "\n" not in message and message
        if args is not None:
            # The same words; the command names its file or option before them, "the mesh" here.
            expected = cli_message(cli, *args).removesuffix(" (see --help)")
            assert (message == expected or expected.endswith(": " + message)
                    or message.split(": ", 1)[-1] == expected.split(": ", 1)[-1]), (message, expected)


def test_bad_arguments(cube):
    V, F = cube
    with pytest.raises(ValueError, match="not both"):
        lrvd.compute(V, F, n=5, points=V)
    with pytest.raises(ValueError, match="unknown diagram 'voronoi'"):
        lrvd.compute(V, F, n=5, diagram="voronoi")
    with pytest.raises(ValueError, match="not a power diagram"):
        lrvd.compute(V, F, n=3, weights=[0.0, 0.0, 0.0])
    with pytest.raises(ValueError, match="2 weights were given for the 8 points"):
        lrvd.compute(V, F, points=V, diagram="rpd", weights=[0.0, 0.0])
    with pytest.raises(ValueError, match="thread count"):
        lrvd.compute(V, F, n=5, threads=0)
    with pytest.raises(TypeError, match="thread count"):
        lrvd.compute(V, F, n=5, threads=1.5)
    with pytest.raises(ValueError, match="seed"):
        lrvd.compute(V, F, n=5, seed=-1)
    with pytest.raises(ValueError, match="seed"):
        lrvd.compute(V, F, n=5, seed=2**64)
    with pytest.raises(ValueError, match="--refine"):
        lrvd.compute(V, F, n=5, refine="fine")
    with pytest.raises(ValueError, match="--optimizer"):
        lrvd.remesh(V, F, 10, optimizer="newton")
    with pytest.raises(ValueError, match="--repair-scope"):
        lrvd.remesh(V, F, 10, repair_scope="global")
    with pytest.raises(ValueError, match="remesh uses a Voronoi diagram"):
        lrvd.remesh(V, F, 10, diagram="lrpd")
    with pytest.raises(ValueError, match="unknown"):
        lrvd.stress("no_such_mesh")
    with pytest.raises(ValueError, match="scale"):
        lrvd.stress("comb", scale=0)
    with pytest.raises(ValueError, match="--size"):
        lrvd.render(V, F, size=(8, 8))
    with pytest.raises(ValueError, match="--up"):
        lrvd.render(V, F, up="w")
    with pytest.raises(ValueError, match="--color quality"):
        lrvd.render(V, F, n=5, color="quality")
    with pytest.raises(ValueError, match="vertex index"):
        lrvd.quality(V, F, V, np.array([[0, 1, 99]]))
    with pytest.raises(ValueError, match="weld"):
        lrvd.read_mesh("x.off", weld=-1.0)
    with pytest.raises(TypeError, match="split_factor must be a number"):
        lrvd.mps(V, F, 0.1, split_factor="big")
    with pytest.raises(ValueError, match="--split-factor is 1 to 64"):
        lrvd.mps(V, F, 0.1, split_factor=100)


def test_a_failed_check_is_no_exception(cube):
    V, F = cube
    # A remesh that crosses itself: two copies of the cube's triangles shifted into each other.
    V2 = np.vstack([V, V + 0.5])
    F2 = np.vstack([F, F + 8])
    q = lrvd.quality(V, F, V2, F2)
    assert q["verification"]["passed"] is False and q["quality"]["self_intersections"] > 0
