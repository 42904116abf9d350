"""Arguments checked as strictly as the command line checks its options:
types here, values by the library's own tables and ranges (the ones
`subsurf halfspace` and `subsurf render` read), in the same words, after the
function's and the argument's names."""
import ctypes
import numbers
import os

import numpy as np

from . import _lib
from ._lib import ArgumentError, ArgumentTypeError


def _is_bool(value):
    return isinstance(value, (bool, np.bool_))


def number_text(where, name, value):
    """A real number (not a bool) as the text the command line would be given."""
    if _is_bool(value) or not isinstance(value, numbers.Real):
        raise ArgumentTypeError(f"{where}: {name}: expected a number, got {type(value).__name__}")
    if isinstance(value, numbers.Integral):
        return str(int(value))
    return repr(float(value))


def number(command, where, name, value):
    """`value` read as the command's `--NAME` (the name with '-' for '_'), from
    the library's table for the command ("halfspace" or "render")."""
    text = number_text(where, name, value)
    out = ctypes.c_double()
    err = _lib.error_buffer()
    if _lib.ss_ffi_arg_parse(command.encode(), name.replace("_", "-").encode(), text.encode(),
                             ctypes.byref(out), err, len(err)):
        _lib.raise_error(err, _lib.INVALID_ARGUMENT, f"{where}: {name}")
    return out.value


def whole(command, where, name, value):
    """A whole-number argument of the command's table, as an int."""
    return int(number(command, where, name, value))


def real(where, name, value):
    """A real number whose range the library checks (NaN and inf included)."""
    number_text(where, name, value)
    return float(value)


def array(where, name, value):
    """Real numbers as a contiguous float64 array, whose range the library checks."""
    try:
        a = np.asarray(value)
    except ValueError:
        raise ArgumentError(f"{where}: {name}: expected an array of numbers") from None
    if a.dtype.kind == "O":
        try:
            a = a.astype(np.float64)
        except TypeError:
            raise ArgumentTypeError(f"{where}: {name}: expected numbers") from None
        except (ValueError, OverflowError):
            raise ArgumentError(f"{where}: {name}: expected finite numbers") from None
    if a.dtype.kind not in "iuf":
        raise ArgumentTypeError(f"{where}: {name}: expected numbers, got {a.dtype}")
    return np.array(a, dtype=np.float64)  # a C-contiguous copy, 0-d kept


def rgb(where, name, value):
    """One number or three (RGB), each finite as the command line's --NAME."""
    a = array(where, name, value)
    if a.shape not in ((), (3,)):
        raise ArgumentError(f"{where}: {name}: expected one number or three (RGB), "
                            f"got shape {a.shape}")
    a = np.ascontiguousarray(np.broadcast_to(a, (3,)))
    for x in a:
        number("halfspace", where, name, float(x))
    return a


def channel(where, value):
    """A colour channel: 0, 1 or 2."""
    if _is_bool(value) or not isinstance(value, numbers.Integral):
        raise ArgumentTypeError(f"{where}: channel: expected 0, 1 or 2, got "
                                f"{type(value).__name__}")
    if int(value) not in (0, 1, 2):
        raise ArgumentError(f"{where}: channel: expected 0, 1 or 2, got {int(value)}")
    return int(value)


def text(where, name, value):
    """A name as bytes: a str without NUL characters, not empty."""
    if not isinstance(value, str):
        raise ArgumentTypeError(f"{where}: {name}: expected a str, got {type(value).__name__}")
    if not value or "\0" in value:
        raise ArgumentError(f"{where}: {name}: expected a name, got {value!r}")
    return value.encode()


def path(where, name, value):
    """A file name (str, bytes or os.PathLike) as bytes: not empty, no NUL."""
    if not isinstance(value, (str, bytes, os.PathLike)):
        raise ArgumentTypeError(f"{where}: {name}: expected a path, got {type(value).__name__}")
    p = os.fsencode(value)
    if not p or b"\0" in p:
        raise ArgumentError(f"{where}: {name}: expected a file name, got {value!r}")
    return p
