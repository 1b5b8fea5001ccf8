"""encore.batch's keywords for files that would stop a batch and for WebDataset shards, as
`encore batch` takes them (--model-timeout, --max-texture-size, --shards, --shard-size)."""

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
