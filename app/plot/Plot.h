#pragma once
// Small dependency-free x/y charts for reports: one layout, drawn either as an
// SVG document or into a rad::Image (with an embedded bitmap font), so the two
// outputs agree pixel for pixel in where things are.

#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "image/Image.h"

namespace rad::plot {

struct Series {
    std::string label;  // empty: no legend entry
    std::vector<double> x, y;
    bool lines = true;
    bool points = true;
    std::array<float, 3> color = {0.0f, 0.0f, 0.0f};  // linear RGB in [0,1], as in rad::Image
    std::vector<std::string> pointLabels;              // optional text beside each point
};

struct Chart {
    std::string title, xLabel, yLabel;
    bool logX = false, logY = false;
    std::vector<Series> series;
    std::optional<std::pair<double, double>> diagonal;  // draw y = x over [a,b], dashed
};

// Complete SVG document: axes, ticks with numbers, labels, legend, title.
std::string toSvg(const Chart& chart, int width = 800, int height = 500);

// The same drawing in linear RGB on a white background.
Image toImage(const Chart& chart, int width = 800, int height = 500);

// Writes pathWithoutExtension + ".svg" and + ".png", each atomically.
void writeChart(const Chart& chart, const std::string& pathWithoutExtension);
// Several charts side by side in one .svg and one .png.
void writeCharts(const std::vector<Chart>& charts, const std::string& pathWithoutExtension, int width = 800,
                 int height = 500);

// Where the data point (x, y) lands in toSvg/toImage of the same size, in
// pixels from the top-left corner; nullopt when it is not drawable (non-finite,
// or non-positive on a log axis). For tests and for callers adding overlays.
std::optional<std::array<double, 2>> dataToPixel(const Chart& chart, double x, double y,
                                                 int width = 800, int height = 500);

}  // namespace rad::plot
