#!/usr/bin/env python3
"""Lists the headers of Encore's installed API and checks that include/encore holds no others.

The API is what users of the installed CMake package call: the roots below and every header
they include, transitively (`#include "encore/..."`). Everything else is internal and lives
beside its sources under src/<folder>/ (or bench/).

    scripts/api-headers.py           prints the API headers, one a line
    scripts/api-headers.py --check   also fails (exit 1) when include/encore holds a header
                                     outside the API, or an API header includes a missing one
"""

import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
INCLUDE = ROOT / "include"

# Loading, the Renderer, the device, results, batch rendering and image I/O.
API_ROOTS = [
    "encore/scene/SceneData.h",  # loadScene, loadSceneFromMemory, SceneData
    "encore/render/Renderer.h",
    "encore/gpu/Context.h",
    "encore/core/Result.h",
    "encore/batch/Batch.h",
    "encore/image/ImageCodec.h",
    "encore/image/HdrImage.h",
]

INCLUDE_LINE = re.compile(r'^\s*#\s*include\s+"(encore/[^"]+)"', re.MULTILINE)
# Any quoted include: an API header may include only API headers (a user's compiler sees no src/).
QUOTED_INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.MULTILINE)


def closure(roots):
    seen, missing, todo = set(), set(), list(roots)
    while todo:
        header = todo.pop()
        if header in seen:
            continue
        path = INCLUDE / header
        if not path.is_file():
            missing.add(header)
            continue
        seen.add(header)
        todo.extend(INCLUDE_LINE.findall(path.read_text()))
    return seen, missing


def main():
    api, missing = closure(API_ROOTS)
    for header in sorted(api):
        print(header)
    if "--check" not in sys.argv[1:]:
        return 0
    present = {str(p.relative_to(INCLUDE)) for p in INCLUDE.rglob("*") if p.is_file()}
    extra = sorted(present - api)
    for header in sorted(missing):
        print(f"error: an API header includes {header}, which include/ lacks", file=sys.stderr)
    for header in extra:
        print(f"error: include/{header} is outside the API: move it beside its sources in src/",
              file=sys.stderr)
    internal = sorted(
        (header, included)
        for header in api
        for included in QUOTED_INCLUDE.findall((INCLUDE / header).read_text())
        if not included.startswith("encore/")
    )
    for header, included in internal:
        print(f"error: include/{header} includes \"{included}\", which is not an API header",
              file=sys.stderr)
    return 1 if missing or extra or internal else 0


if __name__ == "__main__":
    sys.exit(main())
