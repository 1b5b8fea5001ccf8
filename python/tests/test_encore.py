"""Tests of the Python module `encore` on generated scenes (no shared models needed).

Run by CTest (python_module_tests, label gpu) with PYTHONPATH pointing at the built module and
ENCORE_BINARY at the encore executable, which generates the scenes.
"""

import hashlib
import io
import json
import math
import os
import signal
import struct
import subprocess
import threading
import time

import numpy as np
import pytest

import encore
from batch_output import files_under, read_png


def generate(path, objects=8, seed=1):
    path.parent.mkdir(parents=True, exist_ok=True)
    subprocess.run([os.environ["ENCORE_BINARY"], "gen", "--objects", str(objects), "--seed",
                    str(seed), "-o", str(path)], check=True, capture_output=True)
    return path


@pytest.fixture(scope="module")
def renderer():
    renderer = encore.Renderer()
    # Dawn's Null backend would render nothing: GPU tests need Vulkan (lavapipe).
    assert "Vulkan" in renderer.adapter
    return renderer


def test_render_views_returns_images_and_cameras(renderer, tmp_path):
    scene = renderer.load(str(generate(tmp_path / "scene.glb")))
    images, intrinsics, cameras = renderer.render_views(scene, views=4, size=(64, 48))
    assert images.shape == (4, 48, 64, 4)
    assert images.dtype == np.uint8
    assert (images[:, 0, 0, 3] == 0).all(), "the background is transparent"
    assert (images[..., 3] == 255).any(axis=(1, 2)).all(), "every view shows the model"

    fov = 2.0 * math.atan(16.0 / 35.0)
    assert intrinsics.shape == (3, 3)
    assert intrinsics[0, 0] == pytest.approx(32.0 / math.tan(fov / 2.0), rel=1e-5)
    assert intrinsics[0, 2] == 32.0 and intrinsics[1, 2] == 24.0

    assert cameras.shape == (4, 4, 4)
    for camera in cameras:
        eye = camera[:3, 3]
        assert np.linalg.norm(eye) == pytest.approx(1.5, rel=1e-5)
        assert math.degrees(math.asin(eye[1] / 1.5)) == pytest.approx(30.0, abs=1e-3)
        forward = -camera[:3, 2]  # OpenGL cameras look along -Z.
        assert np.dot(forward, -eye / 1.5) == pytest.approx(1.0, abs=1e-5)
    assert cameras[0][2, 3] > 0.0  # View 0 on +Z.

    again, _, _ = renderer.render_views(scene, views=4, size=(64, 48))
    assert np.array_equal(images, again)


def test_render_views_matches_the_batch_command(renderer, tmp_path):
    model = generate(tmp_path / "in" / "scene.glb", seed=4)
    summary = encore.batch(str(tmp_path / "in"), str(tmp_path / "out"), random_views=3, seed=9,
                           size=32)
    assert summary["rendered"] == 1 and summary["failed"] == 0
    transforms = json.loads((tmp_path / "out" / "scene" / "transforms.json").read_text())
    # The batch draws each model's views from the seed and the model's name.
    _, _, cameras = renderer.render_views(renderer.load(str(model)), views=3, size=32,
                                          random=True, seed=9, name="scene")
    expected = np.array([frame["transform_matrix"] for frame in transforms["frames"]])
    assert np.allclose(cameras, expected, atol=1e-6)


