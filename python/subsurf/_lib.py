"""Loading libsubsurf.so and declaring the flat interface of include/subsurf/ffi.h."""
import ctypes
import ctypes.util
import os

try:
    from . import _paths  # written by `make install`
except ImportError:  # running from the source tree
    _paths = None


class SubsurfError(Exception):
    """An error reported by the library (its message names the cause)."""


class ArgumentError(SubsurfError, ValueError):
    """An argument outside what it takes: the command line's grammar and
    ranges, in its words, after the function's and the argument's names."""


class ArgumentTypeError(SubsurfError, TypeError):
    """An argument of a type it cannot take (text for a number, a bool for a
    count, a list for a number...)."""


# ss_status (include/subsurf/status.h) of an argument out of range.
INVALID_ARGUMENT = 1


def _locate(env, installed, fallback, what):
    """$env, else the installed file (installed(_paths)), else fallback()."""
    explicit = os.environ.get(env)
    if explicit:
        return explicit
    if _paths is not None and os.path.exists(installed(_paths)):
        return installed(_paths)
    found = fallback()
    if found:
        return found
    raise SubsurfError(f"{what} not found: install subsurf (make install PREFIX=...) "
                       f"or set {env}")


def _find_library():
    return _locate("SUBSURF_LIB", lambda p: os.path.join(p.LIBDIR, "libsubsurf.so.0"),
                   lambda: ctypes.util.find_library("subsurf"), "libsubsurf.so")


lib = ctypes.CDLL(_find_library())

_d = ctypes.c_double
_dp = ctypes.POINTER(ctypes.c_double)
_fp = ctypes.POINTER(ctypes.c_float)
_ip = ctypes.POINTER(ctypes.c_int)
_cp = ctypes.c_char_p
_sz = ctypes.c_size_t
_vp = ctypes.c_void_p


def _proto(name, restype, *argtypes):
    f = getattr(lib, name)
    f.restype = restype
    f.argtypes = list(argtypes)
    return f


ss_ffi_version = _proto("ss_ffi_version", _cp)
ss_ffi_arg_parse = _proto("ss_ffi_arg_parse", ctypes.c_int, _cp, _cp, _cp, _dp, _cp, _sz)
ss_ffi_model_names = _proto("ss_ffi_model_names", None, _cp, _sz)
ss_ffi_preset_names = _proto("ss_ffi_preset_names", None, _cp, _sz)
ss_ffi_preset = _proto("ss_ffi_preset", ctypes.c_int, _cp, _d, _d, _dp, _dp, _dp, _cp, _sz)
ss_ffi_model_create = _proto("ss_ffi_model_create", _vp, _cp, _dp, _dp, _dp, _d,
                             ctypes.POINTER(_cp), ctypes.POINTER(_cp), ctypes.c_int, _ip, _cp,
                             _sz)
ss_ffi_model_destroy = _proto("ss_ffi_model_destroy", None, _vp)
ss_ffi_model_flags = _proto("ss_ffi_model_flags", ctypes.c_uint, _vp)
ss_ffi_model_profile = _proto("ss_ffi_model_profile", ctypes.c_int, _vp, ctypes.c_int, _dp, _sz,
                              _dp, _dp, _dp, _cp, _sz)
ss_ffi_model_total_reflectance = _proto("ss_ffi_model_total_reflectance", ctypes.c_int, _vp, _d,
                                        _dp, _cp, _sz)
ss_ffi_model_exitance = _proto("ss_ffi_model_exitance", ctypes.c_int, _vp, _d, _dp, _dp, _sz, _dp,
                               _cp, _sz)
ss_ffi_model_radiance = _proto("ss_ffi_model_radiance", ctypes.c_int, _vp, _d, _dp, _dp, _dp, _sz,
                               _dp, _cp, _sz)
ss_ffi_halfspace = _proto("ss_ffi_halfspace", ctypes.c_int, _dp, _dp, _dp, ctypes.c_int, _d, _d,
                          _d, ctypes.c_uint64, ctypes.c_uint64, ctypes.c_int, _d, _d,
                          ctypes.c_int, _dp, _dp, _dp, _dp, _dp, _cp, _sz)
ss_ffi_scene_load = _proto("ss_ffi_scene_load", _vp, _cp, _cp, _sz)
ss_ffi_scene_destroy = _proto("ss_ffi_scene_destroy", None, _vp)
ss_ffi_scene_size = _proto("ss_ffi_scene_size", None, _vp, _ip, _ip)
ss_ffi_render = _proto("ss_ffi_render", ctypes.c_int, _vp, _cp, ctypes.c_int,
                       ctypes.POINTER(ctypes.c_uint64), ctypes.c_int, _fp, _dp, _cp, _sz)
ss_ffi_image_read = _proto("ss_ffi_image_read", ctypes.c_int, _cp, _ip, _ip, _ip, _fp, _sz,
                           _cp, _sz)


def error_buffer():
    return ctypes.create_string_buffer(1024)


def raise_error(buf, status=0, where=None):
    """Raises the library's message (after `where: ` when given): an
    ArgumentError for SS_ERR_INVALID_ARGUMENT, else a SubsurfError."""
    message = buf.value.decode("utf-8", "replace")
    if where:
        message = f"{where}: {message}"
    raise (ArgumentError if status == INVALID_ARGUMENT else SubsurfError)(message)


def names(fn):
    buf = ctypes.create_string_buffer(8192)
    fn(buf, len(buf))
    return [n for n in buf.value.decode().split("\n") if n]


def binary():
    """The subsurf command-line program: $SUBSURF_BIN, the installed one, or PATH's."""
    import shutil
    return _locate("SUBSURF_BIN", lambda p: os.path.join(p.BINDIR, "subsurf"),
                   lambda: shutil.which("subsurf"), "the subsurf program")
