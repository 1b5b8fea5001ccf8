#include "render/Environment.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>
#include <numbers>
#include <string>
#include <thread>
#include <vector>

#include "core/Elapsed.h"
#include "core/Log.h"
#include "gpu/BindingResource.h"
#include "image/ImageResize.h"
#include "render/MipChain.h"

namespace encore::render {

namespace {

constexpr std::uint32_t kWorkgroupSize = 8;  // @workgroup_size(8, 8, 1) in every shader.
constexpr std::uint32_t kCubeFaces = 6;
// Uniform slots of one build, one per dispatch that takes parameters; 256 bytes apart to meet
// minUniformBufferOffsetAlignment.
constexpr std::uint64_t kSlotStride = 256;
// The LUT depends on no panorama; it is integrated once, with enough samples that the table is
// smooth without filtered importance sampling (it has no texture to filter).
constexpr std::uint32_t kLutSamples = 1024;

// Mirrors the Params structs of environment_specular.wgsl and environment_irradiance.wgsl.
struct CubeParams {
    std::uint32_t face = 0;
    std::uint32_t sampleCount = 0;
    float roughness = 0.0f;
    float sourceTexelSolidAngle = 0.0f;
    float sourceMaxLod = 0.0f;
    std::uint32_t padding[3] = {};
};

// Mirrors the Params struct of environment_atlas_pack.wgsl.
struct PackParams {
    std::uint32_t origin[2] = {};
    std::uint32_t size = 0;
    float level = 0.0f;
};

std::string sizeText(std::uint32_t width, std::uint32_t height) {
    return std::to_string(width) + "x" + std::to_string(height);
}

// Radiance is finite and non-negative: NaN and negatives become 0, and values beyond the
// largest half (65504) clamp to it rather than turning into infinity. Rounds to nearest even.
std::uint16_t toHalf(float value) {
    if (!(value > 0.0f)) {
        return 0;
    }
    const std::uint32_t bits = std::bit_cast<std::uint32_t>(std::min(value, 65504.0f));
    const int exponent = static_cast<int>((bits >> 23) & 0xff) - 127 + 15;
    std::uint32_t mantissa = bits & 0x7fffff;
    auto roundShifted = [](std::uint32_t value, int shift) {
        std::uint32_t shifted = value >> shift;
        const std::uint32_t remainder = value & ((1u << shift) - 1);
        const std::uint32_t halfway = 1u << (shift - 1);
        if (remainder > halfway || (remainder == halfway && (shifted & 1))) {
            ++shifted;  // A carry into the exponent is the correct result.
        }
        return shifted;
    };
    if (exponent <= 0) {  // A subnormal half, or zero.
        if (exponent < -10) {
            return 0;
        }
        mantissa |= 0x800000;
        return static_cast<std::uint16_t>(roundShifted(mantissa, 14 - exponent));
    }
    return static_cast<std::uint16_t>((std::uint32_t(exponent) << 10) + roundShifted(mantissa, 13));
}

// Waits for a future. Instances without TimedWaitAny refuse a timeout, so poll them instead.
bool waitFor(const wgpu::Instance& instance, const wgpu::Future& future) {
    wgpu::WaitStatus status = instance.WaitAny(future, UINT64_MAX);
    while (status != wgpu::WaitStatus::Success) {
        status = instance.WaitAny(future, 0);
        if (status == wgpu::WaitStatus::Error) {
            return false;
        }
        if (status == wgpu::WaitStatus::TimedOut) {
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        }
    }
    return true;
}

wgpu::Texture createCube(const wgpu::Device& device,
                         const char* label,
                         std::uint32_t size,
                         std::uint32_t levels) {
    wgpu::TextureDescriptor descriptor{};
    descriptor.label = label;
    descriptor.size = {size, size, kCubeFaces};
    descriptor.mipLevelCount = levels;
    descriptor.format = Environment::kCubeFormat;
    descriptor.usage = wgpu::TextureUsage::TextureBinding | wgpu::TextureUsage::StorageBinding |
                       wgpu::TextureUsage::CopySrc | wgpu::TextureUsage::CopyDst;
    return device.CreateTexture(&descriptor);
}

wgpu::TextureView cubeView(const wgpu::Texture& texture) {
    wgpu::TextureViewDescriptor descriptor{};
    descriptor.dimension = wgpu::TextureViewDimension::Cube;
    descriptor.arrayLayerCount = kCubeFaces;
    return texture.CreateView(&descriptor);
}

// The six faces of one level, as the compute shaders read and write them.
wgpu::TextureView levelView(const wgpu::Texture& texture, std::uint32_t level) {
    wgpu::TextureViewDescriptor descriptor{};
    descriptor.dimension = wgpu::TextureViewDimension::e2DArray;
    descriptor.baseMipLevel = level;
    descriptor.mipLevelCount = 1;
    descriptor.arrayLayerCount = kCubeFaces;
    return texture.CreateView(&descriptor);
}

template <typename Params = CubeParams>
gpu::BindingResource slotResource(std::uint32_t binding,
                                  const wgpu::Buffer& buffer,
                                  std::uint32_t slot) {
    return {binding, buffer, slot * kSlotStride, sizeof(Params)};
}

wgpu::BindGroup bindGroup(const wgpu::Device& device,
                          const wgpu::ComputePipeline& pipeline,
                          std::initializer_list<gpu::BindingResource> resources) {
    return gpu::makeBindGroup(device, pipeline.GetBindGroupLayout(0), resources);
}

std::uint32_t groups(std::uint32_t size) {
    return (size + kWorkgroupSize - 1) / kWorkgroupSize;
}

Result<void> checkOptions(const EnvironmentOptions& options, const wgpu::Limits& limits) {
    auto invalid = [](const std::string& message) {
        return makeError(ErrorCode::InvalidArgument, "Environment options: " + message);
    };
    const std::uint32_t largestCube = limits.maxTextureDimension2D;
    for (auto [name, size] : {std::pair{"specularSize", options.specularSize},
                              std::pair{"irradianceSize", options.irradianceSize},
                              std::pair{"lutSize", options.lutSize}}) {
        if (size == 0 || size > largestCube) {
            return invalid(std::string(name) + " (" + std::to_string(size) + ") must be in 1.." +
                           std::to_string(largestCube) + ".");
        }
    }
    const std::uint32_t fullChain = fullMipLevelCount(options.specularSize, options.specularSize);
    if (options.specularLevels == 0 || options.specularLevels > fullChain) {
        return invalid("specularLevels (" + std::to_string(options.specularLevels) +
                       ") must be in 1.." + std::to_string(fullChain) + " for specularSize " +
                       std::to_string(options.specularSize) + ".");
    }
    if (options.specularLevels > EnvironmentAtlasLayout::kMaxSpecularLevels) {
        return invalid("specularLevels (" + std::to_string(options.specularLevels) +
                       ") must be at most " +
                       std::to_string(EnvironmentAtlasLayout::kMaxSpecularLevels) + ".");
    }
    const EnvironmentAtlasLayout atlas = layoutEnvironmentAtlas(
        options.specularSize, options.specularLevels, options.irradianceSize, options.lutSize);
    if (atlas.width > limits.maxTextureDimension2D || atlas.height > limits.maxTextureDimension2D) {
        return invalid(
            "the environment atlas for specularSize " + std::to_string(options.specularSize) +
            " would be " + sizeText(atlas.width, atlas.height) + ", larger than the device's " +
            "maxTextureDimension2D (" + std::to_string(limits.maxTextureDimension2D) + ").");
    }
    if (options.specularSamples == 0 || options.irradianceSamples == 0) {
        return invalid("sample counts must be positive (specularSamples " +
                       std::to_string(options.specularSamples) + ", irradianceSamples " +
                       std::to_string(options.irradianceSamples) + ").");
    }
    return {};
}

Result<void> checkPanorama(const image::HdrImage& panorama) {
    if (panorama.width == 0 || panorama.height == 0 ||
        panorama.rgb.size() != std::size_t(panorama.width) * panorama.height * 3) {
        return makeError(ErrorCode::InvalidArgument,
                         "The environment panorama is empty or inconsistent (" +
                             sizeText(panorama.width, panorama.height) + ", " +
                             std::to_string(panorama.rgb.size()) + " floats).");
    }
    return {};
}

// Larger than a texture can be: box-filtered down (ImageResize.h), as material images are.
// Empty when `original` fits within `largest`.
image::HdrImage downscaledToFit(const image::HdrImage& original, std::uint32_t largest) {
    image::HdrImage downscaled;
    const image::ImageSize fitted = image::fitWithin({original.width, original.height}, largest);
    if (fitted.width != original.width || fitted.height != original.height) {
        downscaled = {
            fitted.width, fitted.height,
            image::downscaleRgbFloat(original.rgb, {original.width, original.height}, fitted)};
        logWarning("The environment panorama is " + sizeText(original.width, original.height) +
                   ", larger than the device's maxTextureDimension2D (" + std::to_string(largest) +
                   "); downscaled to " + sizeText(fitted.width, fitted.height) + ".");
    }
    return downscaled;
}

// rgba32float is not filterable in core WebGPU; half floats are, and keep 11 bits of
// mantissa, more than RGBE's 8.
std::vector<std::uint16_t> halfRgba(const image::HdrImage& panorama) {
    std::vector<std::uint16_t> halves(std::size_t(panorama.width) * panorama.height * 4);
    for (std::size_t i = 0, j = 0; i < panorama.rgb.size(); i += 3, j += 4) {
        halves[j] = toHalf(panorama.rgb[i]);
        halves[j + 1] = toHalf(panorama.rgb[i + 1]);
        halves[j + 2] = toHalf(panorama.rgb[i + 2]);
        halves[j + 3] = toHalf(1.0f);
    }
    return halves;
}

// The specular levels' faces (from level 1), then the irradiance faces, then the LUT.
std::vector<CubeParams> cubeParams(const EnvironmentOptions& options,
                                   std::uint32_t sourceSize,
                                   std::uint32_t sourceLevels) {
    const float texelSolidAngle =
        4.0f * std::numbers::pi_v<float> / (6.0f * float(sourceSize) * float(sourceSize));
    std::vector<CubeParams> params;
    for (std::uint32_t level = 1; level < options.specularLevels; ++level) {
        for (std::uint32_t face = 0; face < kCubeFaces; ++face) {
            params.push_back({face, options.specularSamples,
                              float(level) / float(options.specularLevels - 1), texelSolidAngle,
                              float(sourceLevels - 1)});
        }
    }
    for (std::uint32_t face = 0; face < kCubeFaces; ++face) {
        params.push_back(
            {face, options.irradianceSamples, 0.0f, texelSolidAngle, float(sourceLevels - 1)});
    }
    params.push_back({0, kLutSamples});
    return params;
}

// The atlas regions: the specular levels, the irradiance, the table.
std::vector<PackParams> packParams(const EnvironmentOptions& options,
                                   const EnvironmentAtlasLayout& atlas) {
    std::vector<PackParams> packs;
    for (std::uint32_t level = 0; level < options.specularLevels; ++level) {
        const AtlasRegion& region = atlas.specular[level];
        packs.push_back({{region.x, region.y}, region.size, float(level)});
    }
    packs.push_back({{atlas.irradiance.x, atlas.irradiance.y}, atlas.irradiance.size, 0.0f});
    packs.push_back({{atlas.brdf.x, atlas.brdf.y}, atlas.brdf.size, 0.0f});
    return packs;
}

// Pops the two error scopes build() pushed (their errors come back as one value), then waits
// for the GPU.
Result<void> popErrorScopesAndWait(const wgpu::Device& device, const wgpu::Queue& queue) {
    const wgpu::Instance instance = device.GetAdapter().GetInstance();
    std::string errors;
    bool outOfMemory = false;
    auto collect = [&errors, &outOfMemory](wgpu::PopErrorScopeStatus, wgpu::ErrorType type,
                                           wgpu::StringView message) {
        outOfMemory |= type == wgpu::ErrorType::OutOfMemory;
        if (type != wgpu::ErrorType::NoError) {
            errors += (errors.empty() ? "" : "; ") + std::string(std::string_view(message));
        }
    };
    const bool popped =
        waitFor(instance, device.PopErrorScope(wgpu::CallbackMode::WaitAnyOnly, collect)) &&
        waitFor(instance, device.PopErrorScope(wgpu::CallbackMode::WaitAnyOnly, collect));
    // The build time includes the GPU's work: wait until it has finished.
    bool done = false;
    const bool waited = waitFor(
        instance,
        queue.OnSubmittedWorkDone(wgpu::CallbackMode::WaitAnyOnly,
                                  [&done](wgpu::QueueWorkDoneStatus status, wgpu::StringView) {
                                      done = status == wgpu::QueueWorkDoneStatus::Success;
                                  }));
    if (!errors.empty()) {
        return makeError(outOfMemory ? ErrorCode::OutOfMemory : ErrorCode::ValidationError,
                         "Computing the environment maps failed (" + errors + ").");
    }
    if (!popped || !waited || !done) {
        return makeError(ErrorCode::DeviceError,
                         "Waiting for the environment maps failed (the device may be lost).");
    }
    return {};
}

}  // namespace

struct Environment::Pipelines {
    wgpu::ComputePipeline panorama;
    wgpu::ComputePipeline downsample;
    wgpu::ComputePipeline specular;
    wgpu::ComputePipeline irradiance;
    wgpu::ComputePipeline lut;
    wgpu::ComputePipeline packCube;
    wgpu::ComputePipeline packTable;
    wgpu::Sampler panoramaSampler;  // Repeats across the longitude seam.
};

Result<Environment> Environment::create(const wgpu::Device& device,
                                        const wgpu::Queue& queue,
                                        shaders::ShaderLibrary& shaders,
                                        const image::HdrImage& panorama,
                                        const EnvironmentOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    wgpu::Limits limits{};
    device.GetLimits(&limits);
    ENCORE_TRY(checkOptions(options, limits));

    Environment environment;
    environment.mDevice = device;
    environment.mQueue = queue;
    environment.mShaders = &shaders;
    environment.mOptions = options;

    auto pipelines = std::make_shared<Pipelines>();
    auto computePipeline = [&](const char* file, wgpu::ComputePipeline& out,
                               const char* entryPoint = "main") -> Result<void> {
        auto module = shaders.module(file);
        if (!module) {
            return module.error().withContext("Creating the environment pipelines");
        }
        wgpu::ComputePipelineDescriptor descriptor{};
        descriptor.label = file;
        descriptor.compute.module = *module;
        descriptor.compute.entryPoint = entryPoint;
        out = device.CreateComputePipeline(&descriptor);
        return {};
    };
    ENCORE_TRY(computePipeline("environment_panorama.wgsl", pipelines->panorama));
    ENCORE_TRY(computePipeline("environment_downsample.wgsl", pipelines->downsample));
    ENCORE_TRY(computePipeline("environment_specular.wgsl", pipelines->specular));
    ENCORE_TRY(computePipeline("environment_irradiance.wgsl", pipelines->irradiance));
    ENCORE_TRY(computePipeline("environment_brdf_lut.wgsl", pipelines->lut));
    ENCORE_TRY(computePipeline("environment_atlas_pack.wgsl", pipelines->packCube, "packCube"));
    ENCORE_TRY(computePipeline("environment_atlas_pack.wgsl", pipelines->packTable, "packTable"));

    wgpu::SamplerDescriptor panoramaSampler{};
    panoramaSampler.label = "environment panorama";
    panoramaSampler.addressModeU = wgpu::AddressMode::Repeat;
    panoramaSampler.addressModeV = wgpu::AddressMode::ClampToEdge;
    panoramaSampler.magFilter = wgpu::FilterMode::Linear;
    panoramaSampler.minFilter = wgpu::FilterMode::Linear;
    pipelines->panoramaSampler = device.CreateSampler(&panoramaSampler);
    environment.mPipelines = std::move(pipelines);

    environment.mSampler = makeLinearClampSampler(device, "environment");

    // The source has the specular cube's size so its level 0 is copied, not resampled, into
    // the mirror level.
    environment.mSource = createCube(device, "environment source", options.specularSize,
                                     fullMipLevelCount(options.specularSize, options.specularSize));
    environment.mSourceView = cubeView(environment.mSource);
    environment.mSpecular =
        createCube(device, "environment specular", options.specularSize, options.specularLevels);
    environment.mSpecularView = cubeView(environment.mSpecular);
    environment.mIrradiance =
        createCube(device, "environment irradiance", options.irradianceSize, 1);
    environment.mIrradianceView = cubeView(environment.mIrradiance);

    wgpu::TextureDescriptor lut{};
    lut.label = "environment BRDF LUT";
    lut.size = {options.lutSize, options.lutSize, 1};
    lut.format = wgpu::TextureFormat::RGBA16Float;
    lut.usage = wgpu::TextureUsage::TextureBinding | wgpu::TextureUsage::StorageBinding |
                wgpu::TextureUsage::CopySrc;
    environment.mLut = device.CreateTexture(&lut);
    environment.mLutView = environment.mLut.CreateView();

    environment.mAtlasLayout = layoutEnvironmentAtlas(options.specularSize, options.specularLevels,
                                                      options.irradianceSize, options.lutSize);
    wgpu::TextureDescriptor atlas{};
    atlas.label = "environment atlas";
    atlas.size = {environment.mAtlasLayout.width, environment.mAtlasLayout.height, 1};
    atlas.format = wgpu::TextureFormat::RGBA16Float;
    atlas.usage = wgpu::TextureUsage::TextureBinding | wgpu::TextureUsage::StorageBinding |
                  wgpu::TextureUsage::CopySrc;
    environment.mAtlas = device.CreateTexture(&atlas);
    environment.mAtlasView = environment.mAtlas.CreateView();

    ENCORE_TRY(environment.build(panorama, /*withLut=*/true));
    environment.mPanorama = std::make_shared<const image::HdrImage>(panorama);
    environment.mLastBuildMilliseconds = millisecondsSince(start);
    return environment;
}

Result<void> Environment::load(const image::HdrImage& panorama) {
    const auto start = std::chrono::steady_clock::now();
    ENCORE_TRY(build(panorama, /*withLut=*/false));  // The LUT depends on no panorama.
    mPanorama = std::make_shared<const image::HdrImage>(panorama);
    mLastBuildMilliseconds = millisecondsSince(start);
    return {};
}

// The uniform slots of one build's dispatches (kSlotStride apart), and where each kind starts:
// the specular levels' faces, the irradiance faces, the LUT, then the atlas regions.
struct Environment::ParameterSlots {
    wgpu::Buffer buffer;
    std::uint32_t firstIrradiance = 0;
    std::uint32_t lut = 0;
    std::uint32_t firstPack = 0;
    std::vector<PackParams> packs;  // Per atlas region, from slot firstPack.
};

Result<void> Environment::build(const image::HdrImage& original, bool withLut) {
    wgpu::Limits limits{};
    mDevice.GetLimits(&limits);
    ENCORE_TRY(checkPanorama(original));
    const image::HdrImage downscaled = downscaledToFit(original, limits.maxTextureDimension2D);
    const image::HdrImage& panorama = downscaled.rgb.empty() ? original : downscaled;
    // Everything below is validated in one scope so a mistake comes back as a value rather
    // than only through the device's uncaptured-error callback.
    mDevice.PushErrorScope(wgpu::ErrorFilter::OutOfMemory);
    mDevice.PushErrorScope(wgpu::ErrorFilter::Validation);

    const wgpu::Texture panoramaTexture = uploadPanorama(panorama);
    const ParameterSlots slots = writeParameters();
    const wgpu::CommandEncoder encoder = mDevice.CreateCommandEncoder();
    encodeMaps(encoder, panoramaTexture, slots, withLut);
    encodeAtlas(encoder, slots, withLut);
    const wgpu::CommandBuffer commands = encoder.Finish();
    mQueue.Submit(1, &commands);
    return popErrorScopesAndWait(mDevice, mQueue);
}

wgpu::Texture Environment::uploadPanorama(const image::HdrImage& panorama) const {
    const std::vector<std::uint16_t> halves = halfRgba(panorama);
    wgpu::TextureDescriptor panoramaDescriptor{};
    panoramaDescriptor.label = "environment panorama";
    panoramaDescriptor.size = {panorama.width, panorama.height, 1};
    panoramaDescriptor.format = wgpu::TextureFormat::RGBA16Float;
    panoramaDescriptor.usage = wgpu::TextureUsage::TextureBinding | wgpu::TextureUsage::CopyDst;
    const wgpu::Texture panoramaTexture = mDevice.CreateTexture(&panoramaDescriptor);
    wgpu::TexelCopyTextureInfo destination{};
    destination.texture = panoramaTexture;
    wgpu::TexelCopyBufferLayout layout{};
    layout.bytesPerRow = panorama.width * 8;
    layout.rowsPerImage = panorama.height;
    const wgpu::Extent3D panoramaExtent{panorama.width, panorama.height, 1};
    mQueue.WriteTexture(&destination, halves.data(), halves.size() * sizeof(std::uint16_t), &layout,
                        &panoramaExtent);
    return panoramaTexture;
}

Environment::ParameterSlots Environment::writeParameters() const {
    // Parameters of every dispatch that takes them, one uniform slot each.
    ParameterSlots slots;
    const std::vector<CubeParams> cubes =
        cubeParams(mOptions, mSource.GetWidth(), mSource.GetMipLevelCount());
    slots.firstIrradiance = (mOptions.specularLevels - 1) * kCubeFaces;
    slots.lut = slots.firstIrradiance + kCubeFaces;
    slots.packs = packParams(mOptions, mAtlasLayout);
    slots.firstPack = static_cast<std::uint32_t>(cubes.size());
    std::vector<std::uint8_t> slotBytes((cubes.size() + slots.packs.size()) * kSlotStride);
    for (std::size_t i = 0; i < cubes.size(); ++i) {
        std::memcpy(&slotBytes[i * kSlotStride], &cubes[i], sizeof(CubeParams));
    }
    for (std::size_t i = 0; i < slots.packs.size(); ++i) {
        std::memcpy(&slotBytes[(slots.firstPack + i) * kSlotStride], &slots.packs[i],
                    sizeof(PackParams));
    }
    wgpu::BufferDescriptor slotDescriptor{};
    slotDescriptor.label = "environment parameters";
    slotDescriptor.size = slotBytes.size();
    slotDescriptor.usage = wgpu::BufferUsage::Uniform | wgpu::BufferUsage::CopyDst;
    slots.buffer = mDevice.CreateBuffer(&slotDescriptor);
    mQueue.WriteBuffer(slots.buffer, 0, slotBytes.data(), slotBytes.size());
    return slots;
}

void Environment::encodeMaps(const wgpu::CommandEncoder& encoder,
                             const wgpu::Texture& panoramaTexture,
                             const ParameterSlots& slots,
                             bool withLut) const {
    const Pipelines& pipelines = *mPipelines;
    const std::uint32_t sourceLevels = mSource.GetMipLevelCount();
    const std::uint32_t sourceSize = mSource.GetWidth();
    wgpu::ComputePassDescriptor passDescriptor{};
    passDescriptor.label = "environment";
    const wgpu::ComputePassEncoder pass = encoder.BeginComputePass(&passDescriptor);
    // Each dispatch is its own usage scope, so a level written by one dispatch is read by the
    // next without further synchronisation; one face or level per dispatch keeps each short
    // (lavapipe runs a dispatch to completion before anything else).
    pass.SetPipeline(pipelines.panorama);
    pass.SetBindGroup(0, bindGroup(mDevice, pipelines.panorama,
                                   {{0, panoramaTexture.CreateView()},
                                    {1, pipelines.panoramaSampler},
                                    {2, levelView(mSource, 0)}}));
    pass.DispatchWorkgroups(groups(sourceSize), groups(sourceSize), kCubeFaces);

    pass.SetPipeline(pipelines.downsample);
    for (std::uint32_t level = 1; level < sourceLevels; ++level) {
        const std::uint32_t size = std::max(sourceSize >> level, 1u);
        pass.SetBindGroup(
            0, bindGroup(mDevice, pipelines.downsample,
                         {{0, levelView(mSource, level - 1)}, {1, levelView(mSource, level)}}));
        pass.DispatchWorkgroups(groups(size), groups(size), kCubeFaces);
    }

    pass.SetPipeline(pipelines.specular);
    for (std::uint32_t level = 1; level < mOptions.specularLevels; ++level) {
        const std::uint32_t size = std::max(mOptions.specularSize >> level, 1u);
        const wgpu::TextureView target = levelView(mSpecular, level);
        for (std::uint32_t face = 0; face < kCubeFaces; ++face) {
            const std::uint32_t slot = (level - 1) * kCubeFaces + face;
            pass.SetBindGroup(0, bindGroup(mDevice, pipelines.specular,
                                           {{0, mSourceView},
                                            {1, mSampler},
                                            {2, target},
                                            slotResource(3, slots.buffer, slot)}));
            pass.DispatchWorkgroups(groups(size), groups(size), 1);
        }
    }

    pass.SetPipeline(pipelines.irradiance);
    const wgpu::TextureView irradianceTarget = levelView(mIrradiance, 0);
    for (std::uint32_t face = 0; face < kCubeFaces; ++face) {
        pass.SetBindGroup(0,
                          bindGroup(mDevice, pipelines.irradiance,
                                    {{0, mSourceView},
                                     {1, mSampler},
                                     {2, irradianceTarget},
                                     slotResource(3, slots.buffer, slots.firstIrradiance + face)}));
        const std::uint32_t size = mOptions.irradianceSize;
        pass.DispatchWorkgroups(groups(size), groups(size), 1);
    }

    if (withLut) {
        pass.SetPipeline(pipelines.lut);
        pass.SetBindGroup(0, bindGroup(mDevice, pipelines.lut,
                                       {{0, mLutView}, slotResource(1, slots.buffer, slots.lut)}));
        pass.DispatchWorkgroups(groups(mOptions.lutSize), groups(mOptions.lutSize), 1);
    }
    pass.End();
}

void Environment::encodeAtlas(const wgpu::CommandEncoder& encoder,
                              const ParameterSlots& slots,
                              bool withLut) const {
    const Pipelines& pipelines = *mPipelines;
    // Roughness 0 is a mirror: the specular cube's level 0 is the source's.
    const std::uint32_t sourceSize = mSource.GetWidth();
    wgpu::TexelCopyTextureInfo copySource{};
    copySource.texture = mSource;
    wgpu::TexelCopyTextureInfo copyDestination{};
    copyDestination.texture = mSpecular;
    const wgpu::Extent3D faces{sourceSize, sourceSize, kCubeFaces};
    encoder.CopyTextureToTexture(&copySource, &copyDestination, &faces);

    // Everything the frame samples, into the atlas (after the copy: level 0 is packed too).
    wgpu::ComputePassDescriptor passDescriptor{};
    passDescriptor.label = "environment atlas";
    const wgpu::ComputePassEncoder packPass = encoder.BeginComputePass(&passDescriptor);
    packPass.SetPipeline(pipelines.packCube);
    for (std::uint32_t i = 0; i < mOptions.specularLevels + 1; ++i) {
        const bool irradiance = i == mOptions.specularLevels;
        const std::uint32_t span = slots.packs[i].size + 2;
        packPass.SetBindGroup(
            0, bindGroup(mDevice, pipelines.packCube,
                         {{0, irradiance ? mIrradianceView : mSpecularView},
                          {1, mSampler},
                          {2, mAtlasView},
                          slotResource<PackParams>(3, slots.buffer, slots.firstPack + i)}));
        packPass.DispatchWorkgroups(groups(3 * span), groups(2 * span), 1);
    }
    if (withLut) {
        packPass.SetPipeline(pipelines.packTable);
        const std::uint32_t slot = slots.firstPack + mOptions.specularLevels + 1;
        packPass.SetBindGroup(0, bindGroup(mDevice, pipelines.packTable,
                                           {{2, mAtlasView},
                                            slotResource<PackParams>(3, slots.buffer, slot),
                                            {4, mLutView}}));
        const std::uint32_t size = mAtlasLayout.brdf.size + 2;
        packPass.DispatchWorkgroups(groups(size), groups(size), 1);
    }
    packPass.End();
}

}  // namespace encore::render
