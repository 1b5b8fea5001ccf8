"""What a batch wrote, for the tests that compare two runs byte for byte or read its images."""

import json
import struct
import zlib

import numpy as np


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


def read_png(path):
    """The pixels of a PNG of 8 or 16 bits, greyscale or RGBA, as `encore batch` writes them:
    uint8 or uint16, (H, W) or (H, W, 4). Small images only: the filters are undone in Python."""
    data = path.read_bytes()
    position, compressed = 8, b""
    while position < len(data):
        length, kind = struct.unpack(">I4s", data[position:position + 8])
        body = data[position + 8:position + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour = struct.unpack(">IIBB", body[:10])
        elif kind == b"IDAT":
            compressed += body
        position += 12 + length
    assert depth in (8, 16) and colour in (0, 6), (depth, colour)
    channels = 4 if colour == 6 else 1
    step = channels * depth // 8  # Bytes per pixel, what the filters look back.
    stride = width * step
    raw = zlib.decompress(compressed)
    rows, previous = [], bytearray(stride)
    for y in range(height):
        kind = raw[y * (stride + 1)]
        row = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for x in range(stride):
            left = row[x - step] if x >= step else 0
            up = previous[x]
            corner = previous[x - step] if x >= step else 0
            if kind == 1:
                row[x] = (row[x] + left) & 0xFF
            elif kind == 2:
                row[x] = (row[x] + up) & 0xFF
            elif kind == 3:
                row[x] = (row[x] + ((left + up) >> 1)) & 0xFF
            elif kind == 4:
                estimate = left + up - corner
                nearest = min((abs(estimate - left), 0, left), (abs(estimate - up), 1, up),
                              (abs(estimate - corner), 2, corner))
                row[x] = (row[x] + nearest[2]) & 0xFF
        rows.append(bytes(row))
        previous = row
    pixels = np.frombuffer(b"".join(rows), np.uint8 if depth == 8 else ">u2")
    shape = (height, width, 4) if channels == 4 else (height, width)
    return pixels.reshape(shape).astype(np.uint8 if depth == 8 else np.uint16)
