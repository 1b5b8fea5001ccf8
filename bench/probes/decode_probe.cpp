// Issue 48: decodes every image file given, THREADS threads at once, each image ROUNDS times,
// and prints the mean milliseconds per decode of each file (bench/probes/per-model-gpu.sh runs
// it on the device machine). Not part of the build; from the repository root, after a build:
//   g++ -std=c++20 -O2 -Iinclude bench/probes/decode_probe.cpp build/src/image/libencore_image.a
//       build/src/core/libencore_core.a /usr/lib/x86_64-linux-gnu/libstb.a -lspng -ljpeg
//       -ldeflate -lwebp -lpthread -o decode_probe
//   decode_probe THREADS ROUNDS FILES...

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <thread>
#include <vector>

#include "encore/image/ImageCodec.h"

namespace {

using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 4) {
        std::fprintf(stderr, "usage: decode_probe THREADS ROUNDS FILES...\n");
        return 2;
    }
    const int threads = std::atoi(argv[1]);
    const int rounds = std::atoi(argv[2]);
    for (int file = 3; file < argc; ++file) {
        std::ifstream stream(argv[file], std::ios::binary);
        const std::vector<unsigned char> encoded((std::istreambuf_iterator<char>(stream)), {});
        std::atomic<bool> failed{false};
        std::vector<double> decodeMilliseconds(threads, 0.0);  // Summed per thread.
        const Clock::time_point start = Clock::now();
        std::vector<std::thread> workers;
        for (int thread = 0; thread < threads; ++thread) {
            workers.emplace_back([&, thread] {
                for (int round = 0; round < rounds; ++round) {
                    const Clock::time_point decodeStart = Clock::now();
                    if (!encore::image::decodeImage(encoded).ok()) {
                        failed = true;
                    }
                    decodeMilliseconds[thread] += millisecondsSince(decodeStart);
                }
            });
        }
        for (std::thread& worker : workers) {
            worker.join();
        }
        if (failed) {
            std::fprintf(stderr, "%s does not decode\n", argv[file]);
            return 1;
        }
        double total = 0.0;
        for (const double milliseconds : decodeMilliseconds) {
            total += milliseconds;
        }
        const double decodes = double(threads) * rounds;
        std::printf("%-28s %2d threads: %.1f ms per decode (%.0f decodes/s)\n", argv[file], threads,
                    total / decodes, decodes / (millisecondsSince(start) / 1000.0));
    }
    return 0;
}
