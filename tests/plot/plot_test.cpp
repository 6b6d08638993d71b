// rad::plot: the files writeCharts leaves on disk, decoded and parsed: PNG
// size and pixels where the data should land, SVG structure and text, errors.

#include "plot/Plot.h"

#include <expat.h>
#include <gtest/gtest.h>
#include <stb/stb_image.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "image/Image.h"
#include "support/Cli.h"
#include "support/TempDir.h"

namespace rad::plot {
namespace {

using Rgb = std::array<float, 3>;
const Rgb kRed = {0.8f, 0.05f, 0.05f};
const Rgb kBlue = {0.05f, 0.1f, 0.8f};

// Designated initializers would need every member spelled out under -Wextra (GCC 12).
Series makeSeries(std::vector<double> x, std::vector<double> y, Rgb color, std::string label = {},
                  bool lines = true) {
    Series s;
    s.x = std::move(x);
    s.y = std::move(y);
    s.color = color;
    s.label = std::move(label);
    s.lines = lines;
    return s;
}

Chart sampleChart() {
    Chart c;
    c.title = "Error & time <per frame>";
    c.xLabel = "patches";
    c.yLabel = "seconds";
    Series b = makeSeries({150, 300}, {0.3, 0.9}, kBlue, "scatter", false);
    b.pointLabels = {"p1", "p2"};
    c.series = {makeSeries({100, 200, 400, 800}, {0.1, 0.25, 0.5, 1.2}, kRed, "solve"), b};
    return c;
}

// A decoded PNG, 8-bit sRGB.
struct Png {
    int width = 0, height = 0;
    std::vector<unsigned char> rgb;

    std::array<int, 3> at(int x, int y) const {
        const unsigned char* p = &rgb[3 * (static_cast<std::size_t>(y) * width + x)];
        return {p[0], p[1], p[2]};
    }
};

Png readPng(const std::string& path) {
    Png png;
    int channels = 0;
    const std::unique_ptr<unsigned char, decltype(&stbi_image_free)> data(
        stbi_load(path.c_str(), &png.width, &png.height, &channels, 3), &stbi_image_free);
    if (!data) throw std::runtime_error(path + ": not a decodable image");
    png.rgb.assign(data.get(), data.get() + static_cast<std::size_t>(png.width) * png.height * 3);
    return png;
}

// What a linear chart colour looks like in the PNG.
std::array<int, 3> srgb(const Rgb& c) {
    return {encodeSrgb(c[0]), encodeSrgb(c[1]), encodeSrgb(c[2])};
}

bool near(const std::array<int, 3>& a, const std::array<int, 3>& b, int tolerance = 2) {
    for (int k = 0; k < 3; ++k)
        if (std::abs(a[k] - b[k]) > tolerance) return false;
    return true;
}

std::array<double, 2> pixelOf(const Chart& c, double x, double y, int width = 800,
                              int height = 500) {
    const auto p = dataToPixel(c, x, y, width, height);
    if (!p) throw std::logic_error("point not drawable");
    return *p;
}

// The colour at the pixel holding (x, y) of the 800 x 500 chart c, drawn
// offsetX pixels to the right in the file.
std::array<int, 3> colourAt(const Png& png, const Chart& c, double x, double y, int offsetX = 0) {
    const auto p = pixelOf(c, x, y);
    return png.at(offsetX + static_cast<int>(p[0]), static_cast<int>(p[1]));
}

// Every pixel of that colour lies within radius of one of the centres.
void expectColourOnlyNear(const Png& png, const std::array<int, 3>& colour,
                          const std::vector<std::array<double, 2>>& centres, double radius) {
    int found = 0;
    for (int y = 0; y < png.height; ++y)
        for (int x = 0; x < png.width; ++x) {
            if (!near(png.at(x, y), colour)) continue;
            ++found;
            bool close = false;
            for (const auto& c : centres)
                close |= std::hypot(x + 0.5 - c[0], y + 0.5 - c[1]) <= radius;
            EXPECT_TRUE(close) << "colour at " << x << "," << y << " away from every data point";
        }
    EXPECT_GT(found, 0);
}

int darkPixelsIn(const Png& png, int x0, int y0, int x1, int y1) {
    int n = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) n += png.at(x, y)[0] < 128;
    return n;
}

std::size_t count(const std::string& haystack, const std::string& needle) {
    std::size_t n = 0;
    for (std::size_t at = haystack.find(needle); at != std::string::npos;
         at = haystack.find(needle, at + 1))
        ++n;
    return n;
}

// The SVG parsed by expat: whether it is well-formed, its root element and
// the character data inside <title> and <desc>.
struct ParsedSvg {
    bool wellFormed = false;
    std::string error, root, title, desc;
};

ParsedSvg parseSvg(const std::string& text) {
    struct State {
        ParsedSvg result;
        std::vector<std::string> open;
    } state;
    const std::unique_ptr<std::remove_pointer_t<XML_Parser>, decltype(&XML_ParserFree)> parser(
        XML_ParserCreate(nullptr), &XML_ParserFree);
    XML_SetUserData(parser.get(), &state);
    XML_SetElementHandler(
        parser.get(),
        [](void* data, const XML_Char* name, const XML_Char**) {
            auto& s = *static_cast<State*>(data);
            if (s.open.empty()) s.result.root = name;
            s.open.emplace_back(name);
        },
        [](void* data, const XML_Char*) { static_cast<State*>(data)->open.pop_back(); });
    XML_SetCharacterDataHandler(parser.get(), [](void* data, const XML_Char* chars, int length) {
        auto& s = *static_cast<State*>(data);
        if (s.open.empty()) return;
        if (s.open.back() == "title") s.result.title.append(chars, length);
        if (s.open.back() == "desc") s.result.desc.append(chars, length);
    });
    state.result.wellFormed = XML_Parse(parser.get(), text.data(), static_cast<int>(text.size()),
                                        XML_TRUE) == XML_STATUS_OK;
    if (!state.result.wellFormed)
        state.result.error = XML_ErrorString(XML_GetErrorCode(parser.get()));
    return state.result;
}

TEST(Plot, WritesAPngOfTheRequestedSizeAndAnSvgBeside) {
    test::TempDir dir;
    const std::string base = (dir / "chart").string();
    writeCharts({sampleChart(), sampleChart()}, base, false, 640, 360);

    const Png png = readPng(base + ".png");
    EXPECT_EQ(png.width, 2 * 640);  // side by side
    EXPECT_EQ(png.height, 360);
    const std::string svg = test::readFile(base + ".svg");
    EXPECT_NE(svg.find("width=\"1280px\" height=\"360px\""), std::string::npos);
    // Only the two files: no temporaries left behind.
    int files = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path())) ++files;
    EXPECT_EQ(files, 2);
}

