#include "batch/ModelLoader.h"

#include <chrono>

#include "core/Elapsed.h"

namespace encore::batch {

std::uint64_t sceneBytes(const scene::SceneData& scene) {
    std::uint64_t bytes = 0;
    for (const scene::Buffer& buffer : scene.buffers) {
        bytes += buffer.bytes.size();
    }
    for (const scene::Image& image : scene.images) {
        bytes += image.rgba8.size();
    }
    return bytes;
}

ModelLoader::ModelLoader(ThreadPool& pool,
                         std::span<const BatchInput> inputs,
                         const scene::LoadOptions& options,
                         std::uint64_t memoryLimitBytes,
                         std::size_t ahead,
                         Order order)
    : mPool(&pool),
      mInputs(inputs),
      mOptions(options),
      mMemoryLimit(memoryLimitBytes),
      mAhead(std::max<std::size_t>(ahead, 1)),
      mOrder(order) {
    std::lock_guard lock(mMutex);
    startLoads();
}

void ModelLoader::startLoads() {
    // The scenes held count against the limit; a load's size is unknown until it ends, so the
    // limit may be passed by the loads running when it is reached. With nothing loaded or
    // loading ahead of the GPU thread, one load always starts, whatever the scene the GPU
    // thread holds: models larger than the limit still render, one at a time.
    while (!mStopped && mNextToStart < mInputs.size() && mRunning < mAhead &&
           (mBytesHeld < mMemoryLimit || (mReady.empty() && mRunning == 0))) {
        const std::size_t order = mNextToStart++;
        ++mRunning;
        mPool->submit([this, order] {
            const auto start = std::chrono::steady_clock::now();
            const double cpuStart = threadCpuSeconds();
            LoadedModel loaded;
            loaded.order = order;
            loaded.scene = loadModelFile(mInputs[order].path, mOptions, loaded.facts);
            if (loaded.scene) {
                loaded.bytes = sceneBytes(*loaded.scene);
            }
            loaded.seconds = secondsSince(start);
            loaded.cpuSeconds = threadCpuSeconds() - cpuStart;
            std::lock_guard lock(mMutex);
            --mRunning;
            mBytesHeld += loaded.bytes;
            mReady.emplace(order, std::move(loaded));
            mLoaded.notify_all();
            startLoads();
        });
    }
}

bool ModelLoader::nextLoaded() const {
    return mOrder == Order::InOrder ? mReady.contains(mNextToTake) : !mReady.empty();
}

bool ModelLoader::exhausted() {
    std::lock_guard lock(mMutex);
    return mStopped || mTaken >= mInputs.size();
}

void ModelLoader::waitForNext(int milliseconds) {
    std::unique_lock lock(mMutex);
    mLoaded.wait_for(lock, std::chrono::milliseconds(milliseconds),
                     [this] { return mStopped || nextLoaded(); });
}

std::optional<LoadedModel> ModelLoader::takeLoaded() {
    if (mStopped || !nextLoaded()) {
        return std::nullopt;
    }
    auto node =
        mOrder == Order::InOrder ? mReady.extract(mNextToTake++) : mReady.extract(mReady.begin());
    ++mTaken;
    return std::move(node.mapped());
}

std::optional<LoadedModel> ModelLoader::tryTake() {
    std::lock_guard lock(mMutex);
    return takeLoaded();
}

std::optional<LoadedModel> ModelLoader::take() {
    std::unique_lock lock(mMutex);
    mLoaded.wait(lock, [this] { return mStopped || mTaken >= mInputs.size() || nextLoaded(); });
    return takeLoaded();
}

void ModelLoader::release(std::uint64_t bytes) {
    std::lock_guard lock(mMutex);
    mBytesHeld -= std::min(bytes, mBytesHeld);
    startLoads();
}

void ModelLoader::stop() {
    std::lock_guard lock(mMutex);
    mStopped = true;
    mLoaded.notify_all();
}

void ModelLoader::finish() {
    stop();
    std::unique_lock lock(mMutex);
    mLoaded.wait(lock, [this] { return mRunning == 0; });
    mReady.clear();
}

}  // namespace encore::batch
