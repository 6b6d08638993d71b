// rad::plot: SVG structure, raster output and files on disk.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <cctype>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "plot/Plot.h"
#include "support/TempDir.h"

namespace rad::plot {
namespace {

std::size_t count(const std::string& haystack, const std::string& needle) {
    std::size_t n = 0;
    for (std::size_t at = haystack.find(needle); at != std::string::npos; at = haystack.find(needle, at + 1)) ++n;
    return n;
}

// Designated initializers would need every member spelled out under -Wextra (GCC 12).
Series makeSeries(std::vector<double> x, std::vector<double> y, std::array<float, 3> color = {0, 0, 0},
                  std::string label = {}) {
    Series s;
    s.x = std::move(x);
    s.y = std::move(y);
    s.color = color;
    s.label = std::move(label);
    return s;
}

bool isWhite(const Image& img, int x, int y) {
    const float* p = img.pixel(x, y);
    return p[0] == 1.0f && p[1] == 1.0f && p[2] == 1.0f;
}

int nonWhiteIn(const Image& img, int x0, int y0, int x1, int y1) {
    int n = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) n += !isWhite(img, x, y);
    return n;
}

Chart sampleChart() {
    Chart c;
    c.title = "Error & time <per frame>";
    c.xLabel = "patches";
    c.yLabel = "seconds";
    Series a;
    a.label = "solve";
    a.x = {100, 200, 400, 800};
    a.y = {0.1, 0.25, 0.5, 1.2};
    a.color = {0.8f, 0.1f, 0.1f};
    Series b;
    b.label = "scatter";
    b.lines = false;
    b.x = {150, 300};
    b.y = {0.3, 0.9};
    b.color = {0.1f, 0.2f, 0.8f};
    b.pointLabels = {"p1", "p2"};
    Series c2;
    c2.label = "update";
    c2.x = {100, 800};
    c2.y = {0.05, 0.3};
    c2.color = {0.1f, 0.6f, 0.1f};
    c.series = {a, b, c2};
    return c;
}

TEST(Plot, SvgIsADocumentWithLabelsAndOnePathPerLineSeries) {
    const std::string svg = toSvg(sampleChart());
    EXPECT_EQ(svg.rfind("<svg", 0), 0u);
    std::string trimmed = svg;
    while (!trimmed.empty() && std::isspace(static_cast<unsigned char>(trimmed.back()))) trimmed.pop_back();
    EXPECT_TRUE(trimmed.ends_with("</svg>"));
    EXPECT_NE(svg.find("Error &amp; time &lt;per frame&gt;"), std::string::npos);
    EXPECT_EQ(svg.find("Error & time"), std::string::npos);
    EXPECT_EQ(svg.find("<per frame>"), std::string::npos);
    EXPECT_NE(svg.find(">patches<"), std::string::npos);
    EXPECT_NE(svg.find(">seconds<"), std::string::npos);
    EXPECT_NE(svg.find(">solve<"), std::string::npos);  // legend
    EXPECT_NE(svg.find(">p2<"), std::string::npos);     // point label
    EXPECT_EQ(count(svg, "<path"), 2u);                 // two of the three series have lines
    EXPECT_EQ(count(svg, "<text"), count(svg, "</text>"));
    // Tick numbers: 1/2/5 steps on this range.
    EXPECT_NE(svg.find(">0.4<"), std::string::npos);
    EXPECT_NE(svg.find(">400<"), std::string::npos);
}

TEST(Plot, EmptyChartAndEmptySeriesGiveAxesOnly) {
    Chart empty;
    const std::string svg = toSvg(empty);
    EXPECT_EQ(svg.rfind("<svg", 0), 0u);
    EXPECT_NE(svg.find("</svg>"), std::string::npos);
    EXPECT_EQ(count(svg, "<path"), 0u);
    EXPECT_GT(count(svg, "<text"), 2u);  // tick numbers

    Chart withEmptySeries;
    withEmptySeries.series.push_back(makeSeries({}, {}, {0, 0, 0}, "nothing"));
    EXPECT_EQ(count(toSvg(withEmptySeries), "<path"), 0u);
    const Image img = toImage(withEmptySeries);
    EXPECT_EQ(img.width, 800);
    EXPECT_EQ(img.height, 500);
}

TEST(Plot, LogAxesUseDecadesAndSkipNonPositiveAndNonFinite) {
    Chart c;
    c.logX = c.logY = true;
    const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    c.series.push_back(makeSeries({-1, 0, 1, 10, 100, 1000, nan, 1e4}, {5, 1, 1, 0.1, 0.01, -3, 1e-3, inf},
                                  {0, 0, 0}, "err"));
    const std::string svg = toSvg(c);
    EXPECT_NE(svg.find(">100<"), std::string::npos);
    EXPECT_NE(svg.find(">0.01<"), std::string::npos);
    // No "nan" or "inf" as a word anywhere (std::regex trips GCC 12's
    // -Wmaybe-uninitialized under the sanitizer build).
    std::string lower = svg;
    for (char& ch : lower) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    for (const std::string word : {"nan", "inf"})
        for (std::size_t at = lower.find(word); at != std::string::npos; at = lower.find(word, at + 1)) {
            const bool before = at > 0 && std::isalpha(static_cast<unsigned char>(lower[at - 1]));
            const bool after = at + 3 < lower.size() && std::isalpha(static_cast<unsigned char>(lower[at + 3]));
            EXPECT_TRUE(before || after) << "non-finite value written at " << at;
        }
    // The path is broken where points were skipped, but stays one element.
    EXPECT_EQ(count(svg, "<path"), 1u);
    const Image img = toImage(c);
    EXPECT_EQ(img.rgb.size(), 800u * 500u * 3u);
    EXPECT_FALSE(dataToPixel(c, 0, 1).has_value());
    EXPECT_TRUE(dataToPixel(c, 10, 0.1).has_value());

    // All values invalid on a log axis: still a document.
    Chart bad;
    bad.logY = true;
    bad.series.push_back(makeSeries({1, 2}, {0, -1}));
    bad.diagonal = std::make_pair(-1.0, 2.0);
    EXPECT_NE(toSvg(bad).find("</svg>"), std::string::npos);
    toImage(bad);
}

TEST(Plot, PointsAllAtOnePlaceColourThatPlace) {
    Chart c;
    c.series.push_back(makeSeries({0, 10}, {0, 10}, {0.0f, 0.0f, 1.0f}));
    c.series.push_back(makeSeries({2, 2, 2}, {8, 8, 8}, {1.0f, 0.0f, 0.0f}));
    const Image img = toImage(c);
    const auto at = dataToPixel(c, 2, 8);
    ASSERT_TRUE(at.has_value());
    const int px = static_cast<int>((*at)[0]), py = static_cast<int>((*at)[1]);
    const float* p = img.pixel(px, py);
    EXPECT_FLOAT_EQ(p[0], 1.0f);
    EXPECT_FLOAT_EQ(p[1], 0.0f);
    EXPECT_FLOAT_EQ(p[2], 0.0f);
    // Red only around that point.
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const float* q = img.pixel(x, y);
            if (q[0] > 0.5f && q[1] < 0.5f && q[2] < 0.5f) {
                EXPECT_LE(std::abs(x - px), 6);
                EXPECT_LE(std::abs(y - py), 6);
            }
        }
    // Also for a chart whose only data is that one point (degenerate ranges).
    Chart single;
    single.series.push_back(makeSeries({5}, {5}, {1.0f, 0.0f, 0.0f}));
    const auto mid = dataToPixel(single, 5, 5);
    ASSERT_TRUE(mid.has_value());
    const Image one = toImage(single);
    EXPECT_FLOAT_EQ(one.pixel(static_cast<int>((*mid)[0]), static_cast<int>((*mid)[1]))[0], 1.0f);
    EXPECT_FLOAT_EQ(one.pixel(static_cast<int>((*mid)[0]), static_cast<int>((*mid)[1]))[1], 0.0f);
}