TEST(Plot, MarkersAppearWhereTheirDataMapsOnLinearAxes) {
    Chart left;
    left.series = {makeSeries({0, 5, 10}, {0, 5, 10}, kRed, {}, false)};
    Chart right;
    right.series = {makeSeries({2, 4}, {8, 1}, kBlue, {}, false)};
    test::TempDir dir;
    writeCharts({left, right}, (dir / "chart").string(), false);
    const Png png = readPng((dir / "chart.png").string());

    // Equal steps in data are equal steps on screen, y up.
    const auto p0 = pixelOf(left, 0, 0), p5 = pixelOf(left, 5, 5), p10 = pixelOf(left, 10, 10);
    EXPECT_NEAR(p5[0] - p0[0], p10[0] - p5[0], 1e-9);
    EXPECT_NEAR(p5[1] - p0[1], p10[1] - p5[1], 1e-9);
    EXPECT_GT(p5[0], p0[0]);
    EXPECT_LT(p5[1], p0[1]);

    for (double v : {0.0, 5.0, 10.0}) EXPECT_TRUE(near(colourAt(png, left, v, v), srgb(kRed))) << v;
    expectColourOnlyNear(png, srgb(kRed), {p0, p5, p10}, 5);
    // The second chart is the right-hand half.
    auto q1 = pixelOf(right, 2, 8), q2 = pixelOf(right, 4, 1);
    EXPECT_TRUE(near(colourAt(png, right, 2, 8, 800), srgb(kBlue)));
    EXPECT_TRUE(near(colourAt(png, right, 4, 1, 800), srgb(kBlue)));
    q1[0] += 800;
    q2[0] += 800;
    expectColourOnlyNear(png, srgb(kBlue), {q1, q2}, 5);
}

