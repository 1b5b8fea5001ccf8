"""The visibility batch benchmark of docs/benchmarks/2026-11-26-lavapipe-visibility-batch.md:
`encore batch` with the default strategy against `--strategy visibility`, in alternation in one
run, on dense generated models (`encore gen --objects 24 --meshes 4 --tessellation T --seed N`,
issue 28's batch target) and on the ten shared models of compare.py. Views per second are the
batch's own (its summary line: models drawn, not process start); with --before, a second build
(the code before a change) runs beside it in the same rounds.

    python3 bench/collections/visibility_batch.py --encore build/apps/encore/encore \
        --models ../shared/models [--before OLD/encore] [--dense 4] [--tessellation 64] \
        [--views 12] [--size 256] [--samples 4 1] [--repeats 2] [--renderers N] --json out.json
"""

import argparse
import json
import os
import re
import shutil
import subprocess
import tempfile

from compare import model_files

SUMMARY = re.compile(r"(\d+) views in ([\d.]+) s \(([\d.]+) views/s\)")


def run(encore, listing, arguments, samples, strategy):
    output = tempfile.mkdtemp(prefix="encore-visibility-batch-")
    try:
        command = [encore, "batch", listing, "-o", output, "--views", str(arguments.views),
                   "--size", str(arguments.size), "--samples", str(samples), "--quiet"]
        if strategy:
            command += ["--strategy", strategy]
        if arguments.renderers:
            command += ["--renderers", str(arguments.renderers)]
        load = os.getloadavg()[0]
        done = subprocess.run(command, capture_output=True, text=True)
        match = SUMMARY.search(done.stdout + done.stderr)
        if done.returncode != 0 or not match:
            return {"error": (done.stdout + done.stderr).strip()[-2000:],
                    "load_average_before": round(load, 2)}
        return {"views": int(match.group(1)), "seconds": float(match.group(2)),
                "views_per_s": float(match.group(3)), "load_average_before": round(load, 2)}
    finally:
        shutil.rmtree(output, ignore_errors=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--encore", required=True)
    parser.add_argument("--before", help="an older build to measure in the same rounds")
    parser.add_argument("--models", required=True)
    parser.add_argument("--dense", type=int, default=4, help="generated dense models")
    parser.add_argument("--tessellation", type=int, default=64)
    parser.add_argument("--views", type=int, default=12)
    parser.add_argument("--size", type=int, default=256)
    parser.add_argument("--samples", type=int, nargs="+", default=[4, 1])
    parser.add_argument("--repeats", type=int, default=2)
    parser.add_argument("--renderers", type=int, help="encore batch --renderers (default: its own)")
    parser.add_argument("--light-copies", type=int, default=1,
                        help="list the ten models this many times (folders of links: the "
                             "issue's 1,000-file job is 100)")
    parser.add_argument("--json")
    arguments = parser.parse_args()

    folder = tempfile.mkdtemp(prefix="encore-visibility-batch-models-")
    dense = []
    for seed in range(1, arguments.dense + 1):
        path = os.path.join(folder, "m%d.glb" % seed)
        subprocess.run([arguments.encore, "gen", "--objects", "24", "--meshes", "4",
                        "--tessellation", str(arguments.tessellation), "--seed", str(seed), "-o",
                        path], capture_output=True, check=True)
        dense.append(path)
    light = []
    for copy in range(arguments.light_copies):
        for model in model_files(os.path.abspath(arguments.models)):
            if arguments.light_copies == 1:
                light.append(model)
                continue
            # A link to the model's folder: a distinct path (a model of its own for the batch)
            # whose .gltf finds its buffers and images beside it.
            link = os.path.join(folder, "light%03d" % copy, os.path.basename(os.path.dirname(
                os.path.dirname(model))))
            os.makedirs(os.path.dirname(link), exist_ok=True)
            os.symlink(os.path.dirname(model), link)
            light.append(os.path.join(link, os.path.basename(model)))
    lists = {"dense": dense, "light": light}
    listings = {}
    for name, files in lists.items():
        listings[name] = os.path.join(folder, name + ".txt")
        with open(listings[name], "w") as out:
            out.write("\n".join(files) + "\n")
    adapter = subprocess.run([arguments.encore, "info"], capture_output=True, text=True).stdout
    adapter_line = next((line.strip() for line in adapter.splitlines()
                         if re.search(r"adapter|Vulkan", line, re.I)), "")
    builds = {"after": arguments.encore}
    if arguments.before:
        builds["before"] = arguments.before
    results = []
    for repeat in range(arguments.repeats):
        for samples in arguments.samples:
            for models in listings:
                for build, encore in builds.items():
                    for strategy in (None, "visibility"):
                        result = run(encore, listings[models], arguments, samples, strategy)
                        result.update({"repeat": repeat, "samples": samples, "models": models,
                                       "build": build, "strategy": strategy or "default"})
                        results.append(result)
                        print(result, flush=True)
    report = {"adapter": adapter_line, "views": arguments.views, "size": arguments.size,
              "tessellation": arguments.tessellation, "models": {k: len(v) for k, v in
                                                                 lists.items()},
              "results": results}
    if arguments.json:
        with open(arguments.json, "w") as out:
            json.dump(report, out, indent=1)
    shutil.rmtree(folder, ignore_errors=True)


if __name__ == "__main__":
    main()
