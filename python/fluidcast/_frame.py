"""Frame: numpy particle arrays viewed as an fc_frame, copied only when they must be."""

import ctypes

import numpy as np

from ._capi import FcFrame

_UINT32_MAX = 0xFFFFFFFF


def _as_array(name, value, dtype, columns, count):
    """``value`` as a C-contiguous, aligned, native-endian array of ``dtype``.

    The array itself when it already is one (no copy); a converted copy
    otherwise. ``columns`` is 3 for (N, 3) arrays and None for (N,) arrays;
    ``count`` the N it must have (None: any N >= 0). Returns (array, copied).
    """
    source = value
    array = np.asarray(value)
    if array.dtype.kind not in "fiu":
        raise TypeError("%s: expected real numbers, got an array of dtype %s" % (name, array.dtype))
    if columns is None:
        if array.ndim != 1:
            raise ValueError("%s: expected shape (N,), got %s" % (name, array.shape))
    elif array.ndim != 2 or array.shape[1] != columns:
        raise ValueError("%s: expected shape (N, %d), got %s" % (name, columns, array.shape))
    if count is not None and array.shape[0] != count:
        raise ValueError("%s: %d rows, but positions has %d" % (name, array.shape[0], count))
    if dtype == np.uint32 and array.dtype != np.uint32 and array.size:
        if array.dtype.kind == "f":
            raise TypeError("%s: particle ids must be integers, got dtype %s" % (name, array.dtype))
        lo, hi = int(array.min()), int(array.max())
        if lo < 0 or hi > _UINT32_MAX:
            raise ValueError("%s: ids must fit uint32 (0..%d), got %d..%d" % (name, _UINT32_MAX, lo, hi))
    # np.require returns its argument unchanged when dtype (native byte order),
    # C order and alignment already hold, and a converted copy otherwise.
    array = np.require(array, dtype=dtype, requirements=("C_CONTIGUOUS", "ALIGNED"))
    copied = not (isinstance(source, np.ndarray) and array.ctypes.data == source.ctypes.data
                  and array.dtype == source.dtype)
    return array, copied


class Frame:
    """Particle arrays ready to send, viewed as an fc_frame.

    Arguments (numpy arrays or anything ``numpy.asarray`` takes):
        positions: shape (N, 3), x y z per particle, world units.
        density: shape (N,), or None.
        velocity: shape (N, 3), world units per frame, or None.
        ids: shape (N,), persistent particle ids as uint32 (fc_frame's ``uint32_t *ids``), or None.
        radius: shape (N,), per-particle splat radii in world units (fc_frame's ``float *radius``), or None.
            The server refuses a radius that is not finite, not > 0 or above 1e6 (INVALID_VALUE naming the
            particle); a settings ``radius`` > 0 overrides every particle's.

    No copy is made of an array that is already C-contiguous and aligned with
    the element type the C frame holds (float32 for positions, density,
    velocity and radius, uint32 for ids): the fc_frame points into the array itself, and
    libfluidcast writes it to the socket from there. Any other array is
    converted once, into a new array: float64 positions are rounded to
    float32 (about 7 significant digits: keep coordinates near the origin),
    other integer ids are checked to fit uint32, and a strided view (``a[::2]``,
    a transposed or Fortran-ordered array) is made contiguous. ``copied`` names
    the arrays that were converted.

    The Frame keeps the arrays alive; modifying an uncopied source array
    changes what a later send of this Frame sends.
    """

    def __init__(self, positions, density=None, velocity=None, ids=None, radius=None):
        self.positions, c_pos = _as_array("positions", positions, np.float32, 3, None)
        n = self.positions.shape[0]
        copied = ["positions"] if c_pos else []
        self.density = self.velocity = self.ids = self.radius = None
        if density is not None:
            self.density, c = _as_array("density", density, np.float32, None, n)
            copied += ["density"] if c else []
        if velocity is not None:
            self.velocity, c = _as_array("velocity", velocity, np.float32, 3, n)
            copied += ["velocity"] if c else []
        if ids is not None:
            self.ids, c = _as_array("ids", ids, np.uint32, None, n)
            copied += ["ids"] if c else []
        if radius is not None:
            self.radius, c = _as_array("radius", radius, np.float32, None, n)
            copied += ["radius"] if c else []
        #: names of the arrays that had to be converted (copied), e.g. ("positions",) for float64 input
        self.copied = tuple(copied)
        self.count = n

        def pointer(array, ctype):
            return None if array is None else array.ctypes.data_as(ctypes.POINTER(ctype))

        #: the fc_frame handed to libfluidcast; its pointers address the arrays above
        self.c_frame = FcFrame(n, pointer(self.positions, ctypes.c_float), pointer(self.density, ctypes.c_float),
                               pointer(self.velocity, ctypes.c_float), pointer(self.ids, ctypes.c_uint32),
                               pointer(self.radius, ctypes.c_float))

    def __len__(self):
        return self.count

    def __repr__(self):
        present = [k for k in ("density", "velocity", "ids", "radius") if getattr(self, k) is not None]
        return "<fluidcast.Frame %d particles%s%s>" % (
            self.count, " with " + ", ".join(present) if present else "",
            " (copied: %s)" % ", ".join(self.copied) if self.copied else "")


def as_frame(positions, density=None, velocity=None, ids=None, radius=None):
    """A Frame from arrays, or ``positions`` itself when it is a Frame (the others must be None)."""
    if isinstance(positions, Frame):
        if density is not None or velocity is not None or ids is not None or radius is not None:
            raise TypeError("pass either a Frame or arrays, not both")
        return positions
    return Frame(positions, density, velocity, ids, radius)
