"""Frame without a daemon: which arrays are sent in place and which are copied,
shape and type checks; and how the package finds libfluidcast."""

import os
import shutil
import subprocess
import sys
import ctypes.util

import numpy as np
import pytest

import fluidcast
from helpers import REPO, ball


def address(pointer):
    return ctypes.cast(pointer, ctypes.c_void_p).value


def test_contiguous_float32_is_used_in_place():
    positions = ball(100)
    density = np.ones(100, np.float32)
    velocity = np.zeros((100, 3), np.float32)
    ids = np.arange(100, dtype=np.uint32)
    frame = fluidcast.Frame(positions, density, velocity, ids)
    assert frame.copied == ()
    assert frame.positions is positions and frame.ids is ids
    c = frame.c_frame
    assert c.count == 100
    assert address(c.positions) == positions.ctypes.data
    assert address(c.density) == density.ctypes.data
    assert address(c.velocity) == velocity.ctypes.data
    assert address(c.ids) == ids.ctypes.data
    # What the fc_frame points at is the caller's memory: a change shows through it.
    positions[7, 2] = 42.0
    assert c.positions[7 * 3 + 2] == 42.0


def test_float64_strided_and_other_ints_are_converted_once():
    p64 = ball(50).astype(np.float64)
    frame = fluidcast.Frame(p64, ids=np.arange(50, dtype=np.int64))
    assert frame.copied == ("positions", "ids")
    assert frame.positions.dtype == np.float32 and frame.positions.flags.c_contiguous
    assert address(frame.c_frame.positions) == frame.positions.ctypes.data != p64.ctypes.data
    np.testing.assert_array_equal(frame.positions, p64.astype(np.float32))
    assert frame.ids.dtype == np.uint32

    strided = ball(100)[::2]           # float32, but every other row
    assert fluidcast.Frame(strided).copied == ("positions",)
    fortran = np.asfortranarray(ball(10))
    assert fluidcast.Frame(fortran).copied == ("positions",)
    big_endian = ball(10).astype(">f4")
    frame = fluidcast.Frame(big_endian)
    assert frame.copied == ("positions",) and frame.positions.dtype == np.float32
    assert fluidcast.Frame(ball(10).tolist()).copied == ("positions",)
    absent = fluidcast.Frame(ball(10)).c_frame
    assert not absent.density and not absent.velocity and not absent.ids and not absent.radius


def test_radius_is_used_in_place_or_converted():
    radius = np.full(100, 0.05, np.float32)
    frame = fluidcast.Frame(ball(100), radius=radius)
    assert frame.copied == () and frame.radius is radius
    assert address(frame.c_frame.radius) == radius.ctypes.data
    frame = fluidcast.Frame(ball(100), radius=np.full(100, 0.05))   # float64: converted once
    assert frame.copied == ("radius",) and frame.radius.dtype == np.float32
    assert frame.c_frame.radius[99] == np.float32(0.05)
    assert "radius" in repr(frame)


@pytest.mark.parametrize("kwargs, error", [
    (dict(positions=np.zeros((4, 2), np.float32)), ValueError),
    (dict(positions=np.zeros(12, np.float32)), ValueError),
    (dict(positions=np.zeros((4, 3)), density=np.zeros(5)), ValueError),
    (dict(positions=np.zeros((4, 3)), density=np.zeros((4, 1))), ValueError),
    (dict(positions=np.zeros((4, 3)), velocity=np.zeros((4, 2))), ValueError),
    (dict(positions=np.zeros((4, 3)), ids=np.array([0, 1, 2, -1])), ValueError),
    (dict(positions=np.zeros((4, 3)), ids=np.array([0, 1, 2, 1 << 32])), ValueError),
    (dict(positions=np.zeros((4, 3)), ids=np.zeros(4)), TypeError),
    (dict(positions=np.zeros((4, 3)), radius=np.ones(3)), ValueError),
    (dict(positions=np.zeros((4, 3)), radius=np.ones((4, 1))), ValueError),
    (dict(positions=np.zeros((4, 3), complex)), TypeError),
    (dict(positions=np.array([["a", "b", "c"]])), TypeError),
])
def test_bad_shapes_and_types_are_refused(kwargs, error):
    with pytest.raises(error):
        fluidcast.Frame(**kwargs)


def test_errors_carry_code_and_message():
    e = fluidcast.Error(7, "server: radius -1 is outside [0, 1e+06]")
    assert e.code is fluidcast.Code.INVALID_VALUE and e.message.startswith("server: ")
    assert str(e) == "INVALID_VALUE: server: radius -1 is outside [0, 1e+06]"
    assert fluidcast.Error(99, "?").code == 99


def _import_in_subprocess(env, cwd):
    return subprocess.run([sys.executable, "-c", "import fluidcast; print(fluidcast.library_path)"],
                          env=env, cwd=cwd, capture_output=True, text=True)


def _env(**changes):
    env = {k: v for k, v in os.environ.items() if k not in ("FLUIDCAST_LIBRARY", "LD_LIBRARY_PATH")}
    env.update(changes)
    return env


def test_library_path_from_the_environment_is_the_only_one_tried(tmp_path):
    missing = str(tmp_path / "nowhere" / "libfluidcast.so")
    result = _import_in_subprocess(_env(FLUIDCAST_LIBRARY=missing), tmp_path)
    assert result.returncode != 0
    assert "ImportError" in result.stderr and missing in result.stderr and "FLUIDCAST_LIBRARY" in result.stderr


def test_library_next_to_the_package_and_the_error_without_one(tmp_path):
    """A copy of the package with the library in it loads that one; without, the ImportError lists the places."""
    package = tmp_path / "site" / "fluidcast"
    shutil.copytree(os.path.join(REPO, "python", "fluidcast"), package,
                    ignore=shutil.ignore_patterns("__pycache__"))
    env = _env(PYTHONPATH=str(tmp_path / "site"), PYTHONDONTWRITEBYTECODE="1")
    if ctypes.util.find_library("fluidcast") is None:
        result = _import_in_subprocess(env, tmp_path)
        assert result.returncode != 0
        for tried in (str(package / "libfluidcast.so"), str(tmp_path / "build" / "lib" / "libfluidcast.so"),
                      "find_library", "FLUIDCAST_LIBRARY"):
            assert tried in result.stderr, tried
    shutil.copy(fluidcast.library_path, package / "libfluidcast.so")
    result = _import_in_subprocess(env, tmp_path)
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == str(package / "libfluidcast.so")
