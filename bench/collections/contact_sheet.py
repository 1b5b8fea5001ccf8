"""A contact sheet of the collection benchmark's ten models: Encore's views beside Blender's.

    /usr/bin/python3 bench/collections/contact_sheet.py --encore build/apps/encore/encore \\
        --models ../shared/models --work /tmp/sheet --out sheet.png [--views 0,3,6,9]

One row per model, in compare.py's order (Duck, BoxTextured, CesiumMilkTruck, BrainStem,
2CylinderEngine, ReciprocatingSaw, AlphaBlendModeTest, Fox, MetalRoughSpheresNoTextures,
Avocado), its name above it; on the left the views `encore batch` renders (12 views at 512x512,
4x multisampling), on the right the same views from Blender EEVEE (blender_views.py: 16 samples,
the dataset scripts' unit box, area light and 35 mm lens on the same camera circle), both
composited over the same neutral grey and scaled down to --tile pixels. The cameras are the same,
so each pair shows the same object from the same side; the shading differs (Encore's studio
environment against Blender's area light), which is what a reader compares.

Renders what is missing under --work and reuses what is there: `encore batch` skips finished
models, and Blender (about 4 s a view on two cores) renders only the views the sheet shows.
Needs numpy (Debian's python3-numpy), not PIL: PNG is decoded and encoded here with zlib.
"""

import argparse
import json
import os
import struct
import subprocess
import sys
import zlib

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from compare import MODELS, SIZE, VIEWS, model_files  # noqa: E402

BACKGROUND = np.array([118, 118, 118], dtype=np.float64)  # Behind each model: neutral grey.
SHEET = np.array([40, 40, 40], dtype=np.uint8)  # Between the tiles.
LABEL = np.array([235, 235, 235], dtype=np.uint8)
GAP = 4  # Pixels between tiles.
COLUMN_GAP = 16  # Between Encore's views and Blender's.
FONT_SCALE = 2

# ---------------------------------------------------------------------------------------------
# PNG, 8 bits per channel, not interlaced: what `encore batch` and Blender write.

_CHANNELS = {0: 1, 2: 3, 4: 2, 6: 4}  # Colour type: greyscale, RGB, grey + alpha, RGBA.


def _unfilter(raw, height, stride, channels):
    """Undoes the per-row filters of a decompressed PNG image (RFC 2083, section 6)."""
    rows = np.frombuffer(raw, dtype=np.uint8).reshape(height, stride + 1)
    out = np.zeros((height, stride), dtype=np.uint8)
    previous = np.zeros(stride, dtype=np.uint8)
    for y in range(height):
        kind, line = rows[y, 0], rows[y, 1:]
        if kind == 0:
            row = line.copy()
        elif kind == 2:
            row = line + previous
        elif kind == 1:
            # Each byte adds the reconstructed byte one pixel to its left: a running sum per
            # channel, modulo 256.
            row = np.cumsum(line.reshape(-1, channels).astype(np.uint32), axis=0)
            row = (row & 0xFF).astype(np.uint8).reshape(-1)
        else:
            # Average and Paeth depend on the reconstructed left byte: byte by byte, on plain
            # ints (numpy's per-element access would be several times slower).
            row = line.tolist()
            up = previous.tolist()
            if kind == 3:
                for x in range(stride):
                    left = row[x - channels] if x >= channels else 0
                    row[x] = (row[x] + ((left + up[x]) >> 1)) & 0xFF
            else:
                for x in range(stride):
                    if x < channels:
                        row[x] = (row[x] + up[x]) & 0xFF  # Left and upper left are 0.
                        continue
                    left, above, corner = row[x - channels], up[x], up[x - channels]
                    to_left = abs(above - corner)  # |estimate - left|, estimate = l + a - c.
                    to_above = abs(left - corner)
                    to_corner = abs(left + above - 2 * corner)
                    if to_left <= to_above and to_left <= to_corner:
                        predictor = left
                    elif to_above <= to_corner:
                        predictor = above
                    else:
                        predictor = corner
                    row[x] = (row[x] + predictor) & 0xFF
            row = np.array(row, dtype=np.uint8)
        out[y] = row
        previous = row
    return out


