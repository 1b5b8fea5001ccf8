#include "encore/render/MaterialResources.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <chrono>
#include <cstring>
#include <optional>
#include <string>
#include <tuple>
#include <utility>

#include "FittedImage.h"
#include "MipmapGenerator.h"
#include "encore/core/Elapsed.h"
#include "encore/gpu/Upload.h"
#include "encore/render/GltfToWebGpu.h"
#include "encore/render/StagedImages.h"

namespace encore::render {

namespace {

constexpr std::uint64_t kUniformSize = sizeof(MaterialUniform);
// RenderAttachment for the mip generator's passes; CopySrc so tests and tools can read any
// level back (it costs nothing on the drivers Encore targets).
constexpr wgpu::TextureUsage kTextureUsage =
    wgpu::TextureUsage::TextureBinding | wgpu::TextureUsage::CopyDst |
    wgpu::TextureUsage::RenderAttachment | wgpu::TextureUsage::CopySrc;

std::string describeImage(scene::ImageId id, const scene::Image& image) {
    if (!id.valid()) {
        return "Image '" + image.name + "'";  // A replacement, not one of the scene's images.
    }
    return "Image " + std::to_string(id.value) + " ('" + image.name + "')";
}

std::string describeMaterial(scene::MaterialId id, const scene::Material& material) {
    return "Material " + std::to_string(id.value) + " ('" + material.name + "')";
}

wgpu::SamplerDescriptor samplerDescriptor(const scene::Sampler& sampler) {
    wgpu::SamplerDescriptor descriptor{};
    descriptor.addressModeU = addressMode(sampler.wrapS);
    descriptor.addressModeV = addressMode(sampler.wrapT);
    descriptor.addressModeW = wgpu::AddressMode::Repeat;
    descriptor.magFilter = filterMode(sampler.magFilter);
    descriptor.minFilter = filterMode(sampler.minFilter);
    descriptor.mipmapFilter = mipmapFilterMode(sampler.mipmapFilter);
    if (!sampler.useMipmaps) {
        // glTF's minFilter NEAREST/LINEAR means "no mipmaps": pin sampling to level 0.
        descriptor.mipmapFilter = wgpu::MipmapFilterMode::Nearest;
        descriptor.lodMaxClamp = 0.0f;
    }
    descriptor.maxAnisotropy = 1;
    return descriptor;
}

bool sameSampler(const wgpu::SamplerDescriptor& a, const wgpu::SamplerDescriptor& b) {
    return a.addressModeU == b.addressModeU && a.addressModeV == b.addressModeV &&
           a.magFilter == b.magFilter && a.minFilter == b.minFilter &&
           a.mipmapFilter == b.mipmapFilter && a.lodMaxClamp == b.lodMaxClamp;
}

}  // namespace

// Creation state that the finished MaterialResources does not keep.
struct MaterialResources::Builder {
    const wgpu::Device& device;
    const wgpu::Queue& queue;
    const scene::SceneData& scene;
    MaterialResources& out;
    MipmapGenerator& mipmaps;
    wgpu::CommandEncoder encoder;
    StagedImages* staged = nullptr;
    std::uint32_t maxDimension = 8192;

