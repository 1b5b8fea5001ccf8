"""Tests of Renderer.render_views(..., passes=...): every pass of `encore batch` as NumPy arrays,
on two quads side by side whose values are known (docs/batch.md#passes).

Run by CTest (python_passes_tests, label gpu) with PYTHONPATH pointing at the built module.
"""

import base64
import json
import math
import struct

import numpy as np
import pytest

import encore

ALL = ("rgba", "albedo", "normal", "material", "segmentation", "depth", "hdr")
# 64 x 64, one view on +Z at elevation 0: a pixel on each quad and one in the gap.
LEFT, RIGHT, GAP, ROW = 18, 46, 32, 32


def write_flat_pieces(path, pieces, materials, nodes):
    """A glTF of flat polygons facing +Z at z = 0: `pieces` are (corners (x, y), triangles,
    mesh name or None), mesh i drawn with material i; `materials` and `nodes` as glTF writes
    them, every node in the scene."""
    data = b""
    views, accessors, meshes = [], [], []
    for index, (corners, triangles, name) in enumerate(pieces):
        positions = b"".join(struct.pack("<3f", x, y, 0) for x, y in corners)
        normals = struct.pack("<3f", 0, 0, 1) * len(corners)
        indices = struct.pack(f"<{len(triangles)}H", *triangles)
        for chunk in (positions, normals, indices):
            views.append({"buffer": 0, "byteOffset": len(data), "byteLength": len(chunk)})
            data += chunk + b"\0" * (-len(chunk) % 4)
        first = len(accessors)
        accessors += [
            {"bufferView": first, "componentType": 5126, "count": len(corners), "type": "VEC3",
             "min": [min(x for x, _ in corners), min(y for _, y in corners), 0],
             "max": [max(x for x, _ in corners), max(y for _, y in corners), 0]},
            {"bufferView": first + 1, "componentType": 5126, "count": len(corners),
             "type": "VEC3"},
            {"bufferView": first + 2, "componentType": 5123, "count": len(triangles),
             "type": "SCALAR"}]
        mesh = {"primitives": [{
            "attributes": {"POSITION": first, "NORMAL": first + 1}, "indices": first + 2,
            "material": index}]}
        if name:
            mesh["name"] = name
        meshes.append(mesh)
    document = {
        "asset": {"version": "2.0"},
        "buffers": [{"uri": "data:application/octet-stream;base64," +
                     base64.b64encode(data).decode(), "byteLength": len(data)}],
        "bufferViews": views,
        "accessors": accessors,
        "materials": materials,
        "meshes": meshes,
        "nodes": nodes,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "scene": 0,
    }
    path.write_text(json.dumps(document))
    return path


def write_quads(path):
    """Two quads facing +Z at z = 0 (x from -1 to -0.2 and 0.2 to 1), nodes "left" and
    "right", each with its own mesh and material: red rough, white partly metallic."""
    quad = [0, 1, 2, 0, 2, 3]
    return write_flat_pieces(
        path,
        [([(x0, -0.5), (x1, -0.5), (x1, 0.5), (x0, 0.5)], quad, name)
         for x0, x1, name in ((-1.0, -0.2, "left mesh"), (0.2, 1.0, "right mesh"))],
        [{"name": "red", "pbrMetallicRoughness": {
            "baseColorFactor": [0.8, 0.2, 0.1, 1], "metallicFactor": 0,
            "roughnessFactor": 0.6}},
         {"name": "white", "pbrMetallicRoughness": {
             "baseColorFactor": [1, 1, 1, 1], "metallicFactor": 0.25,
             "roughnessFactor": 0.4}}],
        [{"name": "left", "mesh": 0}, {"name": "right", "mesh": 1}])


def srgb(linear):
    encoded = 12.92 * linear if linear <= 0.0031308 else 1.055 * linear ** (1 / 2.4) - 0.055
    return round(encoded * 255)


@pytest.fixture(scope="module")
def renderer():
    renderer = encore.Renderer(samples=1)
    assert "Vulkan" in renderer.adapter
    return renderer


@pytest.fixture
def quads(renderer, tmp_path):
    return renderer.load(str(write_quads(tmp_path / "quads.gltf")))


def render(renderer, scene, **keywords):
    return renderer.render_views(scene, views=1, size=64, elevation=0.0, **keywords)


