"""Finding and loading libfluidcast.so.

The library is looked for, in this order:

1. ``$FLUIDCAST_LIBRARY``: the path of the shared library. When it is set, it is
   the only place tried: a wrong path is an error rather than a silent fallback
   to some other copy of the library.
2. Next to the package: ``libfluidcast.so`` (or a versioned ``libfluidcast.so.N``)
   in the ``fluidcast/`` package directory itself, for a copy of the package
   shipped together with the library.
3. The build tree of the checkout the package lives in: ``<checkout>/build/lib/``,
   where ``deploy/build.sh`` builds it, when the package is used straight from
   ``<checkout>/python/`` (``PYTHONPATH=<checkout>/python``). Other build
   directories (``build-debug/`` ...) are not guessed: point
   ``FLUIDCAST_LIBRARY`` at them.
4. ``ctypes.util.find_library("fluidcast")``: an installed library the dynamic
   linker knows (``ldconfig``, ``LD_LIBRARY_PATH``).

If none loads, importing :mod:`fluidcast` raises an :class:`ImportError` that
lists every place tried and why each failed.
"""

import ctypes
import ctypes.util
import glob
import os

ENV_VAR = "FLUIDCAST_LIBRARY"
_NAME = "libfluidcast.so"


def _package_dir():
    return os.path.dirname(os.path.abspath(__file__))


def _candidates_next_to_package():
    """Library files in the package directory, unversioned name first."""
    here = _package_dir()
    found = [os.path.join(here, _NAME)]
    found += sorted(glob.glob(os.path.join(here, _NAME + ".*")))
    return found


def _candidate_in_checkout_build():
    """<checkout>/build/lib/libfluidcast.so for the package at <checkout>/python/fluidcast."""
    checkout = os.path.dirname(os.path.dirname(_package_dir()))
    return os.path.join(checkout, "build", "lib", _NAME)


def load():
    """Loads libfluidcast and returns ``(ctypes.CDLL, path)``; ImportError when it cannot."""
    tried = []

    def attempt(path):
        try:
            return ctypes.CDLL(path)
        except OSError as e:
            tried.append("%s (%s)" % (path, e))
            return None

    explicit = os.environ.get(ENV_VAR)
    if explicit:
        lib = attempt(explicit)
        if lib is not None:
            return lib, explicit
        raise ImportError("fluidcast: cannot load libfluidcast from $%s: %s" % (ENV_VAR, tried[0]))

    for path in _candidates_next_to_package() + [_candidate_in_checkout_build()]:
        if not os.path.exists(path):
            tried.append("%s (no such file)" % path)
            continue
        lib = attempt(path)
        if lib is not None:
            return lib, path

    name = ctypes.util.find_library("fluidcast")
    if name is None:
        tried.append('ctypes.util.find_library("fluidcast") (not found by the dynamic linker\'s cache)')
    else:
        lib = attempt(name)
        if lib is not None:
            return lib, name

    raise ImportError(
        "fluidcast: cannot find libfluidcast.so. Build it (cmake --build BUILD; it is BUILD/lib/libfluidcast.so) "
        "and set %s to its path. Tried: $%s (not set); %s" % (ENV_VAR, ENV_VAR, "; ".join(tried)))
