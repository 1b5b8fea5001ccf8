#pragma once

// Reproducible camera paths through the generated benchmark scenes (encore bench --scene
// flythrough|city): the camera of frame f of F depends on nothing but the scene's generator
// options, so every strategy, run and machine renders the same views. Each path is a closed
// loop in a horizontal plane (straight runs joined by quarter circles) that stays in the
// scene's free space; the camera moves along it at constant speed and looks where it goes, so
// most objects are behind or beside it and the nearest ones hide many of the others.

#include <cstdint>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "encore/render/Camera.h"
#include "scene/SceneGenerator.h"

namespace encore::render {

class CameraPath {
  public:
    // The renderer's usual field of view (72 degrees across at 16:9); the near plane is small
    // against the gap (0.15 or more) between the path and the nearest objects.
    static constexpr float kFovRadians = kFramingFovRadians;
    static constexpr float kNearPlane = 0.05f;

    // Through a SceneLayout::Lattice scene of `options`: a square loop around the middle half of
    // the lattice, along the aisles between its points, at the height of the aisle between its
    // middle layers (above the only layer when there is one), turning where aisles cross.
    static CameraPath flythrough(const scene::GeneratorOptions& options);
    // Through a SceneLayout::City scene of `options`: along the centre lines of the streets
    // around the middle half of the city at eye height (1 unit; buildings are 1.5 to 8 tall),
    // turning at four crossings.
    static CameraPath city(const scene::GeneratorOptions& options);
    // The path of the options' layout: flythrough for Lattice, city for City; none for Grid,
    // which is seen from outside (Camera::framing).
    static std::optional<CameraPath> forLayout(const scene::GeneratorOptions& options);

    // The point `fraction` of the way round (any real number: it wraps around), and the unit
    // direction of travel there.
    glm::vec3 position(float fraction) const;
    glm::vec3 direction(float fraction) const;
    float length() const { return mLength; }

    // The camera `fraction` of the way round, looking along the path, for a target of `aspect`.
    Camera cameraAt(float fraction, float aspect) const;
    // Frame `frame` of `frameCount`: the frames go round the loop once, evenly spaced. In the
    // largest scenes that is a long step per frame (about 8 units for a million-object lattice
    // over 60 frames); cameraAtDistance moves at a chosen speed instead.
    Camera camera(std::uint32_t frame, std::uint32_t frameCount, float aspect) const;
    // The camera `distance` units along the path from its start (wrapping around).
    Camera cameraAtDistance(float distance, float aspect) const {
        return cameraAt(distance / mLength, aspect);
    }

  private:
    // A straight run from `start` along `direction`, or a quarter circle around `center` that
    // starts heading along `direction` and ends heading along `turnedDirection`.
    struct Piece {
        glm::vec3 start;
        glm::vec3 direction;
        glm::vec3 turnedDirection;
        glm::vec3 center;
        float radius = 0.0f;  // 0: straight.
        float length = 0.0f;
    };
    struct Point {
        glm::vec3 position;
        glm::vec3 direction;
    };

    // The rectangle [low, high] (in X and Z) at `height`, its corners rounded with `radius`.
    CameraPath(glm::vec2 low, glm::vec2 high, float height, float radius, float farPlane);
    Point at(float fraction) const;

    std::vector<Piece> mPieces;
    float mLength = 0.0f;
    float mFarPlane = 0.0f;
};

}  // namespace encore::render