TEST(Plot, LogAxesSpaceDecadesEvenlyAndLeaveOutWhatTheyCannotShow) {
    Chart c;
    c.logX = c.logY = true;
    const double nan = std::numeric_limits<double>::quiet_NaN(),
                 inf = std::numeric_limits<double>::infinity();
    c.series = {makeSeries({1, 10, 100, 1000, 0, -1, nan, 10}, {1, 10, 100, 1000, 5, 1, 1, inf},
                           kRed, {}, false)};
    test::TempDir dir;
    writeCharts({c}, (dir / "log").string(), false);
    const Png png = readPng((dir / "log.png").string());

    std::vector<std::array<double, 2>> decades;
    for (double v : {1.0, 10.0, 100.0, 1000.0}) decades.push_back(pixelOf(c, v, v));
    for (std::size_t i = 1; i + 1 < decades.size(); ++i) {
        EXPECT_NEAR(decades[i][0] - decades[i - 1][0], decades[i + 1][0] - decades[i][0], 1e-9);
        EXPECT_NEAR(decades[i][1] - decades[i - 1][1], decades[i + 1][1] - decades[i][1], 1e-9);
    }
    for (double v : {1.0, 10.0, 100.0, 1000.0})
        EXPECT_TRUE(near(colourAt(png, c, v, v), srgb(kRed))) << v;
    // Nothing drawn for zero, negative or non-finite values.
    EXPECT_FALSE(dataToPixel(c, 0, 5).has_value());
    EXPECT_FALSE(dataToPixel(c, -1, 1).has_value());
    EXPECT_FALSE(dataToPixel(c, 10, inf).has_value());
    expectColourOnlyNear(png, srgb(kRed), decades, 5);

    // Grid lines at the decades, and none halfway between them (in log terms).
    const int row = static_cast<int>(pixelOf(c, 1, 300)[1]);
    const std::array<int, 3> white = {255, 255, 255};
    for (double decade : {10.0, 100.0}) {
        const int column = static_cast<int>(pixelOf(c, decade, 1)[0]);
        EXPECT_FALSE(near(png.at(column, row), white, 10)) << "no grid line at " << decade;
    }
    EXPECT_TRUE(near(png.at(static_cast<int>(pixelOf(c, std::sqrt(10.0) * 10, 1)[0]), row), white));
}

TEST(Plot, TitleAxisLabelsAndLegendAreDrawnWithoutHidingData) {
    Chart with = sampleChart();
    Chart without = with;
    without.title.clear();
    without.xLabel.clear();
    without.yLabel.clear();
    for (Series& s : without.series) s.label.clear();
    test::TempDir dir;
    writeCharts({with}, (dir / "with").string(), false);
    writeCharts({without}, (dir / "without").string(), false);
    const Png a = readPng((dir / "with.png").string()), b = readPng((dir / "without.png").string());

    // Title across the top middle, x label along the bottom, y label up the left.
    EXPECT_GT(darkPixelsIn(a, 250, 0, 550, 35), 150);
    EXPECT_EQ(darkPixelsIn(b, 250, 0, 550, 10), 0);
    EXPECT_GT(darkPixelsIn(a, 350, 475, 450, 500), 40);
    EXPECT_GT(darkPixelsIn(a, 0, 200, 30, 300), 40);
    // Background white all round.
    EXPECT_EQ(
        darkPixelsIn(a, 0, 0, a.width, 4) + darkPixelsIn(a, 0, a.height - 4, a.width, a.height), 0);

    // A legend box somewhere in the plot that the unlabelled chart lacks ...
    int differing = 0;
    const auto corner = pixelOf(with, 100, 1.2);
    for (int y = static_cast<int>(corner[1]); y < a.height - 60; ++y)
        for (int x = 100; x < a.width - 30; ++x) differing += !near(a.at(x, y), b.at(x, y), 40);
    EXPECT_GT(differing, 300);
    // ... that leaves every marker visible.
    for (const Series& s : with.series)
        for (std::size_t i = 0; i < s.x.size(); ++i)
            EXPECT_TRUE(near(colourAt(a, with, s.x[i], s.y[i]), srgb(s.color)))
                << s.label << " " << i;
}

TEST(Plot, SvgIsWellFormedAndCarriesItsTextAsWellAsItsGlyphs) {
    test::TempDir dir;
    Chart with = sampleChart();
    Chart without = with;
    without.title.clear();
    writeCharts({with}, (dir / "with").string(), false);
    writeCharts({without}, (dir / "without").string(), false);
    const std::string svg = test::readFile((dir / "with.svg").string());

    const ParsedSvg parsed = parseSvg(svg);
    ASSERT_TRUE(parsed.wellFormed) << parsed.error;
    EXPECT_EQ(parsed.root, "svg");
    EXPECT_NE(parsed.title.find("Error & time <per frame>"), std::string::npos) << parsed.title;
    for (const char* text : {"patches", "seconds", "solve", "scatter"})
        EXPECT_NE(parsed.desc.find(text), std::string::npos) << text << " not in " << parsed.desc;
    // Cairo draws text as glyph outlines placed by <use>, one per character:
    // the title accounts for exactly its own.
    const std::string untitled = test::readFile((dir / "without.svg").string());
    EXPECT_EQ(count(svg, "<use"), count(untitled, "<use") + with.title.size());
}

