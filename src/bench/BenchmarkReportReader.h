#pragma once

// Reads back the reports `encore bench` writes (toJson in Benchmark.h): joins the reports of
// separate runs, and gathers the results of scenes with an object-count axis into series of
// points, the curves that `encore plot` draws. Reports come from files, so nothing here trusts
// their shape: every missing or mistyped field is an InvalidFormat error that names it.

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "encore/core/Result.h"

namespace encore::bench {

// A median and where its whisker ends: the p95 for times, the maximum for triangle counts.
struct Spread {
    double median = 0.0;
    double high = 0.0;  // 0 when the report has none: no whisker is drawn.
};

// One result of a series: its object count and per-frame measurements.
struct ScalingPoint {
    double objects = 0.0;
    Spread cpu;
    std::optional<Spread> gpu;
    std::optional<Spread> triangles;  // Per frame: drawn after GPU culling, else submitted.
};

// The results of one scene kind and strategy (and, for crowds, animation path), by object count.
struct ScalingSeries {
    std::string scene;
    std::string animation;  // Crowds: "cpu" or "gpu", where the animation was evaluated.
    std::string strategy;
    std::string label;
    std::vector<ScalingPoint> points;
};

// The series of a report's "results" array, from the results whose "scene" is
//   - "generated": one series per "strategy", labelled with it;
//   - "animometer": their own series, one per strategy, labelled with it, or "animometer
//     <strategy>" where another series has the same strategy;
//   - "crowd": one series per strategy and "animation", labelled "<animation>-animated
//     <strategy>" ("still <strategy>" without one);
//   - "flythrough" or "city": one series per scene and strategy, labelled "<scene>: <strategy>".
// Other scenes (single models) have no object-count axis and are left out. Generated series
// come first, then the others, each in report order; points are sorted by "objects".
//
// A point's CPU time is "cpuMs" where the result has it, otherwise "encodeMs" + "submitMs" (the
// p95 then being the sum of both p95s, an upper bound); its GPU time is "gpuMs" unless that is
// null (no timestamp queries); its triangles are the median and maximum of "trianglesDrawn", or
// of "trianglesSubmitted" where "trianglesDrawn" is null or empty. Values are as written, not
// checked for sign or finiteness.
//
// Returns an InvalidFormat error naming the result and the field when a result lacks a "scene",
// or a kept result lacks a "strategy", an "objects" count or a CPU median, or when a triangle
// count array holds a non-number.
Result<std::vector<ScalingSeries>> readScalingSeries(const nlohmann::json& results);

// One parsed report and the name (its path) that error messages use.
struct NamedReport {
    std::string name;
    nlohmann::json report;
};

// Joins several reports of one adapter into one, so runs made separately (one per object count)
// plot as one set of curves: the "results" arrays are concatenated in order, and every other field
// (adapter, date, frames, ...) is the first report's. Returns an InvalidFormat error when there
// is no report, when one lacks a "results" array, or when an "adapter" differs from the first's.
Result<nlohmann::json> mergeReports(const std::vector<NamedReport>& reports);

}  // namespace encore::bench
