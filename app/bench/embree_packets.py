"""Embree's packet API as the tracer's peer: ``rtcIntersect16`` and ``rtcOccluded16`` from compiled code.

``embreex`` traces from Python on the calling thread only, which is not
Embree's fastest path.  This module calls Embree's own C API in the
``libembree4`` library that ships inside the embreex wheel: the scene is
built through it (one triangle geometry on shared float32 buffers, committed
with Embree's default build), and the rays are traced in packets of 16 by a
numba kernel that calls ``rtcIntersect16`` (closest hit) or
``rtcOccluded16`` (any hit) through ctypes function pointers, on numba's
threads -- the same threads, and the same number, as our tracer uses.  Each
packet holds 16 consecutive rays of the given order (the bench orders primary
rays by tiles of 4 x 4 pixels, as our packets are).

The packet layout is that of ``RTCRayHit16`` in Embree 4's ``rtcore_ray.h``:
structure of arrays, each field 16 floats (or unsigned ints), aligned to 64
bytes -- ray ``org_x, org_y, org_z, tnear, dir_x, dir_y, dir_z, time, tfar,
mask, id, flags``, then hit ``Ng_x, Ng_y, Ng_z, u, v, primID, geomID,
instID``.  ``rtcOccluded16`` takes the ray part alone and sets ``tfar`` to
``-inf`` for every ray that is blocked; the kernel then writes 0 for those rays only into
the results (filled with -1, none, before), as our shadow-ray kernel writes only the blocked
rays' answers.

The kernel calls foreign functions at fixed addresses, so numba cannot cache
it: it is compiled once per run, at the first call (:attr:`EmbreePackets.compile_seconds`).
"""

from __future__ import annotations

import ctypes
import functools
import importlib.util
import math
import time
from pathlib import Path

import numpy as np

LANES = 16
#: Field offsets in ``RTCRayHit16``, in 4-byte words (16 lanes each).
_ORG, _TNEAR, _DIR, _TIME, _TFAR, _MASK, _ID, _FLAGS = 0, 48, 64, 112, 128, 144, 160, 176
_U, _V, _PRIM_ID, _GEOM_ID = 240, 256, 272, 288
_RAYHIT_WORDS = 320  # through instID[0]; the struct's size, rounded up to 64 bytes
_INVALID_ID = 0xFFFFFFFF  # RTC_INVALID_GEOMETRY_ID
_GEOMETRY_TYPE_TRIANGLE, _BUFFER_TYPE_INDEX, _BUFFER_TYPE_VERTEX = 0, 0, 1
_FORMAT_UINT3, _FORMAT_FLOAT3 = 0x5003, 0x9003


def find_library() -> Path | None:
    """The ``libembree4`` shared library of the installed embreex wheel, ``None`` without embreex."""
    spec = importlib.util.find_spec("embreex")
    if spec is None or not spec.submodule_search_locations:
        return None
    package = Path(next(iter(spec.submodule_search_locations)))
    for folder in (package.parent / "embreex.libs", package):
        found = sorted(folder.glob("libembree4*.so*")) + sorted(folder.glob("embree4*.dll"))
        if found:
            return found[0]
    return None


@functools.cache
def _c_api(path: Path) -> ctypes.CDLL:
    """The library with the argument and result types of the functions used here (loaded once).

    Pointers and handles pass as ``size_t`` (the same register as a pointer on
    every 64-bit ABI), which numba passes from an array's ``.ctypes.data``.
    """
    lib = ctypes.CDLL(str(path))
    ptr, size, uint = ctypes.c_size_t, ctypes.c_size_t, ctypes.c_uint
    for name, restype, argtypes in (
            ("rtcNewDevice", ptr, [ctypes.c_char_p]),
            ("rtcGetDeviceError", ctypes.c_int, [ptr]),
            ("rtcNewScene", ptr, [ptr]),
            ("rtcNewGeometry", ptr, [ptr, ctypes.c_int]),
            ("rtcSetSharedGeometryBuffer", None,
             [ptr, ctypes.c_int, uint, ctypes.c_int, ptr, size, size, size]),
            ("rtcCommitGeometry", None, [ptr]),
            ("rtcAttachGeometry", uint, [ptr, ptr]),
            ("rtcReleaseGeometry", None, [ptr]),
            ("rtcCommitScene", None, [ptr]),
            ("rtcReleaseScene", None, [ptr]),
            ("rtcReleaseDevice", None, [ptr]),
            ("rtcIntersect16", None, [ptr, ptr, ptr, ptr]),
            ("rtcOccluded16", None, [ptr, ptr, ptr, ptr])):
        function = getattr(lib, name)
        function.restype, function.argtypes = restype, argtypes
    return lib


