"""The Python bad-input sweep, the module's counterpart of
tests/cli/test_bad_input_sweep.c: every function, every argument, each
hostile value its documented range excludes (negative, zero, NaN, inf,
1e308, integers past 2^31, 2^32 and 2^64, fractions, text, None, bools,
lists, complex numbers). Each call must raise ArgumentError (a ValueError) or
ArgumentTypeError (a TypeError) naming the argument, before any work; a crash
of the interpreter fails the whole run."""
import math
import re
import subprocess

import numpy as np
import pytest

import subsurf

VALUES = {"neg": -1, "zero": 0, "nan": math.nan, "inf": math.inf, "ninf": -math.inf,
          "huge": 1e308, "int31": 2**31, "int32": 2**32 + 1, "int64": 2**64, "frac": 2.5,
          "text": "5", "none": None, "bool": True, "list": [1, 2], "complex": 1j}

MED = subsurf.Medium(1.0, 0.01)
FAST = dict(paths=10, rbins=4)


def halfspace(**kw):
    return lambda v: subsurf.halfspace(MED, **{**FAST, **{k: v for k in kw}})


# (function, the argument as its message names it (a pattern), how to call it with v, the
# tags of VALUES that are valid for it and so not tried).
CASES = [
    ("halfspace", "channel", halfspace(channel=1), "zero"),
    ("halfspace", "theta_i", halfspace(theta_i=1), "zero"),
    ("halfspace", "thickness", halfspace(thickness=1), "inf frac"),
    ("halfspace", "paths", halfspace(paths=1), "int31 int32"),
    ("halfspace", "seed", halfspace(seed=1), "zero int31 int32"),
    ("halfspace", "threads", halfspace(threads=1), "zero"),
    ("halfspace", "rmin", halfspace(rmin=1), "frac"),
    ("halfspace", "rmax", halfspace(rmax=1), "frac"),
    ("halfspace", "rbins", halfspace(rbins=1), ""),
    ("halfspace", "medium", lambda v: subsurf.halfspace(v, **FAST), ""),
    ("halfspace", "sigma_s", lambda v: subsurf.halfspace(subsurf.Medium(v, 0.01), **FAST),
     "zero frac"),
    ("halfspace", "sigma_a", lambda v: subsurf.halfspace(subsurf.Medium(1.0, v), **FAST),
     "zero frac"),
    ("halfspace", "g", lambda v: subsurf.halfspace(subsurf.Medium(1.0, 0.01, v), **FAST), "zero"),
    ("halfspace", "eta", lambda v: subsurf.halfspace(subsurf.Medium(1.0, 0.01, 0, v), **FAST),
     "frac"),
    ("Model", "name|model", lambda v: subsurf.Model(v, MED), ""),
    ("Model", "sigma_s", lambda v: subsurf.Model("dipole", subsurf.Medium(v, 0.01)), "zero frac"),
    ("Model", "sigma_a", lambda v: subsurf.Model("dipole", subsurf.Medium(1.0, v)), "zero frac"),
    ("Model", "g", lambda v: subsurf.Model("dipole", subsurf.Medium(1.0, 0.01, v)), "zero"),
    ("Model", "eta", lambda v: subsurf.Model("dipole", subsurf.Medium(1.0, 0.01, 0, v)), "frac"),
    ("Model", "beam_samples", lambda v: subsurf.Model("pbd", MED, beam_samples=v), ""),
    ("Medium.preset", "name|preset", lambda v: subsurf.Medium.preset(v), ""),
    ("Medium.preset", "scale", lambda v: subsurf.Medium.preset("skin1", scale=v), "frac"),
    ("Medium.preset", "g", lambda v: subsurf.Medium.preset("skin1", g=v), "zero"),
]