TEST(Plot, BackgroundStaysWhiteAwayFromThePlot) {
    const Image img = toImage(sampleChart());
    // A border all round, and the corners beside the title and below the y axis.
    EXPECT_EQ(nonWhiteIn(img, 0, 0, img.width, 4), 0);
    EXPECT_EQ(nonWhiteIn(img, 0, img.height - 4, img.width, img.height), 0);
    EXPECT_EQ(nonWhiteIn(img, 0, 0, 4, img.height), 0);
    EXPECT_EQ(nonWhiteIn(img, img.width - 4, 0, img.width, img.height), 0);
    EXPECT_EQ(nonWhiteIn(img, 0, 0, 150, 30), 0);
    EXPECT_EQ(nonWhiteIn(img, 0, img.height - 30, 60, img.height), 0);
}

TEST(Plot, TitleIsDrawnAsTextAtTheTop) {
    Chart with = sampleChart();
    Chart without = with;
    without.title.clear();
    const Image a = toImage(with), b = toImage(without);
    // A band across the middle of the top: title pixels, nothing when untitled.
    EXPECT_GT(nonWhiteIn(a, 250, 0, 550, 30), 200);
    EXPECT_EQ(nonWhiteIn(b, 250, 0, 550, 10), 0);
    // Text is dark, drawn at full coverage.
    bool dark = false;
    for (int y = 0; y < 30 && !dark; ++y)
        for (int x = 250; x < 550 && !dark; ++x) dark = a.pixel(x, y)[0] < 0.01f;
    EXPECT_TRUE(dark);
}

TEST(Plot, DiagonalIsDashedAndIncludedInTheRange) {
    Chart c;
    c.series.push_back(makeSeries({1, 2}, {1.5, 1.8}, {0, 0, 0}, "measured"));
    c.series.back().lines = false;
    c.diagonal = std::make_pair(0.0, 4.0);
    const std::string svg = toSvg(c);
    EXPECT_NE(svg.find("stroke-dasharray"), std::string::npos);
    EXPECT_NE(svg.find(">y = x<"), std::string::npos);
    EXPECT_NE(svg.find(">4<"), std::string::npos);
    EXPECT_TRUE(dataToPixel(c, 4, 4).has_value());
}

TEST(Plot, WriteChartWritesSvgAndPng) {
    test::TempDir dir;
    const std::string base = (dir / "chart").string();
    writeChart(sampleChart(), base);
    ASSERT_TRUE(std::filesystem::exists(base + ".svg"));
    ASSERT_TRUE(std::filesystem::exists(base + ".png"));
    std::ifstream png(base + ".png", std::ios::binary);
    char magic[4] = {};
    png.read(magic, 4);
    EXPECT_EQ(std::string(magic + 1, 3), "PNG");
    std::ifstream svgFile(base + ".svg");
    std::stringstream svg;
    svg << svgFile.rdbuf();
    EXPECT_EQ(svg.str(), toSvg(sampleChart()));
    // No temporaries left behind.
    int files = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path())) ++files;
    EXPECT_EQ(files, 2);
}

}  // namespace
}  // namespace rad::plot
