#include <gtest/gtest.h>

#include <string_view>

#include "render/PassAttachments.h"

// What each pass of a frame loads, keeps, resolves and clears to (PassAttachments.h), for every
// shape of frame: one view, views side by side, two phases; with and without multisampling and
// HDR. The expected values are written out case by case.

namespace encore::render {
namespace {

using wgpu::LoadOp;
using wgpu::StoreOp;

// The operations of one pass, as a row of a table.
struct Ops {
    LoadOp colorLoad;
    StoreOp colorStore;
    bool resolve;
    LoadOp depthLoad;
    StoreOp depthStore;
};

void expectOps(const PassAttachments& actual, const Ops& expected) {
    EXPECT_EQ(actual.colorLoadOp, expected.colorLoad);
    EXPECT_EQ(actual.colorStoreOp, expected.colorStore);
    EXPECT_EQ(actual.resolve, expected.resolve);
    EXPECT_EQ(actual.depthLoadOp, expected.depthLoad);
    EXPECT_EQ(actual.depthStoreOp, expected.depthStore);
    EXPECT_EQ(actual.depthClearValue, 1.0f);
}

void expectClearColor(const PassAttachments& actual, double r, double g, double b, double a) {
    EXPECT_EQ(actual.clearColor.r, r);
    EXPECT_EQ(actual.clearColor.g, g);
    EXPECT_EQ(actual.clearColor.b, b);
    EXPECT_EQ(actual.clearColor.a, a);
}

PassPlan plan(std::size_t view, std::size_t viewCount, DrawPhase phase, bool multisampled) {
    PassPlan result;
    result.view = view;
    result.viewCount = viewCount;
    result.phase = phase;
    result.multisampled = multisampled;
    return result;
}

TEST(PassAttachmentsTest, OneMultisampledViewClearsResolvesAndDiscards) {
    const PassAttachments pass = passAttachments(plan(0, 1, DrawPhase::Whole, true));
    expectOps(pass, {LoadOp::Clear, StoreOp::Discard, true, LoadOp::Clear, StoreOp::Discard});
    EXPECT_EQ(std::string_view(pass.label), "encore frame");
    EXPECT_EQ(std::string_view(pass.timestampLabel), "scene");
}

TEST(PassAttachmentsTest, OneViewWithoutMultisamplingStoresItsColour) {
    const PassAttachments pass = passAttachments(plan(0, 1, DrawPhase::Whole, false));
    expectOps(pass, {LoadOp::Clear, StoreOp::Store, false, LoadOp::Clear, StoreOp::Discard});
    EXPECT_EQ(std::string_view(pass.label), "encore frame");
    EXPECT_EQ(std::string_view(pass.timestampLabel), "scene");
}

TEST(PassAttachmentsTest, ClearsToTheOpaqueBackgroundWithoutHdr) {
    PassPlan srgb = plan(0, 1, DrawPhase::Whole, true);
    srgb.backgroundColor = {0.25f, 0.5f, 0.75f};
    expectClearColor(passAttachments(srgb), 0.25, 0.5, 0.75, 1.0);
}

TEST(PassAttachmentsTest, ClearsToTransparentBlackWithHdr) {
    // Alpha is coverage for the tone mapper, whatever the background colour.
    PassPlan hdr = plan(0, 1, DrawPhase::Whole, true);
    hdr.hdr = true;
    hdr.backgroundColor = {0.25f, 0.5f, 0.75f};
    expectClearColor(passAttachments(hdr), 0.0, 0.0, 0.0, 0.0);
}

TEST(PassAttachmentsTest, SideBySideViewsClearOnceAndResolveAfterTheLast) {
    // Three multisampled views: the first clears colour and depth, the middle one loads and
    // keeps both, the last loads them, resolves and discards depth.
    const Ops expected[] = {
        {LoadOp::Clear, StoreOp::Store, false, LoadOp::Clear, StoreOp::Store},
        {LoadOp::Load, StoreOp::Store, false, LoadOp::Load, StoreOp::Store},
        {LoadOp::Load, StoreOp::Store, true, LoadOp::Load, StoreOp::Discard},
    };
    for (std::size_t view = 0; view < 3; ++view) {
        SCOPED_TRACE("view " + std::to_string(view));
        PassPlan views = plan(view, 3, DrawPhase::Whole, true);
        views.backgroundColor = {0.5f, 0.25f, 0.125f};
        const PassAttachments pass = passAttachments(views);
        expectOps(pass, expected[view]);
        expectClearColor(pass, 0.5, 0.25, 0.125, 1.0);
        EXPECT_EQ(std::string_view(pass.label), "encore frame");
        EXPECT_EQ(std::string_view(pass.timestampLabel), "scene");
    }
}

TEST(PassAttachmentsTest, TwoViewsSideBySide) {
    expectOps(passAttachments(plan(0, 2, DrawPhase::Whole, true)),
              {LoadOp::Clear, StoreOp::Store, false, LoadOp::Clear, StoreOp::Store});
    expectOps(passAttachments(plan(1, 2, DrawPhase::Whole, true)),
              {LoadOp::Load, StoreOp::Store, true, LoadOp::Load, StoreOp::Discard});
}

TEST(PassAttachmentsTest, SideBySideViewsWithoutMultisamplingNeverResolve) {
    const Ops expected[] = {
        {LoadOp::Clear, StoreOp::Store, false, LoadOp::Clear, StoreOp::Store},
        {LoadOp::Load, StoreOp::Store, false, LoadOp::Load, StoreOp::Store},
        {LoadOp::Load, StoreOp::Store, false, LoadOp::Load, StoreOp::Discard},
    };
    for (std::size_t view = 0; view < 3; ++view) {
        SCOPED_TRACE("view " + std::to_string(view));
        expectOps(passAttachments(plan(view, 3, DrawPhase::Whole, false)), expected[view]);
    }
}

TEST(PassAttachmentsTest, TwoPhasesKeepUnresolvedColourAndDepthForTheSecond) {
    const PassAttachments first = passAttachments(plan(0, 1, DrawPhase::First, true));
    expectOps(first, {LoadOp::Clear, StoreOp::Store, false, LoadOp::Clear, StoreOp::Store});
    EXPECT_EQ(std::string_view(first.label), "encore frame (first phase)");
    EXPECT_EQ(std::string_view(first.timestampLabel), "scene (first phase)");

    const PassAttachments second = passAttachments(plan(0, 1, DrawPhase::Second, true));
    expectOps(second, {LoadOp::Load, StoreOp::Discard, true, LoadOp::Load, StoreOp::Discard});
    EXPECT_EQ(std::string_view(second.label), "encore frame (second phase)");
    EXPECT_EQ(std::string_view(second.timestampLabel), "scene (second phase)");
}

TEST(PassAttachmentsTest, TwoPhasesWithoutMultisampling) {
    expectOps(passAttachments(plan(0, 1, DrawPhase::First, false)),
              {LoadOp::Clear, StoreOp::Store, false, LoadOp::Clear, StoreOp::Store});
    expectOps(passAttachments(plan(0, 1, DrawPhase::Second, false)),
              {LoadOp::Load, StoreOp::Store, false, LoadOp::Load, StoreOp::Discard});
}

TEST(PassAttachmentsTest, TwoPhasesClearToTheSameColourAsOnePass) {
    for (DrawPhase phase : {DrawPhase::First, DrawPhase::Second}) {
        PassPlan srgb = plan(0, 1, phase, true);
        srgb.backgroundColor = {0.25f, 0.5f, 0.75f};
        expectClearColor(passAttachments(srgb), 0.25, 0.5, 0.75, 1.0);
        PassPlan hdr = srgb;
        hdr.hdr = true;
        expectClearColor(passAttachments(hdr), 0.0, 0.0, 0.0, 0.0);
    }
}

// KHR_materials_transmission: the scene pass keeps colour and depth (and still resolves, for the
// copy), the transmission pass loads them and finishes as the scene pass would have.
TEST(PassAttachmentsTest, TransmissionPassLoadsWhatTheScenePassKept) {
    PassPlan scene = plan(0, 1, DrawPhase::Whole, true);
    scene.transmissionFollows = true;
    expectOps(passAttachments(scene),
              {LoadOp::Clear, StoreOp::Store, true, LoadOp::Clear, StoreOp::Store});
    PassPlan transmission = scene;
    transmission.transmissionFollows = false;
    transmission.transmission = true;
    const PassAttachments pass = passAttachments(transmission);
    expectOps(pass, {LoadOp::Load, StoreOp::Discard, true, LoadOp::Load, StoreOp::Discard});
    EXPECT_EQ(std::string_view(pass.label), "encore transmission");
    EXPECT_EQ(std::string_view(pass.timestampLabel), "transmission");

    transmission.multisampled = false;
    expectOps(passAttachments(transmission),
              {LoadOp::Load, StoreOp::Store, false, LoadOp::Load, StoreOp::Discard});
}

TEST(PassAttachmentsTest, TransmissionPassesOfSeveralViewsResolveOnceAtTheEnd) {
    PassPlan first = plan(0, 2, DrawPhase::Whole, true);
    first.transmission = true;
    expectOps(passAttachments(first),
              {LoadOp::Load, StoreOp::Store, false, LoadOp::Load, StoreOp::Store});
    PassPlan last = plan(1, 2, DrawPhase::Whole, true);
    last.transmission = true;
    expectOps(passAttachments(last),
              {LoadOp::Load, StoreOp::Discard, true, LoadOp::Load, StoreOp::Discard});
    // The last view's scene pass still resolves (the copy reads the result) and keeps depth.
    PassPlan lastScene = plan(1, 2, DrawPhase::Whole, true);
    lastScene.transmissionFollows = true;
    expectOps(passAttachments(lastScene),
              {LoadOp::Load, StoreOp::Store, true, LoadOp::Load, StoreOp::Store});
}

TEST(PassAttachmentsTest, SecondPhaseBeforeTransmissionKeepsItsDepth) {
    PassPlan second = plan(0, 1, DrawPhase::Second, true);
    second.transmissionFollows = true;
    expectOps(passAttachments(second),
              {LoadOp::Load, StoreOp::Store, true, LoadOp::Load, StoreOp::Store});
}

}  // namespace
}  // namespace encore::render
