#pragma once

// Plots of `encore bench` reports. A report holds one entry per (scene, strategy, object count);
// the scaling plot shows how the per-frame CPU and GPU time (and, for culling strategies, the
// triangles drawn) of each strategy grow with the number of objects, so strategies can be
// compared across several orders of magnitude at a glance.

#include <nlohmann/json.hpp>

#include <string>

#include "encore/core/Result.h"

namespace encore::bench {

// Renders the scaling curves of a benchmark report as a self-contained SVG document (about
// 900×560 px, 1320 px wide with three panels; no external fonts, scripts or images).
//
// Plotted are the series bench::readScalingSeries reads (BenchmarkReportReader.h), from the
// results whose "scene" is
//   - "generated": one series per "strategy";
//   - "animometer": their own series, one per strategy;
//   - "crowd": one series per strategy and "animation" (where the animation was evaluated);
//   - "flythrough" or "city" (generated walkthroughs): one series per scene and strategy, named
//     "<scene>: <strategy>".
// Points are sorted by "objects" (characters for crowds). Other scenes (single models) have no
// object-count axis and are left out. Both axes are log10: x is the object count.
//
// Each point is a median with a whisker. The first panel shows CPU time per frame in ms: "cpuMs"
// where the report has it, otherwise "encodeMs" + "submitMs" (the p95 then being the sum of both
// p95s, an upper bound). A second panel with "gpuMs" appears when any plotted result has GPU
// timings; "gpuMs": null means the adapter had no timestamp queries. Time whiskers end at the p95.
// A last panel, "triangles per frame", appears when any plotted result has per-frame triangle
// counts: the median of "trianglesDrawn" (what GPU culling let through), or of
// "trianglesSubmitted" where "trianglesDrawn" is null or empty (strategies that draw what they
// submit), with a whisker up to the largest count. Points whose values are not positive are
// skipped, since a log axis cannot show them.
//
// The output depends only on the report: the same JSON gives the same bytes, with coordinates
// printed to one decimal whatever the process locale.
//
// Returns an InvalidFormat error naming the offending field when the report lacks "results" or
// "adapter.name", when a plotted result lacks a "strategy", an "objects" count or a CPU median,
// when a triangle count array holds a non-number, or when no result is plottable at all.
Result<std::string> plotScalingSvg(const nlohmann::json& report);

}  // namespace encore::bench
