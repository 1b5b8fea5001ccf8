// Fresh-page throughput: each of N processes maps an anonymous region, writes every page, and
// unmaps it, again and again (what a malloc/free of a large block costs once glibc returns the
// block to the kernel), or writes the same region again (`reuse`: the pages stay mapped).
// Prints the GiB/s of all processes together, to see whether the kernel (and the hypervisor
// behind it) serves page faults of several processes in parallel.
//   fresh_pages PROCESSES MIB_PER_ROUND ROUNDS fresh|reuse
#define _GNU_SOURCE
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

static double now(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + t.tv_nsec * 1e-9;
}

static void work(size_t bytes, int rounds, int fresh) {
    char* kept = fresh ? NULL : mmap(NULL, bytes, PROT_READ | PROT_WRITE,
                                     MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    for (int r = 0; r < rounds; ++r) {
        char* p = kept ? kept
                       : mmap(NULL, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS,
                              -1, 0);
        for (size_t i = 0; i < bytes; i += 4096) {
            p[i] = (char)r;
        }
        if (!kept) {
            munmap(p, bytes);
        }
    }
}

int main(int argc, char** argv) {
    if (argc != 5) {
        fprintf(stderr, "usage: fresh_pages PROCESSES MIB ROUNDS fresh|reuse\n");
        return 2;
    }
    int processes = atoi(argv[1]);
    size_t bytes = (size_t)atoi(argv[2]) << 20;
    int rounds = atoi(argv[3]);
    int fresh = strcmp(argv[4], "fresh") == 0;
    double start = now();
    for (int i = 0; i < processes; ++i) {
        if (fork() == 0) {
            work(bytes, rounds, fresh);
            _exit(0);
        }
    }
    while (wait(NULL) > 0) {
    }
    double seconds = now() - start;
    double gib = (double)processes * rounds * bytes / (1 << 30);
    printf("%s processes=%d %.1f GiB in %.2f s: %.2f GiB/s all, %.2f per process\n", argv[4],
           processes, gib, seconds, gib / seconds, gib / seconds / processes);
    return 0;
}
