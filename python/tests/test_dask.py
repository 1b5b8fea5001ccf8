"""Tests of encore.dask on encore.dask.gpu_cluster with two worker processes (lavapipe listed
twice: two devices on one adapter stand in for two GPUs), on generated scenes.

Run by CTest (python_dask_tests, label gpu) with PYTHONPATH pointing at the built package and
ENCORE_BINARY at the encore executable, which generates the scenes and runs the reference
single-process batch.
"""

import json
import os
import signal
import subprocess
import threading
import time

import pytest

distributed = pytest.importorskip("distributed")

import encore  # noqa: E402
import encore.dask  # noqa: E402
from batch_output import files_under  # noqa: E402

OPTIONS = {"views": 3, "size": 64}


def generate(path, seed, objects=6):
    path.parent.mkdir(parents=True, exist_ok=True)
    subprocess.run([os.environ["ENCORE_BINARY"], "gen", "--objects", str(objects), "--seed",
                    str(seed), "-o", str(path)], check=True, capture_output=True)


def read_failures(output):
    return [json.loads(line) for line in (output / "failures.jsonl").read_text().splitlines()]


@pytest.fixture(scope="module")
def client():
    # Worker processes inherit PYTHONPATH and import encore.dask when a task arrives. The
    # machine's one adapter twice: what gpu_cluster() makes of a two-GPU machine.
    cluster = encore.dask.gpu_cluster(devices=[0, 0])
    with distributed.Client(cluster) as client:
        yield client
    cluster.close()


@pytest.fixture(scope="module")
def collection(tmp_path_factory):
    """Six models in two folders (two called model.glb), a malformed file and a model whose
    buffer is missing."""
    root = tmp_path_factory.mktemp("collection")
    for index in range(3):
        generate(root / "a" / f"m{index}.glb", seed=index + 1)
    generate(root / "b" / "model.glb", seed=7)
    generate(root / "c" / "model.glb", seed=8)
    generate(root / "d.glb", seed=9)
    (root / "broken.gltf").write_text('{"asset": ')
    (root / "missing.gltf").write_text(json.dumps({
        "asset": {"version": "2.0"},
        "buffers": [{"uri": "missing.bin", "byteLength": 36}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}]}))
    return root


def test_output_equals_the_batch_command_and_reruns_skip(client, collection, tmp_path):
    reference = tmp_path / "reference"
    command = subprocess.run([os.environ["ENCORE_BINARY"], "batch", str(collection), "-o",
                              str(reference), "--views", "3", "--size", "64", "--quiet"],
                             capture_output=True, text=True)
    assert command.returncode == 1, command.stderr  # Two bad files.

    output = tmp_path / "dask"
    summary = encore.dask.render_collection(client, str(collection), str(output), chunk_size=2,
                                            **OPTIONS)
    assert (summary["total"], summary["rendered"], summary["failed"], summary["skipped"]) == (
        8, 6, 2, 0)
    assert summary["views"] == 18
    assert summary["tasks"] == 4
    assert set(summary["stages"]) == {"load", "upload", "render", "gpu", "readback", "encode",
                                      "load_cpu", "encode_cpu"}
    assert summary["stages"]["gpu"] > 0.0

    produced = files_under(output)
    assert "b/model/000.png" in produced and "c/model/transforms.json" in produced
    assert produced == files_under(reference), "the same files, byte for byte"
    transforms = json.loads(produced["a/m0/transforms.json"])
    assert [frame["file_path"] for frame in transforms["frames"]] == ["./000", "./001", "./002"]

    # Each bad file once, with the stage and the message of the command's log.
    expected = {entry["file"]: entry for entry in read_failures(reference)}
    failures = read_failures(output)
    assert sorted(entry["file"] for entry in failures) == sorted(expected)
    for entry in failures:
        assert entry == expected[entry["file"]]
        assert entry["stage"] == "load"
    assert [os.path.basename(entry["file"]) for entry in failures] == [
        "broken.gltf", "missing.gltf"], "in input order"

    again = encore.dask.render_collection(client, str(collection), str(output), chunk_size=2,
                                          **OPTIONS)
    assert (again["rendered"], again["failed"], again["skipped"]) == (0, 2, 6)
    assert files_under(output) == produced
    assert len(read_failures(output)) == 2


