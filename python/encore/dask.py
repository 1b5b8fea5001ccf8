"""Rendering a collection of glTF models across a Dask cluster (distributed's scheduler).

    from distributed import Client
    import encore.dask
    client = Client(encore.dask.gpu_cluster())   # one worker process per GPU of this machine
    summary = encore.dask.render_collection(client, "models/", "out/", views=12, size=512)

A worker renders on the GPU its ENCORE_DEVICE environment variable names (an index of
encore.adapters(); unset: 0). gpu_cluster() starts one worker per GPU with that variable set;
on a cluster of machines, start one `dask worker` per GPU the same way (docs/batch.md).

The models are split into chunks of `chunk_size`, one task each. A worker runs
`tasks_per_gpu` tasks at once (gpu_cluster's, 2 by default), each on an encore.Renderer (a GPU
device) of its own, created by the first task that needs it and reused by the tasks after it;
its batch renderer (environment maps, pipelines, pools, staging buffers) is likewise built once
and kept (Renderer.batch keeps it between calls with the same size and samples). Each task
renders its chunk as `encore batch` does, into the same output folder: that
folder must be the same path on every worker (shared storage). The files are those a single
`encore batch` writes, byte for byte.

Tasks are idempotent: a finished model is skipped and every file is written under a temporary
name and renamed, so when a worker dies Dask runs its task again elsewhere and nothing is lost
or written twice. Failures come back with the tasks' results; the client writes
OUTPUT/failures.jsonl once, after the last task.
"""

import contextlib
import json
import os
import threading
import time

import distributed

from . import Renderer, discover_inputs
from . import adapters as adapters_list

__all__ = ["gpu_cluster", "gpu_devices", "render_collection"]

_STAGES = ("load", "upload", "render", "gpu", "readback", "encode", "load_cpu", "encode_cpu")


class _WorkerRenderers:
    """The renderers of this process, each checked out by one task at a time: a device costs far
    more to create than most models take to render, so tasks share them. A worker running two
    tasks at once (gpu_cluster's tasks_per_gpu) gets two renderers, two devices on its GPU: one
    task's batch fills and drains (its first loads, its last encodes) while the other's renders."""

    def __init__(self):
        self._lock = threading.Lock()
        self._idle = {}  # samples -> renderers no task holds
        self.created = 0

    @contextlib.contextmanager
    def checkout(self, samples):
        with self._lock:
            idle = self._idle.setdefault(samples, [])
            renderer = idle.pop() if idle else None
        if renderer is None:
            renderer = Renderer(samples=samples)
            with self._lock:
                self.created += 1
        try:
            yield renderer
        finally:
            with self._lock:
                self._idle[samples].append(renderer)


_worker_renderers = _WorkerRenderers()


def _render_chunk(models, output, options):
    """One task: the chunk's models on this worker's renderer. Runs on a worker."""
    options = dict(options)
    with _worker_renderers.checkout(options.pop("samples", 4)) as renderer:
        summary = renderer.batch(models, output, failure_log=False, **options)
        summary["device"] = renderer.device
    summary["worker"] = distributed.get_worker().address
    return summary


def gpu_devices(devices="all"):
    """The adapter indices that `devices` names, as `encore batch --devices` reads it: "all"
    (every adapter of the first one's type: a GPU machine's GPUs, without the CPU renderer
    beside them), or a sequence of indices (one may repeat: two workers on one GPU)."""
    adapters = adapters_list()
    if isinstance(devices, str):
        if devices != "all":
            raise ValueError(f"devices must be 'all' or a sequence of indices, not {devices!r}")
        first = adapters[0]
        return [adapter["index"] for adapter in adapters
                if adapter["type"] == first["type"] and adapter["backend"] == first["backend"]]
    devices = [int(device) for device in devices]
    for device in devices:
        if not 0 <= device < len(adapters):
            raise ValueError(f"there is no device {device}: this machine has {len(adapters)} "
                             f"adapter{'s' if len(adapters) != 1 else ''} (encore.adapters() "
                             "lists them)")
    if not devices:
        raise ValueError("devices is empty")
    return devices