TEST(Plot, DiagonalIsDashedAndInsideTheRange) {
    Chart c;
    c.series = {makeSeries({1, 2}, {1.5, 1.8}, kRed, "measured", false)};
    c.diagonal = std::make_pair(0.0, 4.0);
    test::TempDir dir;
    writeCharts({c}, (dir / "diagonal").string(), false);
    const Png png = readPng((dir / "diagonal.png").string());

    const auto end = pixelOf(c, 4, 4);
    EXPECT_GT(end[0], 0);
    EXPECT_LT(end[0], png.width);
    EXPECT_GT(end[1], 0);
    // Along y = x: grey dashes with white gaps between them.
    int dash = 0, gap = 0;
    for (double v = 2.2; v < 3.4; v += 0.01) {
        const auto colour = colourAt(png, c, v, v);
        dash += colour[0] < 200;
        gap += near(colour, {255, 255, 255}, 30);
    }
    EXPECT_GT(dash, 10);
    EXPECT_GT(gap, 10);
}

TEST(Plot, DegenerateDataStillGivesACompleteChart) {
    Chart empty;
    Chart emptySeries;
    emptySeries.series = {makeSeries({}, {}, kRed, "nothing")};
    Chart allInvalidOnLog;
    allInvalidOnLog.logY = true;
    allInvalidOnLog.series = {makeSeries({1, 2}, {0, -1}, kRed)};
    allInvalidOnLog.diagonal = std::make_pair(-1.0, 2.0);
    Chart single;  // one point: the range opens around it
    single.series = {makeSeries({5}, {5}, kRed)};
    test::TempDir dir;
    writeCharts({empty, emptySeries, allInvalidOnLog, single}, (dir / "odd").string(), false);

    const Png png = readPng((dir / "odd.png").string());
    EXPECT_EQ(png.width, 4 * 800);
    EXPECT_TRUE(parseSvg(test::readFile((dir / "odd.svg").string())).wellFormed);
    const auto mid = pixelOf(single, 5, 5);
    EXPECT_NEAR(mid[0], 800 / 2.0, 100);
    EXPECT_TRUE(near(colourAt(png, single, 5, 5, 3 * 800), srgb(kRed)));
    // Axes with numbers even without data.
    const auto origin = pixelOf(empty, 0, 0);
    EXPECT_GT(
        darkPixelsIn(png, 0, static_cast<int>(origin[1]) - 10, static_cast<int>(origin[0]), 500),
        50);
}

TEST(Plot, AnUnwritablePathIsAOneLineErrorNamingTheFile) {
    test::TempDir dir;
    const std::string base = (dir / "missing" / "chart").string();
    try {
        writeCharts({sampleChart()}, base, false);
        FAIL() << "no error";
    } catch (const std::runtime_error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(base + ".png"), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "missing"));
}

TEST(Plot, ExistingFilesAreReplacedOnlyWhenAskedTo) {
    test::TempDir dir;
    const std::string base = (dir / "chart").string();
    writeCharts({sampleChart()}, base, false);
    const std::string before = test::readFile(base + ".svg");

    Chart other = sampleChart();
    other.title = "Another";
    EXPECT_THROW(writeCharts({other}, base, false), std::runtime_error);
    EXPECT_EQ(test::readFile(base + ".svg"), before);
    // Refused for the SVG alone too, without touching the PNG.
    std::filesystem::remove(base + ".png");
    EXPECT_THROW(writeCharts({other}, base, false), std::runtime_error);
    EXPECT_FALSE(std::filesystem::exists(base + ".png"));

    writeCharts({other}, base, true);
    EXPECT_NE(test::readFile(base + ".svg").find("Another"), std::string::npos);
    EXPECT_EQ(readPng(base + ".png").width, 800);
}

TEST(Plot, TextCairoCannotDrawIsAnErrorNamingTheFile) {
    Chart c = sampleChart();
    c.xLabel = "bad \xff byte";  // not UTF-8
    test::TempDir dir;
    const std::string base = (dir / "chart").string();
    try {
        writeCharts({c}, base, false);
        FAIL() << "no error";
    } catch (const std::runtime_error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(base + ".png"), std::string::npos) << message;
        EXPECT_NE(message.find("UTF-8"), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
    EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

}  // namespace
}  // namespace rad::plot
