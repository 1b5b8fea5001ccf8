// The default studio panorama, generated in code so that rendering needs no environment file.
//
// Radiance levels are chosen so that the lights, not the backdrop, shape a model: the sky
// (about 0.6 at the horizon to 1.1 at the zenith) gives a soft fill, the sun (a 2.5 degree disk
// of radiance 300, about 1.8 of irradiance facing it) a crisp key highlight and the directional
// light, and the two box lights (radiance 6 and 4) long highlights on the sides of glossy
// objects.

#include <algorithm>
#include <cmath>
#include <numbers>

#include "encore/image/HdrImage.h"

namespace encore::image {
namespace {

struct Rgb {
    float r, g, b;
};

Rgb operator*(Rgb c, float s) {
    return {c.r * s, c.g * s, c.b * s};
}
Rgb operator+(Rgb a, Rgb b) {
    return {a.r + b.r, a.g + b.g, a.b + b.b};
}
Rgb mix(Rgb a, Rgb b, float t) {
    return a * (1.0f - t) + b * t;
}

float smoothstep(float edge0, float edge1, float x) {
    const float t = std::clamp((x - edge0) / (edge1 - edge0), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

constexpr float kPi = std::numbers::pi_v<float>;
constexpr float kDegree = kPi / 180.0f;

// The smallest angle between two longitudes.
float longitudeDistance(float a, float b) {
    const float d = std::fmod(std::fabs(a - b), 2.0f * kPi);
    return std::min(d, 2.0f * kPi - d);
}

// A rectangle in (longitude, elevation) with edges softened over `soft` radians: 1 inside,
// falling smoothly to 0 outside, so the boxes read as diffusers rather than hard cards.
float softBox(float phi,
              float elevation,
              float centrePhi,
              float centreElevation,
              float halfWidth,
              float halfHeight,
              float soft) {
    const float dx = longitudeDistance(phi, centrePhi);
    const float dy = std::fabs(elevation - centreElevation);
    return (1.0f - smoothstep(halfWidth - soft, halfWidth + soft, dx)) *
           (1.0f - smoothstep(halfHeight - soft, halfHeight + soft, dy));
}

}  // namespace

HdrImage makeStudioEnvironment(std::uint32_t width) {
    HdrImage image;
    image.height = std::max(width / 2, 4u);
    image.width = image.height * 2;
    image.rgb.resize(std::size_t(image.width) * image.height * 3);

    const Rgb horizon{0.62f, 0.63f, 0.66f};
    const Rgb zenith{1.00f, 1.06f, 1.15f};
    const Rgb groundNear{0.30f, 0.25f, 0.20f};  // Warm floor near the horizon...
    const Rgb groundFar{0.16f, 0.13f, 0.10f};   // ...darker straight down.
    const Rgb sunColor{1.0f, 0.96f, 0.90f};
    const float sunRadiance = 300.0f;
    const float sunRadius = 2.5f * kDegree;
    // High in the sky, in front of and to the right of a viewer on +Z looking at the origin.
    const float sunElevation = 55.0f * kDegree;
    const float sunPhi = 60.0f * kDegree;
    const float sunX = std::cos(sunElevation) * std::cos(sunPhi);
    const float sunY = std::sin(sunElevation);
    const float sunZ = std::cos(sunElevation) * std::sin(sunPhi);
    // Pixels are width / 360 per degree; the disk's edge is blurred over about one pixel so the
    // sun does not alias however small the panorama is.
    const float pixelAngle = 2.0f * kPi / float(image.width);
    const float sunSoft = std::max(pixelAngle, 0.3f * kDegree);

    for (std::uint32_t row = 0; row < image.height; ++row) {
        const float theta = kPi * (float(row) + 0.5f) / float(image.height);
        const float elevation = 0.5f * kPi - theta;
        const float sinTheta = std::sin(theta);
        const float y = std::cos(theta);
        for (std::uint32_t column = 0; column < image.width; ++column) {
            const float phi = 2.0f * kPi * (float(column) + 0.5f) / float(image.width);
            const float x = sinTheta * std::cos(phi);
            const float z = sinTheta * std::sin(phi);

            // Sky brighter upward; the horizon blends into the ground over a few degrees so
            // the seam does not ring in the prefiltered maps.
            const float up = std::max(y, 0.0f);
            const Rgb sky = mix(horizon, zenith, std::sqrt(up));
            const Rgb ground = mix(groundNear, groundFar, std::sqrt(std::max(-y, 0.0f)));
            Rgb radiance = mix(ground, sky, smoothstep(-3.0f * kDegree, 3.0f * kDegree, elevation));

            // Two soft boxes at horizon height, left (-X) and right (+X) of the viewer.
            const float box = 6.0f * softBox(phi, elevation, 0.0f, 12.0f * kDegree, 18.0f * kDegree,
                                             12.0f * kDegree, 4.0f * kDegree) +
                              4.0f * softBox(phi, elevation, kPi, 12.0f * kDegree, 18.0f * kDegree,
                                             12.0f * kDegree, 4.0f * kDegree);
            radiance = radiance + Rgb{1.0f, 1.0f, 1.0f} * box;

            const float cosToSun = std::clamp(x * sunX + y * sunY + z * sunZ, -1.0f, 1.0f);
            const float sunAngle = std::acos(cosToSun);
            const float sun = 1.0f - smoothstep(sunRadius - sunSoft, sunRadius + sunSoft, sunAngle);
            radiance = radiance + sunColor * (sunRadiance * sun);

            float* out = &image.rgb[(std::size_t(row) * image.width + column) * 3];
            out[0] = radiance.r;
            out[1] = radiance.g;
            out[2] = radiance.b;
        }
    }
    return image;
}

}  // namespace encore::image