def test_render_views_returns_the_batch_commands_normals_and_depth(renderer, tmp_path):
    model = generate(tmp_path / "in" / "scene.glb", seed=5)
    out = tmp_path / "out"
    subprocess.run([os.environ["ENCORE_BINARY"], "batch", str(tmp_path / "in"), "-o", str(out),
                    "--views", "3", "--size", "32", "--normals", "--depth", "--quiet"],
                   check=True, capture_output=True)
    scene = renderer.load(str(model))
    images, _, _, normals, depth = renderer.render_views(scene, views=3, size=32, normals=True,
                                                         depth=True)
    assert normals.shape == (3, 32, 32, 4) and normals.dtype == np.uint8
    assert depth.shape == (3, 32, 32) and depth.dtype == np.float32

    folder = out / "scene"
    scale = json.loads((folder / "transforms.json").read_text())["depth_scale"]
    for view in range(3):
        assert np.array_equal(images[view], read_png(folder / f"{view:03}.png"))
        assert np.array_equal(normals[view], read_png(folder / f"{view:03}_normal.png"))
        steps = read_png(folder / f"{view:03}_depth.png")
        assert np.allclose(depth[view], steps * scale, rtol=1e-6, atol=0.0)

    # What they mean: the model lies within the orbit (1.5 units away, inside a unit box);
    # normals are unit vectors wherever a pixel is covered.
    covered = depth > 0.0
    assert covered.any()
    assert (depth[covered] > 1.5 - 0.9).all() and (depth[covered] < 1.5 + 0.9).all()
    assert ((images[..., 3] == 0) <= (depth == 0.0)).all(), "no depth where nothing is drawn"
    vectors = normals[..., :3][normals[..., 3] == 255] / 255.0 * 2.0 - 1.0
    lengths = np.linalg.norm(vectors, axis=1)
    assert np.median(np.abs(lengths - 1.0)) < 0.02

    # One or the other alone: one array appended.
    assert len(renderer.render_views(scene, views=3, size=32, depth=True)) == 4
    only_normals = renderer.render_views(scene, views=3, size=32, normals=True)
    assert np.array_equal(only_normals[3], normals)


def test_load_error_carries_the_loader_message(renderer, tmp_path):
    broken = tmp_path / "broken.gltf"
    broken.write_text('{"asset": ')
    with pytest.raises(encore.LoadError) as raised:
        renderer.load(str(broken))
    assert "broken.gltf" in str(raised.value)
    assert "JSON is invalid" in str(raised.value)
    assert isinstance(raised.value, encore.Error)
    assert isinstance(raised.value, RuntimeError)


def test_batch_lists_failures_and_skips_finished_models(tmp_path):
    generate(tmp_path / "in" / "a" / "model.glb", seed=1)
    generate(tmp_path / "in" / "b" / "model.glb", seed=2)
    (tmp_path / "in" / "broken.gltf").write_text("not json")
    out = tmp_path / "out"
    summary = encore.batch(str(tmp_path / "in"), str(out), views=3, size=32)
    assert (summary["rendered"], summary["failed"], summary["skipped"]) == (2, 1, 0)
    assert summary["views"] == 6
    assert set(summary["stages"]) == {"load", "upload", "render", "gpu", "readback", "encode",
                                      "load_cpu", "encode_cpu"}
    for name in ("a/model", "b/model"):
        assert sorted(p.name for p in (out / name).iterdir()) == [
            "000.png", "001.png", "002.png", "metadata.json", "transforms.json"]
    failures = [json.loads(line) for line in (out / "failures.jsonl").read_text().splitlines()]
    assert [(f["stage"], os.path.basename(f["file"])) for f in failures] == [
        ("load", "broken.gltf")]
    again = encore.batch(str(tmp_path / "in"), str(out), views=3, size=32)
    assert (again["rendered"], again["failed"], again["skipped"]) == (0, 1, 2)


