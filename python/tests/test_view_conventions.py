"""Tests of render_views' pass conventions (docs/batch.md#conventions): depth along rays and in
the model's units, normals in camera axes, object coordinates, the cameras' axes and the views
placed as `encore batch` places them, each equal to what the batch writes at the same options.

Run by CTest (python_passes_tests, label gpu) with PYTHONPATH pointing at the built module.
"""

import json
import math

import numpy as np
import pytest

import encore
from batch_output import read_png
from test_passes import GAP, LEFT, RIGHT, ROW, write_quads

# glTF's world into Blender's ((x, y, z) -> (x, -z, y)), and OpenGL's camera axes into OpenCV's.
GLTF_TO_BLENDER = np.array([[1, 0, 0, 0], [0, 0, -1, 0], [0, 1, 0, 0], [0, 0, 0, 1]], float)
FLIP_YZ = np.diag([1.0, -1.0, -1.0, 1.0])


@pytest.fixture(scope="module")
def renderer():
    renderer = encore.Renderer(samples=1)
    assert "Vulkan" in renderer.adapter
    return renderer


@pytest.fixture(scope="module")
def quads(renderer, tmp_path_factory):
    folder = tmp_path_factory.mktemp("in")
    write_quads(folder / "quads.gltf")
    return renderer.load(str(folder / "quads.gltf"))


def render(renderer, scene, **keywords):
    return renderer.render_views(scene, views=1, size=64, elevation=0.0, **keywords)


def ray_factor(intrinsics, x, y):
    """1 / cos of the angle between pixel (x, y)'s ray and the camera's axis."""
    dx = (x + 0.5 - intrinsics[0, 2]) / intrinsics[0, 0]
    dy = (y + 0.5 - intrinsics[1, 2]) / intrinsics[1, 1]
    return math.sqrt(1.0 + dx * dx + dy * dy)


@pytest.mark.parametrize("pass_frames", (False, True))
def test_ray_depth_is_z_depth_over_the_cosine(renderer, quads, pass_frames):
    z = render(renderer, quads, passes=("depth",), pass_frames=pass_frames)
    ray = render(renderer, quads, passes=("depth",), depth_kind="ray", pass_frames=pass_frames)
    for x, y in ((LEFT, ROW), (RIGHT, 24), (LEFT + 2, 40)):
        factor = ray_factor(z["intrinsics"], x, y)
        assert factor > 1.01, "an off-centre pixel"
        assert z["depth"][0, y, x] == pytest.approx(1.5, abs=1e-3), "the quads face the camera"
        assert ray["depth"][0, y, x] == pytest.approx(z["depth"][0, y, x] * factor, rel=1e-6)
    assert math.isinf(ray["depth"][0, ROW, GAP])
    # The quads' largest side is 2 model units, the unit box's 1: model depth is twice as long.
    model = render(renderer, quads, passes=("depth",), depth_unit="model",
                   pass_frames=pass_frames)
    assert model["depth"][0, ROW, LEFT] == pytest.approx(2.0 * z["depth"][0, ROW, LEFT],
                                                         rel=1e-6)


def covered_mean(normals):
    covered = normals[0][normals[0, ..., 3] == 1.0]
    assert len(covered) > 100
    return covered[:, :3].mean(axis=0)


def test_camera_space_normals_face_the_camera_in_each_convention(renderer, quads):
    for convention, facing in (("opengl", (0, 0, 1)), ("blender", (0, 0, 1)),
                               ("opencv", (0, 0, -1))):
        result = render(renderer, quads, passes=("normal",), normal_space="camera",
                        normal_format="exr", camera_convention=convention)
        normals = result["normal"]
        assert normals.dtype == np.float32 and normals.shape == (1, 64, 64, 4)
        assert list(normals[0, ROW, LEFT]) == pytest.approx([*facing, 1.0], abs=2e-3), convention
        assert list(normals[0, ROW, GAP]) == [0.0, 0.0, 0.0, 0.0]
    # From 40 degrees towards +X the quads' world normal +Z is turned in the camera's axes:
    # (-sin 40, 0, cos 40) (OpenGL's +X right, +Z toward the viewer).
    turned = dict(azimuths=[40.0], passes=("normal",), normal_format="exr")
    camera = covered_mean(render(renderer, quads, normal_space="camera", **turned)["normal"])
    angle = math.radians(40.0)
    assert list(camera) == pytest.approx([-math.sin(angle), 0.0, math.cos(angle)], abs=3e-3)
    world = covered_mean(render(renderer, quads, **turned)["normal"])
    assert list(world) == pytest.approx([0.0, 0.0, 1.0], abs=3e-3)
    # A flat quad's triangles are its vertex normals' plane.
    geometric = render(renderer, quads, normal_kind="geometric", **turned)["normal"]
    assert list(covered_mean(geometric)) == pytest.approx(list(world), abs=3e-3)


