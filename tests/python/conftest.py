"""Fixtures of the Python binding's tests: a real fluidcastd and clients of it.

ctest sets the environment (tests/python/CMakeLists.txt): PYTHONPATH (the
package), FLUIDCAST_LIBRARY (the build's libfluidcast.so), FLUIDCASTD (the
build's daemon) and FC_TEST_CC (the C compiler, for the layout test).
"""

import pytest

import fluidcast
from helpers import Daemon


@pytest.fixture(scope="session")
def daemon():
    d = Daemon()
    yield d
    status = d.stop()
    log = d.read_log()
    d.remove_files()
    assert status == 0, "fluidcastd exited with %s after SIGTERM; log:\n%s" % (status, log)


@pytest.fixture
def connect(daemon):
    """connect(**kw): a new client of the daemon, closed at the end of the test."""
    clients = []

    def make(**kw):
        kw.setdefault("name", "pytest")
        kw.setdefault("reply_timeout", 60)
        c = fluidcast.connect(daemon.address, **kw)
        clients.append(c)
        return c

    yield make
    for c in clients:
        c.close()


@pytest.fixture
def client(connect):
    return connect()
