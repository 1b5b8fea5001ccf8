#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>

#include "trace/Bvh.h"

namespace encore::trace {
namespace {

bool contains(const BvhNode& outer, const glm::vec3& min, const glm::vec3& max) {
    return glm::all(glm::lessThanEqual(outer.min, min)) &&
           glm::all(glm::greaterThanEqual(outer.max, max));
}

std::vector<scene::Bounds> randomBoxes(std::size_t count, std::uint32_t seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<float> position(-10.0f, 10.0f);
    std::uniform_real_distribution<float> size(0.01f, 1.0f);
    std::vector<scene::Bounds> boxes(count);
    for (scene::Bounds& box : boxes) {
        const glm::vec3 corner(position(random), position(random), position(random));
        box.extend(corner);
        box.extend(corner + glm::vec3(size(random), size(random), size(random)));
    }
    return boxes;
}

// Every node encloses its children or its items; every item lies in exactly one leaf.
void expectWellFormed(const Bvh& bvh, std::span<const scene::Bounds> boxes, std::uint32_t maxLeaf) {
    std::vector<int> seen(boxes.size(), 0);
    std::vector<std::uint32_t> stack{0};
    std::size_t visited = 0;
    while (!stack.empty()) {
        const BvhNode node = bvh.nodes[stack.back()];
        stack.pop_back();
        ++visited;
        if (node.leaf()) {
            EXPECT_LE(node.count, maxLeaf);
            ASSERT_LE(node.first + node.count, bvh.items.size());
            for (std::uint32_t i = node.first; i < node.first + node.count; ++i) {
                const std::uint32_t item = bvh.items[i];
                ASSERT_LT(item, boxes.size());
                ++seen[item];
                EXPECT_TRUE(contains(node, boxes[item].min, boxes[item].max)) << "item " << item;
            }
            continue;
        }
        ASSERT_LT(node.first + 1, bvh.nodes.size());
        for (std::uint32_t child = node.first; child <= node.first + 1; ++child) {
            EXPECT_TRUE(contains(node, bvh.nodes[child].min, bvh.nodes[child].max));
            stack.push_back(child);
        }
    }
    EXPECT_EQ(visited, bvh.nodes.size()) << "every node is reachable once";
    for (std::size_t item = 0; item < boxes.size(); ++item) {
        EXPECT_EQ(seen[item], boxes[item].empty() ? 0 : 1) << "item " << item;
    }
}

TEST(BvhTest, EveryItemLiesInOneLeafInsideEveryBoxAboveIt) {
    auto builder = BvhBuilder::create();
    ASSERT_TRUE(builder.ok()) << builder.error().message;
    const std::vector<scene::Bounds> boxes = randomBoxes(5000, 7);
    auto bvh = builder->build(boxes, {.maxLeafSize = 4});
    ASSERT_TRUE(bvh.ok()) << bvh.error().message;
    EXPECT_EQ(bvh->items.size(), boxes.size());
    // A binary tree with leaves of at most 4 items: at least 2 * 5000 / 4 - 1 nodes.
    EXPECT_GE(bvh->nodes.size(), 2 * boxes.size() / 4 - 1);
    expectWellFormed(*bvh, boxes, 4);
}

TEST(BvhTest, EmptyBoxesAreLeftOutAndNoBoxesMakeNoTree) {
    auto builder = BvhBuilder::create();
    ASSERT_TRUE(builder.ok());
    std::vector<scene::Bounds> boxes = randomBoxes(10, 3);
    boxes[4] = scene::Bounds{};  // Empty: no finite point.
    auto bvh = builder->build(boxes);
    ASSERT_TRUE(bvh.ok());
    EXPECT_EQ(bvh->items.size(), 9u);
    EXPECT_EQ(std::count(bvh->items.begin(), bvh->items.end(), 4u), 0);
    expectWellFormed(*bvh, boxes, BvhBuildOptions{}.maxLeafSize);

    auto none = builder->build(std::vector<scene::Bounds>(3));
    ASSERT_TRUE(none.ok());
    EXPECT_TRUE(none->nodes.empty());
    EXPECT_TRUE(none->items.empty());
}

TEST(BvhTest, OneItemIsALeafAtTheRoot) {
    auto builder = BvhBuilder::create();
    ASSERT_TRUE(builder.ok());
    const std::vector<scene::Bounds> boxes = randomBoxes(1, 5);
    auto bvh = builder->build(boxes);
    ASSERT_TRUE(bvh.ok());
    ASSERT_EQ(bvh->nodes.size(), 1u);
    EXPECT_EQ(bvh->nodes[0].count, 1u);
    EXPECT_EQ(bvh->nodes[0].min, boxes[0].min);
    EXPECT_EQ(bvh->nodes[0].max, boxes[0].max);
}

// The same boxes give the same nodes, so that a scene traces the same way every run.
TEST(BvhTest, TheSameBoxesGiveTheSameTree) {
    auto builder = BvhBuilder::create();
    ASSERT_TRUE(builder.ok());
    const std::vector<scene::Bounds> boxes = randomBoxes(20000, 11);
    auto first = builder->build(boxes);
    auto second = builder->build(boxes);
    ASSERT_TRUE(first.ok() && second.ok());
    ASSERT_EQ(first->nodes.size(), second->nodes.size());
    EXPECT_EQ(first->items, second->items);
    EXPECT_EQ(0, std::memcmp(first->nodes.data(), second->nodes.data(),
                             first->nodes.size() * sizeof(BvhNode)));
}

}  // namespace
}  // namespace encore::trace