def test_coordinates_lie_in_the_unit_box(renderer, quads):
    result = render(renderer, quads, passes=("rgba", "coordinates"))
    coordinates = result["coordinates"]
    assert coordinates.dtype == np.float32 and coordinates.shape == (1, 64, 64, 4)
    covered = coordinates[0, ..., 3] == 1.0
    assert covered.sum() > 100
    inside = coordinates[0][covered]
    assert (inside[:, :3] >= 0.0).all() and (inside[:, :3] <= 1.0).all()
    # The quads span x from 0 to 1 of the box (the largest side), y 0.25 to 0.75, at z = 0.5.
    assert inside[:, 2] == pytest.approx(0.5, abs=1e-3)
    assert 0.0 <= coordinates[0, ROW, LEFT, 0] <= 0.4 <= 0.6 <= coordinates[0, ROW, RIGHT, 0]
    assert ((inside[:, 1] > 0.24) & (inside[:, 1] < 0.76)).all()
    assert list(coordinates[0, ROW, GAP]) == [0.0, 0.0, 0.0, 0.0]
    assert np.array_equal(coordinates[0, ..., 3] > 0, result["rgba"][0, ..., 3] > 0)


def test_arrays_equal_the_batch_files_at_the_same_options(renderer, quads, tmp_path):
    """One batch with every convention changed, and render_views with the same keywords: the
    files' pixels are the arrays, quantised as the batch stores them."""
    options = dict(size=48, azimuths=[0.0, 40.0], elevations=[0.0, 15.0], distances=[1.5, 1.8],
                   camera_convention="opencv", normal_space="camera", normal_format="png16",
                   depth_kind="ray")
    folder = tmp_path / "in"
    folder.mkdir()
    write_quads(folder / "quads.gltf")
    summary = renderer.batch(str(folder), str(tmp_path / "out"), normals=True, depth=True,
                             coordinates=True, **options)
    assert summary["rendered"] == 1 and summary["failed"] == 0
    model = tmp_path / "out" / "quads"
    transforms = json.loads((model / "transforms.json").read_text())

    result = renderer.render_views(quads, passes=("normal", "depth", "coordinates"), **options)
    assert len(result["cameras"]) == 2, "the lists' length is the number of views"
    expected = np.array([frame["transform_matrix"] for frame in transforms["frames"]])
    assert np.allclose(result["cameras"], expected, atol=1e-6)
    assert result["normal"].dtype == np.uint16
    scale = transforms["depth_scale"]
    for view in range(2):
        assert np.array_equal(result["normal"][view], read_png(model / f"{view:03}_normal.png"))
        depth = result["depth"][view].astype(np.float64)  # As the batch divides, in doubles.
        steps = np.where(np.isinf(depth), 0, np.clip(np.round(depth / scale), 1, 65535))
        assert np.array_equal(steps, read_png(model / f"{view:03}_depth.png"))
        coordinates = np.clip(result["coordinates"][view].astype(np.float64), 0.0, 1.0)
        coordinates = np.round(coordinates * 65535)
        assert np.array_equal(coordinates, read_png(model / f"{view:03}_coordinates.png"))


def test_camera_convention_turns_the_returned_cameras(renderer, quads):
    def cameras(**keywords):
        return renderer.render_views(quads, views=3, size=16, elevation=25.0, **keywords)[2]

    opengl = cameras()
    opencv = cameras(camera_convention="opencv")
    blender = cameras(camera_convention="blender")
    assert np.allclose(opencv, opengl @ FLIP_YZ, atol=1e-6)
    assert np.allclose(blender, GLTF_TO_BLENDER @ opengl, atol=1e-6)
    # An OpenCV camera looks along its +Z: from the camera towards the origin.
    for camera in opencv:
        assert np.dot(camera[:3, 2], -camera[:3, 3]) > 0.0


def test_orthographic_views_have_parallel_rays(renderer, quads):
    keywords = dict(passes=("depth",), projection="orthographic", ortho_scale=2.0)
    z = render(renderer, quads, **keywords)
    ray = render(renderer, quads, depth_kind="ray", **keywords)
    assert np.array_equal(z["depth"], ray["depth"])
    # 2 units across 64 pixels: 32 pixels per unit, the left quad (x from -0.5 to -0.1 in the
    # unit box) from pixel 16 to 28.8.
    assert z["intrinsics"][0, 0] == pytest.approx(32.0)
    assert np.isfinite(z["depth"][0, ROW, 20]) and np.isinf(z["depth"][0, ROW, 30])


