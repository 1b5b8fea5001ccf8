#include "shaders/ShaderLibrary.h"

#include <cstring>
#include <functional>
#include <string_view>

#include "shaders/ShaderComposer.h"

namespace encore::shaders {

std::set<std::string, std::less<>> ShaderVariantKey::flags() const {
    std::set<std::string, std::less<>> result;
    if (instanceSource != InstanceSource::NodeUniform) {
        result.insert("INSTANCE_STORAGE");
    }
    if (instanceSource == InstanceSource::VisibleList) {
        result.insert("VISIBLE_LIST");
    }
    if (materials) {
        result.insert("MATERIALS");
    }
    if (hasTexcoord) {
        result.insert("HAS_TEXCOORD");
    }
    if (hasColor) {
        result.insert("HAS_COLOR");
    }
    if (alphaMask) {
        result.insert("ALPHA_MASK");
    }
    if (hasTexcoord1) {
        result.insert("HAS_TEXCOORD1");
    }
    if (materials && materialTextures) {
        result.insert("MATERIAL_TEXTURES");
    }
    if (hasTangent) {
        result.insert("HAS_TANGENT");
    }
    if (skinned) {
        result.insert("SKINNED");
    }
    if (skinned && skinned8) {
        result.insert("SKINNED_8");
    }
    if (morphed) {
        result.insert("MORPHED");
    }
    if (materials && materialExtensions) {
        result.insert("MATERIAL_EXTENSIONS");
    }
    if (materials && materialTextures && samplerPalette) {
        result.insert("SAMPLER_PALETTE");
    }
    if (animated()) {
        result.insert("ANIMATED");
    }
    if (materials && passTargets != 0) {
        result.insert("PASS_TARGETS");
        if (passTargets == 2) {
            result.insert("SEGMENT_BY_MESH");
        } else if (passTargets == 3) {
            result.insert("SEGMENT_BY_MATERIAL");
        }
    }
    return result;
}

std::string ShaderVariantKey::describe() const {
    std::string text;
    for (const auto& flag : flags()) {
        text += text.empty() ? flag : " " + flag;
    }
    return text.empty() ? "(no flags)" : text;
}

std::size_t ShaderVariantKeyHash::operator()(const ShaderVariantKey& key) const noexcept {
    static_assert(sizeof(ShaderVariantKey) == 16, "keep ShaderVariantKey padded and small");
    return std::hash<std::string_view>{}(
        std::string_view(reinterpret_cast<const char*>(&key), sizeof(key)));
}

namespace {

wgpu::ShaderModule createModule(const wgpu::Device& device,
                                const std::string& source,
                                const std::string& label) {
    wgpu::ShaderSourceWGSL wgsl;
    wgsl.code = source.c_str();
    wgpu::ShaderModuleDescriptor descriptor{};
    descriptor.nextInChain = &wgsl;
    descriptor.label = label.c_str();
    return device.CreateShaderModule(&descriptor);
}

}  // namespace

Result<wgpu::ShaderModule> ShaderLibrary::meshModule(const ShaderVariantKey& key) {
    if (auto found = mMeshModules.find(key); found != mMeshModules.end()) {
        return found->second;
    }
    ENCORE_TRY_ASSIGN(auto source, composeEmbeddedShader("mesh.wgsl", key.flags()));
    auto module = createModule(mDevice, source, "mesh.wgsl " + key.describe());
    mMeshModules.emplace(key, module);
    return module;
}

Result<wgpu::ShaderModule> ShaderLibrary::module(const std::string& fileName,
                                                 const std::set<std::string, std::less<>>& flags) {
    std::string cacheKey = fileName;
    for (const auto& flag : flags) {
        cacheKey += " " + flag;
    }
    if (auto found = mOtherModules.find(cacheKey); found != mOtherModules.end()) {
        return found->second;
    }
    ENCORE_TRY_ASSIGN(auto source, composeEmbeddedShader(fileName, flags));
    auto module = createModule(mDevice, source, cacheKey);
    mOtherModules.emplace(cacheKey, module);
    return module;
}

}  // namespace encore::shaders
