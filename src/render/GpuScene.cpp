#include "render/GpuScene.h"

#include <algorithm>
#include <chrono>
#include <optional>
#include <string>

#include "core/Elapsed.h"
#include "gpu/ResourcePool.h"
#include "render/TransmissionPass.h"

namespace encore::render {

namespace {

// Times one member's construction into `milliseconds` (members are built in the initialiser
// list, where no statement can stand).
template <typename Build>
auto timed(double& milliseconds, Build&& build) {
    const auto start = std::chrono::steady_clock::now();
    auto built = build();
    milliseconds += millisecondsSince(start);
    return built;
}

}  // namespace

Result<std::unique_ptr<GpuScene>> GpuScene::create(const RenderSetup& setup,
                                                   const scene::SceneData& scene,
                                                   const scene::AnimationPlayer* player,
                                                   const StagedUploads& staged) {
    std::optional<scene::AnimationPlayer> restPose;
    if (!player) {
        player = &restPose.emplace(scene);
    }
    // One submit for the scene: the geometry's staged copies, the textures' copies and their mip
    // passes (issue 48: every submit is a round trip into the driver).
    const wgpu::CommandEncoder uploads = setup.device.CreateCommandEncoder();
    std::unique_ptr<GpuScene> created(
        new GpuScene(setup, scene, *player, staged.geometry, uploads));
    PrepareTimes& times = setup.prepareTimes;
    const auto start = std::chrono::steady_clock::now();
    ENCORE_TRY_ASSIGN(
        created->mMaterials,
        MaterialResources::create(setup.device, setup.queue, *setup.shaders, *setup.layouts, scene,
                                  SampledTextures::all(), setup.limits.maxTextureDimension2D,
                                  setup.mipmaps, staged.images, setup.resources, uploads));
    const auto submitStart = std::chrono::steady_clock::now();
    const wgpu::CommandBuffer commands = uploads.Finish();
    setup.queue.Submit(1, &commands);
    const double submitMilliseconds = millisecondsSince(submitStart);
    times.materials += millisecondsSince(start);
    const TextureUploadTimes& upload = created->mMaterials->uploadTimes();
    times.textureCreation += upload.creation;
    times.textureWrites += upload.writes;
    times.mipmaps += upload.mipmaps;
    times.materialSubmit += upload.submit + submitMilliseconds;
    // Every material of the file counts, those of variants included: a variant switch then
    // never needs a texture that is not there.
    const bool transmissive = std::any_of(
        scene.materials.begin(), scene.materials.end(),
        [](const scene::Material& material) { return material.transmission.has_value(); });
    if (transmissive) {
        created->mTransmissionBackground = TransmissionPass::createBackground(setup.device);
    }
    return created;
}

GpuScene::GpuScene(const RenderSetup& setup,
                   const scene::SceneData& scene,
                   const scene::AnimationPlayer& player,
                   StagedGeometry* stagedGeometry,
                   const wgpu::CommandEncoder& uploads)
    : mSetup(&setup),
      mScene(&scene),
      mAnimation(AnimationBuffers::create(setup.device,
                                          setup.queue,
                                          *setup.layouts,
                                          scene,
                                          player,
                                          setup.resources)),
      mGeometry(timed(setup.prepareTimes.geometry,
                      [&] {
                          return GeometryBuffers(setup.device, scene, 0, stagedGeometry,
                                                 setup.resources, uploads);
                      })),
      mInstances(timed(setup.prepareTimes.instances, [&] {
          return InstanceBuffer(setup.device, *setup.layouts, scene, setup.resources);
      })) {
    mWorlds.reserve(scene.instances.size());
    for (const scene::Instance& instance : scene.instances) {
        mWorlds.push_back(instance.world);
    }
}

GpuScene::~GpuScene() {
    gpu::ResourcePool* pool = mSetup->resources;
    if (!pool) {
        return;
    }
    mGeometry.giveBackTo(*pool);
    mInstances.giveBackTo(*pool);
    if (mAnimation) {
        mAnimation->giveBackTo(*pool);
    }
    if (mMaterials) {
        mMaterials->giveBackTo(*pool);
    }
}

Result<void> GpuScene::updateInstance(std::size_t instance, const glm::mat4& world) {
    if (instance >= mWorlds.size()) {
        return makeError(ErrorCode::InvalidArgument, "Instance " + std::to_string(instance) +
                                                         " does not exist (the scene has " +
                                                         std::to_string(mWorlds.size()) +
                                                         " instances).");
    }
    mWorlds[instance] = world;
    mInstances.update(mSetup->queue, instance, world);
    return {};
}

Result<void> GpuScene::checkMaterial(scene::MaterialId material) const {
    if (!material.valid() || material.index() >= mMaterials->materialCount()) {
        return makeError(ErrorCode::InvalidArgument,
                         "Material " + std::to_string(material.value) + " does not exist.");
    }
    return {};
}

Result<void> GpuScene::updateMaterial(scene::MaterialId material, const scene::Material& value) {
    ENCORE_TRY(checkMaterial(material));
    // These extensions choose the material's pipelines (and transmission its pass): an edit
    // changes their factors, never whether they are there.
    const scene::Material& prepared = data().materials[material.index()];
    const auto differ = [](const auto& a, const auto& b) { return a.has_value() != b.has_value(); };
    if (differ(prepared.iridescence, value.iridescence) ||
        differ(prepared.anisotropy, value.anisotropy) ||
        differ(prepared.transmission, value.transmission) ||
        differ(prepared.diffuseTransmission, value.diffuseTransmission)) {
        return makeError(ErrorCode::InvalidArgument,
                         "Material " + std::to_string(material.value) +
                             ": an edit cannot add or remove KHR_materials_iridescence, "
                             "anisotropy, transmission or diffuse transmission (they choose its "
                             "pipelines); load the "
                             "scene with them instead.");
    }
    mMaterials->updateMaterial(mSetup->queue, material, value);
    return {};
}

Result<void> GpuScene::replaceBaseColorImage(scene::MaterialId material,
                                             const scene::Image& image) {
    ENCORE_TRY(checkMaterial(material));
    return mMaterials->replaceBaseColorImage(mSetup->device, mSetup->queue, *mSetup->shaders,
                                             *mSetup->layouts, material, image);
}

Result<void> GpuScene::selectVariant(std::optional<scene::VariantId> variant) {
    if (variant && variant->index() >= mScene->variants.size()) {
        return makeError(ErrorCode::InvalidArgument,
                         "Material variant " + std::to_string(variant->value) +
                             " does not exist (the scene has " +
                             std::to_string(mScene->variants.size()) + " variants).");
    }
    if (variant != mVariant) {
        mVariant = variant;
        ++mVariantSwitches;
    }
    return {};
}

AnimationUploadStats GpuScene::writeAnimation(const scene::AnimationPlayer& player) {
    return mAnimation ? mAnimation->write(mSetup->queue, player) : AnimationUploadStats{};
}

}  // namespace encore::render
