"""Driver allocation round trips on one GPU per process, for 1..N processes at once.

Each process, on its own GPU, repeats a driver call pair for a fixed time: pinned host memory
(cudaHostAlloc + cudaFreeHost: the kind of memory a mapped staging buffer is), device memory
(cudaMalloc + cudaFree), and a host-to-device copy from pinned memory with a synchronise (a
submit and a fence). Prints the mean microseconds per pair in each process, to see whether the
driver serves several GPUs' calls in parallel.
    python3 driver_calls.py PROCESSES [MIB]
"""
import multiprocessing as mp
import sys
import time


def run(device, mib, seconds, queue):
    import cupy
    from cupy.cuda import runtime

    cupy.cuda.Device(device).use()
    size = mib << 20
    results = {}
    runtime.free(runtime.malloc(1))  # context creation outside the timing

    def timed(name, body):
        count = 0
        start = time.perf_counter()
        while time.perf_counter() - start < seconds:
            body()
            count += 1
        results[name] = (time.perf_counter() - start) / count * 1e6

    def host():
        runtime.freeHost(runtime.hostAlloc(size, 0))

    def device_memory():
        runtime.free(runtime.malloc(size))

    pinned = runtime.hostAlloc(size, 0)
    target = runtime.malloc(size)

    def copy():
        runtime.memcpy(target, pinned, size, runtime.memcpyHostToDevice)

    timed("hostAlloc+freeHost", host)
    timed("malloc+free", device_memory)
    timed("copy+sync", copy)
    queue.put((device, results))


if __name__ == "__main__":
    processes = int(sys.argv[1])
    mib = int(sys.argv[2]) if len(sys.argv) > 2 else 16
    ctx = mp.get_context("spawn")
    queue = ctx.Queue()
    workers = [ctx.Process(target=run, args=(d, mib, 3.0, queue)) for d in range(processes)]
    for w in workers:
        w.start()
    rows = [queue.get() for _ in workers]
    for w in workers:
        w.join()
    for device, results in sorted(rows):
        print(f"processes={processes} gpu={device} {mib} MiB: " +
              ", ".join(f"{k} {v:.0f} us" for k, v in results.items()))
