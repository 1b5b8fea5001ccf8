#!/usr/bin/env python3
"""Writes the hostile files of issue 51 into OUT/<kind>/ (the same kinds as
tests/cli/UntrustedCollectionTest.cpp): buffer uris out of the folder by absolute path and `..`,
an image outside, a PNG header declaring 60000x60000, a decompression bomb (IMAGES images of a
2048x2048 PNG), JSON 600 deep, a node cycle. hostile-collection.sh adds what cannot travel as
files (a FIFO, a link out, a truncated GLB). Usage: hostile_files.py OUT [IMAGES]"""

import json
import pathlib
import struct
import sys
import zlib


def png(width, height, rgba=(200, 100, 50, 255), declared=None):
    def chunk(kind, data):
        return (struct.pack(">I", len(data)) + kind + data +
                struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))
    w, h = declared or (width, height)
    header = struct.pack(">IIBBBBB", w, h, 8, 6, 0, 0, 0)
    rows = b"".join(b"\0" + bytes(rgba) * width for _ in range(height))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) +
            chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b""))


def triangle(buffer_uri, images=()):
    gltf = {
        "asset": {"version": "2.0"},
        "buffers": [{"uri": buffer_uri, "byteLength": 36}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "nodes": [{"mesh": 0}],
        "scenes": [{"nodes": [0]}],
    }
    if images:
        gltf["images"] = [{"uri": uri} for uri in images]
        gltf["textures"] = [{"source": 0}]
        gltf["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
        gltf["meshes"][0]["primitives"][0]["material"] = 0
    return json.dumps(gltf)


def main():
    out = pathlib.Path(sys.argv[1])
    bomb_images = int(sys.argv[2]) if len(sys.argv) > 2 else 160
    positions = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
    out.mkdir(parents=True, exist_ok=True)
    (out / "secret.bin").write_bytes(positions)
    (out / "secret.png").write_bytes(png(4, 4))

    def model(kind, text, files=()):
        folder = out / kind
        folder.mkdir(exist_ok=True)
        (folder / "model.gltf").write_text(text)
        (folder / "inside.bin").write_bytes(positions)
        for name, data in files:
            (folder / name).write_bytes(data)

    model("absolute", triangle("/etc/passwd"))
    model("dotdot", triangle("../secret.bin"))
    model("link", triangle("link.bin"))  # The link is made where the files land.
    model("fifo", triangle("pipe.bin"))  # So is the FIFO.
    model("image-outside", triangle("inside.bin", ["../secret.png"]))
    model("huge-header", triangle("inside.bin", ["huge.png"]),
          [("huge.png", png(1, 1, declared=(60000, 60000)))])
    model("bomb", triangle("inside.bin", ["big.png"] * bomb_images),
          [("big.png", png(2048, 2048))])
    model("deep", '{"asset": {"version": "2.0"}, "extras": ' + "[" * 600 + "]" * 600 + "}")
    cycle = json.loads(triangle("inside.bin"))
    cycle["nodes"] = [{"children": [1]}, {"children": [0]}]
    model("cycle", json.dumps(cycle))


if __name__ == "__main__":
    main()
