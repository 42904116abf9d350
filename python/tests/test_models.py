"""The models through Python equal the library's answers and obey their identities."""
import math

import numpy as np
import pytest

import subsurf


def test_registry_lists_the_classical_models():
    names = subsurf.models()
    for m in ("dipole", "better-dipole", "pbd", "multipole", "fwddip"):
        assert m in names
    assert "skin1" in [p.lower() for p in subsurf.presets()]


def test_preset_keeps_the_reduced_scattering_coefficient():
    a = subsurf.Medium.preset("skin1", scale=1.0, g=0.0)
    b = subsurf.Medium.preset("skin1", scale=1.0, g=0.8)
    np.testing.assert_allclose(np.asarray(b.sigma_s) * 0.2, a.sigma_s, rtol=1e-12)
    np.testing.assert_allclose(b.sigma_a, a.sigma_a, rtol=0)


def test_dipole_exitance_integrates_to_its_total_reflectance():
    # The exitance of a normal beam, integrated over the plane (2 pi r dr on a
    # log grid), equals the model's own total diffuse reflectance R_d.
    med = subsurf.Medium([1.0, 2.0, 4.0], [0.01, 0.05, 0.2], g=0.0, eta=1.3)
    with subsurf.Model("dipole", med) as m:
        r = np.geomspace(1e-5, 60.0, 20001)
        ex = m.exitance(r, np.zeros_like(r))
        total = np.trapz(ex * (2 * math.pi * r)[:, None], r, axis=0)
        np.testing.assert_allclose(total, m.total_reflectance(), rtol=2e-3)


def test_profile_is_finite_non_negative_and_falls_with_distance():
    med = subsurf.Medium.preset("marble", g=0.0)
    with subsurf.Model("pbd", med) as m:
        p = m.profile(np.linspace(0.05, 20, 200), channel=1)
        assert np.all(np.isfinite(p["value"])) and np.all(p["value"] >= 0)
        assert p["value"][0] > p["value"][-1] > 0
        np.testing.assert_allclose(p["value"], p["ms"] + p["ss"], rtol=1e-12, atol=0)


def test_radiance_of_a_radial_model_is_symmetric_under_rotation_at_normal_incidence():
    med = subsurf.Medium(2.0, 0.02, 0.0, 1.4)
    with subsurf.Model("better-dipole", med) as m:
        assert m.flags & subsurf.RADIAL
        w = np.array([[0.0, 0.0, 1.0], [0.0, 0.0, 1.0]])
        out = m.radiance([0.7, 0.0], [0.0, 0.7], w)
        np.testing.assert_allclose(out[0], out[1], rtol=1e-12)
        assert np.all(out > 0)


def test_model_options_are_set_by_name():
    med = subsurf.Medium(1.0, 0.01, 0.0, 1.3)
    with subsurf.Model("pbd", med, beam_samples=8) as coarse, subsurf.Model("pbd", med) as fine:
        a = coarse.profile([1.0])["value"][0]
        b = fine.profile([1.0])["value"][0]
        assert a != b and abs(a / b - 1) < 0.2


def test_bad_model_input_raises_with_the_cause():
    med = subsurf.Medium(1.0, 0.01)
    with pytest.raises(subsurf.SubsurfError, match="unknown model 'nope'"):
        subsurf.Model("nope", med)
    with pytest.raises(subsurf.SubsurfError, match="beam_samples"):
        subsurf.Model("pbd", med, beam_samples=-3)
    with pytest.raises(subsurf.SubsurfError, match="no_such_option"):
        subsurf.Model("dipole", med, no_such_option=1)
    with pytest.raises(ValueError, match="sigma-a must be in"):
        subsurf.Model("dipole", subsurf.Medium(1.0, -1.0))
    with pytest.raises(subsurf.SubsurfError, match="finite"):
        subsurf.Medium(float("nan"), 0.1).arrays()
    with pytest.raises(subsurf.SubsurfError, match="unknown medium preset"):
        subsurf.Medium.preset("unobtainium")