def test_each_worker_keeps_its_renderers(client, collection, tmp_path):
    summary = encore.dask.render_collection(client, [str(collection / "a" / "m0.glb"),
                                                     str(collection / "a" / "m1.glb"),
                                                     str(collection / "a" / "m2.glb"),
                                                     str(collection / "d.glb")],
                                            str(tmp_path / "out"), chunk_size=1, **OPTIONS)
    assert (summary["rendered"], summary["tasks"]) == (4, 4)
    # Named relative to the deepest folder holding every listed file.
    assert (tmp_path / "out" / "a" / "m2" / "transforms.json").is_file()
    assert (tmp_path / "out" / "d" / "transforms.json").is_file()
    assert sum(summary["workers"].values()) == 4
    # At most one renderer per task a worker runs at once (gpu_cluster's tasks_per_gpu, 2), kept
    # for the tasks after it.
    created = client.run(lambda: encore.dask._worker_renderers.created)
    assert all(count <= 2 for count in created.values()), created
    assert sum(created.values()) >= len(summary["workers"])
    # Every task so far had the same options: each renderer built its batch renderer (the
    # environment maps, the pipelines) once, in its first task, not once per task.
    built = client.run(lambda: [(renderer.batch_renderers_created,
                                 renderer.batch_environments_created)
                                for renderers in encore.dask._worker_renderers._idle.values()
                                for renderer in renderers])
    assert sum(len(counts) for counts in built.values()) == sum(created.values())
    assert all(counts == (1, 1) for every in built.values() for counts in every), built


def test_gpu_cluster_runs_tasks_per_gpu_at_once():
    with pytest.raises(ValueError, match="tasks_per_gpu"):
        encore.dask.gpu_cluster(devices=[0], tasks_per_gpu=0)
    cluster = encore.dask.gpu_cluster(devices=[0], tasks_per_gpu=3)
    try:
        assert [spec["options"]["nthreads"] for spec in cluster.worker_spec.values()] == [3]
    finally:
        cluster.close()


def test_killing_a_worker_mid_run_still_renders_every_model(client, tmp_path):
    models = tmp_path / "models"
    for index in range(12):
        generate(models / f"m{index:02}.glb", seed=20 + index, objects=12)
    output = tmp_path / "out"
    workers = client.run(os.getpid)
    result = {}
    run = threading.Thread(target=lambda: result.update(encore.dask.render_collection(
        client, str(models), str(output), chunk_size=2, views=6, size=128)))
    run.start()
    deadline = time.monotonic() + 60
    while not list(output.glob("*/transforms.json")) and time.monotonic() < deadline:
        time.sleep(0.01)
    victim = sorted(workers)[0]
    os.kill(workers[victim], signal.SIGKILL)
    finished_at_kill = len(list(output.glob("*/transforms.json")))
    run.join(timeout=120)
    assert not run.is_alive()
    # Killed once a model was written (or after a minute without one, on a slow machine).
    assert finished_at_kill < 12, "the worker died while models were left"
    assert result["total"] == 12 and result["failed"] == 0
    assert result["rendered"] + result["skipped"] == 12
    for index in range(12):
        folder = output / f"m{index:02}"
        assert sorted(path.name for path in folder.iterdir()) == [
            "000.png", "001.png", "002.png", "003.png", "004.png", "005.png",
            "metadata.json", "transforms.json"], "every model complete, no temporary file left"
    assert read_failures(output) == []
    # The nanny restarted the worker: the cluster has two again for the tests after this one.
    client.wait_for_workers(2, timeout=60)


def test_each_worker_renders_on_the_device_its_environment_names(client, collection, tmp_path):
    devices = client.run(lambda: os.environ.get("ENCORE_DEVICE"))
    assert sorted(devices.values()) == ["0", "0"], devices
    summary = encore.dask.render_collection(client, str(collection / "a"), str(tmp_path / "out"),
                                            chunk_size=1, **OPTIONS)
    assert summary["rendered"] == 3
    assert set(summary["devices"].values()) == {0}
    assert set(summary["devices"]) == set(summary["workers"])


def test_gpu_devices_reads_all_and_index_lists():
    adapters = encore.adapters()
    assert adapters and adapters[0]["index"] == 0
    assert encore.dask.gpu_devices("all") == [adapter["index"] for adapter in adapters
                                              if adapter["type"] == adapters[0]["type"]]
    assert encore.dask.gpu_devices([0, 0]) == [0, 0]
    with pytest.raises(ValueError, match="there is no device 99"):
        encore.dask.gpu_devices([99])
    with pytest.raises(ValueError):
        encore.dask.gpu_devices("some")


def test_bad_options_fail_on_the_client(client, collection, tmp_path):
    with pytest.raises(ValueError):
        encore.dask.render_collection(client, str(collection), str(tmp_path), chunk_size=0)
    with pytest.raises(TypeError):
        encore.dask.render_collection(client, str(collection), str(tmp_path), failure_log=True)
    with pytest.raises(ValueError):  # Its tasks would number their shards alike.
        encore.dask.render_collection(client, str(collection), str(tmp_path), shards=2)
    with pytest.raises(encore.Error):
        encore.dask.render_collection(client, str(tmp_path / "nothing"), str(tmp_path / "o"))
