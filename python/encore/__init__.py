"""Encore: glTF 2.0 rendering with WebGPU (Dawn), for datasets of rendered views.

    renderer = encore.Renderer()              # one GPU device (device=N: encore.adapters()[N])
    scene = renderer.load("model.glb")        # encore.LoadError with the loader's message
    images, intrinsics, cameras = renderer.render_views(scene, views=12, size=512)
    encore.batch("models/", "out/", views=12)  # the job of `encore batch`, returns its summary

encore.dask spreads a collection over a Dask cluster (it imports distributed when imported).
"""

from ._encore import (Error, LoadError, Renderer, Scene, adapters, batch_options,
                      discover_inputs)

__all__ = ["Error", "LoadError", "Renderer", "Scene", "adapters", "batch", "batch_options",
           "discover_inputs"]

for _public in (Error, LoadError, Renderer, Scene):
    _public.__module__ = __name__  # Tracebacks and reprs name encore.Error, not encore._encore.


def batch(input, output, **options):
    """Runs the job of `encore batch INPUT -o OUTPUT` on a device of its own and returns its
    summary (models rendered, failed, skipped; views; seconds; time per stage; failures).

    `input` is a folder, a list file or a model, or (path, name) pairs from discover_inputs.
    The keywords are those of Renderer.batch (`encore batch`'s options: encore.batch_options()
    lists them, docs/batch.md#options describes them) and `device` (Renderer's).
    Failed models are in OUTPUT/failures.jsonl. The GIL is released while it runs.
    """
    renderer = Renderer(samples=options.pop("samples", 4), device=options.pop("device", None))
    return renderer.batch(input, output, **options)
