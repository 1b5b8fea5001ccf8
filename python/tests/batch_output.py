"""What a batch wrote, for the tests that compare two runs byte for byte."""

import json


def files_under(folder):
    """Every file below `folder` except failures.jsonl, by relative path, with its bytes;
    metadata.json without its timings and GPU creation counts, which differ from run to run."""
    files = {}
    for path in sorted(folder.rglob("*")):
        if not path.is_file() or path.name == "failures.jsonl":
            continue
        if path.name == "metadata.json":
            metadata = json.loads(path.read_text())
            del metadata["seconds"]
            del metadata["gpu"]
            files[str(path.relative_to(folder))] = metadata
        else:
            files[str(path.relative_to(folder))] = path.read_bytes()
    return files
