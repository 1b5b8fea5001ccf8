// Cross-reference and range checks that need the whole document: every index names an existing
// element, every bufferView lies inside its buffer. Later stages rely on these and index freely.

#include "scene/LoadContext.h"

namespace encore::scene {
namespace {

// Checks one reference; `from` is the referring element, `what` the kind of the target.
class ReferenceChecker {
  public:
    void check(const std::string& from,
               std::string_view kind,
               std::uint64_t index,
               std::size_t count,
               std::string_view role = {}) {
        if (mError || index < count) {
            return;
        }
        std::string message =
            from + " refers to " + std::string(kind) + " " + std::to_string(index);
        if (!role.empty()) {
            message += " (" + std::string(role) + ")";
        }
        message += ", but the asset has " + std::to_string(count) + " " + std::string(kind) +
                   (count == 1 ? "" : "s") + ".";
        mError = Error{ErrorCode::InvalidFormat, std::move(message)};
    }
    void check(const std::string& from,
               std::string_view kind,
               const std::optional<std::uint32_t>& index,
               std::size_t count,
               std::string_view role = {}) {
        if (index) {
            check(from, kind, *index, count, role);
        }
    }
    Result<void> result() const {
        if (mError) {
            return *mError;
        }
        return {};
    }

  private:
    std::optional<Error> mError;
};

}  // namespace

std::optional<std::uint64_t> mulAdd(std::uint64_t a, std::uint64_t b, std::uint64_t c) {
    std::uint64_t product = 0;
    std::uint64_t sum = 0;
    if (__builtin_mul_overflow(a, b, &product) || __builtin_add_overflow(product, c, &sum)) {
        return std::nullopt;
    }
    return sum;
}

namespace {

// Buffer views' buffers and accessors' views.
void checkDataReferences(const GltfDocument& document, ReferenceChecker& checker) {
    const std::size_t buffers = document.buffers.size();
    const std::size_t views = document.bufferViews.size();
    const std::size_t accessors = document.accessors.size();
    for (std::size_t i = 0; i < views; ++i) {
        const auto& view = document.bufferViews[i];
        const std::string name = "bufferView " + std::to_string(i);
        checker.check(name, "buffer", view.buffer, buffers);
        if (view.meshopt) {
            checker.check(name + " EXT_meshopt_compression", "buffer", view.meshopt->buffer,
                          buffers);
        }
    }
    for (std::size_t i = 0; i < accessors; ++i) {
        const auto& accessor = document.accessors[i];
        const std::string name = "accessor " + std::to_string(i);
        checker.check(name, "bufferView", accessor.bufferView, views);
        if (accessor.sparse) {
            checker.check(name + " sparse indices", "bufferView", accessor.sparse->indicesView,
                          views);
            checker.check(name + " sparse values", "bufferView", accessor.sparse->valuesView,
                          views);
        }
    }
}

// Primitives' accessors, materials, compressed views and variant mappings.
void checkMeshReferences(const GltfDocument& document, ReferenceChecker& checker) {
    const std::size_t views = document.bufferViews.size();
    const std::size_t accessors = document.accessors.size();
    for (std::size_t m = 0; m < document.meshes.size(); ++m) {
        const auto& primitives = document.meshes[m].primitives;
        for (std::size_t p = 0; p < primitives.size(); ++p) {
            const auto& primitive = primitives[p];
            const std::string name =
                "mesh " + std::to_string(m) + ", primitive " + std::to_string(p);
            for (const auto& [semantic, accessor] : primitive.attributes) {
                checker.check(name, "accessor", accessor, accessors, semantic);
            }
            checker.check(name, "accessor", primitive.indices, accessors, "indices");
            checker.check(name, "material", primitive.material, document.materials.size());
            for (const auto& target : primitive.targets) {
                for (const auto& [semantic, accessor] : target) {
                    checker.check(name, "accessor", accessor, accessors,
                                  "morph target " + semantic);
                }
            }
            if (primitive.draco) {
                checker.check(name + " KHR_draco_mesh_compression", "bufferView",
                              primitive.draco->bufferView, views);
            }
            for (std::size_t i = 0; i < primitive.variantMappings.size(); ++i) {
                const GltfVariantMapping& mapping = primitive.variantMappings[i];
                const std::string from =
                    name + " KHR_materials_variants mapping " + std::to_string(i);
                checker.check(from, "material", mapping.material, document.materials.size());
                for (std::uint32_t variant : mapping.variants) {
                    checker.check(from, "variant", variant, document.variants.size());
                }
            }
        }
    }
}

// The node tree's references, skins', animations' and scenes'.
void checkNodeReferences(const GltfDocument& document, ReferenceChecker& checker) {
    const std::size_t accessors = document.accessors.size();
    for (std::size_t n = 0; n < document.nodes.size(); ++n) {
        const auto& node = document.nodes[n];
        const std::string name = "node " + std::to_string(n);
        checker.check(name, "mesh", node.mesh, document.meshes.size());
        checker.check(name, "skin", node.skin, document.skins.size());
        checker.check(name, "camera", node.camera, document.cameras.size());
        checker.check(name, "light", node.light, document.lights.size(), "KHR_lights_punctual");
        for (std::uint32_t child : node.children) {
            checker.check(name, "node", child, document.nodes.size(), "child");
        }
        if (node.instancing) {
            checker.check(name, "accessor", node.instancing->translation, accessors,
                          "instance TRANSLATION");
            checker.check(name, "accessor", node.instancing->rotation, accessors,
                          "instance ROTATION");
            checker.check(name, "accessor", node.instancing->scale, accessors, "instance SCALE");
        }
    }
    for (std::size_t s = 0; s < document.skins.size(); ++s) {
        const std::string name = "skin " + std::to_string(s);
        checker.check(name, "accessor", document.skins[s].inverseBindMatrices, accessors);
        for (std::uint32_t joint : document.skins[s].joints) {
            checker.check(name, "node", joint, document.nodes.size(), "joint");
        }
        checker.check(name, "node", document.skins[s].skeleton, document.nodes.size(), "skeleton");
    }
    for (std::size_t a = 0; a < document.animations.size(); ++a) {
        const GltfAnimation& animation = document.animations[a];
        const std::string name = "animation " + std::to_string(a);
        for (std::size_t c = 0; c < animation.channels.size(); ++c) {
            const std::string channel = name + ", channel " + std::to_string(c);
            // The sampler index is checked with the animation (it is local to it).
            checker.check(channel, "node", animation.channels[c].node, document.nodes.size(),
                          "target");
        }
        for (std::size_t s = 0; s < animation.samplers.size(); ++s) {
            const std::string sampler = name + ", sampler " + std::to_string(s);
            checker.check(sampler, "accessor", animation.samplers[s].input, accessors, "input");
            checker.check(sampler, "accessor", animation.samplers[s].output, accessors, "output");
        }
    }
    for (std::size_t s = 0; s < document.scenes.size(); ++s) {
        for (std::uint32_t node : document.scenes[s]) {
            checker.check("scene " + std::to_string(s), "node", node, document.nodes.size());
        }
    }
    checker.check("The asset's 'scene' property", "scene", document.scene, document.scenes.size());
}

// Materials' textures, textures' images and samplers, images' views.
void checkMaterialReferences(const GltfDocument& document, ReferenceChecker& checker) {
    const std::size_t views = document.bufferViews.size();
    for (std::size_t m = 0; m < document.materials.size(); ++m) {
        const auto& material = document.materials[m];
        const std::string name = "material " + std::to_string(m);
        const std::size_t textures = document.textures.size();
        for (const GltfMaterialTextureSlot& slot : materialTextureSlots(material)) {
            checker.check(name + " " + slot.slot, "texture", slot.info->index, textures);
        }
    }
    for (std::size_t t = 0; t < document.textures.size(); ++t) {
        const std::string name = "texture " + std::to_string(t);
        checker.check(name, "image", document.textures[t].source, document.images.size());
        checker.check(name + " EXT_texture_webp", "image", document.textures[t].webpSource,
                      document.images.size());
        checker.check(name + " KHR_texture_basisu", "image", document.textures[t].basisuSource,
                      document.images.size());
        checker.check(name, "sampler", document.textures[t].sampler, document.samplers.size());
    }
    for (std::size_t i = 0; i < document.images.size(); ++i) {
        checker.check("image " + std::to_string(i), "bufferView", document.images[i].bufferView,
                      views);
    }
}

}  // namespace

Result<void> validateReferences(const GltfDocument& document) {
    ReferenceChecker checker;
    checkDataReferences(document, checker);
    checkMeshReferences(document, checker);
    checkNodeReferences(document, checker);
    checkMaterialReferences(document, checker);
    return checker.result();
}

Result<void> buildBufferViews(LoadContext& context) {
    const auto& views = context.document.bufferViews;
    auto& scene = context.scene;
    scene.bufferViews.resize(views.size());
    for (std::size_t i = 0; i < views.size(); ++i) {
        const GltfBufferView& source = views[i];
        const std::string name = "bufferView " + std::to_string(i);
        if (source.byteStride &&
            (*source.byteStride < 4 || *source.byteStride > 252 || *source.byteStride % 4 != 0)) {
            return makeError(ErrorCode::InvalidFormat,
                             name + " has an invalid byteStride (" +
                                 std::to_string(*source.byteStride) +
                                 "; it must be a multiple of 4 from 4 to 252).");
        }
        BufferView& view = scene.bufferViews[i];
        view.buffer = BufferId(source.buffer);
        view.byteOffset = source.byteOffset;
        view.byteLength = source.byteLength;
        view.byteStride = static_cast<std::uint32_t>(source.byteStride.value_or(0));
        if (source.meshopt) {
            continue;  // Its own buffer may be the fallback; decodeMeshoptViews checks it.
        }
        const std::uint64_t bufferSize = scene.buffers[source.buffer].bytes.size();
        const auto end = mulAdd(1, source.byteOffset, source.byteLength);
        if (!end || *end > bufferSize) {
            return makeError(ErrorCode::InvalidFormat,
                             name + " reaches past the end of buffer " +
                                 std::to_string(source.buffer) + " (offset " +
                                 std::to_string(source.byteOffset) + " + length " +
                                 std::to_string(source.byteLength) + " > " +
                                 std::to_string(bufferSize) + " bytes).");
        }
    }
    return {};
}

void labelAccessorUses(LoadContext& context) {
    const auto& document = context.document;
    const std::size_t count = document.accessors.size();
    context.accessorUses.assign(count, {});
    context.accessorFilled.assign(count, false);
    std::vector<int> dracoUses(count, 0);
    std::vector<int> otherUses(count, 0);
    auto use = [&](std::uint32_t accessor, std::string label, bool draco) {
        if (context.accessorUses[accessor].empty()) {
            context.accessorUses[accessor] = std::move(label);
        }
        ++(draco ? dracoUses : otherUses)[accessor];
    };
    for (std::size_t m = 0; m < document.meshes.size(); ++m) {
        const auto& primitives = document.meshes[m].primitives;
        for (std::size_t p = 0; p < primitives.size(); ++p) {
            const auto& primitive = primitives[p];
            const bool draco = primitive.draco.has_value();
            const std::string where =
                " of mesh " + std::to_string(m) + ", primitive " + std::to_string(p);
            for (const auto& [semantic, accessor] : primitive.attributes) {
                use(accessor, semantic + where, draco);
            }
            if (primitive.indices) {
                use(*primitive.indices, "indices" + where, draco);
            }
            for (const auto& target : primitive.targets) {
                for (const auto& [semantic, accessor] : target) {
                    use(accessor, "morph target " + semantic + where, false);
                }
            }
        }
    }
    for (std::size_t n = 0; n < document.nodes.size(); ++n) {
        if (const auto& instancing = document.nodes[n].instancing) {
            const std::string where = " of node " + std::to_string(n);
            if (instancing->translation) {
                use(*instancing->translation, "TRANSLATION" + where, false);
            }
            if (instancing->rotation) {
                use(*instancing->rotation, "ROTATION" + where, false);
            }
            if (instancing->scale) {
                use(*instancing->scale, "SCALE" + where, false);
            }
        }
    }
    for (std::size_t s = 0; s < document.skins.size(); ++s) {
        if (const auto& matrices = document.skins[s].inverseBindMatrices) {
            use(*matrices, "inverseBindMatrices of skin " + std::to_string(s), false);
        }
    }
    for (std::size_t a = 0; a < document.animations.size(); ++a) {
        const auto& samplers = document.animations[a].samplers;
        for (std::size_t s = 0; s < samplers.size(); ++s) {
            const std::string where =
                " of animation " + std::to_string(a) + ", sampler " + std::to_string(s);
            use(samplers[s].input, "input" + where, false);
            use(samplers[s].output, "output" + where, false);
        }
    }
    context.accessorDracoOnly.assign(count, false);
    for (std::size_t i = 0; i < count; ++i) {
        context.accessorDracoOnly[i] = dracoUses[i] > 0 && otherUses[i] == 0;
    }
}

}  // namespace encore::scene
