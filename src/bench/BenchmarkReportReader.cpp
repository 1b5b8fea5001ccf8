#include "bench/BenchmarkReportReader.h"

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

namespace encore::bench {
namespace {

using nlohmann::json;

std::string describe(const json& result, size_t index) {
    std::string text = "Benchmark result " + std::to_string(index);
    if (result.contains("label") && result["label"].is_string()) {
        text += " ('" + result["label"].get<std::string>() + "')";
    }
    return text;
}

std::optional<double> numberAt(const json& object, const char* pointer) {
    const json::json_pointer at(pointer);
    if (!object.contains(at) || !object[at].is_number()) {
        return std::nullopt;
    }
    return object[at].get<double>();
}

// A per-frame array of counts; missing and null read as empty. The error message is completed
// by the caller, which knows which result this is.
Result<std::vector<double>> readCounts(const json& result, const char* key) {
    std::vector<double> counts;
    auto it = result.find(key);
    if (it == result.end() || it->is_null()) {
        return counts;
    }
    if (!it->is_array()) {
        return makeError(ErrorCode::InvalidFormat,
                         "has a \"" + std::string(key) + "\" that is neither an array nor null");
    }
    for (const json& count : *it) {
        if (!count.is_number()) {
            return makeError(ErrorCode::InvalidFormat,
                             "has a non-numeric entry in \"" + std::string(key) + "\"");
        }
        counts.push_back(count.get<double>());
    }
    return counts;
}

// The median (the mean of the middle two for an even count) and the maximum.
Spread summarize(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const size_t middle = values.size() / 2;
    const double median =
        values.size() % 2 ? values[middle] : (values[middle - 1] + values[middle]) / 2;
    return {median, values.back()};
}

// The error message is completed by the caller, which knows which result this is.
Result<ScalingPoint> readPoint(const json& result) {
    const auto objects = numberAt(result, "/objects");
    if (!objects) {
        return makeError(ErrorCode::InvalidFormat, "has no numeric \"objects\" count");
    }
    ScalingPoint point{*objects, {}, {}, {}};
    if (auto cpu = numberAt(result, "/cpuMs/median")) {
        point.cpu = {*cpu, numberAt(result, "/cpuMs/p95").value_or(0.0)};
    } else {
        // Reports may only split CPU time into encode and submit; the sum of their p95s bounds
        // the p95 of the sum from above.
        auto encode = numberAt(result, "/encodeMs/median");
        auto submit = numberAt(result, "/submitMs/median");
        if (!encode || !submit) {
            return makeError(ErrorCode::InvalidFormat,
                             "has neither \"cpuMs.median\" nor both \"encodeMs.median\" and "
                             "\"submitMs.median\"");
        }
        point.cpu = {*encode + *submit, numberAt(result, "/encodeMs/p95").value_or(0.0) +
                                            numberAt(result, "/submitMs/p95").value_or(0.0)};
    }
    // "gpuMs": null means the adapter had no timestamp queries.
    if (result.contains("gpuMs") && !result["gpuMs"].is_null()) {
        auto gpu = numberAt(result, "/gpuMs/median");
        if (!gpu) {
            return makeError(ErrorCode::InvalidFormat, "has no numeric \"gpuMs.median\"");
        }
        point.gpu = Spread{*gpu, numberAt(result, "/gpuMs/p95").value_or(0.0)};
    }
    // Strategies without GPU culling draw what they submit and report "trianglesDrawn": null.
    for (const char* key : {"trianglesDrawn", "trianglesSubmitted"}) {
        ENCORE_TRY_ASSIGN(auto counts, readCounts(result, key));
        if (!counts.empty()) {
            point.triangles = summarize(counts);
            break;
        }
    }
    return point;
}

}  // namespace

Result<std::vector<ScalingSeries>> readScalingSeries(const json& results) {
    std::vector<ScalingSeries> series;
    for (size_t i = 0; i < results.size(); ++i) {
        const json& result = results[i];
        if (!result.is_object() || !result.contains("scene") || !result["scene"].is_string()) {
            return makeError(ErrorCode::InvalidFormat,
                             "Benchmark result " + std::to_string(i) + " has no \"scene\" string.");
        }
        const std::string scene = result["scene"].get<std::string>();
        const bool walkthrough = scene == "flythrough" || scene == "city";
        if (scene != "generated" && scene != "animometer" && scene != "crowd" && !walkthrough) {
            continue;  // Single models have no object-count axis.
        }
        const std::string animation =
            result.contains("animation") && result["animation"].is_string()
                ? result["animation"].get<std::string>()
                : std::string();
        if (!result.contains("strategy") || !result["strategy"].is_string()) {
            return makeError(ErrorCode::InvalidFormat,
                             describe(result, i) + " has no \"strategy\" string.");
        }
        auto point = readPoint(result);
        if (!point) {
            return makeError(point.error().code,
                             describe(result, i) + " " + point.error().message + ".");
        }
        const std::string strategy = result["strategy"].get<std::string>();
        auto it = std::find_if(series.begin(), series.end(), [&](const ScalingSeries& s) {
            return s.scene == scene && s.animation == animation && s.strategy == strategy;
        });
        if (it == series.end()) {
            // A crowd's axis counts characters; its series say where the animation ran.
            // Generated walkthroughs share strategy names; the scene tells their curves apart.
            const std::string label =
                scene == "crowd"
                    ? (animation.empty() ? std::string("still") : animation + "-animated") + " " +
                          strategy
                : walkthrough ? scene + ": " + strategy
                              : strategy;
            it = series.insert(series.end(), ScalingSeries{scene, animation, strategy, label, {}});
        }
        it->points.push_back(*point);
    }
    // Generated scenes first (they are the scaling study), animometer after, each in report order.
    std::stable_partition(series.begin(), series.end(),
                          [](const ScalingSeries& s) { return s.scene == "generated"; });
    for (ScalingSeries& s : series) {
        std::stable_sort(
            s.points.begin(), s.points.end(),
            [](const ScalingPoint& a, const ScalingPoint& b) { return a.objects < b.objects; });
        bool clashes = std::any_of(series.begin(), series.end(), [&](const ScalingSeries& other) {
            return &other != &s && other.strategy == s.strategy;
        });
        if (clashes && s.scene == "animometer") {
            s.label = s.scene + " " + s.strategy;
        }
    }
    return series;
}

Result<json> mergeReports(const std::vector<NamedReport>& reports) {
    if (reports.empty()) {
        return makeError(ErrorCode::InvalidFormat, "No benchmark report to merge.");
    }
    json merged;
    for (const NamedReport& named : reports) {
        const json& report = named.report;
        if (!report.is_object() || !report.contains("results") || !report["results"].is_array()) {
            return makeError(ErrorCode::InvalidFormat,
                             named.name + ": the benchmark report has no \"results\" array.");
        }
        if (merged.is_null()) {
            merged = report;
            continue;
        }
        // Timings of different adapters (or drivers) do not belong on one curve.
        const json none;
        const json& first = merged.contains("adapter") ? merged["adapter"] : none;
        const json& adapter = report.contains("adapter") ? report["adapter"] : none;
        if (adapter != first) {
            return makeError(ErrorCode::InvalidFormat,
                             named.name + ": the adapter (" + adapter.dump() +
                                 ") differs from that of " + reports.front().name + " (" +
                                 first.dump() + "); plot reports of one adapter together.");
        }
        for (const json& result : report["results"]) {
            merged["results"].push_back(result);
        }
    }
    return merged;
}

}  // namespace encore::bench
