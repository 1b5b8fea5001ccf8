#include "render/MaterialResources.h"

// MaterialResources::create resolves each material's slots (textureSlots()) to textures and
// samplers that MaterialResources::Builder uploads (MaterialResourcesBuilder.cpp), packs the
// uniforms (MaterialUniform.cpp) and makes the bind groups; the rest of the class keeps them.

#include <algorithm>
#include <array>
#include <cassert>
#include <chrono>
#include <cstring>
#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <utility>

#include "core/Elapsed.h"
#include "core/Log.h"
#include "gpu/ResourcePool.h"
#include "gpu/Upload.h"
#include "render/MaterialResourcesBuilder.h"
#include "render/MipmapGenerator.h"
#include "render/SamplerPalette.h"

namespace encore::render {

namespace {

constexpr std::uint64_t kUniformSize = sizeof(MaterialUniform);

// The glTF sampler of the texture in `slot` of `material` ("the default sampler" for none).
std::string slotSamplerName(const scene::SceneData& scene,
                            const scene::Material& material,
                            std::uint32_t slot) {
    const std::optional<scene::TextureRef> ref = slotTexture(material, TextureSlot(slot));
    const scene::SamplerId sampler = scene.textures[ref->texture.index()].sampler;
    return sampler.valid() ? "sampler " + std::to_string(sampler.value) : "the default sampler";
}

// Names each slot that samples with another sampler than its own, and the one it uses.
void warnApproximatedSamplers(
    const scene::SceneData& scene,
    scene::MaterialId id,
    const std::array<std::optional<std::size_t>, kMaterialTextureSlotCount>& slotSamplers,
    const SamplerPalette& palette) {
    const scene::Material& material = scene.materials[id.index()];
    std::string slots;
    for (const TextureSlot slot : palette.approximated) {
        const std::uint32_t entry = palette.slotEntries[std::uint32_t(slot)];
        // The first slot that brought the entry into the palette names its sampler.
        std::uint32_t owner = 0;
        while (palette.slotEntries[owner] != entry || !slotSamplers[owner] ||
               std::find(palette.approximated.begin(), palette.approximated.end(),
                         TextureSlot(owner)) != palette.approximated.end()) {
            ++owner;
        }
        slots += std::string(slots.empty() ? "" : ", ") +
                 std::string(textureSlotInfo(slot).textureName) + " (" +
                 slotSamplerName(scene, material, std::uint32_t(slot)) + ") samples with " +
                 slotSamplerName(scene, material, owner);
    }
    logWarning(describeMaterial(id, material) + "'s textures use more distinct samplers than the " +
               std::to_string(kMaterialSamplerCount) +
               " a material binds; the nearest stand in: " + slots + ".");
}

}  // namespace

namespace {

// The materials' uniforms: one range per material, each aligned to what a uniform binding
// offset needs (256 by default), and the buffer they go to.
struct UniformStorage {
    std::uint64_t stride = 0;
    std::vector<std::uint8_t> bytes;
    wgpu::Buffer buffer;
};

UniformStorage uniformStorage(const wgpu::Device& device,
                              const wgpu::Limits& limits,
                              std::size_t materialCount,
                              gpu::ResourcePool* pool) {
    UniformStorage storage;
    const std::uint64_t alignment =
        std::max<std::uint64_t>(limits.minUniformBufferOffsetAlignment, 4);
    storage.stride = (kUniformSize + alignment - 1) / alignment * alignment;
    storage.bytes.resize(storage.stride * std::max<std::size_t>(materialCount, 1));
    const wgpu::BufferUsage usage =
        wgpu::BufferUsage::Uniform | wgpu::BufferUsage::CopyDst | wgpu::BufferUsage::CopySrc;
    storage.buffer =
        pool ? pool->buffer(usage, storage.bytes.size(), "material uniforms")
             : gpu::createBuffer(device, usage, storage.bytes.size(), "material uniforms");
    return storage;
}

}  // namespace

Result<MaterialResources> MaterialResources::create(const wgpu::Device& device,
                                                    const wgpu::Queue& queue,
                                                    shaders::ShaderLibrary& shaders,
                                                    const BindGroupLayouts& layouts,
                                                    const scene::SceneData& scene,
                                                    const SampledTextures& sampled,
                                                    std::uint32_t maxTextureDimension,
                                                    MipmapGenerator* mipmaps,
                                                    StagedImages* staged,
                                                    gpu::ResourcePool* pool,
                                                    wgpu::CommandEncoder uploads) {
    std::optional<MipmapGenerator> ownMipmaps;
    if (!mipmaps) {
        ENCORE_TRY_ASSIGN(auto created, MipmapGenerator::create(device, shaders));
        mipmaps = &ownMipmaps.emplace(std::move(created));
    }
    wgpu::Limits limits{};
    device.GetLimits(&limits);

    MaterialResources resources;
    resources.mImageTextures.resize(scene.images.size());
    Builder builder{device,    queue,    scene,
                    resources, *mipmaps, uploads ? uploads : device.CreateCommandEncoder(),
                    staged,    pool};
    builder.maxDimension = maxTextureDimension != 0
                               ? std::min(maxTextureDimension, limits.maxTextureDimension2D)
                               : limits.maxTextureDimension2D;

    // Index 0 in both vectors, so an empty slot needs no lookup.
    const std::uint8_t white[4] = {255, 255, 255, 255};
    builder.addTexture("default white (sRGB)", 1, 1, wgpu::TextureFormat::RGBA8UnormSrgb, white);
    const std::size_t defaultSampler = builder.addSampler(scene::Sampler{}, "default");

    resources.mSceneSamplers.reserve(scene.samplers.size());
    for (std::size_t i = 0; i < scene.samplers.size(); ++i) {
        resources.mSceneSamplers.push_back(
            builder.addSampler(scene.samplers[i], "sampler " + std::to_string(i)));
    }

    const std::size_t materialCount = scene.materials.size();
    UniformStorage storage = uniformStorage(device, limits, materialCount, pool);
    resources.mUniformStride = storage.stride;
    resources.mUniforms = std::move(storage.buffer);
    std::vector<std::uint8_t> uniformBytes = std::move(storage.bytes);

    resources.mBindGroups.resize(materialCount);
    resources.mBaseBindGroups.resize(materialCount);
    for (std::size_t i = 0; i < materialCount; ++i) {
        const scene::MaterialId id{i};
        const scene::Material& material = scene.materials[i];
        SlotIndices textures;
        textures.fill(kDefaultTexture);
        std::array<std::optional<std::size_t>, kMaterialTextureSlotCount> samplers;
        for (const TextureSlotInfo& slot : textureSlots()) {
            const std::uint32_t slotIndex = std::uint32_t(slot.slot);
            const std::optional<scene::TextureRef>& ref = slot.texture(material);
            if (!ref) {
                continue;
            }
            // Unsampled slots are only checked, so they cost neither load time nor memory.
            if (!sampled.sampled(slot.slot) && ref->texture.index() < scene.textures.size()) {
                continue;
            }
            ENCORE_TRY_ASSIGN(auto uploaded, builder.referencedTexture(
                                                 id, ref, slotColorSpace(material, slot.slot)));
            if (uploaded == kNone) {
                continue;  // Missing or undecoded image: the loader warned; white stands in.
            }
            const scene::Texture& texture = scene.textures[ref->texture.index()];
            if (texture.sampler.valid() && texture.sampler.index() >= scene.samplers.size()) {
                return makeError(ErrorCode::InvalidArgument,
                                 describeMaterial(id, material) + ": texture " +
                                     std::to_string(ref->texture.value) + " references sampler " +
                                     std::to_string(texture.sampler.value) +
                                     ", but the scene has " +
                                     std::to_string(scene.samplers.size()) + " samplers.");
            }
            textures[slotIndex] = uploaded;
            samplers[slotIndex] = texture.sampler.valid()
                                      ? resources.mSceneSamplers[texture.sampler.index()]
                                      : defaultSampler;
        }
        const SamplerPalette palette = makeSamplerPalette(samplers, builder.states, defaultSampler);
        if (!palette.approximated.empty()) {
            warnApproximatedSamplers(scene, id, samplers, palette);
        }
        std::array<std::size_t, kMaterialSamplerCount> bound;
        for (std::size_t entry = 0; entry < bound.size(); ++entry) {
            bound[entry] = palette.samplers[entry < palette.samplers.size() ? entry : 0];
        }
        resources.mMaterialTextures.push_back(textures);
        resources.mMaterialPalettes.push_back(bound);
        resources.mMaterialSamplerEntries.push_back(palette.slotEntries);
        resources.mTextured.push_back(std::any_of(
            textures.begin(), textures.end(), [](std::size_t t) { return t != kDefaultTexture; }));
        resources.mShadesExtensions.push_back(materialShadesExtensions(material));

        MaterialUniform uniform = makeMaterialUniform(material, palette.slotEntries);
        uniform.flags[2] = std::uint32_t(i + 1);  // The segmentation id (DebugChannel).
        uniform.flags[3] = resources.texturedSlots(i);
        std::memcpy(uniformBytes.data() + i * resources.mUniformStride, &uniform, kUniformSize);

        resources.createBindGroups(device, layouts, i,
                                   material.name.empty() ? "material" : material.name.c_str());
    }
    queue.WriteBuffer(resources.mUniforms, 0, uniformBytes.data(), uniformBytes.size());

    if (!uploads) {
        const auto submitStart = std::chrono::steady_clock::now();
        wgpu::CommandBuffer commands = builder.encoder.Finish();
        queue.Submit(1, &commands);
        resources.mUploadTimes.submit += millisecondsSince(submitStart);
    }
    return resources;
}

void MaterialResources::giveBackTo(gpu::ResourcePool& pool) {
    mBindGroups.clear();
    mBaseBindGroups.clear();
    for (wgpu::Texture& texture : mTextures) {
        pool.giveBack(std::move(texture));
    }
    mTextures.clear();
    pool.giveBack(std::move(mUniforms));
}

void MaterialResources::createBindGroups(const wgpu::Device& device,
                                         const BindGroupLayouts& layouts,
                                         std::size_t material,
                                         const char* label) {
    mBindGroups[material] = createBindGroup(device, layouts, material, label);
    mBaseBindGroups[material] =
        mTextured[material] && !mShadesExtensions[material]
            ? createBindGroup(device, layouts, material, label, /*baseSlots=*/true)
            : wgpu::BindGroup();
}

wgpu::BindGroup MaterialResources::createBindGroup(const wgpu::Device& device,
                                                   const BindGroupLayouts& layouts,
                                                   std::size_t material,
                                                   const char* label,
                                                   bool baseSlots) const {
    std::array<wgpu::BindGroupEntry, 1 + kMaterialSamplerCount + kMaterialTextureSlotCount>
        entries{};
    entries[0].binding = 0;
    entries[0].buffer = mUniforms;
    entries[0].offset = material * mUniformStride;
    entries[0].size = kUniformSize;
    wgpu::BindGroupDescriptor descriptor{};
    descriptor.label = label;
    if (!mTextured[material]) {
        descriptor.layout = layouts.materialUniformOnly;
        descriptor.entryCount = 1;
        descriptor.entries = entries.data();
        return device.CreateBindGroup(&descriptor);
    }
    for (std::uint32_t entry = 0; entry < kMaterialSamplerCount; ++entry) {
        wgpu::BindGroupEntry& sampler = entries[materialSamplerBinding(entry)];
        sampler.binding = materialSamplerBinding(entry);
        sampler.sampler = mSamplers[mMaterialPalettes[material][entry]];
    }
    const std::uint32_t slots =
        baseSlots ? kMaterialBaseTextureSlotCount : kMaterialTextureSlotCount;
    for (std::uint32_t slot = 0; slot < slots; ++slot) {
        wgpu::BindGroupEntry& texture = entries[materialTextureBinding(slot)];
        texture.binding = materialTextureBinding(slot);
        texture.textureView = mTextures[mMaterialTextures[material][slot]].CreateView();
    }
    descriptor.layout = baseSlots ? layouts.materialBase : layouts.material;
    descriptor.entryCount = 1 + kMaterialSamplerCount + slots;
    descriptor.entries = entries.data();
    return device.CreateBindGroup(&descriptor);
}

Result<void> MaterialResources::replaceBaseColorImage(const wgpu::Device& device,
                                                      const wgpu::Queue& queue,
                                                      shaders::ShaderLibrary& shaders,
                                                      const BindGroupLayouts& layouts,
                                                      scene::MaterialId material,
                                                      const scene::Image& image) {
    if (!material.valid() || material.index() >= mBindGroups.size()) {
        return makeError(ErrorCode::InvalidArgument,
                         "Material " + std::to_string(material.value) + " does not exist.");
    }
    ENCORE_TRY_ASSIGN(auto mipmaps, MipmapGenerator::create(device, shaders));
    const scene::SceneData noScene;
    wgpu::Limits limits{};
    device.GetLimits(&limits);
    Builder builder{device, queue, noScene, *this, mipmaps, device.CreateCommandEncoder()};
    builder.maxDimension = limits.maxTextureDimension2D;
    auto uploaded = builder.uploadImage(scene::ImageId{}, image, ColorSpace::Srgb);
    if (!uploaded) {
        return uploaded.error().withContext("Replacing the base colour image of material " +
                                            std::to_string(material.value));
    }
    if (*uploaded == kNone) {
        return makeError(ErrorCode::InvalidArgument, "The replacement image for material " +
                                                         std::to_string(material.value) +
                                                         " has no pixels.");
    }
    wgpu::CommandBuffer commands = builder.encoder.Finish();
    queue.Submit(1, &commands);

    constexpr std::size_t kBaseColor = std::size_t(TextureSlot::BaseColor);
    const std::size_t old = mMaterialTextures[material.index()][kBaseColor];
    mMaterialTextures[material.index()][kBaseColor] = *uploaded;
    mTextured[material.index()] = true;
    const std::uint32_t slots = texturedSlots(material.index());
    queue.WriteBuffer(mUniforms,
                      material.index() * mUniformStride + offsetof(MaterialUniform, flags) +
                          3 * sizeof(std::uint32_t),
                      &slots, sizeof(slots));
    createBindGroups(device, layouts, material.index(), "material (replaced texture)");
    ++mGeneration;
    ++mUniformGeneration;

    const bool stillUsed =
        old == kDefaultTexture ||
        std::any_of(mMaterialTextures.begin(), mMaterialTextures.end(),
                    [old](const SlotIndices& slots) {
                        return std::find(slots.begin(), slots.end(), old) != slots.end();
                    });
    if (!stillUsed) {
        // Free the GPU memory now: anything still referencing it (a stale bundle) would fail
        // validation at submit instead of drawing old data.
        mTextures[old].Destroy();
    }
    return {};
}

const wgpu::BindGroup& MaterialResources::bindGroup(scene::MaterialId material) const {
    assert(material.index() < mBindGroups.size());
    return mBindGroups[material.index()];
}

bool MaterialResources::shadesExtensions(scene::MaterialId material) const {
    assert(material.index() < mShadesExtensions.size());
    return mShadesExtensions[material.index()];
}

const wgpu::BindGroup& MaterialResources::drawBindGroup(scene::MaterialId material) const {
    assert(material.index() < mBaseBindGroups.size());
    const wgpu::BindGroup& base = mBaseBindGroups[material.index()];
    return base ? base : mBindGroups[material.index()];
}

void MaterialResources::updateMaterial(const wgpu::Queue& queue,
                                       scene::MaterialId material,
                                       const scene::Material& values) {
    assert(material.index() < mBindGroups.size());
    MaterialUniform uniform =
        makeMaterialUniform(values, mMaterialSamplerEntries[material.index()]);
    uniform.flags[2] = std::uint32_t(material.index() + 1);
    uniform.flags[3] = texturedSlots(material.index());
    queue.WriteBuffer(mUniforms, material.index() * mUniformStride, &uniform, kUniformSize);
    ++mUniformGeneration;
}

std::vector<std::uint32_t> MaterialResources::sharedBindingLeaders() const {
    // What a material's bind groups bind besides its uniform (createBindGroup).
    using Bindings =
        std::tuple<bool, bool, std::array<std::size_t, kMaterialSamplerCount>, SlotIndices>;
    std::map<Bindings, std::uint32_t> leaders;
    std::vector<std::uint32_t> result(mBindGroups.size());
    for (std::size_t material = 0; material < mBindGroups.size(); ++material) {
        Bindings bindings{mTextured[material], mShadesExtensions[material], {}, {}};
        if (mTextured[material]) {
            std::get<2>(bindings) = mMaterialPalettes[material];
            std::get<3>(bindings) = mMaterialTextures[material];
        }
        result[material] = leaders.emplace(bindings, std::uint32_t(material)).first->second;
    }
    return result;
}

const wgpu::Texture* MaterialResources::texture(scene::ImageId image, ColorSpace space) const {
    if (image.index() >= mImageTextures.size()) {
        return nullptr;
    }
    const ImageTextures& textures = mImageTextures[image.index()];
    const std::size_t index = space == ColorSpace::Srgb ? textures.srgb : textures.linear;
    return index == kNone ? nullptr : &mTextures[index];
}

const wgpu::Sampler& MaterialResources::sampler(scene::SamplerId sampler) const {
    assert(sampler.index() < mSceneSamplers.size());
    return mSamplers[mSceneSamplers[sampler.index()]];
}

bool MaterialResources::textured(scene::MaterialId material) const {
    assert(material.index() < mTextured.size());
    return mTextured[material.index()];
}

bool MaterialResources::samplesThroughPalette(scene::MaterialId material) const {
    assert(material.index() < mMaterialSamplerEntries.size());
    const SlotSamplerEntries& entries = mMaterialSamplerEntries[material.index()];
    return std::any_of(entries.begin(), entries.end(), [](std::uint32_t e) { return e != 0; });
}

std::uint32_t MaterialResources::texturedSlots(std::size_t material) const {
    std::uint32_t bits = 0;
    for (std::size_t slot = 0; slot < kMaterialTextureSlotCount; ++slot) {
        if (mMaterialTextures[material][slot] != kDefaultTexture) {
            bits |= 1u << slot;
        }
    }
    return bits;
}

bool MaterialResources::usesDefaultBaseColor(scene::MaterialId material) const {
    assert(material.index() < mMaterialTextures.size());
    return mMaterialTextures[material.index()][std::size_t(TextureSlot::BaseColor)] ==
           kDefaultTexture;
}

}  // namespace encore::render
