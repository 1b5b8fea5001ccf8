// A device lane's failures: a model or sample that fails is listed, unless the device was lost
// meanwhile, when it is drawn again (once) on the device created in its place.

#include "batch/DeviceLane.h"

#include <cstdlib>
#include <string>

#include "core/Log.h"

namespace encore::batch {

void DeviceLane::recoverIfLost() {
    if (!mContext.deviceLost()) {
        return;
    }
    // Every read-back in flight belongs to the lost device: those models fail too.
    while (!mChunks.empty()) {
        collectOldest();
    }
    ++mDevicesLost;
    finishTimestamps();
    // The model being drawn was cut short too, whether or not a failure named it yet.
    if (mCurrentModel && !mCurrentModel->retried && !mCurrentModel->failed) {
        mCurrentModel->retry = true;
    }
    for (RendererSlot& slot : mRenderers) {
        if (slot.prepared && slot.model && slot.model->retry) {
            // Drawn again on the new device (run()); its bytes stay held until then.
            mRetries.push_back(std::move(*slot.prepared));
            slot.prepared.reset();
        }
        releasePrepared(slot);
    }
    mRenderers.clear();  // renderModel fails every later model's upload when none is left.
    mRing = nullptr;
    mBatchRenderer.discard();  // Built on the lost device.
    if (auto recreated = mContext.recreateDevice(); recreated) {
        (void)createRenderers();
        logInfo("The GPU device was lost and created again; models in flight drawn again: " +
                std::to_string(mRetries.size()) + ".");
    } else {
        logWarning("The GPU device was lost and could not be created again (" +
                   recreated.error().message + ").");
    }
}

void DeviceLane::failBeforeUpload(ModelProgress& model,
                                  const LoadedModel& loaded,
                                  const char* stage,
                                  const Error& error) {
    model.fail(mShared.failures, mShared.counters, stage, error);
    mShared.loader.release(loaded.bytes);
}

void DeviceLane::failJob(ModelJob& job, const char* stage, const Error& error) {
    if (retryAfterLoss(*job.model)) {
        job.failed = true;  // Nothing of this attempt is written.
        return;
    }
    job.fail(mShared.failures, mShared.counters, stage, error);
}

void DeviceLane::failModel(ModelProgress& model, const char* stage, const Error& error) {
    if (!retryAfterLoss(model)) {
        model.fail(mShared.failures, mShared.counters, stage, error);
    }
}

bool DeviceLane::retryAfterLoss(ModelProgress& model) {
    if (model.retry) {
        return true;  // Already to be drawn again: this attempt's later failures add nothing.
    }
    if (model.retried || model.failed || !mContext.deviceLost()) {
        return false;
    }
    model.retry = true;
    return true;
}

void DeviceLane::injectDeviceLossForTests() {
    // ENCORE_TEST_LOSE_DEVICE_AT_MODEL=K loses the device once, right after the K-th model
    // (from 1) is uploaded, while earlier models' views may still be on the GPU: a driver reset
    // in the middle of a batch.
    static const long loseAt = [] {
        const char* value = std::getenv("ENCORE_TEST_LOSE_DEVICE_AT_MODEL");
        return value ? std::atol(value) : 0L;
    }();
    if (loseAt > 0 && mModelsPrepared == std::uint64_t(loseAt) && mDevicesLost == 0 &&
        !mInjectedLoss) {
        mInjectedLoss = true;
        mContext.device().ForceLoss(wgpu::DeviceLostReason::Unknown,
                                    "forced by ENCORE_TEST_LOSE_DEVICE_AT_MODEL");
        mContext.instance().ProcessEvents();
    }
}

}  // namespace encore::batch
