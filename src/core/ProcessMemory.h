#pragma once

// How the process's allocator returns memory to the kernel, set for work that allocates and
// frees the same large blocks again and again (a batch's decoded images and file buffers).
//
// glibc gives a freed block above its mmap threshold straight back to the kernel (munmap) and
// trims its arenas' free tops (madvise, heap deletion): the next model's block of that size then
// faults in fresh zeroed pages, and every one of those calls changes the process's memory map
// under its mmap lock, which page faults and the GPU driver's mappings of every other thread wait
// on. On the 4 x H200 machine, 14.5% of all CPU samples of a four-GPU batch were threads spinning
// on that lock (osq_lock, issue 48). Keeping freed memory in the process lets later models reuse
// pages already mapped: the process's footprint stays at its peak instead.

namespace encore {

// Raises glibc's mmap and trim thresholds (mallopt) so that freed blocks of up to 32 MiB stay in
// the arenas and arenas are not trimmed. Once per process; the environment variable
// ENCORE_KEEP_FREED_MEMORY=0 leaves the allocator as it is (for comparisons). Returns whether
// the thresholds were set.
bool keepFreedMemoryInProcess();

}  // namespace encore