def test_batch_reuses_its_renderer_across_calls_and_writes_the_commands_files(tmp_path):
    models = [(str(generate(tmp_path / "in" / f"m{seed}.glb", seed=seed)), f"m{seed}")
              for seed in (1, 2, 3, 4)]
    renderer = encore.Renderer()
    assert (renderer.batch_renderers_created, renderer.batch_environments_created) == (0, 0)
    out = tmp_path / "reused"
    # As encore.dask's tasks call it: a few models per call, one renderer for them all.
    for chunk in (models[:1], models[1:3], models[3:]):
        summary = renderer.batch(chunk, str(out), views=3, size=32, failure_log=False)
        assert summary["rendered"] == len(chunk) and summary["failed"] == 0
        assert renderer.batch_renderers_created == 1, "built once, by the first call"
        assert renderer.batch_environments_created == 1

    reference = tmp_path / "command"
    subprocess.run([os.environ["ENCORE_BINARY"], "batch", str(tmp_path / "in"), "-o",
                    str(reference), "--views", "3", "--size", "32", "--quiet"], check=True,
                   capture_output=True)
    assert files_under(out) == files_under(reference), "the same files, byte for byte"

    # Normal images need an HDR target: a new renderer, the same environment maps; and one
    # that still renders what the command renders.
    normals = tmp_path / "normals"
    renderer.batch(models[:2], str(normals), views=3, size=32, normals=True)
    assert (renderer.batch_renderers_created, renderer.batch_environments_created) == (2, 1)
    renderer.batch(models[2:], str(normals), views=3, size=32, normals=True)
    assert (renderer.batch_renderers_created, renderer.batch_environments_created) == (2, 1)
    reference = tmp_path / "command-normals"
    subprocess.run([os.environ["ENCORE_BINARY"], "batch", str(tmp_path / "in"), "-o",
                    str(reference), "--views", "3", "--size", "32", "--normals", "--quiet"],
                   check=True, capture_output=True)
    assert files_under(normals) == files_under(reference)


def test_batch_with_one_renderer_writes_what_the_overlapped_pipeline_writes(tmp_path):
    models = [(str(generate(tmp_path / "in" / f"m{seed}.glb", seed=seed)), f"m{seed}")
              for seed in (5, 6, 7)]
    renderer = encore.Renderer()
    sequential = tmp_path / "one"
    overlapped = tmp_path / "three"
    renderer.batch(models, str(sequential), views=3, size=32, renderers=1)
    renderer.batch(models, str(overlapped), views=3, size=32, renderers=3)
    assert renderer.batch_renderers_created == 2  # A new count builds anew.
    assert files_under(sequential) == files_under(overlapped)
    with pytest.raises(ValueError):
        renderer.batch(models, str(tmp_path / "none"), renderers=0)


def test_batch_renderers_take_the_range_of_the_command_line(tmp_path):
    """renderers= and `encore batch --renderers` accept the same counts, 1 to 8."""
    model = str(generate(tmp_path / "in" / "m.glb", seed=3))
    renderer = encore.Renderer()
    renderer.batch([(model, "m")], str(tmp_path / "eight"), views=1, size=16, renderers=8)

    def command_line(count):
        return subprocess.run([os.environ["ENCORE_BINARY"], "batch", model, "-o",
                               str(tmp_path / "cli"), "--views", "1", "--size", "16",
                               "--renderers", str(count), "--quiet"], capture_output=True)

    for count in (0, 9):
        with pytest.raises(ValueError):
            renderer.batch([(model, "m")], str(tmp_path / "refused"), views=1, size=16,
                           renderers=count)
        assert command_line(count).returncode != 0
    accepted = command_line(8)
    assert accepted.returncode == 0, accepted.stderr


def test_rendering_releases_the_gil(renderer, tmp_path):
    # Enough objects that the views' count, capped for memory (2,000 views of 256x256 RGBA are
    # 512 MB), still makes a call of 0.1 s on a fast runner (30 objects took 0.098 s there).
    scene = renderer.load(str(generate(tmp_path / "gil.glb", objects=1000)))
    renderer.render_views(scene, views=1, size=256)  # Prepared and warm.
    warm_start = time.monotonic()
    renderer.render_views(scene, views=24, size=256)
    warm = time.monotonic() - warm_start
    # One call long enough to see stalls whatever this machine's speed.
    views = min(2000, max(24, math.ceil(24 * 0.4 / max(warm, 1e-3))))
    entered = threading.Event()

    def render():
        entered.set()
        renderer.render_views(scene, views=views, size=256)

    worker = threading.Thread(target=render)
    worker.start()
    entered.wait()
    # With the GIL held for the whole call, this thread could not run again until it returned:
    # it would see the worker alive once at most. Released, it runs all along the render.
    seen_alive = 0
    while worker.is_alive():
        seen_alive += 1
        time.sleep(0.001)
    worker.join()
    assert seen_alive >= 5, seen_alive