@functools.cache
def _kernels(lib):
    """The parallel kernel tracing with ``lib``'s ``rtcIntersect16`` and ``rtcOccluded16`` (made,
    and compiled at its first call, once per run)."""
    from numba import njit, prange

    intersect16, occluded16 = lib.rtcIntersect16, lib.rtcOccluded16

    @njit(nogil=True)
    def packet_buffer():
        """A zeroed ``RTCRayHit16`` aligned to 64 bytes, as float32 and as uint32 words."""
        raw = np.zeros(_RAYHIT_WORDS + LANES, np.float32)
        skip = ((64 - raw.ctypes.data % 64) % 64) // 4
        words = raw[skip:skip + _RAYHIT_WORDS]
        return words, words.view(np.uint32)

    @njit(nogil=True)
    def fill(words, ids, valid, origins, directions, t_min, t_max, first, count, any_hit):
        for r in range(LANES):
            valid[r] = -1 if r < count else 0
            k = first + r if r < count else first
            for a in range(3):
                words[_ORG + a * LANES + r] = origins[k, a]
                words[_DIR + a * LANES + r] = directions[k, a]
            words[_TNEAR + r], words[_TFAR + r], words[_TIME + r] = t_min[k], t_max[k], 0.0
            ids[_MASK + r], ids[_ID + r], ids[_FLAGS + r] = _INVALID_ID, r, 0
            if not any_hit:
                ids[_GEOM_ID + r] = _INVALID_ID

    @njit(nogil=True)
    def worker(w, n_workers, scene, any_hit, origins, directions, t_min, t_max, prims, ts, us, vs):
        words, ids = packet_buffer()
        valid = np.zeros(LANES + 16, np.int32)  # 64-byte aligned below, as the packet
        valid = valid[((64 - valid.ctypes.data % 64) % 64) // 4:][:LANES]
        n = origins.shape[0]
        n_packets = (n + LANES - 1) // LANES
        for p in range(w * n_packets // n_workers, (w + 1) * n_packets // n_workers):
            first = p * LANES
            count = min(LANES, n - first)
            fill(words, ids, valid, origins, directions, t_min, t_max, first, count, any_hit)
            if any_hit:
                occluded16(valid.ctypes.data, scene, words.ctypes.data, 0)
                for r in range(count):
                    if words[_TFAR + r] == -math.inf:
                        prims[first + r] = 0
            else:
                intersect16(valid.ctypes.data, scene, words.ctypes.data, 0)
                for r in range(count):
                    hit = ids[_GEOM_ID + r] != _INVALID_ID
                    prims[first + r] = ids[_PRIM_ID + r] if hit else -1
                    ts[first + r] = words[_TFAR + r] if hit else math.inf
                    us[first + r], vs[first + r] = words[_U + r], words[_V + r]

    @njit(nogil=True, parallel=True)
    def trace(scene, any_hit, origins, directions, t_min, t_max, n_workers, prims, ts, us, vs):
        for w in prange(n_workers):
            worker(w, n_workers, scene, any_hit, origins, directions, t_min, t_max, prims, ts, us, vs)

    return trace


class EmbreePackets:
    """One triangle mesh in an Embree scene, traced in packets of 16 on ``n_workers`` numba threads.

    Parameters
    ----------
    path : the ``libembree4`` library (:func:`find_library`).
    corners : (M, 3, 3) float, the triangles' corners ``A, B, C``; Embree keeps float32 copies.
    n_workers : int, threads tracing (``numba.get_num_threads()``).
    """

    def __init__(self, path: Path, corners: np.ndarray, n_workers: int):
        self._lib = lib = _c_api(path)
        self._n_workers = n_workers
        n = corners.shape[0]
        # Embree reads the last vertex with a 16-byte load: one vertex of padding.
        self._vertices = np.zeros((3 * n + 1, 3), np.float32)
        self._vertices[:-1] = corners.reshape(-1, 3)
        self._indices = np.arange(3 * n, dtype=np.uint32).reshape(n, 3)
        self._device = lib.rtcNewDevice(None)
        if not self._device:
            raise RuntimeError("Embree: rtcNewDevice failed")
        self._scene = lib.rtcNewScene(self._device)
        geometry = lib.rtcNewGeometry(self._device, _GEOMETRY_TYPE_TRIANGLE)
        lib.rtcSetSharedGeometryBuffer(geometry, _BUFFER_TYPE_VERTEX, 0, _FORMAT_FLOAT3,
                                       self._vertices.ctypes.data, 0, 12, 3 * n)
        lib.rtcSetSharedGeometryBuffer(geometry, _BUFFER_TYPE_INDEX, 0, _FORMAT_UINT3,
                                       self._indices.ctypes.data, 0, 12, n)
        lib.rtcCommitGeometry(geometry)
        lib.rtcAttachGeometry(self._scene, geometry)
        lib.rtcReleaseGeometry(geometry)
        start = time.perf_counter()
        lib.rtcCommitScene(self._scene)
        self.build_seconds = time.perf_counter() - start
        error = lib.rtcGetDeviceError(self._device)
        if error:
            raise RuntimeError(f"Embree: building the scene failed with error code {error}")
        self._trace = _kernels(lib)
        #: Seconds of the first trace of this scene, which compiles the kernel if no scene did before.
        self.compile_seconds = None

    def close(self) -> None:
        """Release the scene and the device."""
        self._lib.rtcReleaseScene(self._scene)
        self._lib.rtcReleaseDevice(self._device)

    def tracer(self, origins, directions, t_min, t_max, any_hit: bool):
        """``(trace, results)``: a function tracing these rays once, and the arrays it fills.

        The rays are copied to float32 here, before any clock starts.  ``results`` is
        ``(prims, ts, us, vs)``: per ray the triangle hit (-1: none; with ``any_hit``, 0 where
        blocked), and for closest hits its ``t`` and Embree's barycentric ``u, v`` (weights of
        the corners ``B`` and ``C``).  The first call compiles the kernel
        (:attr:`compile_seconds`).
        """
        rays = [np.ascontiguousarray(a, np.float32) for a in (origins, directions, t_min, t_max)]
        n = rays[0].shape[0]
        results = (np.full(n, -1, np.int64), np.full(n, math.inf, np.float32), np.zeros(n, np.float32),
                   np.zeros(n, np.float32))

        def trace():
            self._trace(self._scene, any_hit, *rays, self._n_workers, *results)

        if self.compile_seconds is None:
            start = time.perf_counter()
            trace()
            self.compile_seconds = time.perf_counter() - start
        return trace, results