def _model_cases():
    m = subsurf.Model("dipole", MED)
    w = [[0.0, 0.0, 1.0]]
    return [
        ("Model.profile", "r", lambda v: m.profile(v), "zero frac list"),
        ("Model.profile", "channel", lambda v: m.profile([1.0], channel=v), "zero"),
        ("Model.total_reflectance", "cos_i", lambda v: m.total_reflectance(v), ""),
        ("Model.exitance", "cos_i", lambda v: m.exitance(1.0, 0.0, v), ""),
        ("Model.exitance", "x", lambda v: m.exitance(v, 0.0), "neg zero frac list"),
        ("Model.exitance", "y", lambda v: m.exitance(0.5, v), "neg zero frac list"),
        ("Model.radiance", "x", lambda v: m.radiance(v, [0.0], w), "neg zero frac"),
        ("Model.radiance", "w_o", lambda v: m.radiance([0.5], [0.0], v), ""),
        ("Model.radiance", "cos_i", lambda v: m.radiance([0.5], [0.0], w, v), ""),
    ]


def _expect_refused(where, name, call, valid):
    tried = 0
    for tag, v in VALUES.items():
        if tag in valid.split():
            continue
        with pytest.raises((subsurf.ArgumentError, subsurf.ArgumentTypeError)) as e:
            call(v)
            pytest.fail(f"{where}: {name}={v!r} was accepted")
        assert isinstance(e.value, (ValueError, TypeError))
        message = str(e.value)
        assert message.startswith((where, "Medium")), message
        assert re.search(name.replace("_", "[-_]"), message), f"{name}={v!r}: {message}"
        tried += 1
    return tried


def test_every_argument_refuses_every_hostile_value_naming_it():
    tried = sum(_expect_refused(*c) for c in CASES + _model_cases())
    assert tried > 300


def test_render_refuses_counts_outside_the_command_line_s_ranges(small_scene):
    with subsurf.Scene(small_scene) as scene:
        for name, valid in (("spp", "none"), ("seed", "none zero int31 int32"),
                            ("threads", "zero")):
            _expect_refused("Scene.render", name, lambda v: scene.render(**{name: v}), valid)
        _expect_refused("Scene.render", "integrator", lambda v: scene.render(integrator=v),
                        "none text")
        with pytest.raises(subsurf.SubsurfError, match="5"):
            scene.render(integrator="5", spp=1)


def test_file_arguments_refuse_what_is_no_file_name_and_name_what_is_missing(tmp_path):
    for where, call in (("Scene", subsurf.Scene), ("read_image", subsurf.read_image)):
        for v in (0, None, 2.5, [1], b"a\0b", ""):
            with pytest.raises((subsurf.ArgumentError, subsurf.ArgumentTypeError), match=where):
                call(v)
        for v in (tmp_path / "missing-dir" / "f", "/", "."):
            with pytest.raises(subsurf.SubsurfError):
                call(v)


def test_compare_passes_numbers_as_text_for_the_command_line_to_refuse(small_scene, tmp_path):
    # 2.5 samples used to run with int(2.5) = 2.
    for name, v in (("spp", 2.5), ("spp", -1), ("spp", math.nan), ("threads", 100000),
                    ("seed", -1)):
        kw = {"spp": 1, name: v}
        with pytest.raises(subsurf.ArgumentError, match=name):
            subsurf.compare(small_scene, ["dipole"], tmp_path / "cmp", **kw)
    with pytest.raises(subsurf.ArgumentTypeError, match="methods"):
        subsurf.compare(small_scene, "dipole", tmp_path / "cmp", spp=1)
    with pytest.raises(subsurf.ArgumentTypeError, match="spp"):
        subsurf.compare(small_scene, ["dipole"], tmp_path / "cmp", spp="1")
    assert not (tmp_path / "cmp" / "results.json").exists()


def test_read_image_reads_subsurf_s_own_png(small_scene, tmp_path):
    out = tmp_path / "img.png"
    rc = subprocess.run([subsurf._lib.binary(), "render", str(small_scene), "-o",
                         str(tmp_path / "img.exr"), "--spp", "1", "--quiet"],
                        capture_output=True, text=True)
    assert rc.returncode == 0, rc.stderr
    exr = subsurf.read_image(tmp_path / "img.exr")
    png = subsurf.read_image(out)
    assert png.shape == exr.shape and png.dtype == np.float32
    assert np.all((png >= 0) & (png <= 1))