def test_a_renderer_draws_with_the_strategy_it_is_given(tmp_path):
    scene_path = str(generate(tmp_path / "in" / "scene.glb", objects=20))
    for samples in (1, 4):
        default = encore.Renderer(samples=samples)
        assert default.strategy is None
        visibility = encore.Renderer(samples=samples, strategy="visibility")
        assert visibility.strategy == "visibility"
        # The reference chooses the same levels of detail as the visibility strategy's cull.
        culled = encore.Renderer(samples=samples, strategy="gpu-culling-bundles")
        expected, _, _ = culled.render_views(culled.load(scene_path), views=3, size=64)
        images, _, _ = visibility.render_views(visibility.load(scene_path), views=3, size=64)
        # The visibility buffer draws what the hardware draws (docs/visibility.md's tolerance),
        # at 4 samples with the edges the hardware's 4x multisampling gives.
        assert images[..., 3].mean() > 10
        differing = np.abs(images.astype(np.int16) - expected.astype(np.int16)).max(axis=-1) > 2
        assert differing.mean() < 0.02, samples
    summary = visibility.batch([(scene_path, "scene")], str(tmp_path / "out"), views=2, size=32)
    assert summary["rendered"] == 1 and summary["failed"] == 0
    assert len(list((tmp_path / "out" / "scene").glob("*.png"))) == 2
    assert encore.Renderer(strategy="naive+bundle").strategy == "naive+bundle"
    assert encore.Renderer(strategy="auto").strategy == "auto"  # The batch's choice per model.
    with pytest.raises(ValueError, match="'fastest' is not one of Encore's strategies"):
        encore.Renderer(strategy="fastest")


def test_the_device_is_chosen_by_index_or_environment(renderer, tmp_path, monkeypatch):
    adapters = encore.adapters()
    assert [adapter["index"] for adapter in adapters] == list(range(len(adapters)))
    assert all(adapter["backend"] == "Vulkan" for adapter in adapters)
    assert renderer.device == 0
    assert adapters[0]["name"] in renderer.adapter
    chosen = encore.Renderer(samples=1, device=0)
    assert chosen.device == 0
    with pytest.raises(encore.Error, match=f"this machine has {len(adapters)} adapter"):
        encore.Renderer(device=len(adapters))
    monkeypatch.setenv("ENCORE_DEVICE", str(len(adapters)))
    with pytest.raises(encore.Error, match=f"there is no device {len(adapters)}"):
        encore.Renderer()
    monkeypatch.setenv("ENCORE_DEVICE", "first")
    with pytest.raises(ValueError, match="not a device index"):
        encore.Renderer()
    assert encore.Renderer(device=0).device == 0  # The argument wins over the environment.


def test_bad_arguments_raise_value_errors(renderer, tmp_path):
    scene = renderer.load(str(generate(tmp_path / "args.glb", objects=2)))
    with pytest.raises(ValueError):
        renderer.render_views(scene, views=0)
    with pytest.raises(ValueError):
        renderer.render_views(scene, size=0)
    with pytest.raises(ValueError):
        encore.Renderer(samples=3)


def test_batch_fast_png_compression_writes_the_same_pixels(renderer, tmp_path):
    models = [(str(generate(tmp_path / "in" / "m.glb", seed=5)), "m")]
    renderer.batch(models, str(tmp_path / "small"), views=2, size=48)
    renderer.batch(models, str(tmp_path / "fast"), views=2, size=48, png_compression="fast")
    for view in ("000.png", "001.png"):
        small, fast = tmp_path / "small" / "m" / view, tmp_path / "fast" / "m" / view
        assert small.read_bytes() != fast.read_bytes()
        assert np.array_equal(read_png(small), read_png(fast))
    with pytest.raises(ValueError):
        renderer.batch(models, str(tmp_path / "bad"), png_compression="tiny")


