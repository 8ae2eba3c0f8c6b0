#pragma once
// The plan's figures in three forms: report.json (machine-readable), report.md (human-readable,
// with a table per circuit) and the stdout summary. All three carry the same figures: fibre
// length, wind time, circuits, coverage, spacing CV, max slippage (of the passes), the stability
// of the turnarounds (max slippage, length above friction, bridging; in report.json and report.md
// also per end), the geodesic turn limit (shapes of revolution only; JSON null / "none" when
// there is no limit), axis ranges, cut-line planes and the files written. Stage timings
// (PlanMetrics::timings) appear in the files only when ExportResult::timings (output.timings) is
// set, so that files stay byte-identical between runs; the stdout summary always shows them.
// Numbers have fixed formats (deterministic).
#include <string>

#include "export/files/export_result.h"
#include "geometry/base/json.h"
#include "planner/plan/plan.h"

namespace windplan {

std::string report_json(const WindingPlan& plan, const ExportResult& result);
std::string report_markdown(const WindingPlan& plan, const ExportResult& result);
/// The summary printed on stdout by `windplan`.
std::string summary_text(const WindingPlan& plan, const ExportResult& result);

/// The turnaround figures of both ends as a JSON array of two objects (start, end): along loop or
/// station, station, length, max_slippage, slip_length, slip_fraction, bridging_length. With
/// `mm_keys` the keys of lengths carry their unit (`length_mm`, ...), as everywhere in
/// report.json; `windplan helices --json` writes them without (its other keys have none).
void turnarounds_json(JsonWriter& j, const PlanMetrics& m, bool mm_keys);
/// The measured coverage (planner/winding/coverage.h) as a JSON object: the figures over all
/// stations and one object per station; lengths with an "_mm" suffix when mm_keys.
void coverage_json(JsonWriter& j, const CoverageReport& c, bool mm_keys);
/// The friction turnarounds (FrictionFigures: winding.slippage > 0) as a JSON object: the bound,
/// mu, the passes' and each end's planned and measured |k_g/k_n| and friction lengths (mm).
void friction_json(JsonWriter& j, const FrictionFigures& f);
/// How the circuits were planned on a shape of revolution (PatternInfo) as a JSON object.
void pattern_json(JsonWriter& j, const PatternInfo& p, bool mm_keys);

}  // namespace windplan
