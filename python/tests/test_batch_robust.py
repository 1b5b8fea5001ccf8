"""encore.batch's keywords for files that would stop a batch and for WebDataset shards, as
`encore batch` takes them (--model-timeout, --max-texture-size, --shards, --shard-size)."""

import json
import os
import subprocess
import tarfile

import pytest

import encore


def generate(path, objects=4, seed=1):
    path.parent.mkdir(parents=True, exist_ok=True)
    subprocess.run([os.environ["ENCORE_BINARY"], "gen", "--objects", str(objects), "--seed",
                    str(seed), "-o", str(path)], check=True, capture_output=True)
    return path


def test_batch_writes_webdataset_shards(tmp_path):
    for seed in (1, 2, 3):
        generate(tmp_path / "in" / f"m{seed}.glb", seed=seed)
    summary = encore.batch(str(tmp_path / "in"), str(tmp_path / "out"), views=2, size=32,
                           samples=1, shards=2, model_timeout=600, max_texture_size=1024)
    assert summary["rendered"] == 3
    shards = sorted(path.name for path in (tmp_path / "out").glob("*.tar"))
    assert shards == ["shard-000000.tar", "shard-000001.tar"]
    names = []
    for shard in shards:
        with tarfile.open(tmp_path / "out" / shard) as tar:
            names += tar.getnames()
    assert sorted(names) == sorted(f"m{seed}.{file}" for seed in (1, 2, 3)
                                   for file in ("000.png", "001.png", "metadata.json",
                                                "transforms.json"))


def test_bad_limits_raise_value_errors(tmp_path):
    generate(tmp_path / "in" / "m.glb")
    with pytest.raises(ValueError):
        encore.batch(str(tmp_path / "in"), str(tmp_path / "out"), views=1, size=16,
                     model_timeout=-1)


def write_triangle(folder, buffer_uri):
    """A one-triangle .gltf in `folder` reading its positions from `buffer_uri`, and the 36 bytes
    it needs written as folder/../shared.bin (outside its folder)."""
    folder.mkdir(parents=True, exist_ok=True)
    (folder.parent / "shared.bin").write_bytes(bytes(36))
    gltf = {
        "asset": {"version": "2.0"},
        "buffers": [{"uri": buffer_uri, "byteLength": 36}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [0, 0, 0]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "nodes": [{"mesh": 0}],
        "scenes": [{"nodes": [0]}],
    }
    path = folder / "model.gltf"
    path.write_text(json.dumps(gltf))
    return path


def test_models_read_only_their_own_folder_unless_allowed(tmp_path):
    model = write_triangle(tmp_path / "model", "../shared.bin")
    renderer = encore.Renderer(samples=1)
    with pytest.raises(encore.LoadError, match="is outside the model's folder"):
        renderer.load(str(model))
    assert renderer.load(str(model), allow_uris_outside=True) is not None
    summary = encore.batch(str(model), str(tmp_path / "confined"), views=1, size=16)
    assert summary["failed"] == 1
    assert "is outside the model's folder" in summary["failures"][0]["error"]
    summary = encore.batch(str(model), str(tmp_path / "allowed"), views=1, size=16,
                           allow_uris_outside=True)
    assert summary["rendered"] == 1
