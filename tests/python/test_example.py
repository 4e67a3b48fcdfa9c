"""python/examples/render_numpy.py runs against the daemon and writes the PNG it says."""

import os
import subprocess
import sys

from helpers import REPO, png_size


def test_render_numpy_example(daemon, tmp_path):
    output = tmp_path / "drop.png"
    script = os.path.join(REPO, "python", "examples", "render_numpy.py")
    result = subprocess.run([sys.executable, script, daemon.address, "-o", str(output), "--size", "320x180",
                             "--spacing", "0.05", "--color-by", "speed"],
                            capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stdout + result.stderr
    assert str(output) in result.stdout
    assert png_size(output.read_bytes()) == (320, 180)
