#include "cli/Report.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace rad::cli {
namespace {

// JSON has no NaN or infinity. Reports write null for them, as the CLI always
// has (nlohmann's dump() would too, silently); one place to change the policy.
void nonFiniteAsNull(Report& value) {
    if (value.is_number_float() && !std::isfinite(value.get<double>())) value = nullptr;
    if (value.is_structured())
        for (Report& child : value) nonFiniteAsNull(child);
}

}  // namespace

void writeReport(const std::string& path, Report report) {
    nonFiniteAsNull(report);
    // A scene path or object name need not be UTF-8: invalid bytes become
    // U+FFFD rather than failing the whole report.
    writeFileAtomically(path, report.dump(2, ' ', false, Report::error_handler_t::replace) + "\n");
}

void writeFileAtomically(const std::string& path, const std::string& text) {
    const std::string tmp = path + ".tmp";
    {
        std::ofstream out(tmp, std::ios::binary);
        if (!out) throw std::runtime_error(path + ": cannot open for writing");
        out << text;
        if (!out) throw std::runtime_error(path + ": write failed");
    }
    std::filesystem::rename(tmp, path);
}

}  // namespace rad::cli