def test_batch_lod_error_draws_coarser_levels_close_to_full_detail(renderer, tmp_path):
    fine = tmp_path / "in" / "fine.glb"
    fine.parent.mkdir(parents=True)
    subprocess.run([os.environ["ENCORE_BINARY"], "gen", "--objects", "60", "--meshes", "3",
                    "--tessellation", "48", "-o", str(fine)], check=True, capture_output=True)
    models = [(str(fine), "fine")]
    renderer.batch(models, str(tmp_path / "full"), views=2, size=128)
    renderer.batch(models, str(tmp_path / "lod"), views=2, size=128, lod_error=0.5)
    changed = False
    for view in ("000.png", "001.png"):
        full = read_png(tmp_path / "full" / "fine" / view).astype(np.int32)
        coarse = read_png(tmp_path / "lod" / "fine" / view).astype(np.int32)
        assert np.abs(full - coarse).mean() < 1.0
        changed = changed or not np.array_equal(full, coarse)
    assert changed, "no view changed: were coarser levels drawn at all?"
    with pytest.raises(ValueError):
        renderer.batch(models, str(tmp_path / "bad"), lod_error=-1.0)


def test_renderer_batch_without_a_log_returns_the_failures(renderer, tmp_path):
    generate(tmp_path / "in" / "good.glb", seed=3)
    (tmp_path / "in" / "broken.gltf").write_text("not json")
    models = encore.discover_inputs(str(tmp_path / "in"))
    assert [name for _, name in models] == ["broken", "good"]
    out = tmp_path / "out"
    summary = renderer.batch(models, str(out), views=2, size=32, failure_log=False)
    assert (summary["rendered"], summary["failed"]) == (1, 1)
    assert not (out / "failures.jsonl").exists()
    [failure] = summary["failures"]
    assert failure["file"] == str(tmp_path / "in" / "broken.gltf")
    assert failure["stage"] == "load" and "JSON is invalid" in failure["error"]
    assert (out / "good" / "transforms.json").is_file()


def test_discover_inputs_names_a_list_of_paths_from_their_common_folder(tmp_path):
    paths = [tmp_path / "set" / "b" / "model.glb", tmp_path / "set" / "a" / "model.glb"]
    assert encore.discover_inputs([str(path) for path in paths]) == [
        (str(paths[0]), "b/model"), (str(paths[1]), "a/model")]
    with pytest.raises(encore.Error):
        encore.discover_inputs(str(tmp_path / "nothing"))


def test_renderer_batch_takes_a_list_of_model_paths(renderer, tmp_path):
    paths = [tmp_path / "in" / "a" / "model.glb", tmp_path / "in" / "b" / "model.glb"]
    for seed, path in enumerate(paths, start=4):
        generate(path, seed=seed)
    out = tmp_path / "out"
    summary = renderer.batch([str(paths[0]), paths[1]], str(out), views=1, size=16,
                             failure_log=False)
    assert (summary["rendered"], summary["failed"]) == (2, 0)
    # Named as discover_inputs names the same list.
    assert [name for _, name in encore.discover_inputs(paths)] == ["a/model", "b/model"]
    assert (out / "a" / "model" / "000.png").is_file()
    assert (out / "b" / "model" / "000.png").is_file()
    with pytest.raises(TypeError, match="not both"):
        renderer.batch([str(paths[0]), (str(paths[1]), "b")], str(out / "mixed"))
    with pytest.raises(TypeError, match="not an item 7"):
        renderer.batch([7], str(out / "bad"))