    std::size_t addTexture(const std::string& label,
                           std::uint32_t width,
                           std::uint32_t height,
                           wgpu::TextureFormat format,
                           const std::uint8_t* pixels,
                           const wgpu::TexelCopyBufferInfo* stagedPixels = nullptr) {
        wgpu::TextureDescriptor descriptor{};
        descriptor.label = label.c_str();
        descriptor.usage = kTextureUsage;
        descriptor.dimension = wgpu::TextureDimension::e2D;
        descriptor.size = {width, height, 1};
        descriptor.format = format;
        descriptor.mipLevelCount = fullMipLevelCount(width, height);
        auto start = std::chrono::steady_clock::now();
        wgpu::Texture texture = device.CreateTexture(&descriptor);
        out.mUploadTimes.creation += millisecondsSince(start);
        start = std::chrono::steady_clock::now();

        wgpu::TexelCopyTextureInfo destination{};
        destination.texture = texture;
        wgpu::TexelCopyBufferLayout layout{};
        layout.bytesPerRow = width * 4;
        layout.rowsPerImage = height;
        const wgpu::Extent3D extent{width, height, 1};
        if (stagedPixels) {
            // Before the mip passes that read it, in the same command buffer.
            encoder.CopyBufferToTexture(stagedPixels, &destination, &extent);
        } else {
            queue.WriteTexture(&destination, pixels, std::size_t(width) * height * 4, &layout,
                               &extent);
        }
        out.mUploadTimes.writes += millisecondsSince(start);
        out.mUploadedBytes += std::uint64_t(width) * height * 4;
        out.mTextures.push_back(std::move(texture));
        return out.mTextures.size() - 1;
    }

    // The texture of `image` in `space`, created on first use; kNone when the image has no
    // pixels (the loader already warned about it).
    Result<std::size_t> imageTexture(scene::ImageId id, ColorSpace space) {
        if (!id.valid()) {
            return kNone;
        }
        if (id.index() >= scene.images.size()) {
            return makeError(ErrorCode::InvalidArgument, "Image " + std::to_string(id.value) +
                                                             " does not exist (the scene has " +
                                                             std::to_string(scene.images.size()) +
                                                             " images).");
        }
        ImageTextures& textures = out.mImageTextures[id.index()];
        std::size_t& slot = space == ColorSpace::Srgb ? textures.srgb : textures.linear;
        if (slot != kNone) {
            return slot;
        }
        auto uploaded = uploadImage(id, scene.images[id.index()], space);
        if (uploaded) {
            slot = *uploaded;
        }
        return uploaded;
    }

    // Validates and uploads one image with its mip chain; kNone when it has no pixels.
    Result<std::size_t> uploadImage(scene::ImageId id, const scene::Image& image,
                                    ColorSpace space) {
        if (image.rgba8.empty() || image.width == 0 || image.height == 0) {
            return kNone;
        }
        const std::uint64_t expected = std::uint64_t(image.width) * image.height * 4;
        if (image.rgba8.size() != expected) {
            return makeError(ErrorCode::InvalidArgument,
                             describeImage(id, image) + " has " +
                                 std::to_string(image.rgba8.size()) + " bytes of pixels (" +
                                 std::to_string(image.width) + "x" + std::to_string(image.height) +
                                 " RGBA8 needs " + std::to_string(expected) + ").");
        }
        const bool srgb = space == ColorSpace::Srgb;
        const FittedImage fitted = fitImage(describeImage(id, image), image, srgb, maxDimension);
        // Staged images hold the original pixels: a downscaled one is written instead.
        const auto waitStart = std::chrono::steady_clock::now();
        const std::optional<wgpu::TexelCopyBufferInfo> stagedPixels =
            staged && fitted.downscaled.empty() ? staged->copySource(id) : std::nullopt;
        out.mUploadTimes.writes += millisecondsSince(waitStart);
        const std::size_t index = addTexture(
            image.name + (srgb ? " (sRGB)" : " (linear)"), fitted.size.width, fitted.size.height,
            srgb ? wgpu::TextureFormat::RGBA8UnormSrgb : wgpu::TextureFormat::RGBA8Unorm,
            fitted.pixels(), stagedPixels ? &*stagedPixels : nullptr);
        const auto start = std::chrono::steady_clock::now();
        ENCORE_TRY(mipmaps.generate(encoder, out.mTextures[index]));
        out.mUploadTimes.mipmaps += millisecondsSince(start);
        return index;
    }