def test_poses_render_the_cameras_of_a_file(renderer, quads, tmp_path):
    """Cameras written in a convention and read back in it draw the same pictures."""
    placed = dict(size=32, azimuths=[0.0, 90.0, 200.0], elevations=[10.0, -20.0, 45.0])
    for convention in ("opengl", "opencv", "blender"):
        images, intrinsics, cameras = renderer.render_views(quads, camera_convention=convention,
                                                            **placed)
        poses = tmp_path / f"{convention}.json"
        poses.write_text(json.dumps(cameras.tolist()))
        again, again_intrinsics, again_cameras = renderer.render_views(
            quads, size=32, poses=poses, camera_convention=convention)
        assert np.allclose(again_cameras, cameras, atol=1e-6), convention
        assert np.array_equal(again_intrinsics, intrinsics)
        assert np.array_equal(again, images), convention
    with pytest.raises(ValueError, match="poses= gives the cameras"):
        renderer.render_views(quads, size=32, poses=poses, azimuths=[0.0])
    with pytest.raises(ValueError, match="missing.json"):
        renderer.render_views(quads, size=32, poses=tmp_path / "missing.json")


def read_ply(path):
    """points.ply's vertices: positions and normals (P, 3) and colours (P, 4)."""
    data = path.read_bytes()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    vertex = np.dtype([("position", "<f4", 3), ("normal", "<f4", 3), ("color", "u1", 4)])
    vertices = np.frombuffer(data[end:], vertex)
    return vertices["position"], vertices["normal"], vertices["color"]


def test_point_cloud_is_the_batch_points_file(renderer, quads, tmp_path):
    folder = tmp_path / "in"
    folder.mkdir()
    write_quads(folder / "quads.gltf")
    summary = renderer.batch(str(folder), str(tmp_path / "out"), views=1, size=16, seed=3,
                             point_cloud=200)
    assert summary["rendered"] == 1 and summary["failed"] == 0
    positions, normals, colors = read_ply(tmp_path / "out" / "quads" / "points.ply")
    # The batch draws the points from the seed and the model's output name.
    cloud = renderer.render_views(quads, views=1, size=16, seed=3, name="quads",
                                  passes=("rgba",), point_cloud=200)["point_cloud"]
    assert cloud["positions"].shape == (200, 3) and cloud["colors"].dtype == np.uint8
    assert np.array_equal(cloud["positions"], positions)
    assert np.array_equal(cloud["normals"], normals)
    assert np.array_equal(cloud["colors"], colors)
    # On the quads: z = 0 in the unit box, facing +Z.
    assert np.abs(positions[:, 2]).max() < 1e-6 and (normals[:, 2] > 0.999).all()
    with pytest.raises(ValueError, match="point_cloud"):
        renderer.render_views(quads, views=1, size=16, point_cloud=10)


def test_camera_distribution_places_the_batch_views(renderer, quads):
    def cameras(**keywords):
        return renderer.render_views(quads, views=3, size=16, **keywords)[2]

    fibonacci = cameras(camera_distribution="fibonacci")
    orbit = cameras(camera_distribution="orbit")
    assert not np.allclose(fibonacci, orbit)
    assert np.allclose(orbit, cameras())
    # The golden-angle spiral's heights: 1 - (2 i + 1) / views.
    heights = fibonacci[:, 1, 3] / np.linalg.norm(fibonacci[:, :3, 3], axis=1)
    assert list(heights) == pytest.approx([2 / 3, 0.0, -2 / 3], abs=1e-5)


def test_bad_conventions_raise_value_errors(renderer, quads):
    for keyword, value, known in (("depth_kind", "far", "z or ray"),
                                  ("depth_unit", "mm", "normalized or model"),
                                  ("normal_space", "tangent", "world or camera"),
                                  ("normal_kind", "bent", "shading or geometric"),
                                  ("normal_format", "tiff", "png8, png16 or exr"),
                                  ("camera_convention", "vulkan", "opengl, opencv or blender"),
                                  ("projection", "fisheye", "perspective or orthographic"),
                                  ("camera_distribution", "grid", "orbit, sphere")):
        with pytest.raises(ValueError, match=f"{keyword} takes {known}"):
            render(renderer, quads, passes=("depth", "normal"), **{keyword: value})
    with pytest.raises(ValueError, match="apply to passes="):
        render(renderer, quads, depth=True, depth_kind="ray")
    with pytest.raises(ValueError, match="not both"):
        render(renderer, quads, random=True, camera_distribution="sphere")
    with pytest.raises(ValueError, match="azimuths"):
        render(renderer, quads, azimuths="0,90")
    with pytest.raises(ValueError, match="azimuths"):
        render(renderer, quads, azimuths=[0.0, 400.0])
    with pytest.raises(ValueError, match="differ in length"):
        render(renderer, quads, azimuths=[0.0, 90.0], elevations=[0.0, 10.0, 20.0])
    with pytest.raises(ValueError, match="Unknown pass 'position'"):
        render(renderer, quads, passes=("position",))