def test_keyboard_interrupt_stops_the_batch_cleanly_and_a_rerun_resumes(tmp_path):
    for index in range(8):
        generate(tmp_path / "in" / f"m{index}.glb", objects=30, seed=index + 1)
    out = tmp_path / "out"
    # One renderer: few models in flight when the interrupt is seen.
    options = {"views": 12, "size": 256, "jobs": 1, "renderers": 1}

    # SIGINT arrives while the GIL is released: Python's handler runs when the batch looks. It is
    # sent once the first model is written, not after a fixed time, which a loaded machine (the
    # tests run two at a time) could let the whole batch outlast.
    def interrupt_after_the_first_model():
        deadline = time.monotonic() + 120
        while not list(out.glob("*/transforms.json")) and time.monotonic() < deadline:
            time.sleep(0.01)
        os.kill(os.getpid(), signal.SIGINT)

    interrupter = threading.Thread(target=interrupt_after_the_first_model)
    interrupter.start()
    with pytest.raises(KeyboardInterrupt):
        encore.batch(str(tmp_path / "in"), str(out), **options)
    interrupter.join()
    finished = [folder for folder in out.iterdir()
                if folder.is_dir() and (folder / "transforms.json").exists()]
    assert len(finished) < 8, "the batch stopped before the end"
    assert not list(out.rglob("*.part")), "the models in flight were finished, not cut"
    for folder in finished:
        assert len(list(folder.glob("*.png"))) == 12
    again = encore.batch(str(tmp_path / "in"), str(out), **options)
    assert (again["skipped"], again["rendered"]) == (len(finished), 8 - len(finished))


