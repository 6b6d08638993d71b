#include "cli/Report.h"

#include <cmath>

#include "image/AtomicFile.h"

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

Report warningsReport(const std::vector<Warning>& warnings) {
    Report list = Report::array();
    for (const Warning& w : warnings)
        list.push_back({{"kind", w.kind}, {"message", w.message}, {"objects", w.objects}, {"amount", w.amount}});
    return list;
}

}  // namespace rad::cli
