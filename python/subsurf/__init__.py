"""subsurf from Python: BSSRDF models, the half-space Monte Carlo reference,
renders and scene comparisons, with numpy arrays in and out.

    import numpy as np, subsurf
    skin = subsurf.Medium.preset("skin1", g=0.0)
    with subsurf.Model("dipole", skin) as m:
        rd = m.total_reflectance()            # RGB, shape (3,)
        prof = m.profile(np.linspace(0.1, 5, 50))["value"]
    ref = subsurf.halfspace(skin, channel=0, paths=100_000)
    print(ref.reflectance)                    # (value, standard error)

See docs/python.md for the whole interface.
"""
import ctypes
import json
import math
import os
import subprocess
from dataclasses import dataclass, field

import numpy as np

from . import _lib
from ._lib import SubsurfError

__all__ = ["SubsurfError", "Medium", "Model", "HalfspaceResult", "Scene", "halfspace",
           "compare", "read_image", "models", "presets", "version"]

RADIAL = 1 << 0
BRDF = 1 << 1


def version():
    """The library's version, "MAJOR.MINOR.PATCH"."""
    return _lib.ss_ffi_version().decode()


def models():
    """Names of the registered BSSRDF models."""
    return _lib.names(_lib.ss_ffi_model_names)


def presets():
    """Names of the measured media presets (mm^-1)."""
    return _lib.names(_lib.ss_ffi_preset_names)


def _rgb(v, name):
    a = np.broadcast_to(np.asarray(v, dtype=np.float64), (3,))
    if not np.all(np.isfinite(a)):
        raise SubsurfError(f"{name} must be finite, got {v!r}")
    return np.ascontiguousarray(a)


def _ptr(a):
    return a.ctypes.data_as(ctypes.POINTER(ctypes.c_double))


@dataclass
class Medium:
    """A homogeneous medium (Henyey-Greenstein phase) behind a boundary of
    relative index eta = n_inside / n_outside. sigma_s, sigma_a and g are one
    number or three (RGB), per unit length."""
    sigma_s: object
    sigma_a: object
    g: object = 0.0
    eta: float = 1.3

    @classmethod
    def preset(cls, name, scale=1.0, g=0.0, eta=None):
        """A measured preset (subsurf.presets()), per mm times `scale`, with
        sigma_s = sigma_s' / (1 - g) so that the reduced coefficient is kept."""
        s = np.zeros(3)
        a = np.zeros(3)
        e = ctypes.c_double()
        err = _lib.error_buffer()
        if _lib.ss_ffi_preset(name.encode(), float(scale), float(g), _ptr(s), _ptr(a),
                              ctypes.byref(e), err, len(err)):
            _lib.raise_error(err)
        return cls(s, a, g, e.value if eta is None else eta)

    def arrays(self):
        return (_rgb(self.sigma_s, "sigma_s"), _rgb(self.sigma_a, "sigma_a"), _rgb(self.g, "g"))


class _Handle:
    """An object of the library behind an opaque handle, freed by close()
    (or at the end of a with block, or by the garbage collector)."""
    _h = None
    _destroy = None

    def close(self):
        if self._h:
            type(self)._destroy(self._h)
            self._h = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __del__(self):
        self.close()

    def _handle(self):
        if not self._h:
            raise SubsurfError(f"{type(self).__name__} is closed")
        return self._h


def _option_text(v):
    if isinstance(v, bool):
        return "true" if v else "false"
    return str(v)


