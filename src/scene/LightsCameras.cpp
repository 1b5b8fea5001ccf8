// Cameras and KHR_lights_punctual lights: read from JSON and checked against the ranges the
// specifications give, so the renderer can build projections and light uniforms without
// guarding against zero fields of view, inverted depth ranges or inverted spot cones.

#include <cmath>

#include "scene/GltfDocument.h"

namespace encore::scene {
namespace {

constexpr double kHalfPi = 1.57079632679489661923;

// A number the specification requires; absent records "lacks the required ..." on the reader.
double requiredNumber(FieldReader& reader, std::string_view key) {
    if (!reader.has(key)) {
        reader.fail(ErrorCode::InvalidFormat,
                    reader.element() + " lacks the required '" + std::string(key) + "' property.");
        return 0.0;
    }
    return reader.number(key, 0.0);
}

void failRange(FieldReader& reader, std::string_view key, double value, std::string_view rule) {
    reader.fail(ErrorCode::InvalidFormat, reader.element() + " has an invalid " + std::string(key) +
                                              " (" + formatNumber(value) + "; " +
                                              std::string(rule) + ").");
}

void readPerspective(FieldReader& reader, CameraData& camera) {
    const Json* object = reader.object("perspective");
    if (!object) {
        if (!reader.failed()) {
            reader.fail(ErrorCode::InvalidFormat, reader.element() +
                                                      " has type 'perspective' but no "
                                                      "'perspective' object.");
        }
        return;
    }
    FieldReader fields(*object, reader.element() + " perspective");
    const double yfov = requiredNumber(fields, "yfov");
    const double aspectRatio = fields.number("aspectRatio", 0.0);
    const double znear = requiredNumber(fields, "znear");
    const double zfar = fields.number("zfar", 0.0);
    if (!fields.failed()) {
        if (yfov <= 0.0) {
            failRange(fields, "yfov", yfov, "it must be greater than 0");
        } else if (fields.has("aspectRatio") && aspectRatio <= 0.0) {
            failRange(fields, "aspectRatio", aspectRatio, "it must be greater than 0");
        } else if (znear <= 0.0) {
            failRange(fields, "znear", znear, "it must be greater than 0");
        } else if (fields.has("zfar") && zfar <= znear) {
            failRange(fields, "zfar", zfar,
                      "it must be greater than znear (" + formatNumber(znear) + ")");
        }
    }
    camera.projection = CameraProjection::Perspective;
    camera.yfov = float(yfov);
    camera.aspectRatio = float(aspectRatio);
    camera.znear = float(znear);
    camera.zfar = float(zfar);
    if (fields.failed()) {
        reader.fail(fields.error().code, fields.error().message);
    }
}

void readOrthographic(FieldReader& reader, CameraData& camera) {
    const Json* object = reader.object("orthographic");
    if (!object) {
        if (!reader.failed()) {
            reader.fail(ErrorCode::InvalidFormat, reader.element() +
                                                      " has type 'orthographic' but no "
                                                      "'orthographic' object.");
        }
        return;
    }
    FieldReader fields(*object, reader.element() + " orthographic");
    const double xmag = requiredNumber(fields, "xmag");
    const double ymag = requiredNumber(fields, "ymag");
    const double znear = requiredNumber(fields, "znear");
    const double zfar = requiredNumber(fields, "zfar");
    if (!fields.failed()) {
        if (xmag == 0.0) {
            failRange(fields, "xmag", xmag, "it must not be 0");
        } else if (ymag == 0.0) {
            failRange(fields, "ymag", ymag, "it must not be 0");
        } else if (znear < 0.0) {
            failRange(fields, "znear", znear, "it must not be negative");
        } else if (zfar <= znear) {
            failRange(fields, "zfar", zfar,
                      "it must be greater than znear (" + formatNumber(znear) + ")");
        }
    }
    camera.projection = CameraProjection::Orthographic;
    camera.xmag = float(xmag);
    camera.ymag = float(ymag);
    camera.znear = float(znear);
    camera.zfar = float(zfar);
    if (fields.failed()) {
        reader.fail(fields.error().code, fields.error().message);
    }
}

void readLight(FieldReader& reader, Light& light) {
    light.name = reader.string("name");
    const std::string type = reader.requiredString("type");
    if (const auto color = reader.numbers("color", 3); color.size() == 3) {
        light.color = glm::vec3(color[0], color[1], color[2]);
    }
    const double intensity = reader.number("intensity", 1.0);
    const double range = reader.number("range", 0.0);
    if (reader.failed()) {
        return;
    }
    if (type == "directional") {
        light.type = LightType::Directional;
    } else if (type == "point") {
        light.type = LightType::Point;
    } else if (type == "spot") {
        light.type = LightType::Spot;
    } else {
        reader.fail(ErrorCode::InvalidFormat, reader.element() + " has an unknown type ('" + type +
                                                  "'; expected directional, point or spot).");
        return;
    }
    if (intensity < 0.0) {
        failRange(reader, "intensity", intensity, "it must not be negative");
        return;
    }
    if (reader.has("range") && range <= 0.0) {
        failRange(reader, "range", range, "it must be greater than 0 when present");
        return;
    }
    light.intensity = float(intensity);
    light.range = float(range);
    if (light.type != LightType::Spot) {
        return;
    }
    if (const Json* spot = reader.object("spot")) {
        FieldReader fields(*spot, reader.element() + " spot");
        const double inner = fields.number("innerConeAngle", 0.0);
        const double outer = fields.number("outerConeAngle", kHalfPi / 2.0);
        // Exporters write pi/2 rounded to float32, a hair above the double value.
        constexpr double kMaxOuter = kHalfPi + 1e-6;
        if (!fields.failed() && !(inner >= 0.0 && inner < outer && outer <= kMaxOuter)) {
            fields.fail(ErrorCode::InvalidFormat,
                        fields.element() + " has invalid cone angles (innerConeAngle " +
                            formatNumber(inner) + ", outerConeAngle " + formatNumber(outer) +
                            "; they must satisfy 0 <= inner < outer <= pi/2).");
        }
        light.innerConeAngle = float(inner);
        light.outerConeAngle = float(outer);
        if (fields.failed()) {
            reader.fail(fields.error().code, fields.error().message);
        }
    }
}

}  // namespace

Result<void> parseLightsAndCameras(const Json& root, GltfDocument& document) {
    ENCORE_TRY(forEachElement(root, "cameras", "camera", [&](FieldReader& reader, std::size_t) {
        CameraData camera;
        camera.name = reader.string("name");
        const std::string type = reader.requiredString("type");
        if (reader.failed()) {
            return;
        }
        if (type == "perspective") {
            readPerspective(reader, camera);
        } else if (type == "orthographic") {
            readOrthographic(reader, camera);
        } else {
            reader.fail(ErrorCode::InvalidFormat, reader.element() + " has an unknown type ('" +
                                                      type +
                                                      "'; expected perspective or orthographic).");
        }
        document.cameras.push_back(std::move(camera));
    }));

    FieldReader top(root, "The glTF document");
    const Json* extension = extensionObject(top, "KHR_lights_punctual");
    if (top.failed()) {
        return top.error();
    }
    if (!extension) {
        return {};
    }
    FieldReader fields(*extension, "The asset's KHR_lights_punctual extension");
    fields.array("lights");  // Records a type error for a 'lights' that is not an array.
    if (fields.failed()) {
        return fields.error();
    }
    return forEachElement(*extension, "lights", "light", [&](FieldReader& reader, std::size_t) {
        Light light;
        readLight(reader, light);
        document.lights.push_back(std::move(light));
    });
}

}  // namespace encore::scene
