"""ctest's entry point for the Python binding's tests: pytest on the files given
(this folder when none), quietly, without writing a cache into the source tree.

Exits 77 (ctest: skipped) when this interpreter lacks numpy or pytest
(Debian: python3-numpy python3-pytest, installed by deploy/setup.sh).
"""

import os
import sys

try:
    import numpy
    import pytest
    assert numpy and pytest
except ImportError as e:
    print("python binding tests skipped: %s (install python3-numpy python3-pytest)" % e)
    sys.exit(77)

here = os.path.dirname(os.path.abspath(__file__))
sys.exit(pytest.main(["-q", "-rs", "-p", "no:cacheprovider", "--rootdir", here] + (sys.argv[1:] or [here])))