class Model(_Handle):
    """A BSSRDF model of the registry (subsurf.models()) for a medium, with the
    model's options as keyword arguments (`subsurf model --help` lists them).
    Use as a context manager, or call close()."""

    def __init__(self, name, medium, **options):
        s, a, g = medium.arrays()
        keys = [k.encode() for k in options]
        values = [_option_text(v).encode() for v in options.values()]
        n = len(keys)
        karr = (ctypes.c_char_p * max(n, 1))(*keys)
        varr = (ctypes.c_char_p * max(n, 1))(*values)
        err = _lib.error_buffer()
        self._h = _lib.ss_ffi_model_create(name.encode(), _ptr(s), _ptr(a), _ptr(g),
                                           float(medium.eta), karr, varr, n, err, len(err))
        if not self._h:
            _lib.raise_error(err)
        self.name = name
        self.medium = medium
        self.flags = _lib.ss_ffi_model_flags(self._h)

    _destroy = staticmethod(_lib.ss_ffi_model_destroy)

    def profile(self, r, channel=0):
        """The radial profile at normal incidence at radii r for one channel:
        a dict of arrays 'value' (what the paper plots), 'ms' (multiple
        scattering) and 'ss' (single scattering)."""
        if channel not in (0, 1, 2):
            raise SubsurfError(f"channel must be 0, 1 or 2, got {channel!r}")
        r = np.ascontiguousarray(np.asarray(r, dtype=np.float64).ravel())
        out = {k: np.empty_like(r) for k in ("value", "ms", "ss")}
        _lib.ss_ffi_model_profile(self._handle(), channel, _ptr(r), r.size, _ptr(out["value"]),
                                  _ptr(out["ms"]), _ptr(out["ss"]))
        return out

    def total_reflectance(self, cos_i=1.0):
        """Total diffuse reflectance per channel for light arriving at cos_i."""
        out = np.empty(3)
        _lib.ss_ffi_model_total_reflectance(self._handle(), float(cos_i), _ptr(out))
        return out

    def exitance(self, x, y, cos_i=1.0):
        """Exitance per unit incident power at points (x, y) of a beam
        entering at the origin at cos_i, travelling toward +x; shape (n, 3)."""
        x, y = np.broadcast_arrays(np.asarray(x, dtype=np.float64),
                                   np.asarray(y, dtype=np.float64))
        x = np.ascontiguousarray(x.ravel())
        y = np.ascontiguousarray(y.ravel())
        out = np.empty((x.size, 3))
        _lib.ss_ffi_model_exitance(self._handle(), float(cos_i), _ptr(x), _ptr(y), x.size,
                                   _ptr(out))
        return out

    def radiance(self, x, y, w_o, cos_i=1.0):
        """Exitant radiance S at points (x, y) toward unit directions w_o
        (shape (n, 3), z up, away from the surface); shape (n, 3)."""
        x = np.ascontiguousarray(np.asarray(x, dtype=np.float64).ravel())
        y = np.ascontiguousarray(np.asarray(y, dtype=np.float64).ravel())
        w = np.ascontiguousarray(np.asarray(w_o, dtype=np.float64).reshape(-1, 3))
        if not (x.size == y.size == w.shape[0]):
            raise SubsurfError("x, y and w_o must hold the same number of points")
        out = np.empty((x.size, 3))
        _lib.ss_ffi_model_radiance(self._handle(), float(cos_i), _ptr(x), _ptr(y), _ptr(w),
                                   x.size, _ptr(out))
        return out


@dataclass
class HalfspaceResult:
    """The half-space reference's answers, each total as (value, standard error)."""
    reflectance: tuple
    transmittance: tuple
    specular: tuple
    absorbed: tuple
    r_lo: np.ndarray = field(repr=False)
    r_hi: np.ndarray = field(repr=False)
    radial: np.ndarray = field(repr=False)
    radial_error: np.ndarray = field(repr=False)


def halfspace(medium, channel=0, theta_i=0.0, thickness=math.inf, paths=100_000, seed=1,
              threads=0, rmin=0.01, rmax=10.0, rbins=64):
    """The plane-parallel Monte Carlo reference (`subsurf halfspace`) for one
    channel: a unit-power beam at theta_i (radians) into a half-space (or a
    slab of `thickness`); totals with standard errors and the radial
    exitance (annulus averages, bin 0 = [0, rmin), then log-spaced bins)."""
    s, a, g = medium.arrays()
    totals = np.empty(8)
    bins = [np.empty(int(rbins)) for _ in range(4)]
    err = _lib.error_buffer()
    if _lib.ss_ffi_halfspace(_ptr(s), _ptr(a), _ptr(g), int(channel), float(medium.eta),
                             float(theta_i), float(thickness), int(paths), int(seed),
                             int(threads), float(rmin), float(rmax), int(rbins), _ptr(totals),
                             *(_ptr(b) for b in bins), err, len(err)):
        _lib.raise_error(err)
    t = [(totals[2 * i], totals[2 * i + 1]) for i in range(4)]
    return HalfspaceResult(*t, *bins)


