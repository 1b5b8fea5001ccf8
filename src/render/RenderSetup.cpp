#include "render/RenderSetup.h"

namespace encore::render {

PrepareTimes& PrepareTimes::operator+=(const PrepareTimes& other) {
    release += other.release;
    animation += other.animation;
    scene += other.scene;
    strategy += other.strategy;
    geometry += other.geometry;
    instances += other.instances;
    materials += other.materials;
    textureCreation += other.textureCreation;
    textureWrites += other.textureWrites;
    mipmaps += other.mipmaps;
    materialSubmit += other.materialSubmit;
    draws += other.draws;
    checks += other.checks;
    return *this;
}

}  // namespace encore::render
