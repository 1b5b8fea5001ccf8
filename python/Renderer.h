#pragma once

// encore.Renderer: one GPU device drawing loaded models (encore.Scene) from a view rig, for
// render_views (NumPy arrays) and batch (the job of `encore batch`). Python threads may share
// one: calls that use the device take its mutex with the GIL released.

#include <pybind11/pybind11.h>

#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "ViewPasses.h"
#include "batch/BatchRenderer.h"
#include "encore/batch/Batch.h"
#include "encore/batch/ViewRig.h"
#include "encore/gpu/Context.h"
#include "encore/render/Renderer.h"
#include "encore/scene/SceneData.h"

namespace encore::python {

namespace py = pybind11;

// A loaded model: immutable, shared by the Python object and the renderer that prepared it.
struct Scene {
    std::shared_ptr<const scene::SceneData> data;
};

class Renderer {
  public:
    Renderer(std::uint32_t samples,
             std::optional<std::size_t> device,
             const std::optional<std::string>& strategy);

    Scene load(const std::string& path, bool allowUrisOutside);

    py::object renderViews(const Scene& scene,
                           std::uint32_t views,
                           const py::object& size,
                           float elevation,
                           float distance,
                           std::optional<float> fov,
                           bool random,
                           std::uint64_t seed,
                           bool normalize,
                           bool normals,
                           bool depth,
                           const std::string& name,
                           const py::object& variantName,
                           const py::object& passes,
                           const std::string& segmentation,
                           const py::object& environment,
                           float intensity,
                           float rotation,
                           float exposure,
                           const std::string& toneMapping,
                           const std::string& background,
                           bool passFrames,
                           const std::string& depthKind,
                           const std::string& depthUnit,
                           const std::string& normalSpace,
                           const std::string& normalKind,
                           const std::string& normalFormat,
                           const std::optional<std::string>& cameraConvention,
                           const std::optional<std::string>& distribution,
                           const std::string& projection,
                           float orthoScale,
                           const py::object& azimuths,
                           const py::object& elevations,
                           const py::object& distances,
                           const py::object& poses,
                           std::uint32_t pointCloud);

    // Runs the job of `encore batch` on this renderer's device.
    py::dict runBatch(const py::object& inputs,
                      const std::string& output,
                      const py::kwargs& keywords);

    std::string adapter() const { return mContext->adapterDescription().summary(); }
    std::size_t device() const { return mContext->adapterDescription().index; }
    batch::BatchRendererCounts batchCounts();
    std::uint32_t samples() const { return mSamples; }
    // The strategy render_views and batch draw with: given, else each one's default.
    std::optional<std::string> strategy() const {
        return mAutoStrategy ? std::optional<std::string>("auto")
               : mStrategy   ? std::optional(render::strategyChoiceName(*mStrategy))
                             : std::nullopt;
    }

  private:
    // A model's views, and its normal and depth images when asked for.
    struct Rendered {
        std::vector<image::ImageRgba8> color;
        std::vector<image::ImageRgba8> normals;
        std::vector<image::ImageGray16> depth;
        std::vector<PassImages> passes;  // With passes=: one per pass asked for, in order.
    };

    Result<Rendered> render(const std::shared_ptr<const scene::SceneData>& scene,
                            std::optional<scene::VariantId> variant,
                            const std::vector<batch::ViewCamera>& views,
                            const batch::ViewRigOptions& rig,
                            std::uint32_t width,
                            std::uint32_t height,
                            bool normals,
                            bool depth,
                            const ViewShading& shading,
                            std::span<const batch::ViewImage> kinds,
                            batch::SegmentationBy by,
                            const PassConventions& conventions,
                            bool passFrames);

    std::uint32_t mSamples;
    std::optional<render::StrategyChoice> mStrategy;
    bool mAutoStrategy = false;  // strategy="auto": batch chooses per model, render_views bundles.
    std::unique_ptr<gpu::Context> mContext;
    std::unique_ptr<render::Renderer> mRenderer;  // After mContext: destroyed before it.
    render::PassTargets mPassTargets = render::PassTargets::None;  // mRenderer's.
    std::unique_ptr<batch::BatchRenderer> mBatchRenderers;         // Kept by batch() between calls.
    std::shared_ptr<const scene::SceneData> mHeld;                 // Last given to prepare().
    std::shared_ptr<const scene::SceneData> mPrepared;             // Prepared successfully.
    std::string mEnvironment;  // The .hdr the renderer lights with; empty: the studio one.
    std::mutex mMutex;
};

}  // namespace encore::python
