"""The half-space reference, renders and compare through Python equal the CLI's."""
import json
import os
import subprocess

import numpy as np
import pytest

import subsurf

BIN = os.environ.get("SUBSURF_BIN", "subsurf")
SOURCE = os.environ.get("SUBSURF_SOURCE_DIR",
                        os.path.join(os.path.dirname(__file__), "..", ".."))


def test_halfspace_equals_the_cli_bit_for_bit(tmp_path):
    med = subsurf.Medium(1.0, 0.1, 0.3, 1.3)
    res = subsurf.halfspace(med, paths=20000, seed=7, threads=1, rbins=16)
    out = tmp_path / "hs.json"
    subprocess.run([BIN, "halfspace", "--sigma-s", "1", "--sigma-a", "0.1", "--g", "0.3", "--phase", "hg",
                    "--eta", "1.3", "--paths", "20000", "--seed", "7", "--threads", "1",
                    "--rbins", "16", "--json", str(out), "--quiet"], check=True,
                   capture_output=True)
    cli = json.loads(out.read_text())
    assert res.reflectance[0] == pytest.approx(cli["reflectance"]["value"], rel=1e-15)
    assert res.reflectance[1] == pytest.approx(cli["reflectance"]["stderr"], rel=1e-12)
    assert 0 < res.reflectance[1] < 0.01
    np.testing.assert_allclose(res.radial, cli["radial"]["value"], rtol=1e-15)


def test_halfspace_of_a_purely_absorbing_medium_reflects_nothing_diffusely():
    res = subsurf.halfspace(subsurf.Medium(0.0, 1.0, 0.0, 1.0), paths=2000, rbins=4)
    assert res.reflectance == (0.0, 0.0)
    assert res.absorbed[0] == pytest.approx(1.0)


def test_bad_halfspace_input_names_the_parameter():
    with pytest.raises(subsurf.SubsurfError, match="eta"):
        subsurf.halfspace(subsurf.Medium(1.0, 0.1, 0.0, 50.0), paths=10)
    with pytest.raises(subsurf.SubsurfError, match="rbins"):
        subsurf.halfspace(subsurf.Medium(1.0, 0.1), paths=10, rbins=0)


def test_render_equals_the_cli_render_and_any_thread_count(small_scene, tmp_path):
    with subsurf.Scene(small_scene) as scene:
        assert (scene.width, scene.height) == (24, 16)
        one = scene.render(spp=4, seed=3, threads=1)
        two = scene.render(spp=4, seed=3, threads=2)
        assert one.shape == (16, 24, 3) and one.dtype == np.float32
        np.testing.assert_array_equal(one, two)
        assert scene.stats["samples"] == 24 * 16 * 4
        exr = tmp_path / "cli.exr"
        subprocess.run([BIN, "render", str(small_scene), "--spp", "4", "--seed", "3", "-o",
                        str(exr), "--quiet", "--no-png"], check=True, capture_output=True)
        np.testing.assert_array_equal(subsurf.read_image(exr)[:, :, :3], one)
        bssrdf = scene.render(integrator="bssrdf", spp=4, seed=3)
        assert np.any(bssrdf != one) and np.all(np.isfinite(bssrdf))


def test_a_pbrt_scene_loads_and_renders_as_the_cli_renders_it(tmp_path):
    """subsurf.Scene picks the reader by extension, as the CLI does."""
    with open(os.path.join(SOURCE, "scenes", "skin_sphere.pbrt")) as f:
        text = f.read()
    text = text.replace('"integer xresolution" [256] "integer yresolution" [256]',
                        '"integer xresolution" [24] "integer yresolution" [16]')
    text = text.replace('"integer subdivisions" [7]', '"integer subdivisions" [3]')
    path = tmp_path / "small.pbrt"
    path.write_text(text)
    with subsurf.Scene(path) as scene:
        assert (scene.width, scene.height) == (24, 16)
        img = scene.render(spp=2, seed=3, threads=1)
    exr = tmp_path / "cli.exr"
    subprocess.run([BIN, "render", str(path), "--spp", "2", "--seed", "3", "-o", str(exr),
                    "--quiet", "--no-png"], check=True, capture_output=True)
    np.testing.assert_array_equal(subsurf.read_image(exr)[:, :, :3], img)
    assert np.any(img > 0)


def test_bad_scene_and_image_raise_with_the_file(tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text('{"camera": {"fov": "wide"}}')
    with pytest.raises(subsurf.SubsurfError, match="bad.json"):
        subsurf.Scene(bad)
    with pytest.raises(subsurf.SubsurfError, match="missing.exr"):
        subsurf.read_image(tmp_path / "missing.exr")


def test_compare_returns_the_results_and_images(small_scene, tmp_path):
    with subsurf.Scene(small_scene) as scene:
        ref = scene.render(spp=16, seed=11)
    # A reference written by the CLI, so that compare does not render one.
    ref_exr = tmp_path / "ref.exr"
    subprocess.run([BIN, "render", str(small_scene), "--spp", "16", "--seed", "11", "-o",
                    str(ref_exr), "--quiet", "--no-png"], check=True, capture_output=True)
    res = subsurf.compare(small_scene, ["volpath", "dipole"], tmp_path / "cmp", spp=2,
                          reference=ref_exr, threads=1)
    assert [m["method"] for m in res["methods"]] == ["volpath", "dipole"]
    np.testing.assert_array_equal(res["reference_array"][:, :, :3], ref)
    for m in res["methods"]:
        assert m["array"].shape[:2] == (16, 24)
        assert m["rel_mse"] > 0
    with pytest.raises(subsurf.SubsurfError, match="unknown"):
        subsurf.compare(small_scene, ["nonesuch"], tmp_path / "cmp2", spp=1, reference=ref_exr)
