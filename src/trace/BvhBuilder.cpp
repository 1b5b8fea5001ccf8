#include "trace/Bvh.h"

#include <embree3/rtcore.h>

#include <string>

namespace encore::trace {

struct BvhBuilder::Device {
    RTCDevice device = nullptr;
    ~Device() {
        if (device) {
            rtcReleaseDevice(device);
        }
    }
};

namespace {

// The tree as Embree's callbacks make it, in memory of its thread-local allocators (freed with
// the RTCBVH); flatten() copies it into the GPU's layout.
struct BuildNode {
    RTCBounds bounds[2];
    BuildNode* children[2] = {nullptr, nullptr};
    const std::uint32_t* items = nullptr;  // A leaf's items; null for an interior node.
    std::uint32_t count = 0;
};

BuildNode* newNode(RTCThreadLocalAllocator allocator) {
    void* memory = rtcThreadLocalAlloc(allocator, sizeof(BuildNode), alignof(BuildNode));
    return new (memory) BuildNode();
}

void* createNode(RTCThreadLocalAllocator allocator, unsigned int /*childCount*/, void*) {
    return newNode(allocator);  // Binary: maxBranchingFactor is 2.
}

void setNodeChildren(void* node, void** children, unsigned int childCount, void*) {
    for (unsigned int child = 0; child < childCount; ++child) {
        static_cast<BuildNode*>(node)->children[child] = static_cast<BuildNode*>(children[child]);
    }
}

void setNodeBounds(void* node, const RTCBounds** bounds, unsigned int childCount, void*) {
    for (unsigned int child = 0; child < childCount; ++child) {
        static_cast<BuildNode*>(node)->bounds[child] = *bounds[child];
    }
}

void* createLeaf(RTCThreadLocalAllocator allocator,
                 const RTCBuildPrimitive* primitives,
                 size_t count,
                 void*) {
    BuildNode* leaf = newNode(allocator);
    auto* items = static_cast<std::uint32_t*>(
        rtcThreadLocalAlloc(allocator, sizeof(std::uint32_t) * count, alignof(std::uint32_t)));
    for (size_t i = 0; i < count; ++i) {
        items[i] = primitives[i].primID;
    }
    leaf->items = items;
    leaf->count = std::uint32_t(count);
    return leaf;
}

BvhNode boxNode(const RTCBounds& bounds) {
    BvhNode node;
    node.min = {bounds.lower_x, bounds.lower_y, bounds.lower_z};
    node.max = {bounds.upper_x, bounds.upper_y, bounds.upper_z};
    return node;
}

// Depth first; an interior node's children are appended together, so they lie side by side.
void flatten(const BuildNode& built, std::size_t index, Bvh& bvh) {
    if (built.items) {
        bvh.nodes[index].first = std::uint32_t(bvh.items.size());
        bvh.nodes[index].count = built.count;
        bvh.items.insert(bvh.items.end(), built.items, built.items + built.count);
        return;
    }
    const std::size_t first = bvh.nodes.size();
    bvh.nodes[index].first = std::uint32_t(first);
    bvh.nodes.push_back(boxNode(built.bounds[0]));
    bvh.nodes.push_back(boxNode(built.bounds[1]));
    flatten(*built.children[0], first, bvh);
    flatten(*built.children[1], first + 1, bvh);
}

}  // namespace

Result<BvhBuilder> BvhBuilder::create() {
    auto device = std::make_shared<Device>();
    device->device = rtcNewDevice(nullptr);
    if (!device->device) {
        return Error{ErrorCode::Unsupported, "Embree could not create a device (error " +
                                                 std::to_string(int(rtcGetDeviceError(nullptr))) +
                                                 ")."};
    }
    return BvhBuilder(std::move(device));
}

Result<Bvh> BvhBuilder::build(std::span<const scene::Bounds> items,
                              const BvhBuildOptions& options) const {
    std::vector<RTCBuildPrimitive> primitives;
    primitives.reserve(items.size());
    scene::Bounds all;
    for (std::size_t i = 0; i < items.size(); ++i) {
        const scene::Bounds& box = items[i];
        if (box.empty()) {
            continue;
        }
        primitives.push_back(RTCBuildPrimitive{box.min.x, box.min.y, box.min.z, 0u, box.max.x,
                                               box.max.y, box.max.z, std::uint32_t(i)});
        all.extend(box);
    }
    Bvh bvh;
    if (primitives.empty()) {
        return bvh;
    }
    RTCBVH handle = rtcNewBVH(mDevice->device);
    RTCBuildArguments arguments = rtcDefaultBuildArguments();
    arguments.buildQuality = RTC_BUILD_QUALITY_MEDIUM;  // HIGH would need spatial splits.
    arguments.maxBranchingFactor = 2;
    arguments.maxDepth = 64;
    arguments.minLeafSize = 1;
    arguments.maxLeafSize = std::max(1u, options.maxLeafSize);
    arguments.traversalCost = options.traversalCost;
    arguments.intersectionCost = options.intersectionCost;
    arguments.bvh = handle;
    arguments.primitives = primitives.data();
    arguments.primitiveCount = primitives.size();
    arguments.primitiveArrayCapacity = primitives.size();
    arguments.createNode = createNode;
    arguments.setNodeChildren = setNodeChildren;
    arguments.setNodeBounds = setNodeBounds;
    arguments.createLeaf = createLeaf;
    const auto* root = static_cast<const BuildNode*>(rtcBuildBVH(&arguments));
    if (!root) {
        rtcReleaseBVH(handle);
        return Error{ErrorCode::LimitExceeded,
                     "Embree could not build a hierarchy of " + std::to_string(primitives.size()) +
                         " boxes (error " +
                         std::to_string(int(rtcGetDeviceError(mDevice->device))) + ")."};
    }
    bvh.items.reserve(primitives.size());
    bvh.nodes.push_back(BvhNode{all.min, 0, all.max, 0});
    flatten(*root, 0, bvh);
    rtcReleaseBVH(handle);
    return bvh;
}

}  // namespace encore::trace
