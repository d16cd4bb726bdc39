# Shared fixtures of the lrvd module's tests: the CGAL meshes, the lrvd command of the same build,
# and a way to compare reports apart from their time fields and file paths.
import os
import subprocess

import pytest

import lrvd


def _required(name):
    value = os.environ.get(name)
    assert value, f"{name} is set by ctest (CMakeLists.txt); run the tests with `ctest -R python`"
    return value


@pytest.fixture(scope="session")
def data_dir():
    return _required("LRVD_CGAL_DATA_DIR")


@pytest.fixture(scope="session")
def cli():
    path = _required("LRVD_CLI")

    def run(*args, check=True):
        result = subprocess.run([path, *map(str, args)], capture_output=True, text=True)
        if check:
            assert result.returncode in (0, 3), result.stderr
        return result

    return run


@pytest.fixture(scope="session")
def elk(data_dir):
    return lrvd.read_mesh(os.path.join(data_dir, "elk.off"))


def without_times_and_paths(value):
    """The report without what differs between two runs of one computation: times and file paths."""
    if isinstance(value, dict):
        return {k: without_times_and_paths(v) for k, v in value.items()
                if "time" not in k and k not in ("path", "output", "reference", "mesh")}
    if isinstance(value, list):
        return [without_times_and_paths(v) for v in value]
    return value