def gpu_cluster(devices="all", tasks_per_gpu=2, **scheduler_options):
    """A cluster of this machine with one worker process per GPU: distributed's SpecCluster (the
    class LocalCluster is made of) whose workers are Nannies with `tasks_per_gpu` threads each
    and ENCORE_DEVICE set to their GPU (gpu_devices(devices)). A worker runs that many tasks at
    once, each on a renderer of its own on the worker's GPU, so that the GPU renders one task's
    models while another task's batch starts or ends (one task at a time left each GPU idle
    between tasks). The other keywords go to the scheduler (dashboard_address, ...). Use it as
    LocalCluster: Client(gpu_cluster()), and close it."""
    if tasks_per_gpu < 1:
        raise ValueError("tasks_per_gpu must be at least 1")
    workers = {
        f"gpu{device}-{position}": {
            "cls": distributed.Nanny,
            "options": {"nthreads": tasks_per_gpu, "env": {"ENCORE_DEVICE": str(device)}},
        }
        for position, device in enumerate(gpu_devices(devices))
    }
    # On the loopback interface, as LocalCluster's: the workers are this machine's.
    scheduler = {"cls": distributed.Scheduler,
                 "options": {"host": "127.0.0.1", "dashboard_address": None,
                             **scheduler_options}}
    return distributed.SpecCluster(workers=workers, scheduler=scheduler)


def _write_failures(output, models, failures):
    """OUTPUT/failures.jsonl in input order, one line per model, written under a temporary
    name and renamed, with the fields and key order of `encore batch`'s log."""
    order = {path: index for index, (path, _) in enumerate(models)}
    by_file = {failure["file"]: failure for failure in failures}
    lines = [json.dumps({"error": failure["error"], "file": failure["file"],
                         "stage": failure["stage"]}, ensure_ascii=False,
                        separators=(",", ":")) + "\n"
             for failure in sorted(by_file.values(),
                                   key=lambda failure: order.get(failure["file"], len(order)))]
    path = os.path.join(output, "failures.jsonl")
    with open(path + ".part", "w", encoding="utf-8") as log:
        log.writelines(lines)
    os.replace(path + ".part", path)
    return list(by_file.values())


def render_collection(client, inputs, output, *, chunk_size=32, retries=2, **options):
    """Renders `inputs` on the workers of `client` (a distributed.Client) into `output`, as
    `encore batch INPUTS -o OUTPUT` does, and returns the summary of the whole collection.

    `inputs` is what encore.discover_inputs takes: a folder, a list file, a model, or a
    sequence of model paths; paths must name the same files on every worker. `chunk_size`
    models make one task (each task's batch starts and drains its pipeline: on two H200s chunks
    of 8 ran at half the views/s of chunks of 32, docs/batch.md); a task that raises (a device
    that cannot be created) runs again up to `retries` times. The other keywords are those of encore.Renderer.batch (`encore
    batch`'s options, as encore.batch_options() lists them; not failure_log, shards or
    shard_size): what is drawn at random depends on the seed and each model's name only, so the
    tasks draw what one `encore batch` would.

    The summary has the models of the collection (`total`) and those rendered, failed and
    skipped (finished by an earlier run, or by a task's attempt on a worker that then died),
    the views written, the wall time (`seconds`), the stage times summed over the tasks, the
    failures as failures.jsonl lists them, the number of tasks, the tasks each worker ran
    (`workers`) and the device each worker rendered on (`devices`, by worker address).
    """
    if chunk_size < 1:
        raise ValueError("chunk_size must be at least 1")
    if "failure_log" in options:
        raise TypeError("render_collection writes failures.jsonl itself")
    if options.get("shards") or options.get("shard_size"):
        # Each task's batch numbers its shards from those in the folder: tasks running at once
        # would write the same names.
        raise ValueError("render_collection writes folders; shards are written by one batch "
                         "(encore.batch or `encore batch --shards`)")
    start = time.monotonic()
    models = discover_inputs(inputs)
    output = os.path.abspath(output)
    os.makedirs(output, exist_ok=True)
    chunks = [models[first:first + chunk_size] for first in range(0, len(models), chunk_size)]
    futures = client.map(_render_chunk, chunks, output=output, options=options, pure=False,
                         retries=retries)
    try:
        results = client.gather(futures)
    finally:
        client.cancel([future for future in futures if not future.done()])

    failures = _write_failures(output, models, [failure for result in results
                                                for failure in result["failures"]])
    workers = {}
    devices = {}
    for result in results:
        workers[result["worker"]] = workers.get(result["worker"], 0) + 1
        devices[result["worker"]] = result["device"]
    return {
        "total": len(models),
        "rendered": sum(result["rendered"] for result in results),
        "failed": len(failures),
        "skipped": sum(result["skipped"] for result in results),
        "views": sum(result["views"] for result in results),
        "seconds": time.monotonic() - start,
        "stages": {stage: sum(result["stages"][stage] for result in results)
                   for stage in _STAGES},
        "failures": failures,
        "tasks": len(chunks),
        "workers": workers,
        "devices": devices,
    }
