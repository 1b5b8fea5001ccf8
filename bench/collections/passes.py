"""The passes benchmark of docs/benchmarks/2026-11-26-passes.md: `encore batch` on the ten shared
models of compare.py, RGBA only against RGBA with passes (normals and depth, then every pass),
in alternation so that a change of load hits each alike; with --blender, Blender EEVEE (16
samples, one process per model under xvfb-run, as the dataset scripts run it) writing RGBA
alone and RGBA with its albedo, normal and depth passes (blender_views.py), in the same rounds.
Run it with Debian's /usr/bin/python3 (Blender's Python needs its numpy).

    python3 bench/collections/passes.py --encore build/apps/encore/encore \
        --models ../shared/models [--views 12] [--size 256] [--repeats 2] --json report.json \
        [--only "rgba;all passes;all passes, frames"] [--list l1.txt] [--blender]

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

ALL_PASSES = ["--normals", "--depth", "--depth-format", "exr", "--albedo", "--material",
              "--segmentation", "--hdr"]
# The H100 target set: RGBA + normal + depth + albedo + segmentation.
TARGET_SET = ["--normals", "--depth", "--albedo", "--segmentation"]
# Each pass set drawn both ways: in the colour frame's render pass (pass targets, the default)
# and one frame per pass (--pass-frames, the path before them).
CONFIGURATIONS = {
    "rgba": [],
    "normals+depth": ["--normals", "--depth"],
    "normals+depth, frames": ["--normals", "--depth", "--pass-frames"],
    "target set": TARGET_SET,
    "target set, frames": TARGET_SET + ["--pass-frames"],
    "all passes": ALL_PASSES,
    "all passes, frames": ALL_PASSES + ["--pass-frames"],
}


def run(encore, listing, views, size, samples, extra):
    output = tempfile.mkdtemp(prefix="encore-passes-")
    try:
        load = os.getloadavg()[0]
        start = time.perf_counter()
        before = os.times()
        command = subprocess.run(
            [encore, "batch", listing, "-o", output, "--views", str(views), "--size", str(size),
             "--samples", str(samples), "--quiet", *extra], capture_output=True, text=True, check=True)
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
    parser.add_argument("--samples", type=int, default=1,
                        help="1 (segmentation needs it) or 4 (then leave segmentation out)")
    parser.add_argument("--blender", action="store_true",
                        help="also Blender EEVEE, RGBA alone and with albedo, normal and depth")
    parser.add_argument("--json")
    parser.add_argument("--only", help="configurations to run, separated by ';' (default: all)")
    parser.add_argument("--list", help="a batch input list to render instead of the ten models")
    arguments = parser.parse_args()
    configurations = CONFIGURATIONS
    if arguments.only:
        configurations = {name: CONFIGURATIONS[name] for name in arguments.only.split(";")}
    if arguments.list:
        listing = arguments.list
        with open(listing) as names:
            model_count = sum(1 for line in names if line.strip())
    else:
        listing = os.path.join(tempfile.mkdtemp(prefix="encore-passes-list-"), "models.txt")
        with open(listing, "w") as out:
            out.write("\n".join(model_files(arguments.models)) + "\n")
        model_count = 10
    adapter = subprocess.run([arguments.encore, "info"], capture_output=True, text=True).stdout
    adapter_line = next((line.strip() for line in adapter.splitlines()
                         if re.search(r"adapter|Vulkan", line, re.I)), "")
    results = {name: [] for name in configurations}
    if arguments.blender:
        results.update({"blender rgba": [], "blender albedo+normal+depth": []})
    for _ in range(arguments.repeats):
        for name, extra in configurations.items():
            result = run(arguments.encore, listing, arguments.views, arguments.size,
                         arguments.samples, extra)
            result["views_per_s"] = round(model_count * arguments.views / result["wall_s"], 2)
            results[name].append(result)
            print(name, result, flush=True)
        if arguments.blender:
            models = [line.strip() for line in open(listing) if line.strip()]
            for name, passes in (("blender rgba", False), ("blender albedo+normal+depth", True)):
                result = run_blender(models, arguments.views, arguments.size, passes)
                result["views_per_s"] = round(len(models) * arguments.views / result["wall_s"], 3)
                results[name].append(result)
                print(name, result, flush=True)
    report = {"adapter": adapter_line, "views": arguments.views, "size": arguments.size,
              "samples": arguments.samples, "models": model_count, "results": results}
    if arguments.json:
        with open(arguments.json, "w") as out:
            json.dump(report, out, indent=1)


if __name__ == "__main__":
    main()
