"""Issue 48's Dask row: encore.dask.render_collection on encore.dask.gpu_cluster() (one worker per
GPU, chunks of the documented default size), timed as `encore batch` reports views/s.
    python dask_gpus.py LIST OUTPUT [chunk_size [tasks_per_gpu]]
Run through probe_python's PY on the device machine: worker processes start through the packed
interpreter that ENCORE_PYTHON names."""
import multiprocessing
import os
import sys


def main():
    import encore
    import encore.dask
    from distributed import Client

    if os.environ.get("ENCORE_PYTHON"):
        multiprocessing.set_executable(os.environ["ENCORE_PYTHON"])
    models = [line.strip() for line in open(sys.argv[1]) if line.strip()]
    options = {} if len(sys.argv) < 4 else {"chunk_size": int(sys.argv[3])}
    cluster_options = {} if len(sys.argv) < 5 else {"tasks_per_gpu": int(sys.argv[4])}
    print("adapters:", [(a["index"], a["name"], a["backend"]) for a in encore.adapters()])
    with encore.dask.gpu_cluster(**cluster_options) as cluster, Client(cluster) as client:
        summary = encore.dask.render_collection(client, models, sys.argv[2], views=12, **options)
    seconds = summary["seconds"]
    print(f"dask: {summary['views']} views in {seconds * 1000:.0f} ms: "
          f"{summary['views'] / seconds:.0f} views/s; rendered {summary['rendered']}, failed "
          f"{summary['failed']}, {summary['tasks']} tasks, devices {sorted(summary['devices'].values())}, "
          f"tasks per worker {sorted(summary['workers'].values())}")
    print("stages (s, summed over tasks):",
          {name: round(value, 1) for name, value in summary["stages"].items()})


if __name__ == "__main__":
    main()
