"""``python -m app pixel``: the verdict of a pixel through the command, on scenes answered by hand.

The scenes and their worked answers are in ``tests/verdict_scenes.py``.
"""

import json
import subprocess
import sys

import pytest
import verdict_scenes as vs
from checkout import ROOT

from core.files import scene_file


def _run(*args):
    return subprocess.run([sys.executable, "-m", "app", "pixel", *args], cwd=ROOT,
                          capture_output=True, text=True, timeout=300)


def _saved(tmp_path, scene):
    path = tmp_path / "scene.json"
    scene_file.save(scene, path)
    return str(path)


def _json(tmp_path, scene, pixel, mode):
    result = _run(_saved(tmp_path, scene), "--at", f"{pixel[0]},{pixel[1]}", "--mode", mode, "--json")
    assert result.returncode == 0, result.stderr
    return json.loads(result.stdout)


RASTER_CASES = {
    # scene: (verdict, object, sorted (object, fate, plane) of every fragment)
    "back_face_only": ("culled", None, [("ground", "culled", None)]),
    "two_quads": ("visible", "near", [("far", "failed z-test", None), ("near", "kept", None)]),
    "before_near_plane": ("clipped", None, [("pane", "clipped", "near")]),
    "beyond_far_plane": ("frustum-culled", None, [("distant", "frustum-culled", "far")]),
    "pane_over_box": ("blended", "pane", [("box", "culled", None), ("box", "kept", None),
                                          ("pane", "blended", None)]),
}


@pytest.mark.parametrize("name", RASTER_CASES)
def test_raster_verdict_and_every_fragments_fate(tmp_path, name):
    data = _json(tmp_path, getattr(vs, name)(), vs.PIXEL, "raster")
    verdict, obj, fragments = RASTER_CASES[name]
    assert (data["verdict"], data["object"]) == (verdict, obj)
    assert sorted((f["object"], f["fate"], f["plane"]) for f in data["fragments"]) == fragments
    assert all(f["polygon"].startswith("triangle ") for f in data["fragments"])
    assert data["sentence"]


def test_an_object_outside_the_frustum_is_said_to_be_culled_by_it(tmp_path):
    data = _json(tmp_path, vs.beyond_far_plane(), vs.PIXEL, "raster")  # worked in its docstring
    assert data["sentence"].startswith("Culled by the frustum at the far plane")
    assert "frustum culling dropped the whole object" in data["sentence"]
    assert "clipped" not in data["sentence"].lower()
    assert data["fragments"][0]["depth"] == pytest.approx(40.0)


def test_traced_shadow_names_the_blocker_and_the_lights(tmp_path):
    data = _json(tmp_path, vs.ball_shadow(), (20, 15), "raycast")
    assert (data["verdict"], data["object"]) == ("hit", "floor")
    assert data["lights"] == [
        {"name": "sun", "lit": False, "blocked_by": "ball", "status": "blocked: in shadow"},
        {"name": "fill", "lit": True, "blocked_by": None, "status": "reached the light"}]
    assert data["rays"] == {"primary": 1, "shadow": 2, "reflection": 0, "refraction": 0}


def test_traced_mirror_and_glass(tmp_path):
    mirror = _json(tmp_path, vs.mirror_ball(), (20, 15), "raytrace")
    assert (mirror["verdict"], mirror["object"]) == ("hit", "mirror")
    assert "reflected ray, which hits wall" in mirror["sentence"]
    glass = _json(tmp_path, vs.glass_ball(), (20, 15), "raytrace")
    assert (glass["verdict"], glass["object"]) == ("hit", "glass")
    assert "R = 0.04" in glass["sentence"] and "T = 0.96" in glass["sentence"]
    assert glass["rays"]["refraction"] >= 1


def test_total_internal_reflection_inside_a_glass_block(tmp_path):
    data = _json(tmp_path, vs.glass_block(), (20, 15), "raytrace")  # worked in its docstring
    assert (data["verdict"], data["object"]) == ("hit", "glass")
    assert "total internal reflection inside glass" in data["sentence"]
    assert "critical angle 41.8°" in data["sentence"]
    first = data["total_internal_reflection"][0]
    assert first["object"] == "glass" and first["critical_deg"] == pytest.approx(41.8103149, abs=1e-6)
    assert first["point"] == pytest.approx([1, 1 - 2 ** -0.5, 0], abs=1e-9)
    assert len(data["total_internal_reflection"]) == 2


def test_without_json_the_sentence_comes_first_then_the_fragments(tmp_path):
    result = _run(_saved(tmp_path, vs.two_quads()), "--at", "22,14", "--mode", "raster")
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert lines[0].startswith("Triangle 0 of near is kept by the z-buffer")
    assert any("far" in line and "failed z-test" in line for line in lines[1:])


@pytest.mark.parametrize("at, says", [("40,0", "outside the 40 x 30 image"), ("1;2", "two whole numbers"),
                                      ("-1,3", "outside"), ("1.5,2", "two whole numbers")])
def test_a_bad_pixel_is_refused_in_one_line(tmp_path, at, says):
    result = _run(_saved(tmp_path, vs.two_quads()), "--at", at)
    assert result.returncode == 2
    assert "--at" in result.stderr and says in result.stderr
    assert "Traceback" not in result.stderr and len(result.stderr.strip().splitlines()) == 1


def test_a_broken_scene_file_is_refused_in_one_line(tmp_path):
    path = tmp_path / "broken.json"
    path.write_text('{"objects": [')
    result = _run(str(path), "--at", "1,1", "--mode", "raster", "--json")
    assert result.returncode == 2 and result.stdout == ""
    assert "broken.json" in result.stderr and "Traceback" not in result.stderr
    assert len(result.stderr.strip().splitlines()) == 1
