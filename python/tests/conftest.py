"""Fixtures of the Python module's tests: a small copy of the skin sphere."""
import json
import os

import pytest

SOURCE = os.environ.get("SUBSURF_SOURCE_DIR",
                        os.path.join(os.path.dirname(__file__), "..", ".."))


@pytest.fixture
def small_scene(tmp_path):
    """scenes/skin_sphere.json at 24 x 16 pixels with a coarser sphere."""
    with open(os.path.join(SOURCE, "scenes", "skin_sphere.json")) as f:
        scene = json.load(f)
    scene["camera"]["resolution"] = [24, 16]
    scene["shapes"][0]["subdivisions"] = 3
    path = tmp_path / "small.json"
    path.write_text(json.dumps(scene))
    return path
