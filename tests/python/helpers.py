"""Helpers the Python binding's tests share: a daemon process, a particle scene, a camera on it, PNG headers."""

import ctypes
import os
import shutil
import signal
import subprocess
import tempfile
import time

import numpy as np

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"
SIZE = (160, 120)   # small images keep software rendering quick


def _die_with_parent():
    """In the daemon's process: be killed when the test process dies (a crash, ctest's timeout)."""
    PR_SET_PDEATHSIG = 1
    ctypes.CDLL(None, use_errno=True).prctl(PR_SET_PDEATHSIG, signal.SIGKILL)


class Daemon:
    """A fluidcastd on 127.0.0.1 and a free port, software GL, its log in a file."""

    def __init__(self, *extra_args):
        path = os.environ.get("FLUIDCASTD") or os.path.join(REPO, "build", "bin", "fluidcastd")
        self.dir = tempfile.mkdtemp(prefix="fc-pytest-")
        port_file = os.path.join(self.dir, "port")
        self.log_path = os.path.join(self.dir, "fluidcastd.log")
        self.log = open(self.log_path, "wb")
        self.process = subprocess.Popen(
            [path, "--listen", "127.0.0.1:0", "--port-file", port_file, "--gpu", "software", *extra_args],
            stdout=self.log, stderr=subprocess.STDOUT, preexec_fn=_die_with_parent)
        deadline = time.monotonic() + 60
        port = 0
        while time.monotonic() < deadline:
            if os.path.exists(port_file):
                text = open(port_file).read().strip()
                if text.isdigit() and 0 < int(text) < 65536:
                    port = int(text)
                    break
            if self.process.poll() is not None:
                break
            time.sleep(0.02)
        if not port:
            self.stop()
            log = self.read_log()
            self.remove_files()
            raise RuntimeError("%s did not announce its port (exit %s); log:\n%s"
                               % (path, self.process.returncode, log))
        self.address = "127.0.0.1:%d" % port

    def read_log(self):
        with open(self.log_path, "rb") as f:
            return f.read().decode("utf-8", "replace")

    def stop(self):
        """SIGTERM, then the exit status (0 for a clean shutdown)."""
        if self.process.poll() is None:
            self.process.send_signal(signal.SIGTERM)
            try:
                self.process.wait(timeout=20)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
        self.log.close()
        return self.process.returncode

    def remove_files(self):
        shutil.rmtree(self.dir, ignore_errors=True)


def ball(count=2000, radius=0.5, centre=(0.0, 0.0, 0.0), seed=1):
    """``count`` particles filling a ball, float32 (N, 3), C-contiguous."""
    rng = np.random.default_rng(seed)
    points = rng.normal(size=(count, 3))
    points /= np.linalg.norm(points, axis=1)[:, None]
    points *= radius * rng.random(count)[:, None] ** (1 / 3)
    return (points + np.asarray(centre)).astype(np.float32)


# Water that absorbs enough to show a small ball plainly blue, for the tests
# that find the fluid by its colour: the default look's shallow water is
# nearly clear (tests/support/tinted_look.h holds the same for the C tests).
TINTED_LOOK_ABSORPTION = (0.2, 0.07, 0.035)


def look_at_ball(client, size=SIZE):
    """A camera that sees ball() in the middle of the image, with room around it."""
    client.set_camera(eye=(0, -4, 0), target=(0, 0, 0), up=(0, 0, 1), fov=40, size=size)


def png_size(data):
    """(width, height) from a PNG's IHDR, checking the magic and the chunk's name."""
    assert data[:8] == PNG_MAGIC, data[:8]
    assert data[12:16] == b"IHDR"
    return int.from_bytes(data[16:20], "big"), int.from_bytes(data[20:24], "big")


# The corners of a box by bit (x: 1, y: 2, z: 4) and its 12 triangles,
# counter-clockwise seen from outside (as tests/integration/test_client_mesh.c).
_BOX_INDICES = [[0, 2, 3], [0, 3, 1], [4, 5, 7], [4, 7, 6], [0, 1, 5], [0, 5, 4],
                [2, 6, 7], [2, 7, 3], [0, 4, 6], [0, 6, 2], [1, 3, 7], [1, 7, 5]]


def box(lo, hi):
    """An axis-aligned box from corner ``lo`` to ``hi``: vertices (8, 3) float32 and indices (12, 3) uint32."""
    vertices = np.array([[(lo, hi)[(i >> k) & 1][k] for k in range(3)] for i in range(8)], np.float32)
    return vertices, np.array(_BOX_INDICES, np.uint32)
