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
import numbers
import os
import subprocess
from dataclasses import dataclass, field

import numpy as np

from . import _args, _lib
from ._lib import ArgumentError, ArgumentTypeError, SubsurfError

__all__ = ["SubsurfError", "ArgumentError", "ArgumentTypeError", "Medium", "Model",
           "HalfspaceResult", "Scene", "halfspace", "compare", "read_image", "models", "presets",
           "version"]

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
        where = "Medium.preset"
        key = _args.text(where, "name", name)
        scale = _args.real(where, "scale", scale)
        g = _args.real(where, "g", g)
        s = np.zeros(3)
        a = np.zeros(3)
        e = ctypes.c_double()
        err = _lib.error_buffer()
        rc = _lib.ss_ffi_preset(key, scale, g, _ptr(s), _ptr(a), ctypes.byref(e), err, len(err))
        if rc:
            _lib.raise_error(err, rc, where)
        return cls(s, a, g, e.value if eta is None else eta)

    def __post_init__(self):
        self.arrays("Medium")

    def arrays(self, where="Medium"):
        """sigma_s, sigma_a and g as three RGB arrays, each number finite (as
        the command line's --sigma-s, --sigma-a, --g); raises otherwise."""
        return (_args.rgb(where, "sigma_s", self.sigma_s), _args.rgb(where, "sigma_a", self.sigma_a),
                _args.rgb(where, "g", self.g))

    def eta_value(self, where="Medium"):
        """eta, a finite number (as the command line's --eta)."""
        return _args.number("halfspace", where, "eta", self.eta)


def _medium(where, medium):
    """A Medium's sigma_s, sigma_a, g (RGB arrays) and eta, each checked."""
    if not isinstance(medium, Medium):
        raise ArgumentTypeError(f"{where}: medium: expected a subsurf.Medium, got "
                                f"{type(medium).__name__}")
    return (*medium.arrays(where), medium.eta_value(where))


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


def _option_text(name, v):
    """A model option's value as the text `subsurf model --NAME` would be given."""
    if isinstance(v, (bool, np.bool_)):
        return "true" if v else "false"
    if isinstance(v, str):
        return v
    if isinstance(v, numbers.Real):
        return _args.number_text("Model", name, v)
    raise ArgumentTypeError(f"Model: {name}: expected a number, a bool or a str, got "
                            f"{type(v).__name__}")


