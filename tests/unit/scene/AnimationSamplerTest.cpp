// sampleAnimation against hand-computed values: STEP, LINEAR (scalars and shortest-path slerp),
// CUBICSPLINE (tangents scaled by the key interval), clamping outside the keys, and the cursor.

#include <gtest/gtest.h>

#include <cmath>

#include <glm/glm.hpp>

#include "encore/scene/SceneData.h"

namespace encore::scene {
namespace {

AnimationSampler scalarSampler(Interpolation mode,
                               std::vector<float> times,
                               std::vector<float> values) {
    AnimationSampler sampler;
    sampler.interpolation = mode;
    sampler.times = std::move(times);
    sampler.values = std::move(values);
    sampler.components = 1;
    return sampler;
}

float sample(const AnimationSampler& sampler, float time) {
    SamplerCursor cursor;
    float out = -1.0f;
    sampleAnimation(sampler, time, false, cursor, std::span<float>(&out, 1));
    return out;
}

TEST(AnimationSamplerTest, StepHoldsTheValueOfTheKeyAtOrBefore) {
    const auto sampler = scalarSampler(Interpolation::Step, {0, 1, 2}, {0, 10, 20});
    EXPECT_EQ(sample(sampler, 0.0f), 0.0f);
    EXPECT_EQ(sample(sampler, 0.5f), 0.0f);
    EXPECT_EQ(sample(sampler, 1.0f), 10.0f);
    EXPECT_EQ(sample(sampler, 1.99f), 10.0f);
    EXPECT_EQ(sample(sampler, 2.0f), 20.0f);
}

TEST(AnimationSamplerTest, LinearInterpolatesAndClampsOutsideTheKeys) {
    const auto sampler = scalarSampler(Interpolation::Linear, {1, 2, 4}, {0, 10, 30});
    EXPECT_FLOAT_EQ(sample(sampler, 1.25f), 2.5f);
    EXPECT_FLOAT_EQ(sample(sampler, 3.0f), 20.0f);
    EXPECT_EQ(sample(sampler, 0.0f), 0.0f);  // Before the first key.
    EXPECT_EQ(sample(sampler, -5.0f), 0.0f);
    EXPECT_EQ(sample(sampler, 4.0f), 30.0f);  // At and after the last.
    EXPECT_EQ(sample(sampler, 100.0f), 30.0f);
    EXPECT_EQ(sample(sampler, std::nanf("")), 0.0f);
}

TEST(AnimationSamplerTest, SingleKeyIsConstant) {
    const auto sampler = scalarSampler(Interpolation::Linear, {0.5f}, {7});
    EXPECT_EQ(sample(sampler, 0.0f), 7.0f);
    EXPECT_EQ(sample(sampler, 3.0f), 7.0f);
}

AnimationSampler rotationSampler(std::vector<float> values) {
    AnimationSampler sampler;
    sampler.interpolation = Interpolation::Linear;
    sampler.times = {0, 1};
    sampler.values = std::move(values);
    sampler.components = 4;
    return sampler;
}

TEST(AnimationSamplerTest, LinearRotationIsAShortestPathSlerp) {
    const float h = std::sqrt(0.5f);  // 90 degrees about z: (0, 0, sin 45, cos 45).
    const float s = std::sin(glm::radians(22.5f));
    const float c = std::cos(glm::radians(22.5f));
    for (const float sign : {1.0f, -1.0f}) {  // -q is the same rotation: still the short way.
        const auto sampler = rotationSampler({0, 0, 0, 1, 0, 0, sign * h, sign * h});
        SamplerCursor cursor;
        float q[4];
        sampleAnimation(sampler, 0.5f, true, cursor, q);
        EXPECT_NEAR(q[0], 0.0f, 1e-6f);
        EXPECT_NEAR(q[1], 0.0f, 1e-6f);
        EXPECT_NEAR(q[2], s, 1e-6f) << "sign " << sign;
        EXPECT_NEAR(q[3], c, 1e-6f) << "sign " << sign;
        // A quarter of the way: 22.5 degrees, not the 25% chord (slerp has constant speed).
        sampleAnimation(sampler, 0.25f, true, cursor, q);
        EXPECT_NEAR(q[2], std::sin(glm::radians(11.25f)), 1e-6f);
        EXPECT_NEAR(q[3], std::cos(glm::radians(11.25f)), 1e-6f);
    }
}

TEST(AnimationSamplerTest, RotationsAreNormalisedAndZeroBecomesIdentity) {
    AnimationSampler sampler = rotationSampler({0, 0, 0, 2, 0, 0, 0, 0});
    sampler.interpolation = Interpolation::Step;
    SamplerCursor cursor;
    float q[4];
    sampleAnimation(sampler, 0.0f, true, cursor, q);
    EXPECT_FLOAT_EQ(q[3], 1.0f);
    sampleAnimation(sampler, 1.0f, true, cursor, q);
    EXPECT_EQ(q[0], 0.0f);
    EXPECT_EQ(q[3], 1.0f);
}

TEST(AnimationSamplerTest, CubicSplineScalesTangentsByTheKeyInterval) {
    // Keys at 0 and 2 s. Per key: in-tangent, value, out-tangent.
    //   p0 = 0, out-tangent 3; p1 = 1, in-tangent -1; interval 2; at t = 1, u = 0.5:
    //   h00 = 0.5, h10 = 0.125, h01 = 0.5, h11 = -0.125
    //   p = 0.5 * 0 + 0.125 * 2 * 3 + 0.5 * 1 + (-0.125) * 2 * (-1) = 0.75 + 0.5 + 0.25 = 1.5
    const auto sampler = scalarSampler(Interpolation::CubicSpline, {0, 2}, {9, 0, 3, -1, 1, 9});
    EXPECT_FLOAT_EQ(sample(sampler, 1.0f), 1.5f);
    // u = 0.25: h00 = 0.84375, h10 = 0.140625, h01 = 0.15625, h11 = -0.046875
    //   p = 0.140625 * 6 + 0.15625 + 0.046875 * 2 = 0.84375 + 0.15625 + 0.09375 = 1.09375
    EXPECT_FLOAT_EQ(sample(sampler, 0.5f), 1.09375f);
    // Outside the keys: the values, never the tangents.
    EXPECT_EQ(sample(sampler, -1.0f), 0.0f);
    EXPECT_EQ(sample(sampler, 2.0f), 1.0f);
    EXPECT_EQ(sample(sampler, 3.0f), 1.0f);
}

TEST(AnimationSamplerTest, CubicSplineVectorsUseTheirOwnComponents) {
    AnimationSampler sampler;
    sampler.interpolation = Interpolation::CubicSpline;
    sampler.times = {0, 1};
    // Key 0: in (0,0), value (0,10), out (1,0); key 1: in (1,0), value (1,10), out (0,0).
    sampler.values = {0, 0, 0, 10, 1, 0, 1, 0, 1, 10, 0, 0};
    sampler.components = 2;
    SamplerCursor cursor;
    float out[2];
    sampleAnimation(sampler, 0.5f, false, cursor, out);
    // x: tangents 1 at both ends of a unit ramp: the ramp itself.
    EXPECT_FLOAT_EQ(out[0], 0.5f);
    EXPECT_FLOAT_EQ(out[1], 10.0f);
}

TEST(AnimationSamplerTest, CursorGivesTheSameValuesInAnyOrder) {
    std::vector<float> times, values;
    for (int k = 0; k < 50; ++k) {
        times.push_back(k * 0.1f);
        values.push_back(float(k * k));
    }
    const auto sampler = scalarSampler(Interpolation::Linear, times, values);
    SamplerCursor forward;
    SamplerCursor scattered;
    for (int i = 0; i < 600; ++i) {
        const float t = i * 0.01f - 0.5f;
        float a = 0.0f, b = 0.0f;
        sampleAnimation(sampler, t, false, forward, std::span<float>(&a, 1));
        const float u = float((i * 7919) % 600) * 0.01f - 0.5f;  // A scattered order.
        sampleAnimation(sampler, u, false, scattered, std::span<float>(&b, 1));
        EXPECT_EQ(a, sample(sampler, t)) << t;
        EXPECT_EQ(b, sample(sampler, u)) << u;
    }
}

}  // namespace
}  // namespace encore::scene
