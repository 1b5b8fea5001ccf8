"""A job to NumPy arrays (no files) through the Python module, in views per second: RGBA at 4
and 1 samples, then RGBA with albedo, normal, depth and segmentation (twice). Models are loaded
by a thread pool ahead of the renderer (Renderer.load releases the GIL), as a user of the
module would; views=12 at 512x512 per model.

    PYTHONPATH=build/python python3 bench/collections/numpy_views.py LIST [MODELS [THREADS]]

LIST: a file of model paths, one per line; MODELS (default 100) of them are rendered.
"""
import sys
import time
from concurrent.futures import ThreadPoolExecutor

import numpy

import encore

models = [line.strip() for line in open(sys.argv[1]) if line.strip()]
models = models[:int(sys.argv[2]) if len(sys.argv) > 2 else 100]
threads = int(sys.argv[3]) if len(sys.argv) > 3 else 8
SET = ("rgba", "albedo", "normal", "depth", "segmentation")
for samples, passes in ((4, None), (1, None), (1, SET), (1, SET)):
    renderer = encore.Renderer(samples=samples)
    start = time.monotonic()
    views = 0
    covered = 0
    with ThreadPoolExecutor(threads) as pool:
        for scene in pool.map(renderer.load, models):
            if passes is None:
                images, intrinsics, cameras = renderer.render_views(scene, views=12, size=512)
            else:
                arrays = renderer.render_views(scene, views=12, size=512, passes=passes)
                images = arrays["rgba"]
            covered += int(numpy.count_nonzero(images[..., 3]) > 0)
            views += images.shape[0]
    seconds = time.monotonic() - start
    print(f"{renderer.adapter} samples={samples} passes={passes}: {len(models)} models, {views} "
          f"views in {seconds:.2f} s = {views / seconds:.1f} views/s ({threads} loading "
          f"threads); models with covered pixels {covered}", flush=True)
