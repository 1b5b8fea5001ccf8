// encore batch's images as PNG rows ready to compress (batch/PngRowsPass): for each view (a
// strip of the wide target), each row's filter-type byte and its samples filtered exactly as
// image/PngWriter.cpp filters them on the CPU, so that only deflate is left to the CPU. One
// invocation writes one 32-bit word (four bytes) of a view's rows; words past the rows are 0.
//
// The samples come from the source texture as the CPU path makes them from the read-back:
//   Bytes        RGBA8 as stored (the texture is read through an rgba8unorm view);
//   LinearBytes  the same with R, G and B sRGB-decoded through `linearOfSrgb` (normal and
//                material images: linear values that the sRGB target encoded);
//   Depth        16-bit depth from the depth-and-id target (R depth x coverage, A coverage):
//                round(depth / coverage x depthFactor), at least 1; 0 under half coverage;
//   Ids          16-bit ids from the same target (G id % 256, B id / 256, both x coverage).
// 16-bit samples are big-endian, as PNG stores them.

const kBytes = 0u;
const kLinearBytes = 1u;
const kDepth = 2u;
const kIds = 3u;

const kFilterUp = 0u;  // Every row Up, the first None (nothing is above it).
const kFilterPaeth = 1u;

const kWorkgroupSize = 64u;

struct Rows {
    viewSize: vec2u,
    source: u32,
    rowFilter: u32,
    bytesPerPixel: u32,  // 4 (RGBA8) or 2 (16-bit grey).
    viewWords: u32,  // Words from one view's rows to the next's.
    firstWord: u32,  // Where view 0's rows start in `streams`.
    counted: u32,  // Whether `covered` counts each view's pixels with a non-zero alpha.
    groupsX: u32,  // Workgroups along x: the grid folds what exceeds 65535 into z.
    depthFactor: f32,
}

@group(0) @binding(0) var source: texture_2d<f32>;
@group(0) @binding(1) var<storage, read_write> streams: array<u32>;
@group(0) @binding(2) var<uniform> rows: Rows;
@group(0) @binding(3) var<uniform> linearOfSrgb: array<vec4u, 64>;
@group(0) @binding(4) var<storage, read_write> covered: array<atomic<u32>>;

var<workgroup> coveredHere: atomic<u32>;

fn texel(view: u32, x: u32, y: u32) -> vec4f {
    return textureLoad(source, vec2u(view * rows.viewSize.x + x, y), 0);
}

// Rounds as the CPU's lround does for the non-negative values here.
fn rounded(value: f32) -> u32 {
    return u32(floor(value + 0.5));
}

fn sixteenBits(view: u32, x: u32, y: u32) -> u32 {
    let value = texel(view, x, y);
    let coverage = value.a;
    if (!(coverage >= 0.5)) {
        return 0u;
    }
    if (rows.source == kDepth) {
        return clamp(rounded(value.r / coverage * rows.depthFactor), 1u, 65535u);
    }
    let low = rounded(value.g / coverage);
    let high = rounded(value.b / coverage);
    return min(high * 256u + low, 65535u);
}

// Sample byte `channel` of pixel (x, y) of a view, before filtering.
fn sampleByte(view: u32, x: u32, y: u32, channel: u32) -> u32 {
    if (rows.source == kDepth || rows.source == kIds) {
        let value = sixteenBits(view, x, y);
        return select(value & 0xffu, value >> 8u, channel == 0u);
    }
    let byte = rounded(texel(view, x, y)[channel] * 255.0);
    if (rows.source == kLinearBytes && channel < 3u) {
        return linearOfSrgb[byte / 4u][byte % 4u];
    }
    return byte;
}

fn paeth(left: i32, above: i32, aboveLeft: i32) -> i32 {
    let towardsLeft = abs(above - aboveLeft);
    let towardsAbove = abs(left - aboveLeft);
    let towardsAboveLeft = abs(left + above - 2 * aboveLeft);
    if (towardsLeft <= towardsAbove && towardsLeft <= towardsAboveLeft) {
        return left;
    }
    return select(aboveLeft, above, towardsAbove <= towardsAboveLeft);
}

// Byte `position` of a view's filtered rows; counts the pixel whose alpha it is.
fn filteredByte(view: u32, position: u32, coveredPixels: ptr<function, u32>) -> u32 {
    let rowBytes = rows.viewSize.x * rows.bytesPerPixel;
    let y = position / (rowBytes + 1u);
    if (y >= rows.viewSize.y) {
        return 0u;
    }
    let column = position - y * (rowBytes + 1u);
    if (column == 0u) {
        return select(select(2u, 0u, y == 0u), 4u, rows.rowFilter == kFilterPaeth);
    }
    let x = (column - 1u) / rows.bytesPerPixel;
    let channel = (column - 1u) % rows.bytesPerPixel;
    let current = sampleByte(view, x, y, channel);
    if (channel == 3u && current != 0u) {
        *coveredPixels += 1u;
    }
    let above = select(0u, sampleByte(view, x, y - 1u, channel), y > 0u);
    var predicted = above;
    if (rows.rowFilter == kFilterPaeth) {
        let left = select(0u, sampleByte(view, x - 1u, y, channel), x > 0u);
        let aboveLeft = select(0u, sampleByte(view, x - 1u, y - 1u, channel), x > 0u && y > 0u);
        predicted = u32(paeth(i32(left), i32(above), i32(aboveLeft)));
    }
    return (current - predicted) & 0xffu;
}

@compute @workgroup_size(kWorkgroupSize)
fn writeRows(@builtin(workgroup_id) group: vec3u, @builtin(local_invocation_index) local: u32) {
    let view = group.y;
    let word = (group.z * rows.groupsX + group.x) * kWorkgroupSize + local;
    if (local == 0u) {
        atomicStore(&coveredHere, 0u);
    }
    workgroupBarrier();
    var coveredPixels = 0u;
    if (word < rows.viewWords) {
        var packed = 0u;
        for (var i = 0u; i < 4u; i++) {
            packed |= filteredByte(view, word * 4u + i, &coveredPixels) << (8u * i);
        }
        streams[rows.firstWord + view * rows.viewWords + word] = packed;
    }
    if (rows.counted != 0u && coveredPixels > 0u) {
        atomicAdd(&coveredHere, coveredPixels);
    }
    workgroupBarrier();
    if (rows.counted != 0u && local == 0u) {
        let total = atomicLoad(&coveredHere);
        if (total > 0u) {
            atomicAdd(&covered[view], total);
        }
    }
}
