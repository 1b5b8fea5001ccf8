#pragma once

// Plots of `encore bench` reports. A report holds one entry per (scene, strategy, object count);
// the scaling plot shows how the per-frame time of each strategy grows with the number of
// objects, so strategies can be compared across several orders of magnitude at a glance.

#include <nlohmann/json_fwd.hpp>

#include <string>

#include "encore/core/Result.h"

namespace encore::app {

// Renders the scaling curves of a benchmark report as a self-contained SVG document (about
// 900×560 px, no external fonts, scripts or images).
//
// Plotted are the results whose "scene" is "generated" (one series per "strategy", points sorted
// by "objects") and those whose "scene" is "animometer" (their own series, one per strategy);
// other scenes (single models) have no object-count axis and are left out. Both axes are log10:
// x is the object count, y milliseconds. Each point is a median with a whisker up to the p95.
// The left (or only) panel shows CPU time per frame: "cpuMs" where the report has it, otherwise
// "encodeMs" + "submitMs" (the p95 then being the sum of both p95s, an upper bound). A second
// panel with "gpuMs" appears when any plotted result has GPU timings; "gpuMs": null means the
// adapter had no timestamp queries. Points whose values are not positive are skipped, since a
// log axis cannot show them.
//
// The output depends only on the report: the same JSON gives the same bytes, with coordinates
// printed to one decimal whatever the process locale.
//
// Returns an InvalidFormat error naming the offending field when the report lacks "results" or
// "adapter.name", when a plotted result lacks a "strategy", an "objects" count or a CPU median,
// or when no result is plottable at all.
Result<std::string> plotScalingSvg(const nlohmann::json& report);

}  // namespace encore::app