class Model(_Handle):
    """A BSSRDF model of the registry (subsurf.models()) for a medium, with the
    model's options as keyword arguments (`subsurf model --help` lists them).
    Use as a context manager, or call close()."""

    def __init__(self, name, medium, **options):
        key = _args.text("Model", "name", name)
        s, a, g, eta = _medium("Model", medium)
        keys = [k.encode() for k in options]
        values = [_args.text("Model", k, _option_text(k, v)) for k, v in options.items()]
        n = len(keys)
        karr = (ctypes.c_char_p * max(n, 1))(*keys)
        varr = (ctypes.c_char_p * max(n, 1))(*values)
        err = _lib.error_buffer()
        status = ctypes.c_int()
        self._h = _lib.ss_ffi_model_create(key, _ptr(s), _ptr(a), _ptr(g), eta, karr, varr, n,
                                           ctypes.byref(status), err, len(err))
        if not self._h:
            _lib.raise_error(err, status.value, "Model")
        self.name = name
        self.medium = medium
        self.flags = _lib.ss_ffi_model_flags(self._h)

    _destroy = staticmethod(_lib.ss_ffi_model_destroy)

    def profile(self, r, channel=0):
        """The radial profile at normal incidence at radii r for one channel:
        a dict of arrays 'value' (what the paper plots), 'ms' (multiple
        scattering) and 'ss' (single scattering)."""
        where = "Model.profile"
        channel = _args.channel(where, channel)
        r = _args.array(where, "r", r).ravel()
        out = {k: np.empty_like(r) for k in ("value", "ms", "ss")}
        err = _lib.error_buffer()
        rc = _lib.ss_ffi_model_profile(self._handle(), channel, _ptr(r), r.size, _ptr(out["value"]),
                                       _ptr(out["ms"]), _ptr(out["ss"]), err, len(err))
        if rc:
            _lib.raise_error(err, rc, where)
        return out

    def total_reflectance(self, cos_i=1.0):
        """Total diffuse reflectance per channel for light arriving at cos_i."""
        where = "Model.total_reflectance"
        cos_i = _args.real(where, "cos_i", cos_i)
        out = np.empty(3)
        err = _lib.error_buffer()
        rc = _lib.ss_ffi_model_total_reflectance(self._handle(), cos_i, _ptr(out), err, len(err))
        if rc:
            _lib.raise_error(err, rc, where)
        return out

    def exitance(self, x, y, cos_i=1.0):
        """Exitance per unit incident power at points (x, y) of a beam
        entering at the origin at cos_i, travelling toward +x; shape (n, 3)."""
        where = "Model.exitance"
        cos_i = _args.real(where, "cos_i", cos_i)
        x, y = _args.array(where, "x", x), _args.array(where, "y", y)
        try:
            x, y = np.broadcast_arrays(x, y)
        except ValueError:
            raise ArgumentError(f"{where}: x and y must have one shape (or broadcast), got "
                                f"{x.shape} and {y.shape}") from None
        x = np.ascontiguousarray(x.ravel())
        y = np.ascontiguousarray(y.ravel())
        out = np.empty((x.size, 3))
        err = _lib.error_buffer()
        rc = _lib.ss_ffi_model_exitance(self._handle(), cos_i, _ptr(x), _ptr(y), x.size, _ptr(out),
                                        err, len(err))
        if rc:
            _lib.raise_error(err, rc, where)
        return out

    def radiance(self, x, y, w_o, cos_i=1.0):
        """Exitant radiance S at points (x, y) toward unit directions w_o
        (shape (n, 3), z up, away from the surface); shape (n, 3)."""
        where = "Model.radiance"
        cos_i = _args.real(where, "cos_i", cos_i)
        x = _args.array(where, "x", x).ravel()
        y = _args.array(where, "y", y).ravel()
        w = _args.array(where, "w_o", w_o)
        if w.size % 3:
            raise ArgumentError(f"{where}: w_o: expected 3 numbers per direction, got shape "
                                f"{w.shape}")
        w = np.ascontiguousarray(w.reshape(-1, 3))
        if not (x.size == y.size == w.shape[0]):
            raise ArgumentError(f"{where}: x, y and w_o must hold the same number of points")
        out = np.empty((x.size, 3))
        err = _lib.error_buffer()
        rc = _lib.ss_ffi_model_radiance(self._handle(), cos_i, _ptr(x), _ptr(y), _ptr(w), x.size,
                                        _ptr(out), err, len(err))
        if rc:
            _lib.raise_error(err, rc, where)
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
    channel: a unit-power beam at theta_i (radians) into a half-space
    (thickness inf) or a slab of `thickness`; totals with standard errors and
    the radial exitance (annulus averages, bin 0 = [0, rmin), then log-spaced
    bins). Every argument is checked as `subsurf halfspace` checks its
    options (threads at most 4096, paths >= 1, ...)."""
    where = "halfspace"
    s, a, g, eta = _medium(where, medium)
    channel = _args.channel(where, channel)
    num = {k: _args.number("halfspace", where, k, v) for k, v in
           (("theta_i", theta_i), ("thickness", thickness), ("rmin", rmin), ("rmax", rmax))}
    whole = {k: _args.whole("halfspace", where, k, v) for k, v in
             (("paths", paths), ("seed", seed), ("threads", threads), ("rbins", rbins))}
    totals = np.empty(8)
    bins = [np.empty(whole["rbins"]) for _ in range(4)]
    err = _lib.error_buffer()
    rc = _lib.ss_ffi_halfspace(_ptr(s), _ptr(a), _ptr(g), channel, eta, num["theta_i"],
                               num["thickness"], whole["paths"], whole["seed"], whole["threads"],
                               num["rmin"], num["rmax"], whole["rbins"], _ptr(totals),
                               *(_ptr(b) for b in bins), err, len(err))
    if rc:
        _lib.raise_error(err, rc)
    t = [(totals[2 * i], totals[2 * i + 1]) for i in range(4)]
    return HalfspaceResult(*t, *bins)


class Scene(_Handle):
    """A scene file, JSON (docs/scene-format.md) or pbrt-v3 by a .pbrt extension
    (docs/pbrt-import.md), loaded and ready to render."""

    def __init__(self, path):
        p = _args.path("Scene", "path", path)
        err = _lib.error_buffer()
        self._h = _lib.ss_ffi_scene_load(p, err, len(err))
        if not self._h:
            _lib.raise_error(err)
        w, h = ctypes.c_int(), ctypes.c_int()
        _lib.ss_ffi_scene_size(self._h, ctypes.byref(w), ctypes.byref(h))
        self.width, self.height = w.value, h.value
        self.stats = None

    _destroy = staticmethod(_lib.ss_ffi_scene_destroy)

    def render(self, integrator=None, spp=None, seed=None, threads=0):
        """Renders the image (the scene's integrator, spp and seed unless
        given, checked as `subsurf render` checks --spp, --seed and --threads);
        returns float32 RGB of shape (height, width, 3). self.stats then holds
        seconds, samples and the NaN/Inf samples dropped."""
        where = "Scene.render"
        name = None if integrator is None else _args.text(where, "integrator", integrator)
        spp = 0 if spp is None else _args.whole("render", where, "spp", spp)
        seed = None if seed is None else ctypes.c_uint64(_args.whole("render", where, "seed", seed))
        threads = _args.whole("render", where, "threads", threads)
        h = self._handle()
        img = np.empty((self.height, self.width, 3), dtype=np.float32)
        stats = np.empty(3)
        err = _lib.error_buffer()
        rc = _lib.ss_ffi_render(h, name, spp, None if seed is None else ctypes.byref(seed), threads,
                                img.ctypes.data_as(ctypes.POINTER(ctypes.c_float)), _ptr(stats),
                                err, len(err))
        if rc:
            _lib.raise_error(err, rc)
        self.stats = {"seconds": stats[0], "samples": int(stats[1]), "nonfinite": int(stats[2])}
        return img


def read_image(path):
    """An EXR, PFM or PNG image (told by its first bytes; a PNG's sRGB codes
    decoded to linear values) as float32 of shape (height, width, channels)."""
    w, h, c = ctypes.c_int(), ctypes.c_int(), ctypes.c_int()
    err = _lib.error_buffer()
    p = _args.path("read_image", "path", path)
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
    where = "compare"
    if (spp is None) == (time is None):
        raise ArgumentError("compare: give exactly one of spp and time")
    if isinstance(methods, (str, bytes)) or not all(isinstance(m, str) for m in methods):
        raise ArgumentTypeError("compare: methods: expected a list of str")
    scene, output_dir = (os.fsdecode(_args.path(where, k, v)) for k, v in
                         (("scene", scene), ("output_dir", output_dir)))
    # The numbers go to the command line as the text it reads and checks.
    cmd = [_lib.binary(), "compare", scene, "--methods", ",".join(methods), "-o", output_dir,
           "--quiet"]
    for flag, v in (("--spp", spp), ("--time", time), ("--reference-spp", reference_spp),
                    ("--threads", threads), ("--seed", seed)):
        if v is not None:
            cmd += [flag, _args.number_text(where, flag[2:].replace("-", "_"), v)]
    if reference is not None:
        cmd += ["--reference", os.fsdecode(_args.path(where, "reference", reference))]
    run = subprocess.run(cmd, capture_output=True, text=True)
    if run.returncode != 0:
        # Exit status 2: the command line refused an argument.
        error = ArgumentError if run.returncode == 2 else SubsurfError
        raise error(run.stderr.strip() or f"subsurf compare exited {run.returncode}")
    with open(os.path.join(output_dir, "results.json")) as f:
        results = json.load(f)
    results["reference_array"] = read_image(os.path.join(output_dir, results["reference"]))
    for m in results["methods"]:
        m["array"] = read_image(os.path.join(output_dir, m["image"] + ".exr"))
    return results
