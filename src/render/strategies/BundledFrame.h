#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "render/BundleRecorder.h"

namespace encore::render {

// The render bundles a frame replays: one for opaque and masked geometry, recorded once and
// again only when invalidated or when a referenced resource was replaced (a new resource
// generation); one for blended geometry, recorded again only when the back-to-front order
// changes.
class BundledFrame {
  public:
    void invalidate() { mStale = true; }

    template <typename RecordOpaque, typename RecordBlended>
    void update(const RenderSetup& setup,
                std::uint64_t resourceGeneration,
                std::vector<std::uint32_t> blendOrder,
                RecordOpaque&& recordOpaque,
                RecordBlended&& recordBlended) {
        if (resourceGeneration != mGeneration) {
            mStale = true;
        }
        if (mStale) {
            mOpaque = recordBundle(setup, "encore opaque and masked geometry", recordOpaque);
            ++mRecorded;
        }
        if (!blendOrder.empty() && (mStale || blendOrder != mBlendOrder)) {
            mBlended = recordBundle(
                setup, "encore blended geometry (back to front)",
                [&](RenderEncoder& encoder) { recordBlended(encoder, std::span(blendOrder)); });
            mBlendOrder = std::move(blendOrder);
            ++mRecorded;
        }
        mGeneration = resourceGeneration;
        mStale = false;
    }

    void execute(RenderEncoder& encoder) const {
        if (mBlended.bundle) {
            const wgpu::RenderBundle bundles[] = {mOpaque.bundle, mBlended.bundle};
            encoder.executeBundles(bundles);
        } else {
            encoder.executeBundles(std::span(&mOpaque.bundle, 1));
        }
    }

    DrawCounters contents() const {
        DrawCounters contents = mOpaque.contents;
        contents += mBlended.contents;
        return contents;
    }
    std::uint64_t recorded() const { return mRecorded; }

  private:
    RecordedBundle mOpaque;
    RecordedBundle mBlended;
    std::vector<std::uint32_t> mBlendOrder;
    std::uint64_t mGeneration = 0;
    std::uint64_t mRecorded = 0;
    bool mStale = true;
};

}  // namespace encore::render