def test_every_pass_comes_back_as_an_array_of_known_values(renderer, quads):
    result = render(renderer, quads, passes=ALL)
    assert set(result) == set(ALL) | {"intrinsics", "cameras"}
    rgba, albedo, material = result["rgba"], result["albedo"], result["material"]
    assert rgba.shape == albedo.shape == material.shape == result["normal"].shape == (1, 64, 64, 4)
    assert rgba.dtype == np.uint8
    for name in ("albedo", "material", "normal"):
        assert np.array_equal(result[name][..., 3], rgba[..., 3]), name + " has rgba's alpha"
    assert list(albedo[0, ROW, LEFT, :3]) == pytest.approx([srgb(0.8), srgb(0.2), srgb(0.1)],
                                                           abs=1)
    assert list(material[0, ROW, RIGHT, :3]) == pytest.approx([255, 0.4 * 255, 0.25 * 255],
                                                              abs=1)

    segmentation = result["segmentation"]
    assert segmentation.dtype == np.uint16 and segmentation.shape == (1, 64, 64)
    assert segmentation[0, ROW, LEFT] == 1 and segmentation[0, ROW, RIGHT] == 2
    assert segmentation[0, ROW, GAP] == 0
    assert set(np.unique(segmentation)) == {0, 1, 2}

    depth = result["depth"]
    assert depth.dtype == np.float32 and depth.shape == (1, 64, 64)
    assert depth[0, ROW, LEFT] == pytest.approx(1.5, abs=1e-4)
    assert math.isinf(depth[0, ROW, GAP])

    hdr = result["hdr"]
    assert hdr.shape == (1, 64, 64, 4) and hdr.dtype == np.float32
    assert hdr[0, ROW, LEFT, 3] == 1.0 and hdr[0, ROW, GAP, 3] == 0.0
    assert result["cameras"].shape == (1, 4, 4)


def test_passes_match_the_tuple_and_are_repeatable(renderer, quads):
    images, intrinsics, cameras = render(renderer, quads)
    result = render(renderer, quads, passes=("rgba", "depth"))
    assert np.array_equal(result["rgba"], images)
    assert np.array_equal(result["intrinsics"], intrinsics)
    again = render(renderer, quads, passes=("depth", "rgba"))
    assert np.array_equal(again["depth"], result["depth"])


def test_pass_targets_return_what_one_frame_per_pass_returns(renderer, quads):
    """The passes drawn in the colour's render pass (the default) against pass_frames=True, the
    earlier path of one frame per pass: the same arrays, element for element, with three views
    in one target."""
    keywords = dict(views=3, size=40, elevation=20.0, passes=ALL)
    targets = renderer.render_views(quads, **keywords)
    frames = renderer.render_views(quads, pass_frames=True, **keywords)
    for name in ALL:
        assert targets[name].dtype == frames[name].dtype, name
        assert np.array_equal(targets[name], frames[name]), name
    assert (targets["segmentation"] > 0).sum() > 100


def test_segmentation_counts_meshes_or_materials(renderer, quads):
    for by in ("mesh", "material"):
        ids = render(renderer, quads, passes=("segmentation",), segmentation_by=by)["segmentation"]
        assert ids[0, ROW, LEFT] == 1 and ids[0, ROW, RIGHT] == 2, by


def test_shading_keywords_change_the_rgba_but_not_the_albedo(renderer, quads):
    plain = render(renderer, quads, passes=("rgba", "albedo", "hdr"))
    bright = render(renderer, quads, passes=("rgba", "albedo", "hdr"), environment_intensity=6.0,
                    tone_mapping="none", exposure=1.0)
    assert np.array_equal(plain["albedo"], bright["albedo"])
    assert bright["rgba"][0, ROW, RIGHT, 1] == 255, "saturated without tone mapping"
    assert bright["hdr"][0, ROW, RIGHT, 1] > 1.0
    assert bright["hdr"][0, ROW, RIGHT, 1] == pytest.approx(
        6.0 * plain["hdr"][0, ROW, RIGHT, 1], rel=0.02)
    dark = render(renderer, quads, passes=("rgba", "hdr"), exposure=0.25)
    assert dark["rgba"][0, ROW, RIGHT, :3].sum() < plain["rgba"][0, ROW, RIGHT, :3].sum()
    assert np.array_equal(dark["hdr"], plain["hdr"]), "HDR is the radiance before exposure"
    grey = render(renderer, quads, passes=("rgba",), background="#808080", tone_mapping="none")
    assert list(grey["rgba"][0, ROW, GAP]) == [128, 128, 128, 255]