    // The texture a texture reference binds, validating the reference on the way.
    Result<std::size_t> referencedTexture(scene::MaterialId materialId,
                                          const std::optional<scene::TextureRef>& ref,
                                          ColorSpace space) {
        if (!ref) {
            return kNone;
        }
        if (ref->texture.index() >= scene.textures.size()) {
            return makeError(ErrorCode::InvalidArgument,
                             describeMaterial(materialId, scene.materials[materialId.index()]) +
                                 " references texture " + std::to_string(ref->texture.value) +
                                 ", but the scene has " + std::to_string(scene.textures.size()) +
                                 " textures.");
        }
        auto texture = imageTexture(scene.textures[ref->texture.index()].image, space);
        if (!texture) {
            return texture.error().withContext(
                describeMaterial(materialId, scene.materials[materialId.index()]));
        }
        return texture;
    }

    // One wgpu::Sampler per distinct state; scene samplers with equal state share it.
    std::size_t addSampler(const scene::Sampler& sampler, const std::string& label) {
        const wgpu::SamplerDescriptor wanted = samplerDescriptor(sampler);
        for (std::size_t i = 0; i < descriptors.size(); ++i) {
            if (sameSampler(descriptors[i], wanted)) {
                return i;
            }
        }
        wgpu::SamplerDescriptor labelled = wanted;
        labelled.label = label.c_str();
        out.mSamplers.push_back(device.CreateSampler(&labelled));
        descriptors.push_back(wanted);
        return out.mSamplers.size() - 1;
    }