def write_hdr(path, sky, ground, width=16):
    """A flat Radiance .hdr panorama: `sky` radiance above the horizon, `ground` below."""
    height = width // 2

    def rgbe(colour):
        largest = max(colour)
        mantissa, exponent = math.frexp(largest)
        scale = mantissa * 256.0 / largest
        return bytes([int(c * scale) for c in colour] + [exponent + 128])

    pixels = b"".join((rgbe(sky) if y < height // 2 else rgbe(ground)) * width
                      for y in range(height))
    path.write_bytes(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n" +
                     f"-Y {height} +X {width}\n".encode() + pixels)


def test_batch_takes_the_commands_dataset_options_as_keywords(tmp_path):
    for seed in (1, 2):
        generate(tmp_path / "in" / f"m{seed}.glb", seed=seed, objects=4)
    skies = tmp_path / "skies"
    skies.mkdir()
    write_hdr(skies / "dawn.hdr", (2.0, 0.8, 0.4), (0.3, 0.3, 0.3))
    write_hdr(skies / "noon.hdr", (0.6, 0.8, 2.0), (0.4, 0.4, 0.4))
    encore.batch(str(tmp_path / "in"), str(tmp_path / "python"), views=3, size=32, samples=1,
                 seed=3, camera_distribution="upper-hemisphere", distance=(1.5, 2.2),
                 fov=(30, 60), camera_jitter=5, environment_dir=str(skies),
                 environment_rotation="random", environment_intensity=(0.5, 1.5),
                 layout="objaverse", blank_threshold=4)
    subprocess.run([os.environ["ENCORE_BINARY"], "batch", str(tmp_path / "in"), "-o",
                    str(tmp_path / "command"), "--views", "3", "--size", "32", "--samples", "1",
                    "--seed", "3", "--camera-distribution", "upper-hemisphere", "--distance",
                    "1.5:2.2", "--fov", "30:60", "--camera-jitter", "5", "--environment-dir",
                    str(skies), "--environment-rotation", "random", "--environment-intensity",
                    "0.5:1.5", "--layout", "objaverse", "--blank-threshold", "4", "--quiet"],
                   check=True, capture_output=True)
    produced = files_under(tmp_path / "python")
    assert produced == files_under(tmp_path / "command"), "the same files, byte for byte"
    assert len(produced) == 2 * (3 + 3 + 2)
    frame = json.loads((tmp_path / "python" / "m1" / "transforms.json").read_text())["frames"][0]
    assert frame["environment"] in ("dawn.hdr", "noon.hdr")
    assert 0.5 <= frame["intensity"] <= 1.5
    assert produced["m1/metadata.json"]["blankThreshold"] == 4


def test_objaverse_layout_npy_files_hold_the_blender_world_to_camera_matrix(renderer, tmp_path):
    model = generate(tmp_path / "in" / "m.glb", seed=4)
    out = tmp_path / "out"
    renderer.batch([(str(model), "m")], str(out), views=4, size=16, random_views=4, seed=2,
                   layout="objaverse")
    transforms = json.loads((out / "m" / "transforms.json").read_text())
    # Blender's glTF importer puts glTF's (x, y, z) at (x, -z, y).
    gltf_to_blender = np.array([[1, 0, 0], [0, 0, -1], [0, 1, 0]], dtype=np.float64)
    for view, frame in enumerate(transforms["frames"]):
        path = out / "m" / f"{view:03}.npy"
        with open(path, "rb") as file:
            assert np.lib.format.read_magic(file) == (1, 0)
        rt = np.load(path)
        assert rt.shape == (3, 4) and rt.dtype == np.float64
        if hasattr(np.lib.format, "GROWTH_AXIS_MAX_DIGITS"):  # numpy >= 1.23's header padding.
            saved = io.BytesIO()
            np.save(saved, rt)
            assert saved.getvalue() == path.read_bytes(), "numpy.save's bytes"
        camera_to_world = np.array(frame["transform_matrix"], dtype=np.float64)
        rotation = gltf_to_blender @ camera_to_world[:3, :3]
        location = gltf_to_blender @ camera_to_world[:3, 3]
        # As blender_script.py's get_3x4_RT_matrix_from_blender computes it.
        expected = np.hstack([rotation.T, (-rotation.T @ location)[:, None]])
        assert np.allclose(rt, expected, atol=1e-6)
        # The origin (the model's centre) lies in front of the camera, along its -z.
        assert rt[2, 3] < 0 and abs(rt[0, 3]) < 1e-5 and abs(rt[1, 3]) < 1e-5


def test_batch_writes_metadata_with_the_files_digest(renderer, tmp_path):
    model = generate(tmp_path / "in" / "m.glb", seed=6, objects=5)
    out = tmp_path / "out"
    renderer.batch([(str(model), "m")], str(out), views=2, size=32)
    metadata = json.loads((out / "m" / "metadata.json").read_text())
    assert metadata["sha256"] == hashlib.sha256(model.read_bytes()).hexdigest()
    assert metadata["fileBytes"] == model.stat().st_size
    assert metadata["instances"] == 5 and metadata["triangles"] > 5
    assert metadata["blankViews"] == [] and len(metadata["coveredPixels"]) == 2
    assert set(metadata["seconds"]) == {"load", "upload", "render", "encode"}


def test_bad_dataset_keywords_raise_value_errors(renderer, tmp_path):
    models = [(str(generate(tmp_path / "in" / "m.glb", seed=1, objects=2)), "m")]
    skies = tmp_path / "skies"
    skies.mkdir()
    write_hdr(skies / "sky.hdr", (1.0, 1.0, 1.0), (0.5, 0.5, 0.5))
    for keywords in ({"distance": (2.0, 1.0)}, {"distance": "far"}, {"fov": (0, 40)},
                     {"fov": (10, 20, 30)}, {"camera_distribution": "cube"},
                     {"camera_jitter": 200}, {"environment_rotation": "sideways"},
                     {"environment_rotation": (90, 10)}, {"environment_intensity": -1},
                     {"layout": "zip"}, {"environment_dir": str(tmp_path / "absent")},
                     {"environment_dir": str(tmp_path / "in")},
                     {"environment_dir": str(skies), "environment": str(skies / "sky.hdr")}):
        with pytest.raises(ValueError):
            renderer.batch(models, str(tmp_path / "out"), views=1, size=8, **keywords)
    assert not (tmp_path / "out" / "m").exists()
def write_variant_quad(path):
    """A quad facing +Z, red, whose KHR_materials_variants variant "green" (index 0) maps it to
    a green material; the one variant "blue paint" (index 1) maps it to blue."""
    positions = struct.pack("<12f", -1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0)
    normals = struct.pack("<12f", *([0, 0, 1] * 4))
    indices = struct.pack("<6H", 0, 1, 2, 0, 2, 3) + b"\0\0"
    data = positions + normals + indices
    uri = "data:application/octet-stream;base64," + __import__("base64").b64encode(data).decode()

    def material(r, g, b):
        return {"pbrMetallicRoughness": {"baseColorFactor": [r, g, b, 1], "metallicFactor": 0},
                "doubleSided": True}

    document = {
        "asset": {"version": "2.0"},
        "extensionsUsed": ["KHR_materials_variants"],
        "extensions": {"KHR_materials_variants": {
            "variants": [{"name": "green"}, {"name": "blue paint"}]}},
        "buffers": [{"uri": uri, "byteLength": len(data)}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                        {"buffer": 0, "byteOffset": 48, "byteLength": 48},
                        {"buffer": 0, "byteOffset": 96, "byteLength": 12}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
             "min": [-1, -1, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}],
        "materials": [material(1, 0, 0), material(0, 1, 0), material(0, 0, 1)],
        "meshes": [{"primitives": [{
            "attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "material": 0,
            "extensions": {"KHR_materials_variants": {"mappings": [
                {"material": 1, "variants": [0]}, {"material": 2, "variants": [1]}]}}}]}],
        "nodes": [{"mesh": 0}],
        "scenes": [{"nodes": [0]}],
        "scene": 0,
    }
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(document))
    return path