def test_bad_passes_raise_value_errors(renderer, quads, tmp_path):
    for passes, message in ((("rgba", "sky"), "Unknown pass 'sky'"),
                            (("depth", "depth"), "asked for twice"),
                            ((), "names no pass"),
                            ("rgba", "sequence of names")):
        with pytest.raises(ValueError, match=message):
            render(renderer, quads, passes=passes)
    with pytest.raises(ValueError, match="replaces normals"):
        render(renderer, quads, passes=("rgba",), normals=True)
    with pytest.raises(ValueError, match="segmentation_by"):
        render(renderer, quads, passes=("segmentation",), segmentation_by="scene")
    with pytest.raises(ValueError, match="tone_mapping"):
        render(renderer, quads, passes=("rgba",), tone_mapping="filmic")
    with pytest.raises(ValueError, match="background"):
        render(renderer, quads, passes=("rgba",), background="blue")


def write_cut_square(path):
    """A square facing +Z cut along a slanted line into a triangle (node 0: id 1) and the rest
    (node 3: id 4); nodes 1 and 2 draw nothing, so an average of the ids (2, 3) is no drawn id."""
    return write_flat_pieces(
        path,
        [([(-0.8, -0.8), (0.8, -0.8), (0.8, 0.3)], [0, 1, 2], None),
         ([(-0.8, -0.8), (0.8, 0.3), (0.8, 0.8), (-0.8, 0.8)], [0, 1, 2, 0, 2, 3], None)],
        [{"pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.1, 0.1, 1]}},
         {"pbrMetallicRoughness": {"baseColorFactor": [0.1, 0.2, 0.9, 1]}}],
        [{"mesh": 0}, {}, {}, {"mesh": 1}])


def test_segmentation_at_four_samples_holds_drawn_ids(tmp_path):
    """Issue 50: at samples=4 every id is one that was drawn (one sample's), the same as at
    samples=1 except along edges, in both drawings, while the colour is antialiased."""
    path = str(write_cut_square(tmp_path / "cut.gltf"))
    results = {}
    for samples in (1, 4):
        renderer = encore.Renderer(samples=samples)
        scene = renderer.load(path)
        for frames in (False, True):
            results[samples, frames] = render(renderer, scene, passes=("rgba", "segmentation"),
                                              pass_frames=frames)
    one = results[1, False]["segmentation"][0]
    four = results[4, False]["segmentation"][0]
    assert np.array_equal(results[1, True]["segmentation"][0], one)
    assert np.array_equal(results[4, True]["segmentation"][0], four), "pass_frames differs"
    assert set(np.unique(four)) == {0, 1, 4}
    # The ids at 1 sample within one pixel of each: where the two counts differ, an edge.
    padded = np.pad(one.astype(np.int32), 1, mode="edge")
    shifted = [padded[1 + dy:65 + dy, 1 + dx:65 + dx] for dy in (-1, 0, 1) for dx in (-1, 0, 1)]
    edge = np.any([s != one for s in shifted], axis=0)
    assert np.all(edge[four != one]), "ids differ away from edges"
    cut = np.any([s == 1 for s in shifted], axis=0) & np.any([s == 4 for s in shifted], axis=0)
    assert cut.sum() > 32, "the cut between ids 1 and 4 crosses the image"
    alpha = {samples: results[samples, False]["rgba"][0, ..., 3] for samples in (1, 4)}
    assert set(np.unique(alpha[1])) <= {0, 255}
    assert ((alpha[4] > 0) & (alpha[4] < 255)).sum() > 32, "the colour is antialiased"


def test_batch_takes_the_passes_as_keywords(tmp_path):
    (tmp_path / "in").mkdir()
    write_quads(tmp_path / "in" / "quads.gltf")
    summary = encore.batch(str(tmp_path / "in"), str(tmp_path / "out"), views=1, size=32,
                           samples=1, passes=("albedo", "segmentation", "depth"),
                           segmentation_by="material", depth_format="exr")
    assert summary["rendered"] == 1 and summary["failed"] == 0
    model = tmp_path / "out" / "quads"
    assert sorted(path.name for path in model.iterdir()) == [
        "000.png", "000_albedo.png", "000_depth.exr", "000_segmentation.png", "metadata.json",
        "transforms.json"]
    transforms = json.loads((model / "transforms.json").read_text())
    assert transforms["segmentation_by"] == "material"
    assert [entry["name"] for entry in transforms["segmentation_ids"]] == ["red", "white"]
    # Segmentation at 4 samples too (test_segmentation_at_four_samples_holds_drawn_ids).
    summary = encore.batch(str(tmp_path / "in"), str(tmp_path / "four"), views=1, size=32,
                           samples=4, passes=("segmentation",))
    assert summary["rendered"] == 1 and summary["failed"] == 0
    assert (tmp_path / "four" / "quads" / "000_segmentation.png").exists()
    with pytest.raises(ValueError, match="depth_format"):
        encore.batch(str(tmp_path / "in"), str(tmp_path / "bad"), views=1, size=8,
                     depth_format="tiff")


def test_batch_takes_the_pass_conventions_as_keywords(tmp_path):
    """docs/batch.md#conventions: the keywords come from the option table, as the flags do."""
    (tmp_path / "in").mkdir()
    write_quads(tmp_path / "in" / "quads.gltf")
    summary = encore.batch(str(tmp_path / "in"), str(tmp_path / "out"), views=1, size=32,
                           samples=1, elevation=0, passes=("depth", "normal"),
                           depth_format="exr", depth_kind="ray", depth_unit="model",
                           normal_space="camera", normal_kind="geometric", normal_format="exr",
                           camera_convention="opencv", coordinates=True,
                           coordinates_format="exr", point_cloud=50)
    assert summary["rendered"] == 1 and summary["failed"] == 0
    model = tmp_path / "out" / "quads"
    assert sorted(path.name for path in model.iterdir()) == [
        "000.png", "000_coordinates.exr", "000_depth.exr", "000_normal.exr", "metadata.json",
        "points.ply", "transforms.json"]
    assert b"element vertex 50\n" in (model / "points.ply").read_bytes()[:400]
    transforms = json.loads((model / "transforms.json").read_text())
    assert (transforms["depth_kind"], transforms["depth_unit"]) == ("ray", "model")
    assert (transforms["normal_space"], transforms["normal_kind"],
            transforms["normal_format"]) == ("camera", "geometric", "exr")
    metadata = json.loads((model / "metadata.json").read_text())
    assert metadata["passes"] == {
        "depth": {"kind": "ray", "unit": "model", "format": "exr"},
        "normal": {"space": "camera", "kind": "geometric", "format": "exr"},
        "coordinates": {"space": "normalized box in [0, 1]^3", "format": "exr"}}
    assert metadata["pointCloud"]["points"] == 50
    with pytest.raises(ValueError, match="normal_format"):
        encore.batch(str(tmp_path / "in"), str(tmp_path / "bad"), views=1, size=8,
                     normals=True, normal_format="tiff")
    with pytest.raises(ValueError, match="depth_kind"):
        encore.batch(str(tmp_path / "in"), str(tmp_path / "bad"), views=1, size=8,
                     depth=True, depth_kind="far")


@pytest.mark.parametrize("samples", (1, 4))
def test_batch_png_filtering_on_the_gpu_writes_the_same_files(tmp_path, samples):
    """At 4 samples the GPU's PNG rows read the ids that the sample-0 pass wrote."""
    (tmp_path / "in").mkdir()
    write_quads(tmp_path / "in" / "quads.gltf")
    keywords = dict(views=2, size=40, samples=samples,
                    passes=("albedo", "material", "segmentation", "depth"), normals=True)
    written = {}
    for where in ("cpu", "gpu"):
        summary = encore.batch(str(tmp_path / "in"), str(tmp_path / where), png_filtering=where,
                               **keywords)
        assert summary["rendered"] == 1 and summary["failed"] == 0
        model = tmp_path / where / "quads"
        written[where] = {path.name: path.read_bytes() for path in model.glob("*.png")}
    assert len(written["cpu"]) == 2 * 6
    assert written["gpu"] == written["cpu"]
    with pytest.raises(ValueError, match="png_filtering"):
        encore.batch(str(tmp_path / "in"), str(tmp_path / "bad"), views=1, size=8,
                     png_filtering="fpga")