class Scene(_Handle):
    """A scene file, JSON (docs/scene-format.md) or pbrt-v3 by a .pbrt extension
    (docs/pbrt-import.md), loaded and ready to render."""

    def __init__(self, path):
        err = _lib.error_buffer()
        self._h = _lib.ss_ffi_scene_load(os.fsencode(path), err, len(err))
        if not self._h:
            _lib.raise_error(err)
        w, h = ctypes.c_int(), ctypes.c_int()
        _lib.ss_ffi_scene_size(self._h, ctypes.byref(w), ctypes.byref(h))
        self.width, self.height = w.value, h.value
        self.stats = None

    _destroy = staticmethod(_lib.ss_ffi_scene_destroy)

    def render(self, integrator=None, spp=None, seed=None, threads=0):
        """Renders the image (the scene's integrator, spp and seed unless
        given); returns float32 RGB of shape (height, width, 3). self.stats
        then holds seconds, samples and the NaN/Inf samples dropped."""
        h = self._handle()
        img = np.empty((self.height, self.width, 3), dtype=np.float32)
        stats = np.empty(3)
        err = _lib.error_buffer()
        rc = _lib.ss_ffi_render(h, integrator.encode() if integrator else None,
                                int(spp) if spp else 0, -1 if seed is None else int(seed),
                                int(threads), img.ctypes.data_as(ctypes.POINTER(ctypes.c_float)),
                                _ptr(stats), err, len(err))
        if rc:
            _lib.raise_error(err)
        self.stats = {"seconds": stats[0], "samples": int(stats[1]), "nonfinite": int(stats[2])}
        return img


def read_image(path):
    """An EXR, PFM, PNG or HDR image as float32 of shape (height, width, channels)."""
    w, h, c = ctypes.c_int(), ctypes.c_int(), ctypes.c_int()
    err = _lib.error_buffer()
    p = os.fsencode(path)
    if _lib.ss_ffi_image_read(p, ctypes.byref(w), ctypes.byref(h), ctypes.byref(c), None, 0, err,
                              len(err)):
        _lib.raise_error(err)
    img = np.empty((h.value, w.value, c.value), dtype=np.float32)
    if _lib.ss_ffi_image_read(p, ctypes.byref(w), ctypes.byref(h), ctypes.byref(c),
                              img.ctypes.data_as(ctypes.POINTER(ctypes.c_float)), img.size, err,
                              len(err)):
        _lib.raise_error(err)
    return img


def compare(scene, methods, output_dir, spp=None, time=None, reference=None, reference_spp=None,
            threads=None, seed=None):
    """`subsurf compare`: renders the scene with each method (integrators or
    BSSRDF models, e.g. ["volpath", "dipole", "pbd:beam_samples=50"]) and
    compares each with a reference; returns DIR/results.json as a dict, with
    each method's image added as a numpy array under "array" and the
    reference's under "reference_array"."""
    if (spp is None) == (time is None):
        raise SubsurfError("compare: give exactly one of spp and time")
    cmd = [_lib.binary(), "compare", os.fspath(scene), "--methods", ",".join(methods), "-o",
           os.fspath(output_dir), "--quiet"]
    cmd += ["--spp", str(int(spp))] if spp is not None else ["--time", str(float(time))]
    if reference is not None:
        cmd += ["--reference", os.fspath(reference)]
    if reference_spp is not None:
        cmd += ["--reference-spp", str(int(reference_spp))]
    if threads is not None:
        cmd += ["--threads", str(int(threads))]
    if seed is not None:
        cmd += ["--seed", str(int(seed))]
    run = subprocess.run(cmd, capture_output=True, text=True)
    if run.returncode != 0:
        raise SubsurfError(run.stderr.strip() or f"subsurf compare exited {run.returncode}")
    with open(os.path.join(output_dir, "results.json")) as f:
        results = json.load(f)
    results["reference_array"] = read_image(os.path.join(output_dir, results["reference"]))
    for m in results["methods"]:
        m["array"] = read_image(os.path.join(output_dir, m["image"] + ".exr"))
    return results