def mean_color(images):
    """The mean RGB of the opaque pixels."""
    opaque = images[..., 3] == 255
    return images[..., :3][opaque].astype(float).mean(axis=0)


def test_render_views_draws_a_material_variant(renderer, tmp_path):
    scene = renderer.load(str(write_variant_quad(tmp_path / "quad.gltf")))
    assert scene.variants == ["green", "blue paint"]
    default, _, _ = renderer.render_views(scene, views=2, size=32)
    green, _, _ = renderer.render_views(scene, views=2, size=32, variant="green")
    blue, _, _ = renderer.render_views(scene, views=2, size=32, variant=1)
    again, _, _ = renderer.render_views(scene, views=2, size=32)
    assert np.argmax(mean_color(default)) == 0
    assert np.argmax(mean_color(green)) == 1
    assert np.argmax(mean_color(blue)) == 2
    assert np.array_equal(default, again), "variant=None is the default materials again"
    with pytest.raises(ValueError, match=r"has no material variant 'red' \(its variants: "
                                         r"0 'green', 1 'blue paint'"):
        renderer.render_views(scene, views=1, size=16, variant="red")
    with pytest.raises(TypeError):
        renderer.render_views(scene, views=1, size=16, variant=1.5)


def test_batch_renders_every_variant_as_a_sample(renderer, tmp_path):
    write_variant_quad(tmp_path / "in" / "quad.gltf")
    out = tmp_path / "out"
    summary = renderer.batch(str(tmp_path / "in"), str(out), views=2, size=32, variants="all")
    assert (summary["rendered"], summary["failed"], summary["views"]) == (1, 0, 6)
    for sample in ("quad", "quad@green", "quad@blue_paint"):
        assert (out / sample / "transforms.json").exists(), sample
    one = renderer.batch(str(tmp_path / "in"), str(tmp_path / "one"), views=2, size=32,
                         variant="blue paint")
    assert one["rendered"] == 1
    assert [p.name for p in (tmp_path / "one").iterdir() if p.is_dir()] == ["quad@blue_paint"]
    # The same pixels as the sample of the batch with every variant.
    assert (tmp_path / "one" / "quad@blue_paint" / "000.png").read_bytes() == \
        (out / "quad@blue_paint" / "000.png").read_bytes()
    with pytest.raises(ValueError):
        renderer.batch(str(tmp_path / "in"), str(out), variants="some")
    with pytest.raises(ValueError):
        renderer.batch(str(tmp_path / "in"), str(out), variant="green", variants="all")