def read_png(path):
    """The image as float64 RGBA (height, width, 4), 0 to 255."""
    with open(path, "rb") as file:
        data = file.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError(f"{path} is not a PNG file")
    position, header, compressed = 8, None, []
    while position < len(data):
        length, kind = struct.unpack(">I4s", data[position:position + 8])
        body = data[position + 8:position + 8 + length]
        position += 12 + length
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            compressed.append(body)
        elif kind == b"IEND":
            break
    width, height, depth, colour, _, _, interlace = header
    if depth != 8 or interlace != 0 or colour not in _CHANNELS:
        raise ValueError(f"{path}: only 8-bit, non-interlaced PNG is read here "
                         f"(bit depth {depth}, colour type {colour}, interlace {interlace})")
    channels = _CHANNELS[colour]
    pixels = _unfilter(zlib.decompress(b"".join(compressed)), height, width * channels,
                       channels).reshape(height, width, channels).astype(np.float64)
    if channels in (1, 2):
        pixels = np.concatenate([pixels[..., :1].repeat(3, axis=2), pixels[..., 1:]], axis=2)
    if pixels.shape[2] == 3:
        pixels = np.concatenate([pixels, np.full((height, width, 1), 255.0)], axis=2)
    return pixels


def write_png(path, rgb):
    """Writes uint8 RGB (height, width, 3), each row with the filter that compresses it best
    by the usual heuristic (the least sum of absolute filtered values)."""
    height, width, _ = rgb.shape
    image = rgb.astype(np.int32).reshape(height, width * 3)
    up = np.vstack([np.zeros((1, width * 3), np.int32), image[:-1]])
    left = np.hstack([np.zeros((height, 3), np.int32), image[:, :-3]])
    upper_left = np.hstack([np.zeros((height, 3), np.int32), up[:, :-3]])
    estimate = left + up - upper_left
    to_left, to_up, to_corner = (np.abs(estimate - left), np.abs(estimate - up),
                                 np.abs(estimate - upper_left))
    paeth = np.where((to_left <= to_up) & (to_left <= to_corner), left,
                     np.where(to_up <= to_corner, up, upper_left))
    candidates = [image, image - left, image - up, image - ((left + up) >> 1), image - paeth]
    filtered = [(candidate & 0xFF).astype(np.uint8) for candidate in candidates]
    # Bytes as signed values: small residuals either side of zero cost the same.
    costs = np.stack([np.abs(f.astype(np.int8).astype(np.int32)).sum(axis=1) for f in filtered])
    choice = costs.argmin(axis=0)
    raw = bytearray()
    for y in range(height):
        raw.append(int(choice[y]))
        raw += filtered[choice[y]][y].tobytes()

    def chunk(kind, body):
        return (struct.pack(">I", len(body)) + kind + body +
                struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF))

    with open(path + ".part", "wb") as file:
        file.write(b"\x89PNG\r\n\x1a\n")
        file.write(chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)))
        file.write(chunk(b"IDAT", zlib.compress(bytes(raw), 9)))
        file.write(chunk(b"IEND", b""))
    os.replace(path + ".part", path)


# ---------------------------------------------------------------------------------------------
# Tiles and labels.

def tile(path, size):
    """The view composited over BACKGROUND (straight alpha, as both renderers write it) and
    box-filtered down to size x size."""
    rgba = read_png(path)
    alpha = rgba[..., 3:] / 255.0
    rgb = rgba[..., :3] * alpha + BACKGROUND * (1.0 - alpha)
    height, width, _ = rgb.shape
    if height % size or width % size:
        raise ValueError(f"{path} is {width}x{height}: not a multiple of the {size}-pixel tile")
    factor = height // size
    rgb = rgb.reshape(size, factor, size, factor, 3).mean(axis=(1, 3))
    return np.clip(np.rint(rgb), 0, 255).astype(np.uint8)


# 5x7 capitals and digits, enough for the models' names.
_GLYPHS = {
    "A": "01110100011000111111100011000110001", "B": "11110100011000111110100011000111110",
    "C": "01110100011000010000100001000101110", "D": "11110100011000110001100011000111110",
    "E": "11111100001000011110100001000011111", "F": "11111100001000011110100001000010000",
    "G": "01110100011000010111100011000101111", "H": "10001100011000111111100011000110001",
    "I": "01110001000010000100001000010001110", "J": "00111000100001000010000101001001100",
    "K": "10001100101010011000101001001010001", "L": "10000100001000010000100001000011111",
    "M": "10001110111010110101100011000110001", "N": "10001100011100110101100111000110001",
    "O": "01110100011000110001100011000101110", "P": "11110100011000111110100001000010000",
    "Q": "01110100011000110001101011001001101", "R": "11110100011000111110101001001010001",
    "S": "01111100001000001110000010000111110", "T": "11111001000010000100001000010000100",
    "U": "10001100011000110001100011000101110", "V": "10001100011000110001100010101000100",
    "W": "10001100011000110101101011010101010", "X": "10001100010101000100010101000110001",
    "Y": "10001100010101000100001000010000100", "Z": "11111000010001000100010001000011111",
    "0": "01110100011001110101110011000101110", "1": "00100011000010000100001000010001110",
    "2": "01110100010000100010001000100011111", "3": "11111000100010000010000011000101110",
    "4": "00010001100101010010111110001000010", "5": "11111100001111000001000011000101110",
    "6": "00110010001000011110100011000101110", "7": "11111000010001000100010000100001000",
    "8": "01110100011000101110100011000101110", "9": "01110100011000101111000010001001100",
    " ": "0" * 35, "-": "00000000000000011111000000000000000",
    ",": "00000000000000000000000000110001000",
}


