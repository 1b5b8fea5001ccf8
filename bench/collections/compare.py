"""The collection benchmark of docs/benchmarks: ten shared models, 12 views each at 512x512,
rendered by `encore batch` (4x and 1x multisampling), by one `encore render --yaw` process per
view, by encore.dask on a LocalCluster of two worker processes, and by Blender (EEVEE and
Cycles, 16 samples, one process per model as the dataset scripts run it, under xvfb-run).

    PYTHONPATH=build/python python3 bench/collections/compare.py --encore build/apps/encore/encore \
        --models ../shared/models --json report.json [--repeats 3] [--blender-models 10] [--skip ...]

Every run writes into a fresh temporary folder; wall-clock seconds include process start,
device creation and loading, as a user waits for them. The load average is recorded with each
run: the machine may be shared.
"""

import argparse
import datetime
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time

MODELS = ["Duck", "BoxTextured", "CesiumMilkTruck", "BrainStem", "2CylinderEngine",
          "ReciprocatingSaw", "AlphaBlendModeTest", "Fox", "MetalRoughSpheresNoTextures",
          "Avocado"]
VIEWS = 12
SIZE = 512
HERE = os.path.dirname(os.path.abspath(__file__))


def model_files(models_root):
    index = {entry["name"]: entry for entry in json.load(open(os.path.join(models_root,
                                                                           "index.json")))}
    files = []
    for name in MODELS:
        variants = index[name]["variants"]
        variant = variants.get("glTF-Binary") or variants["glTF"]
        files.append(os.path.join(models_root, variant["file"]))
    return files


def timed(label, function, models, repeat):
    load = os.getloadavg()[0]
    start = time.monotonic()
    details = function() or {}
    seconds = time.monotonic() - start
    result = {"renderer": label, "repeat": repeat, "models": models, "views": models * VIEWS,
              "seconds": round(seconds, 3),
              "views_per_second": round(models * VIEWS / seconds, 3),
              "load_average_before": round(load, 2)}
    result.update(details)
    print(json.dumps(result), flush=True)
    return result


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--encore", required=True)
    parser.add_argument("--models", required=True)
    parser.add_argument("--json", required=True)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--process-repeats", type=int, default=1)
    parser.add_argument("--blender-models", type=int, default=len(MODELS))
    parser.add_argument("--skip", action="append", default=[],
                        help="batch, batch-samples-1, process-per-view, dask, blender-eevee, "
                             "blender-cycles")
    arguments = parser.parse_args()
    encore_binary = os.path.abspath(arguments.encore)
    files = model_files(arguments.models)
    work = tempfile.mkdtemp(prefix="encore-collections-")
    inputs = os.path.join(work, "models.json")
    with open(inputs, "w") as listing:
        json.dump(files, listing)

    def fresh(name):
        path = os.path.join(work, name)
        shutil.rmtree(path, ignore_errors=True)
        return path

    def batch(*extra):
        def run():
            out = fresh("batch")
            command = subprocess.run([encore_binary, "batch", inputs, "-o", out, "--views",
                                      str(VIEWS), "--size", str(SIZE), *extra],
                                     capture_output=True, text=True, check=True)
            return {"summary": command.stdout.strip().splitlines()}
        return run

    def process_per_view():
        out = fresh("render")
        os.makedirs(out)
        for index, model in enumerate(files):
            for view in range(VIEWS):
                subprocess.run([encore_binary, "render", model, "-o",
                                os.path.join(out, f"{index}-{view:03}.png"), "--width",
                                str(SIZE), "--height", str(SIZE), "--background", "transparent",
                                "--yaw", str(360.0 * view / VIEWS)],
                               capture_output=True, check=True)

    def blender(engine, count):
        def run():
            out = fresh(f"blender-{engine}")
            for index, model in enumerate(files[:count]):
                subprocess.run(["xvfb-run", "-a", "blender", "-b", "-P",
                                os.path.join(HERE, "blender_views.py"), "--",
                                model, os.path.join(out, MODELS[index]), engine, str(VIEWS),
                                str(SIZE), "16"], capture_output=True, check=True)
            written = sum(len(names) for _, _, names in os.walk(out))
            if written != count * VIEWS:
                raise RuntimeError(f"Blender wrote {written} of {count * VIEWS} views")
        return run

    runs = []
    started = datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds")
    dask_startup = None
    client = None
    if "dask" not in arguments.skip:
        import distributed
        import encore.dask
        begin = time.monotonic()
        cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1,
                                           dashboard_address=None)
        client = distributed.Client(cluster)
        dask_startup = round(time.monotonic() - begin, 3)

    def dask_run():
        summary = encore.dask.render_collection(client, inputs, fresh("dask"), chunk_size=2,
                                                views=VIEWS, size=SIZE)
        return {"dask_summary": {key: summary[key] for key in
                                 ("rendered", "failed", "tasks", "workers", "stages")}}

    for repeat in range(arguments.repeats):
        if "batch" not in arguments.skip:
            runs.append(timed("encore batch", batch(), len(files), repeat))
        if "batch-samples-1" not in arguments.skip:
            runs.append(timed("encore batch --samples 1", batch("--samples", "1"), len(files),
                              repeat))
        if client is not None:
            # The first run of a cluster also creates the workers' devices.
            runs.append(timed("encore.dask, 2 workers", dask_run, len(files), repeat))
    for repeat in range(arguments.process_repeats):
        if "process-per-view" not in arguments.skip:
            runs.append(timed("encore render --yaw, one process per view", process_per_view,
                              len(files), repeat))
    count = arguments.blender_models
    if "blender-eevee" not in arguments.skip:
        runs.append(timed("Blender EEVEE, 16 samples", blender("eevee", count), count, 0))
    if "blender-cycles" not in arguments.skip:
        runs.append(timed("Blender Cycles (CPU), 16 samples", blender("cycles", count), count, 0))
    if client is not None:
        client.close()

    adapter = subprocess.run([encore_binary, "info"], capture_output=True, text=True).stdout
    blender_version = ""
    if shutil.which("blender"):
        blender_version = subprocess.run(["blender", "--version"], capture_output=True,
                                         text=True).stdout.splitlines()[0]
    report = {"started": started, "host_cpus": os.cpu_count(), "adapter": adapter.strip(),
              "blender": blender_version, "models": MODELS, "views_per_model": VIEWS,
              "size": SIZE, "dask_cluster_startup_seconds": dask_startup, "runs": runs}
    with open(arguments.json, "w") as out:
        json.dump(report, out, indent=2)
        out.write("\n")
    shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
