// Work dealt out over a 64-thread workgroup in batches (visibility_raster.wgsl): each thread
// sets up one entry of the batch (a cluster), which claims some number of slots (its triangles);
// the slots of the whole batch are then dealt out to all 64 threads, so that no thread idles
// while another has a long entry, and the entries' memory waits overlap.

const kBatchEntries = 64u;

// After batchSlots: batchEnds[entry] is one past the last slot of `entry` (an inclusive prefix
// sum of the entries' slots).
var<workgroup> batchEnds: array<u32, kBatchEntries>;

// Returns the slots of the whole batch, given those of thread `lane`'s entry (0 for none).
// Workgroup-uniform control flow only: it synchronises the workgroup.
fn batchSlots(lane: u32, slots: u32) -> u32 {
    batchEnds[lane] = slots;
    workgroupBarrier();
    var sum = slots;
    for (var offset = 1u; offset < kBatchEntries; offset <<= 1u) {
        let before = batchEnds[select(0u, lane - offset, lane >= offset)];
        workgroupBarrier();
        sum += select(0u, before, lane >= offset);
        batchEnds[lane] = sum;
        workgroupBarrier();
    }
    return workgroupUniformLoad(&batchEnds[kBatchEntries - 1u]);
}

// The entry that holds `slot`, searching on from `entry` (a thread's slots only increase).
fn batchEntry(slot: u32, entry: u32) -> u32 {
    var found = entry;
    while (batchEnds[found] <= slot) {
        found++;
    }
    return found;
}

// The first slot of `entry`.
fn batchStart(entry: u32) -> u32 {
    return select(0u, batchEnds[max(entry, 1u) - 1u], entry > 0u);
}

// Entries per batch that spread `count` entries over `groups` workgroups: small batches while
// there are workgroups to spare (each setup waits on memory: more workgroups hide it better),
// up to kBatchEntries when each workgroup has many.
fn batchSize(count: u32, groups: u32) -> u32 {
    return clamp((count + groups - 1u) / groups, 1u, kBatchEntries);
}
