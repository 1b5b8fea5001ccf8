// The samples of a pixel that the shading takes: the covered ones (in the includer's
// `visibility` buffer, `samples` entries per pixel from `first`) whose triangle covers no earlier
// sample of the pixel, so that each distinct triangle of a pixel is shaded once, at the first
// sample it covers (where the composition looks for its colour).
struct DistinctSamples {
    ids: array<u32, 4>,  // The triangle of each covered sample.
    mask: u32,           // A bit per sample taken.
}

fn distinctSamples(first: u32, samples: u32) -> DistinctSamples {
    var result: DistinctSamples;
    var covered = 0u;
    for (var sample = 0u; sample < samples; sample++) {
        let key = visibility[first + sample];
        if (key.y == 0u) {
            continue;
        }
        result.ids[sample] = key.x;
        covered |= 1u << sample;
        var seen = false;
        for (var earlier = 0u; earlier < sample; earlier++) {
            seen = seen || (((covered >> earlier) & 1u) != 0u && result.ids[earlier] == key.x);
        }
        if (!seen) {
            result.mask |= 1u << sample;
        }
    }
    return result;
}
