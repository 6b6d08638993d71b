#include "cli/Warnings.h"

#include <cstdio>
#include <string>

namespace rad::cli {

std::vector<Warning> importWarnings(const ImportNotes& notes) {
    std::vector<Warning> out;
    for (const DuplicatePolygons& d : notes.duplicates) {
        const std::string count = std::to_string(d.count) + (d.count == 1 ? " polygon" : " polygons");
        const std::string message =
            d.kept == d.dropped
                ? count + " of '" + d.kept + "' repeated in place within the object: dropped at import"
                : count + " of '" + d.dropped + "' repeated polygons of '" + d.kept +
                      "' in place (the same geometry twice): dropped at import";
        out.push_back({"duplicates", message, {d.kept, d.dropped}, static_cast<double>(d.count)});
    }
    return out;
}

void printWarnings(const std::vector<Warning>& warnings) {
    for (const Warning& w : warnings) std::fprintf(stderr, "warning: %s\n", w.message.c_str());
}

Report warningsReport(const std::vector<Warning>& warnings) {
    Report list = Report::array();
    for (const Warning& w : warnings)
        list.push_back({{"kind", w.kind}, {"message", w.message}, {"objects", w.objects}, {"amount", w.amount}});
    return list;
}

}  // namespace rad::cli
