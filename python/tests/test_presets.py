"""Issue 50 from Python: preset=, the camera lists as sequences, orthographic views, camera
conventions and poses, through Renderer.batch's keywords (the table the command line uses).

Run with PYTHONPATH pointing at the built module and ENCORE_BINARY at the encore executable.
"""

import json
import os
import subprocess

import pytest

import encore
from test_encore import generate


@pytest.fixture(scope="module")
def renderer():
    renderer = encore.Renderer()
    assert "Vulkan" in renderer.adapter
    return renderer


def test_a_preset_with_an_override(renderer, tmp_path):
    generate(tmp_path / "in" / "m.glb", objects=3)
    summary = renderer.batch(str(tmp_path / "in"), str(tmp_path / "out"), preset="wonder3d",
                             size=32, samples=1, normals=False)
    assert summary["rendered"] == 1
    folder = tmp_path / "out" / "m"
    transforms = json.loads((folder / "transforms.json").read_text())
    assert len(transforms["frames"]) == 6
    assert transforms["projection"] == "orthographic"
    assert transforms["ortho_scale"] == pytest.approx(1.35)
    assert not (folder / "000_normal.png").exists()  # normals=False replaced the preset's.
    metadata = json.loads((folder / "metadata.json").read_text())
    assert metadata["camera"]["preset"] == "wonder3d"


def test_lists_conventions_and_poses(renderer, tmp_path):
    generate(tmp_path / "in" / "m.glb", objects=3)
    renderer.batch(str(tmp_path / "in"), str(tmp_path / "a"), azimuths=[0, 90.5, 180],
                   elevations=(10,), distances=[1.5, 2, 2.5], size=32, samples=1,
                   camera_convention="opencv")
    written = tmp_path / "a" / "m" / "transforms.json"
    transforms = json.loads(written.read_text())
    assert transforms["camera_convention"] == "opencv"
    assert len(transforms["frames"]) == 3
    # OpenCV: the camera's +Z (third column) looks at the origin from view 1 at azimuth 90.5.
    matrix = transforms["frames"][1]["transform_matrix"]
    assert matrix[0][2] < -0.9 and matrix[0][3] > 1.9
    renderer.batch(str(tmp_path / "in"), str(tmp_path / "b"), poses=str(written), size=32,
                   samples=1, camera_convention="opencv")
    for name in ("000.png", "001.png", "002.png", "transforms.json"):
        assert (tmp_path / "a" / "m" / name).read_bytes() == \
            (tmp_path / "b" / "m" / name).read_bytes(), name


def test_bad_presets_lists_and_poses_are_value_errors(renderer, tmp_path):
    with pytest.raises(ValueError, match="preset takes zero123, .* did you mean trellis"):
        renderer.batch(str(tmp_path / "in"), str(tmp_path / "out"), preset="trelis")
    with pytest.raises(TypeError, match="azimuths takes a sequence of numbers"):
        renderer.batch(str(tmp_path / "in"), str(tmp_path / "out"), azimuths=["north"])
    (tmp_path / "poses.json").write_text("{\"frames\": 3}")
    with pytest.raises(ValueError, match="poses '.*poses.json': a JSON object needs \"frames\""):
        renderer.batch(str(tmp_path / "in"), str(tmp_path / "out"),
                       poses=str(tmp_path / "poses.json"))


def test_the_command_line_lists_the_presets():
    listing = subprocess.run([os.environ["ENCORE_BINARY"], "batch", "--preset", "list"],
                             check=True, capture_output=True, text=True).stdout
    for name in ("zero123", "zero123plus", "instantmesh", "wonder3d", "gobjaverse", "trellis",
                 "mvdream", "objaverse-xl"):
        assert f"\n{name}: " in "\n" + listing, name
    assert "https://github.com/microsoft/TRELLIS" in listing
    bad = subprocess.run([os.environ["ENCORE_BINARY"], "batch", "in", "-o", "out", "--preset",
                          "nope"], capture_output=True, text=True)
    assert bad.returncode == 2
    assert "error: --preset takes zero123" in bad.stderr
