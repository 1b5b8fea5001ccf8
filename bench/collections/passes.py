"""The passes benchmark of docs/benchmarks/2026-11-26-passes.md: `encore batch` on the ten shared
models of compare.py, RGBA only against RGBA with passes (normals and depth, then every pass),
in alternation so that a change of load hits each alike; with --blender, Blender EEVEE (16
samples, one process per model under xvfb-run, as the dataset scripts run it) writing RGBA
alone and RGBA with its albedo, normal and depth passes (blender_views.py), in the same rounds.

    python3 bench/collections/passes.py --encore build/apps/encore/encore \
        --models ../shared/models [--views 12] [--size 256] [--repeats 2] [--blender] \
        --json report.json

Wall-clock seconds include process start, device creation and loading; user and system CPU
seconds of the process (the machine may be shared: the load average is recorded per run).
"""

import argparse
import json
import os
import re
import shutil
import subprocess
import tempfile
import time

from compare import HERE, model_files

CONFIGURATIONS = {
    "rgba": [],
    "normals+depth": ["--normals", "--depth"],
    "all passes": ["--normals", "--depth", "--depth-format", "exr", "--albedo", "--material",
                   "--segmentation", "--hdr"],
}


def run(encore, listing, views, size, extra):
    output = tempfile.mkdtemp(prefix="encore-passes-")
    try:
        load = os.getloadavg()[0]
        start = time.perf_counter()
        before = os.times()
        command = subprocess.run(
            [encore, "batch", listing, "-o", output, "--views", str(views), "--size", str(size),
             "--samples", "1", "--quiet", *extra], capture_output=True, text=True, check=True)
        wall = time.perf_counter() - start
        after = os.times()
        files = sum(len(names) for _, _, names in os.walk(output))
        return {"wall_s": round(wall, 2),
                "user_s": round(after.children_user - before.children_user, 2),
                "system_s": round(after.children_system - before.children_system, 2),
                "files": files, "load_average_before": round(load, 2),
                "summary": command.stdout.strip().splitlines()[-3:]}
    finally:
        shutil.rmtree(output, ignore_errors=True)


def run_blender(models, views, size, passes):
    output = tempfile.mkdtemp(prefix="encore-passes-blender-")
    try:
        load = os.getloadavg()[0]
        start = time.perf_counter()
        before = os.times()
        for index, model in enumerate(models):
            out = os.path.join(output, str(index))
            os.makedirs(out)
            # --python-exit-code: a failing script (e.g. no numpy for Blender's Python: run
            # this with Debian's /usr/bin/python3) fails the run instead of writing nothing.
            subprocess.run(["xvfb-run", "-a", "blender", "-b", "--python-exit-code", "1", "-P",
                            os.path.join(HERE, "blender_views.py"), "--", model, out, "eevee",
                            str(views), str(size), "16", "all", "all" if passes else "none"],
                           capture_output=True, text=True, check=True)
        wall = time.perf_counter() - start
        after = os.times()
        files = sum(len(names) for _, _, names in os.walk(output))
        return {"wall_s": round(wall, 2),
                "user_s": round(after.children_user - before.children_user, 2),
                "system_s": round(after.children_system - before.children_system, 2),
                "files": files, "load_average_before": round(load, 2)}
    finally:
        shutil.rmtree(output, ignore_errors=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--encore", required=True)
    parser.add_argument("--models", required=True)
    parser.add_argument("--views", type=int, default=12)
    parser.add_argument("--size", type=int, default=256)
    parser.add_argument("--repeats", type=int, default=2)
    parser.add_argument("--blender", action="store_true",
                        help="also Blender EEVEE, RGBA alone and with albedo, normal and depth")
    parser.add_argument("--json")
    arguments = parser.parse_args()
    listing = os.path.join(tempfile.mkdtemp(prefix="encore-passes-list-"), "models.txt")
    with open(listing, "w") as out:
        out.write("\n".join(model_files(arguments.models)) + "\n")
    adapter = subprocess.run([arguments.encore, "info"], capture_output=True, text=True).stdout
    adapter_line = next((line.strip() for line in adapter.splitlines()
                         if re.search(r"adapter|Vulkan", line, re.I)), "")
    models = model_files(arguments.models)
    results = {name: [] for name in CONFIGURATIONS}
    if arguments.blender:
        results.update({"blender rgba": [], "blender albedo+normal+depth": []})
    for _ in range(arguments.repeats):
        for name, extra in CONFIGURATIONS.items():
            result = run(arguments.encore, listing, arguments.views, arguments.size, extra)
            result["views_per_s"] = round(10 * arguments.views / result["wall_s"], 2)
            results[name].append(result)
            print(name, result, flush=True)
        if arguments.blender:
            for name, passes in (("blender rgba", False), ("blender albedo+normal+depth", True)):
                result = run_blender(models, arguments.views, arguments.size, passes)
                result["views_per_s"] = round(len(models) * arguments.views / result["wall_s"], 3)
                results[name].append(result)
                print(name, result, flush=True)
    report = {"adapter": adapter_line, "views": arguments.views, "size": arguments.size,
              "models": 10, "results": results}
    if arguments.json:
        with open(arguments.json, "w") as out:
            json.dump(report, out, indent=1)


if __name__ == "__main__":
    main()