def draw_text(sheet, text, x, y, colour=LABEL, scale=FONT_SCALE):
    for character in text.upper():
        glyph = _GLYPHS.get(character, _GLYPHS[" "])
        bits = np.array([bit == "1" for bit in glyph]).reshape(7, 5)
        bits = bits.repeat(scale, axis=0).repeat(scale, axis=1)
        region = sheet[y:y + bits.shape[0], x:x + bits.shape[1]]
        region[bits[:region.shape[0], :region.shape[1]]] = colour
        x += 6 * scale


# ---------------------------------------------------------------------------------------------
# Rendering what is missing.

def encore_folders(encore, files, work):
    """Runs `encore batch` on the models (it skips finished ones) and returns each model's
    output folder."""
    listing = os.path.join(work, "models.json")
    with open(listing, "w") as file:
        json.dump(files, file)
    out = os.path.join(work, "encore")
    subprocess.run([encore, "batch", listing, "-o", out, "--views", str(VIEWS), "--size",
                    str(SIZE), "--quiet"], check=True)
    # Named as `encore batch` names a list: relative to the deepest folder holding them all.
    root = os.path.commonpath([os.path.dirname(path) for path in files])
    return [os.path.join(out, os.path.splitext(os.path.relpath(path, root))[0])
            for path in files]


def blender_folders(files, views, work):
    """Renders the `views` of each model with Blender EEVEE where they are missing."""
    folders = []
    for name, path in zip(MODELS, files):
        folder = os.path.join(work, "blender", name)
        if not all(os.path.isfile(os.path.join(folder, f"{view:03}.png")) for view in views):
            print(f"Blender EEVEE: {name}, views {views}", flush=True)
            subprocess.run(["xvfb-run", "-a", "blender", "-b", "-P",
                            os.path.join(HERE, "blender_views.py"), "--", path, folder, "eevee",
                            str(VIEWS), str(SIZE), "16", ",".join(map(str, views))],
                           check=True, capture_output=True)
        folders.append(folder)
    return folders


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--encore", required=True, help="the encore executable")
    parser.add_argument("--models", required=True, help="the shared models folder")
    parser.add_argument("--work", required=True, help="renders are kept and reused here")
    parser.add_argument("--out", required=True, help="the sheet, a PNG file")
    parser.add_argument("--views", default="0,3,6,9", help="views of the 12 shown per model")
    parser.add_argument("--tile", type=int, default=128, help="pixels per view on the sheet")
    arguments = parser.parse_args()
    views = [int(view) for view in arguments.views.split(",")]
    # Absolute: a list file's relative paths are read from the list's folder.
    files = [os.path.abspath(path) for path in model_files(arguments.models)]
    os.makedirs(arguments.work, exist_ok=True)
    encore = encore_folders(os.path.abspath(arguments.encore), files, arguments.work)
    blender = blender_folders(files, views, arguments.work)

    size = arguments.tile
    label_height = 7 * FONT_SCALE + 2 * GAP
    half = len(views) * size + (len(views) - 1) * GAP
    width = GAP + half + COLUMN_GAP + half + GAP
    row_height = label_height + size
    height = label_height + len(MODELS) * row_height + GAP
    sheet = np.empty((height, width, 3), dtype=np.uint8)
    sheet[:] = SHEET
    views_text = " ".join(str(view) for view in views)
    draw_text(sheet, f"Encore, views {views_text}", GAP, GAP)
    draw_text(sheet, f"Blender EEVEE, views {views_text}", GAP + half + COLUMN_GAP, GAP)
    for row, name in enumerate(MODELS):
        top = label_height + row * row_height
        draw_text(sheet, name, GAP, top + GAP)
        for side, folder in enumerate((encore[row], blender[row])):
            left = GAP + side * (half + COLUMN_GAP)
            for column, view in enumerate(views):
                x = left + column * (size + GAP)
                sheet[top + label_height:top + label_height + size, x:x + size] = tile(
                    os.path.join(folder, f"{view:03}.png"), size)
    write_png(arguments.out, sheet)
    print(f"{arguments.out}: {width}x{height}, {os.path.getsize(arguments.out)} bytes")


if __name__ == "__main__":
    main()
