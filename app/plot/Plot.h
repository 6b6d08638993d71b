#pragma once
// x/y charts for reports, drawn with Cairo: one drawing routine renders both
// the PNG and the SVG, so the two files show the same chart.

#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace rad::plot {

struct Series {
    std::string label;  // empty: no legend entry
    std::vector<double> x, y;
    bool lines = true;
    bool points = true;
    std::array<float, 3> color = {0.0f, 0.0f, 0.0f};  // linear RGB in [0,1], as in rad::Image
    std::vector<std::string> pointLabels;             // optional text beside each point
};

struct Chart {
    std::string title, xLabel, yLabel;
    bool logX = false, logY = false;  // non-positive values are left out on a log axis
    std::vector<Series> series;
    std::optional<std::pair<double, double>> diagonal;  // draw y = x over [a,b], dashed
};

// Draws the charts side by side, each width x height pixels, and writes
// pathWithoutExtension + ".png" and + ".svg", each atomically (a temporary
// beside the target, then renamed). An existing file is replaced only when
// overwrite is set. Throws std::runtime_error with a one-line message naming
// the file.
void writeCharts(const std::vector<Chart>& charts, const std::string& pathWithoutExtension,
                 bool overwrite, int width = 800, int height = 500);

// Where the data point (x, y) lands in a width x height chart, in pixels from
// its top-left corner; nullopt when it is not drawable (non-finite, or
// non-positive on a log axis). For tests and for callers adding overlays.
std::optional<std::array<double, 2>> dataToPixel(const Chart& chart, double x, double y,
                                                 int width = 800, int height = 500);

}  // namespace rad::plot