    std::vector<wgpu::SamplerDescriptor> descriptors;  // Parallel to out.mSamplers, unlabelled.
};

Result<MaterialResources> MaterialResources::create(const wgpu::Device& device,
                                                    const wgpu::Queue& queue,
                                                    shaders::ShaderLibrary& shaders,
                                                    const BindGroupLayouts& layouts,
                                                    const scene::SceneData& scene,
                                                    const SampledTextures& sampled,
                                                    std::uint32_t maxTextureDimension,
                                                    MipmapGenerator* mipmaps,
                                                    StagedImages* staged) {
    std::optional<MipmapGenerator> ownMipmaps;
    if (!mipmaps) {
        auto created = MipmapGenerator::create(device, shaders);
        if (!created) {
            return created.error();
        }
        mipmaps = &ownMipmaps.emplace(std::move(*created));
    }
    wgpu::Limits limits{};
    device.GetLimits(&limits);

    MaterialResources resources;
    resources.mImageTextures.resize(scene.images.size());
    Builder builder{device, queue, scene, resources, *mipmaps, device.CreateCommandEncoder(),
                    staged};
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

    // Align each material's range to what a uniform binding offset needs (256 by default).
    const std::uint64_t alignment =
        std::max<std::uint64_t>(limits.minUniformBufferOffsetAlignment, 4);
    resources.mUniformStride = (kUniformSize + alignment - 1) / alignment * alignment;
    const std::size_t materialCount = scene.materials.size();
    std::vector<std::uint8_t> uniformBytes(resources.mUniformStride *
                                           std::max<std::size_t>(materialCount, 1));
    resources.mUniforms = gpu::createBuffer(
        device,
        wgpu::BufferUsage::Uniform | wgpu::BufferUsage::CopyDst | wgpu::BufferUsage::CopySrc,
        uniformBytes.size(), "material uniforms");

    resources.mBindGroups.reserve(materialCount);
    for (std::size_t i = 0; i < materialCount; ++i) {
        const scene::MaterialId id{i};
        const scene::Material& material = scene.materials[i];
        SlotIndices textures;
        SlotIndices samplers;
        textures.fill(kDefaultTexture);
        samplers.fill(defaultSampler);
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
            auto uploaded = builder.referencedTexture(id, ref, slotColorSpace(material, slot.slot));
            if (!uploaded) {
                return uploaded.error();
            }
            if (*uploaded == kNone) {
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
            textures[slotIndex] = *uploaded;
            if (texture.sampler.valid()) {
                samplers[slotIndex] = resources.mSceneSamplers[texture.sampler.index()];
            }
        }
        resources.mMaterialTextures.push_back(textures);
        resources.mMaterialSamplers.push_back(samplers);
        resources.mTextured.push_back(std::any_of(textures.begin(), textures.end(),
                                                  [](std::size_t t) { return t != kDefaultTexture; }));

        const MaterialUniform uniform = makeMaterialUniform(material);
        std::memcpy(uniformBytes.data() + i * resources.mUniformStride, &uniform, kUniformSize);

        resources.mBindGroups.push_back(resources.createBindGroup(
            device, layouts, i, material.name.empty() ? "material" : material.name.c_str()));
    }
    queue.WriteBuffer(resources.mUniforms, 0, uniformBytes.data(), uniformBytes.size());

    const auto submitStart = std::chrono::steady_clock::now();
    wgpu::CommandBuffer commands = builder.encoder.Finish();
    queue.Submit(1, &commands);
    resources.mUploadTimes.submit += millisecondsSince(submitStart);
    return resources;
}

wgpu::BindGroup MaterialResources::createBindGroup(const wgpu::Device& device,
                                                   const BindGroupLayouts& layouts,
                                                   std::size_t material, const char* label) const {
    std::array<wgpu::BindGroupEntry, 1 + 2 * kMaterialTextureSlotCount> entries{};
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
    for (std::uint32_t slot = 0; slot < kMaterialTextureSlotCount; ++slot) {
        wgpu::BindGroupEntry& sampler = entries[1 + 2 * slot];
        sampler.binding = materialSamplerBinding(slot);
        sampler.sampler = mSamplers[mMaterialSamplers[material][slot]];
        wgpu::BindGroupEntry& texture = entries[2 + 2 * slot];
        texture.binding = materialTextureBinding(slot);
        texture.textureView = mTextures[mMaterialTextures[material][slot]].CreateView();
    }
    descriptor.layout = layouts.material;
    descriptor.entryCount = entries.size();
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
    auto mipmaps = MipmapGenerator::create(device, shaders);
    if (!mipmaps) {
        return mipmaps.error();
    }
    const scene::SceneData noScene;
    wgpu::Limits limits{};
    device.GetLimits(&limits);
    Builder builder{device, queue, noScene, *this, *mipmaps, device.CreateCommandEncoder()};
    builder.maxDimension = limits.maxTextureDimension2D;
    auto uploaded = builder.uploadImage(scene::ImageId{}, image, ColorSpace::Srgb);
    if (!uploaded) {
        return uploaded.error().withContext("Replacing the base colour image of material " +
                                            std::to_string(material.value));
    }
    if (*uploaded == kNone) {
        return makeError(ErrorCode::InvalidArgument,
                         "The replacement image for material " + std::to_string(material.value) +
                             " has no pixels.");
    }
    wgpu::CommandBuffer commands = builder.encoder.Finish();
    queue.Submit(1, &commands);

    constexpr std::size_t kBaseColor = std::size_t(TextureSlot::BaseColor);
    const std::size_t old = mMaterialTextures[material.index()][kBaseColor];
    mMaterialTextures[material.index()][kBaseColor] = *uploaded;
    mTextured[material.index()] = true;
    mBindGroups[material.index()] =
        createBindGroup(device, layouts, material.index(), "material (replaced texture)");
    ++mGeneration;

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

void MaterialResources::updateMaterial(const wgpu::Queue& queue,
                                       scene::MaterialId material,
                                       const scene::Material& values) {
    assert(material.index() < mBindGroups.size());
    const MaterialUniform uniform = makeMaterialUniform(values);
    queue.WriteBuffer(mUniforms, material.index() * mUniformStride, &uniform, kUniformSize);
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

bool MaterialResources::usesDefaultBaseColor(scene::MaterialId material) const {
    assert(material.index() < mMaterialTextures.size());
    return mMaterialTextures[material.index()][std::size_t(TextureSlot::BaseColor)] ==
           kDefaultTexture;
}

}  // namespace encore::render
