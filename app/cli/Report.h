#pragma once
// The JSON reports of `solve`, `animate` and `sweep`, and how the CLI writes
// its output files. Every key of every report is documented in README.md
// ("Reports"); tests/cli/cli_report_schema_test.cpp keeps the two in step.

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "radiosity/Stats.h"

namespace rad::cli {

// Keys stay in the order a command adds them, so a report reads top-down.
using Report = nlohmann::ordered_json;

// The value, or null when there is none ("budget": null for no limit).
template <typename T>
Report valueOrNull(const std::optional<T>& v) {
    return v ? Report(*v) : Report(nullptr);
}

// The report's `warnings`: an array of {kind, message, objects, amount}.
Report warningsReport(const std::vector<Warning>& warnings);

// Writes the report as indented JSON, atomically. Non-finite numbers (NaN,
// infinities) are written as null; that policy lives in this function alone.
void writeReport(const std::string& path, Report report);

}  // namespace rad::cli
