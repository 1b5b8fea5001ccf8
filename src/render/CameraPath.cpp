#include "render/CameraPath.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/constants.hpp>

namespace encore::render {

namespace {

// Points round the loop the camera may stand on: the aisle or street about a quarter of the
// way across (index `count / 4`, counted from the one before the first point or block) and the
// one about three quarters across, distinct even for the smallest scenes.
std::pair<int, int> quarterLines(std::uint32_t count, int first) {
    const int low = first + static_cast<int>(std::lround(0.25 * count));
    const int high = std::max(low + 1, first + static_cast<int>(std::lround(0.75 * count)));
    return {low, high};
}

}  // namespace

CameraPath CameraPath::flythrough(const scene::GeneratorOptions& options) {
    const scene::LatticeLayout lattice = scene::latticeLayout(options);
    // Aisle k lies between points k and k + 1; -1 is just outside the first point.
    const auto [low, high] = quarterLines(lattice.side, -1);
    const int middleLayer = static_cast<int>((lattice.layers - 1) / 2);
    const float height = lattice.origin.y + lattice.aisle(middleLayer);
    const glm::vec2 origin(lattice.origin.x, lattice.origin.z);
    // A corner of half the spacing keeps the turn as far from the points around the crossing
    // as the straight runs are from theirs (the arc's centre is a point of the lattice).
    const float width = float(lattice.side) * lattice.spacing;
    const float depth = float(lattice.layers) * lattice.spacing;
    return CameraPath(origin + glm::vec2(lattice.aisle(low)),
                      origin + glm::vec2(lattice.aisle(high)), height, 0.5f * lattice.spacing,
                      std::sqrt(2.0f * width * width + depth * depth) + lattice.spacing);
}

CameraPath CameraPath::city(const scene::GeneratorOptions& options) {
    const scene::CityLayout city = scene::cityLayout(options);
    // Street k borders block k - 1 and block k; streets 0 and blocksPerSide are the outer ones.
    const auto [low, high] = quarterLines(city.blocksPerSide, 0);
    constexpr float kEyeHeight = 1.0f;
    const float width = float(city.blocksPerSide) * city.pitch() + city.streetWidth;
    // Turns within the crossing's own square: a quarter street's radius keeps the camera a
    // street's width from the pavement objects beside the lots nearest the crossing.
    return CameraPath(glm::vec2(city.streetCenter(low)), glm::vec2(city.streetCenter(high)),
                      kEyeHeight, 0.25f * city.streetWidth,
                      std::sqrt(2.0f) * width + city.maxBuildingHeight);
}

std::optional<CameraPath> CameraPath::forLayout(const scene::GeneratorOptions& options) {
    switch (options.layout) {
        case scene::SceneLayout::Lattice:
            return flythrough(options);
        case scene::SceneLayout::City:
            return city(options);
        case scene::SceneLayout::Grid:
            break;
    }
    return std::nullopt;
}

CameraPath::CameraPath(glm::vec2 low, glm::vec2 high, float height, float radius, float farPlane)
    : mFarPlane(farPlane) {
    radius = std::min(radius, 0.5f * std::min(high.x - low.x, high.y - low.y));
    // Counter-clockwise seen from above (+Y): east along the south side first.
    const glm::vec3 corners[4] = {{low.x, height, low.y},
                                  {high.x, height, low.y},
                                  {high.x, height, high.y},
                                  {low.x, height, high.y}};
    for (int i = 0; i < 4; ++i) {
        const glm::vec3& from = corners[i];
        const glm::vec3& to = corners[(i + 1) % 4];
        const glm::vec3& after = corners[(i + 2) % 4];
        const glm::vec3 direction = glm::normalize(to - from);
        const glm::vec3 turned = glm::normalize(after - to);
        Piece straight;
        straight.start = from + direction * radius;
        straight.direction = straight.turnedDirection = direction;
        straight.length = glm::length(to - from) - 2.0f * radius;
        mPieces.push_back(straight);
        if (radius > 0.0f) {
            Piece turn;
            turn.start = to - direction * radius;
            turn.direction = direction;
            turn.turnedDirection = turned;
            turn.center = turn.start + turned * radius;
            turn.radius = radius;
            turn.length = 0.5f * glm::pi<float>() * radius;
            mPieces.push_back(turn);
        }
    }
    for (const Piece& piece : mPieces) {
        mLength += piece.length;
    }
}

CameraPath::Point CameraPath::at(float fraction) const {
    float distance = (fraction - std::floor(fraction)) * mLength;
    for (const Piece& piece : mPieces) {
        if (distance > piece.length && &piece != &mPieces.back()) {
            distance -= piece.length;
            continue;
        }
        const float along = std::min(distance, piece.length);
        if (piece.radius == 0.0f) {
            return {piece.start + piece.direction * along, piece.direction};
        }
        // From the centre the start lies against the turned direction; the heading turns from
        // `direction` to `turnedDirection` over the quarter circle.
        const float angle = along / piece.radius;
        const float c = std::cos(angle);
        const float s = std::sin(angle);
        return {piece.center + piece.radius * (piece.direction * s - piece.turnedDirection * c),
                glm::normalize(piece.direction * c + piece.turnedDirection * s)};
    }
    return {glm::vec3(0.0f), glm::vec3(1.0f, 0.0f, 0.0f)};  // No pieces: not constructed so.
}

glm::vec3 CameraPath::position(float fraction) const {
    return at(fraction).position;
}

glm::vec3 CameraPath::direction(float fraction) const {
    return at(fraction).direction;
}

Camera CameraPath::cameraAt(float fraction, float aspect) const {
    const Point point = at(fraction);
    return Camera::lookAt(point.position, point.position + point.direction, kFovRadians, aspect,
                          kNearPlane, mFarPlane);
}

Camera CameraPath::camera(std::uint32_t frame, std::uint32_t frameCount, float aspect) const {
    return cameraAt(float(frame) / float(std::max(frameCount, 1u)), aspect);
}

}  // namespace encore::render
