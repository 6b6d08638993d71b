#include "plot/Plot.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <type_traits>
#include <variant>

#include "cli/Json.h"

namespace rad::plot {
namespace {

using Rgb = std::array<float, 3>;

struct Pt {
    double x = 0, y = 0;
};

// ---------------------------------------------------------------------------
// Bitmap font: 5x7 glyphs for ASCII 32..126, one byte per column (left to
// right), bit 0 the top row; bit 7 is a descender row below the 7-row cell
// (g j p q y), which layout ignores so text centres on its capitals. Drawn at kScale so it reads at chart sizes; the
// SVG uses a 20px monospace font, whose 0.6em advance matches kAdvance, so
// both outputs lay text out identically.

constexpr int kScale = 2;
constexpr int kAdvance = 6 * kScale;  // 5 columns + 1 spacing
constexpr int kTextH = 7 * kScale;
constexpr int kSvgFontPx = 20;

constexpr std::uint8_t kFont[95][5] = {
    {0x00, 0x00, 0x00, 0x00, 0x00},  // ' '
    {0x00, 0x00, 0x5F, 0x00, 0x00},  // !
    {0x00, 0x07, 0x00, 0x07, 0x00},  // "
    {0x14, 0x7F, 0x14, 0x7F, 0x14},  // #
    {0x24, 0x2A, 0x7F, 0x2A, 0x12},  // $
    {0x23, 0x13, 0x08, 0x64, 0x62},  // %
    {0x36, 0x49, 0x55, 0x22, 0x50},  // &
    {0x00, 0x05, 0x03, 0x00, 0x00},  // '
    {0x00, 0x1C, 0x22, 0x41, 0x00},  // (
    {0x00, 0x41, 0x22, 0x1C, 0x00},  // )
    {0x14, 0x08, 0x3E, 0x08, 0x14},  // *
    {0x08, 0x08, 0x3E, 0x08, 0x08},  // +
    {0x00, 0x50, 0x30, 0x00, 0x00},  // ,
    {0x08, 0x08, 0x08, 0x08, 0x08},  // -
    {0x00, 0x60, 0x60, 0x00, 0x00},  // .
    {0x20, 0x10, 0x08, 0x04, 0x02},  // /
    {0x3E, 0x51, 0x49, 0x45, 0x3E},  // 0
    {0x00, 0x42, 0x7F, 0x40, 0x00},  // 1
    {0x42, 0x61, 0x51, 0x49, 0x46},  // 2
    {0x21, 0x41, 0x45, 0x4B, 0x31},  // 3
    {0x18, 0x14, 0x12, 0x7F, 0x10},  // 4
    {0x27, 0x45, 0x45, 0x45, 0x39},  // 5
    {0x3C, 0x4A, 0x49, 0x49, 0x30},  // 6
    {0x01, 0x71, 0x09, 0x05, 0x03},  // 7
    {0x36, 0x49, 0x49, 0x49, 0x36},  // 8
    {0x06, 0x49, 0x49, 0x29, 0x1E},  // 9
    {0x00, 0x36, 0x36, 0x00, 0x00},  // :
    {0x00, 0x56, 0x36, 0x00, 0x00},  // ;
    {0x08, 0x14, 0x22, 0x41, 0x00},  // <
    {0x14, 0x14, 0x14, 0x14, 0x14},  // =
    {0x00, 0x41, 0x22, 0x14, 0x08},  // >
    {0x02, 0x01, 0x51, 0x09, 0x06},  // ?
    {0x32, 0x49, 0x79, 0x41, 0x3E},  // @
    {0x7E, 0x11, 0x11, 0x11, 0x7E},  // A
    {0x7F, 0x49, 0x49, 0x49, 0x36},  // B
    {0x3E, 0x41, 0x41, 0x41, 0x22},  // C
    {0x7F, 0x41, 0x41, 0x22, 0x1C},  // D
    {0x7F, 0x49, 0x49, 0x49, 0x41},  // E
    {0x7F, 0x09, 0x09, 0x09, 0x01},  // F
    {0x3E, 0x41, 0x49, 0x49, 0x7A},  // G
    {0x7F, 0x08, 0x08, 0x08, 0x7F},  // H
    {0x00, 0x41, 0x7F, 0x41, 0x00},  // I
    {0x20, 0x40, 0x41, 0x3F, 0x01},  // J
    {0x7F, 0x08, 0x14, 0x22, 0x41},  // K
    {0x7F, 0x40, 0x40, 0x40, 0x40},  // L
    {0x7F, 0x02, 0x0C, 0x02, 0x7F},  // M
    {0x7F, 0x04, 0x08, 0x10, 0x7F},  // N
    {0x3E, 0x41, 0x41, 0x41, 0x3E},  // O
    {0x7F, 0x09, 0x09, 0x09, 0x06},  // P
    {0x3E, 0x41, 0x51, 0x21, 0x5E},  // Q
    {0x7F, 0x09, 0x19, 0x29, 0x46},  // R
    {0x46, 0x49, 0x49, 0x49, 0x31},  // S
    {0x01, 0x01, 0x7F, 0x01, 0x01},  // T
    {0x3F, 0x40, 0x40, 0x40, 0x3F},  // U
    {0x1F, 0x20, 0x40, 0x20, 0x1F},  // V
    {0x3F, 0x40, 0x38, 0x40, 0x3F},  // W
    {0x63, 0x14, 0x08, 0x14, 0x63},  // X
    {0x07, 0x08, 0x70, 0x08, 0x07},  // Y
    {0x61, 0x51, 0x49, 0x45, 0x43},  // Z
    {0x00, 0x7F, 0x41, 0x41, 0x00},  // [
    {0x02, 0x04, 0x08, 0x10, 0x20},  // backslash
    {0x00, 0x41, 0x41, 0x7F, 0x00},  // ]
    {0x04, 0x02, 0x01, 0x02, 0x04},  // ^
    {0x40, 0x40, 0x40, 0x40, 0x40},  // _
    {0x00, 0x01, 0x02, 0x04, 0x00},  // `
    {0x20, 0x54, 0x54, 0x54, 0x78},  // a
    {0x7F, 0x48, 0x44, 0x44, 0x38},  // b
    {0x38, 0x44, 0x44, 0x44, 0x20},  // c
    {0x38, 0x44, 0x44, 0x48, 0x7F},  // d
    {0x38, 0x54, 0x54, 0x54, 0x18},  // e
    {0x08, 0x7E, 0x09, 0x01, 0x02},  // f
    {0x18, 0xA4, 0xA4, 0xA4, 0x7C},  // g
    {0x7F, 0x08, 0x04, 0x04, 0x78},  // h
    {0x00, 0x44, 0x7D, 0x40, 0x00},  // i
    {0x40, 0x80, 0x84, 0x7D, 0x00},  // j
    {0x7F, 0x10, 0x28, 0x44, 0x00},  // k
    {0x00, 0x41, 0x7F, 0x40, 0x00},  // l
    {0x7C, 0x04, 0x18, 0x04, 0x78},  // m
    {0x7C, 0x08, 0x04, 0x04, 0x78},  // n
    {0x38, 0x44, 0x44, 0x44, 0x38},  // o
    {0xFC, 0x24, 0x24, 0x24, 0x18},  // p
    {0x18, 0x24, 0x24, 0x24, 0xFC},  // q
    {0x7C, 0x08, 0x04, 0x04, 0x08},  // r
    {0x48, 0x54, 0x54, 0x54, 0x20},  // s
    {0x04, 0x3F, 0x44, 0x40, 0x20},  // t
    {0x3C, 0x40, 0x40, 0x20, 0x7C},  // u
    {0x1C, 0x20, 0x40, 0x20, 0x1C},  // v
    {0x3C, 0x40, 0x30, 0x40, 0x3C},  // w
    {0x44, 0x28, 0x10, 0x28, 0x44},  // x
    {0x1C, 0xA0, 0xA0, 0xA0, 0x7C},  // y
    {0x44, 0x64, 0x54, 0x4C, 0x44},  // z
    {0x00, 0x08, 0x36, 0x41, 0x00},  // {
    {0x00, 0x00, 0x7F, 0x00, 0x00},  // |
    {0x00, 0x41, 0x36, 0x08, 0x00},  // }
    {0x08, 0x04, 0x08, 0x10, 0x08},  // ~
};

int textWidth(const std::string& s) {
    return s.empty() ? 0 : static_cast<int>(s.size()) * kAdvance - kScale;
}

// ---------------------------------------------------------------------------
// Display list: the layout is computed once into these primitives, then
// emitted as SVG or rasterised, so the two outputs cannot drift apart.

struct Stroke {
    std::vector<std::vector<Pt>> parts;  // polylines; gaps where data was skipped
    Rgb color{};
    double width = 1;
    double dash = 0;          // dash and gap length; 0 = solid
    bool clip = false;        // to the plot area
    bool seriesPath = false;  // a data series (an SVG <path>)
};

struct Dot {
    Pt c;
    double r = 3.5;
    Rgb color{};
};

struct Box {
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    Rgb fill{};
};

enum class Anchor { Start, Middle, End };

struct Text {
    Pt at;  // anchor point; vertically the text is centred on it
    std::string s;
    Anchor anchor = Anchor::Start;
    bool vertical = false;  // rotated 90 degrees counter-clockwise (reads bottom to top)
    bool bold = false;
    Rgb color{};
};

using Item = std::variant<Stroke, Dot, Box, Text>;

struct Drawing {
    int width = 0, height = 0;
    int left = 0, top = 0, right = 0, bottom = 0;  // plot area, pixel edges
    std::vector<Item> items;
};

const Rgb kBlack = {0.0f, 0.0f, 0.0f};
const Rgb kDark = {0.03f, 0.03f, 0.03f};
const Rgb kGrid = {0.78f, 0.78f, 0.78f};
const Rgb kMid = {0.25f, 0.25f, 0.25f};
const Rgb kWhite = {1.0f, 1.0f, 1.0f};

// ---------------------------------------------------------------------------
// Axes

struct Axis {
    bool log = false;
    double lo = 0, hi = 1;        // range in transformed units (log10 on log axes)
    double pixLo = 0, pixHi = 1;  // pixel positions of lo and hi
    std::vector<double> ticks;    // transformed
    std::vector<std::string> labels;
    std::vector<double> minor;  // log axes: 2..9 x 10^k, unlabelled

    std::optional<double> transform(double v) const {
        if (!std::isfinite(v) || (log && v <= 0)) return std::nullopt;
        return log ? std::log10(v) : v;
    }
    double toPixel(double t) const { return pixLo + (t - lo) / (hi - lo) * (pixHi - pixLo); }
};

void fitRange(Axis& a, double mn, double mx) {
    if (!(mn <= mx)) {
        mn = 0;  // no data: 0..1, or 1..10 on a log axis
        mx = 1;
    }
    // Keep spans finite so tick arithmetic stays sane for absurd data.
    mn = std::max(mn, -1e300);
    mx = std::min(mx, 1e300);
    if (mx - mn <= 1e-9 * std::max(std::abs(mn), std::abs(mx))) {
        // All values (nearly) equal: open a window around them so they sit mid-axis.
        const double half = a.log ? 0.5 : (mn != 0 ? std::abs(mn) * 0.1 : 1.0);
        mn -= half;
        mx += half;
    }
    const double pad = 0.05 * (mx - mn);
    a.lo = mn - pad;
    a.hi = mx + pad;
}

double niceStep(double raw) {
    const double e = std::pow(10.0, std::floor(std::log10(raw)));
    const double f = raw / e;
    return (f <= 1.0 ? 1.0 : f <= 2.0 ? 2.0 : f <= 5.0 ? 5.0 : 10.0) * e;
}

// "1e+06" -> "1e6": shorter and reads the same.
std::string tidyExponent(std::string s) {
    const auto e = s.find('e');
    if (e == std::string::npos) return s;
    std::string exp = s.substr(e + 1);
    const bool neg = !exp.empty() && exp[0] == '-';
    if (!exp.empty() && (exp[0] == '-' || exp[0] == '+')) exp.erase(0, 1);
    exp.erase(0, std::min(exp.find_first_not_of('0'), exp.size() - 1));
    return s.substr(0, e) + "e" + (neg ? "-" : "") + exp;
}

std::string formatNumber(double v, int digits) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*g", std::clamp(digits, 1, 15), v);
    return tidyExponent(buf);
}

// Ticks at multiples of a 1/2/5 x 10^k step, at most maxCount of them.
void linearTicks(Axis& a, int maxCount) {
    a.ticks.clear();
    a.labels.clear();
    const double span = a.hi - a.lo;
    double step = niceStep(span / std::max(1, maxCount));
    for (int guard = 0; guard < 8 && std::floor(a.hi / step) - std::ceil(a.lo / step) + 1 > maxCount;
         ++guard)
        step = niceStep(step * 1.5);
    if (!std::isfinite(step) || step <= 0) return;
    const double k0 = std::ceil(a.lo / step), k1 = std::floor(a.hi / step);
    if (!(k1 - k0 < 100)) return;
    for (double k = k0; k <= k1; ++k) {
        double v = k * step;
        if (std::abs(v) < step * 1e-6) v = 0;  // no "-0" or "1e-17" at zero
        a.ticks.push_back(v);
    }
    // Enough significant digits to tell neighbouring ticks apart, and to print
    // whole numbers below a million in full (%g switches to an exponent when
    // the precision is shorter than the integer part).
    const int stepExp = static_cast<int>(std::floor(std::log10(step) + 1e-9));
    for (double v : a.ticks) {
        const int vExp = v == 0 ? 0 : static_cast<int>(std::floor(std::log10(std::abs(v)) + 1e-9));
        a.labels.push_back(formatNumber(v, std::max(vExp - stepExp + 1, std::min(vExp + 1, 6))));
    }
}

// Decades (every stride-th when crowded); within less than two decades, the
// 2 and 5 multiples too, so a log axis always has at least two numbers.
void logTicks(Axis& a, int maxCount) {
    a.ticks.clear();
    a.labels.clear();
    a.minor.clear();
    const double k0 = std::ceil(a.lo - 1e-9), k1 = std::floor(a.hi + 1e-9);
    const double decades = k1 - k0 + 1;
    if (decades > 0) {
        const double stride = std::max(1.0, std::ceil(decades / std::max(1, maxCount)));
        for (double k = k0; k <= k1; k += stride) a.ticks.push_back(k);
    }
    if (a.ticks.size() < 2) {
        for (double mantissas : {3.0, 9.0}) {
            a.ticks.clear();
            const double d0 = std::floor(a.lo), d1 = std::ceil(a.hi);
            for (double k = d0; k <= d1; ++k)
                for (double m = 1; m <= 9; ++m) {
                    const bool wanted = mantissas == 9.0 || m == 1 || m == 2 || m == 5;
                    const double t = k + std::log10(m);
                    if (wanted && t >= a.lo && t <= a.hi) a.ticks.push_back(t);
                }
            if (a.ticks.size() >= 2) break;
        }
    }
    for (double t : a.ticks) a.labels.push_back(formatNumber(std::pow(10.0, t), 6));
    if (k1 - k0 < 40)
        for (double k = std::floor(a.lo); k <= a.hi; ++k)
            for (double m = 2; m <= 9; ++m) {
                const double t = k + std::log10(m);
                if (t >= a.lo && t <= a.hi) a.minor.push_back(t);
            }
}

void makeTicks(Axis& a, int maxCount) {
    maxCount = std::max(2, maxCount);
    a.log ? logTicks(a, maxCount) : linearTicks(a, maxCount);
}

int widestLabel(const Axis& a) {
    int w = 0;
    for (const auto& s : a.labels) w = std::max(w, textWidth(s));
    return w;
}

// ---------------------------------------------------------------------------
// Layout

constexpr int kTickLen = 5;
constexpr int kOuter = 12;  // blank border around everything

struct Layout {
    int width = 0, height = 0;
    int left = 0, top = 0, right = 0, bottom = 0;
    Axis x, y;
};

bool seriesPoint(const Layout& l, const Series& s, std::size_t i, Pt& out) {
    const auto tx = l.x.transform(s.x[i]);
    const auto ty = l.y.transform(s.y[i]);
    if (!tx || !ty) return false;
    out = {l.x.toPixel(*tx), l.y.toPixel(*ty)};
    return true;
}

Layout computeLayout(const Chart& chart, int width, int height) {
    Layout l;
    l.width = std::max(1, width);
    l.height = std::max(1, height);
    l.x.log = chart.logX;
    l.y.log = chart.logY;

    // Data ranges, in transformed units, from the points that will be drawn.
    double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY;
    auto include = [&](double x, double y) {
        const auto tx = l.x.transform(x), ty = l.y.transform(y);
        if (!tx || !ty) return;
        xmin = std::min(xmin, *tx);
        xmax = std::max(xmax, *tx);
        ymin = std::min(ymin, *ty);
        ymax = std::max(ymax, *ty);
    };
    for (const auto& s : chart.series)
        for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) include(s.x[i], s.y[i]);
    if (chart.diagonal) {
        include(chart.diagonal->first, chart.diagonal->first);
        include(chart.diagonal->second, chart.diagonal->second);
    }
    fitRange(l.x, xmin, xmax);
    fitRange(l.y, ymin, ymax);

    // Vertical bands: title, plot, tick numbers, x label.
    l.top = chart.title.empty() ? kOuter + kTextH / 2 : kOuter + kTextH + 14;
    const int below = kTickLen + 6 + kTextH + (chart.xLabel.empty() ? 0 : 10 + kTextH) + kOuter;
    l.bottom = std::max(l.top + 1, l.height - below);
    l.y.pixLo = l.bottom;
    l.y.pixHi = l.top;
    makeTicks(l.y, std::min(10, (l.bottom - l.top) / 50 + 1));

    // Left band depends on the y numbers' width.
    l.left = kOuter + (chart.yLabel.empty() ? 0 : kTextH + 10) + widestLabel(l.y) + 6 + kTickLen;
    l.right = std::max(l.left + 1, l.width - 2 * kOuter);
    l.x.pixLo = l.left;
    l.x.pixHi = l.right;
    // Fewer x ticks until their numbers fit side by side.
    const int plotW = l.right - l.left;
    for (int n = std::min(12, plotW / 70 + 1); n >= 2; --n) {
        makeTicks(l.x, n);
        const int need = static_cast<int>(l.x.labels.size()) * (widestLabel(l.x) + 16);
        if (need <= plotW) break;
    }
    return l;
}

// Pixel-centred so 1px lines are crisp in the PNG; harmless in the SVG.
double crisp(double p) { return std::floor(p) + 0.5; }

Stroke line(Pt a, Pt b, Rgb color, double width = 1) {
    Stroke s;
    s.parts = {{a, b}};
    s.color = color;
    s.width = width;
    return s;
}

Text text(double x, double y, std::string s, Anchor anchor, Rgb color = kDark) {
    Text t;
    t.at = {x, y};
    t.s = std::move(s);
    t.anchor = anchor;
    t.color = color;
    return t;
}

Drawing build(const Chart& chart, int width, int height) {
    const Layout l = computeLayout(chart, width, height);
    Drawing d;
    d.width = l.width;
    d.height = l.height;
    d.left = l.left;
    d.top = l.top;
    d.right = l.right;
    d.bottom = l.bottom;
    auto& items = d.items;

    const double L = l.left, T = l.top, R = l.right, B = l.bottom;

    // Grid first so everything else lies on top.
    for (double t : l.x.ticks) {
        const double px = crisp(l.x.toPixel(t));
        items.push_back(line({px, T}, {px, B}, kGrid));
    }
    for (double t : l.y.ticks) {
        const double py = crisp(l.y.toPixel(t));
        items.push_back(line({L, py}, {R, py}, kGrid));
    }

    // Reference diagonal; sampled along x so it stays right when only one axis is logarithmic.
    if (chart.diagonal && std::isfinite(chart.diagonal->first) && std::isfinite(chart.diagonal->second)) {
        const auto [a, b] = *chart.diagonal;
        Stroke s;
        s.color = kMid;
        s.width = 1.5;
        s.dash = 6;
        s.clip = true;
        std::vector<Pt> part;
        const int n = chart.logX == chart.logY ? 1 : 128;
        const bool geometric = chart.logX && a > 0 && b > 0;
        for (int i = 0; i <= n; ++i) {
            const double f = static_cast<double>(i) / n;
            const double v = geometric ? a * std::pow(b / a, f) : a + (b - a) * f;
            const auto tx = l.x.transform(v), ty = l.y.transform(v);
            if (tx && ty) {
                part.push_back({l.x.toPixel(*tx), l.y.toPixel(*ty)});
            } else if (!part.empty()) {
                s.parts.push_back(std::move(part));
                part.clear();
            }
        }
        if (!part.empty()) s.parts.push_back(std::move(part));
        if (!s.parts.empty()) items.push_back(std::move(s));
    }

    // Series: lines, then markers on top, then point labels.
    for (const auto& series : chart.series) {
        const std::size_t n = std::min(series.x.size(), series.y.size());
        if (series.lines) {
            Stroke s;
            s.color = series.color;
            s.width = 2;
            s.clip = true;
            s.seriesPath = true;
            std::vector<Pt> part;
            for (std::size_t i = 0; i < n; ++i) {
                Pt p;
                if (seriesPoint(l, series, i, p)) {
                    part.push_back(p);
                } else if (!part.empty()) {
                    s.parts.push_back(std::move(part));
                    part.clear();
                }
            }
            if (!part.empty()) s.parts.push_back(std::move(part));
            if (!s.parts.empty()) items.push_back(std::move(s));
        }
        for (std::size_t i = 0; i < n; ++i) {
            Pt p;
            if (!seriesPoint(l, series, i, p)) continue;
            if (series.points) items.push_back(Dot{p, 3.5, series.color});
        }
        for (std::size_t i = 0; i < std::min(n, series.pointLabels.size()); ++i) {
            Pt p;
            if (series.pointLabels[i].empty() || !seriesPoint(l, series, i, p)) continue;
            items.push_back(text(p.x + 7, p.y - 9, series.pointLabels[i], Anchor::Start));
        }
    }

    // Frame over the data so lines at the range edge do not hide it.
    Stroke frame;
    frame.parts = {{{L + 0.5, T + 0.5}, {R - 0.5, T + 0.5}, {R - 0.5, B - 0.5}, {L + 0.5, B - 0.5},
                    {L + 0.5, T + 0.5}}};
    frame.color = kDark;
    items.push_back(frame);

    // Ticks and their numbers.
    for (std::size_t i = 0; i < l.x.ticks.size(); ++i) {
        const double px = crisp(l.x.toPixel(l.x.ticks[i]));
        items.push_back(line({px, B}, {px, B + kTickLen}, kDark));
        // Keep the outermost numbers inside the image.
        const double half = textWidth(l.x.labels[i]) / 2.0;
        const double cx = std::clamp(px, half + 2, std::max(half + 2, l.width - half - 2));
        items.push_back(text(cx, B + kTickLen + 6 + kTextH / 2.0, l.x.labels[i], Anchor::Middle));
    }
    for (double t : l.x.minor) {
        const double px = crisp(l.x.toPixel(t));
        items.push_back(line({px, B}, {px, B + kTickLen - 2}, kDark));
    }
    for (std::size_t i = 0; i < l.y.ticks.size(); ++i) {
        const double py = crisp(l.y.toPixel(l.y.ticks[i]));
        items.push_back(line({L - kTickLen, py}, {L, py}, kDark));
        items.push_back(text(L - kTickLen - 6, py, l.y.labels[i], Anchor::End));
    }
    for (double t : l.y.minor) {
        const double py = crisp(l.y.toPixel(t));
        items.push_back(line({L - kTickLen + 2, py}, {L, py}, kDark));
    }

    // Title and axis labels.
    if (!chart.title.empty()) {
        Text t = text(l.width / 2.0, kOuter + kTextH / 2.0, chart.title, Anchor::Middle, kBlack);
        t.bold = true;
        items.push_back(t);
    }
    if (!chart.xLabel.empty())
        items.push_back(text((L + R) / 2, l.height - kOuter - kTextH / 2.0, chart.xLabel, Anchor::Middle));
    if (!chart.yLabel.empty()) {
        Text t = text(kOuter + kTextH / 2.0, (T + B) / 2, chart.yLabel, Anchor::Middle);
        t.vertical = true;
        items.push_back(t);
    }

    // Legend, in whichever inner corner of the plot covers the least data.
    struct Entry {
        std::string label;
        Rgb color;
        bool lines, points;
        double dash;
    };
    std::vector<Entry> entries;
    for (const auto& s : chart.series)
        if (!s.label.empty()) entries.push_back({s.label, s.color, s.lines, s.points, 0});
    if (chart.diagonal && !entries.empty()) entries.push_back({"y = x", kMid, true, false, 6});
    if (!entries.empty()) {
        constexpr int kPad = 6, kRow = 20, kSample = 28;
        int labelW = 0;
        for (const auto& e : entries) labelW = std::max(labelW, textWidth(e.label));
        const double w = kPad + kSample + 8 + labelW + kPad;
        const double h = kRow * static_cast<double>(entries.size()) + kPad;
        const double inset = 8;
        const Pt corners[] = {{R - inset - w, T + inset},
                              {L + inset, T + inset},
                              {R - inset - w, B - inset - h},
                              {L + inset, B - inset - h}};
        std::vector<Pt> samples;
        for (const auto& item : items) {
            if (const auto* s = std::get_if<Stroke>(&item); s && s->clip)
                for (const auto& part : s->parts)
                    for (std::size_t i = 0; i + 1 < part.size(); ++i) {
                        // Every few pixels, so long straight segments are seen too.
                        const double len = std::hypot(part[i + 1].x - part[i].x, part[i + 1].y - part[i].y);
                        const int n = static_cast<int>(std::min(len / 4, 1000.0)) + 1;
                        for (int k = 0; k < n; ++k) {
                            const double f = static_cast<double>(k) / n;
                            samples.push_back({part[i].x + (part[i + 1].x - part[i].x) * f,
                                               part[i].y + (part[i + 1].y - part[i].y) * f});
                        }
                    }
            if (const auto* dot = std::get_if<Dot>(&item)) samples.push_back(dot->c);
            // Point labels (the only text inside the plot).
            if (const auto* t = std::get_if<Text>(&item);
                t && !t->vertical && t->at.x >= L && t->at.x <= R && t->at.y >= T && t->at.y <= B)
                for (int u = 0; u <= textWidth(t->s); u += 4) samples.push_back({t->at.x + u, t->at.y});
        }
        Pt best = corners[0];
        std::size_t bestCount = SIZE_MAX;
        for (const Pt& c : corners) {
            std::size_t count = 0;
            for (const Pt& p : samples)
                count += p.x >= c.x - 4 && p.x <= c.x + w + 4 && p.y >= c.y - 4 && p.y <= c.y + h + 4;
            if (count < bestCount) {
                bestCount = count;
                best = c;
            }
        }
        const double x0 = std::round(best.x), y0 = std::round(best.y);
        items.push_back(Box{x0, y0, x0 + w, y0 + h, kWhite});
        Stroke border;
        border.parts = {{{x0 + 0.5, y0 + 0.5},
                         {x0 + w - 0.5, y0 + 0.5},
                         {x0 + w - 0.5, y0 + h - 0.5},
                         {x0 + 0.5, y0 + h - 0.5},
                         {x0 + 0.5, y0 + 0.5}}};
        border.color = kGrid;
        items.push_back(border);
        for (std::size_t i = 0; i < entries.size(); ++i) {
            const auto& e = entries[i];
            const double cy = y0 + kPad + kTextH / 2.0 + kRow * static_cast<double>(i);
            if (e.lines) {
                Stroke s = line({x0 + kPad, cy}, {x0 + kPad + kSample, cy}, e.color, e.dash > 0 ? 1.5 : 2);
                s.dash = e.dash;
                items.push_back(s);
            }
            if (e.points) items.push_back(Dot{{x0 + kPad + kSample / 2.0, cy}, 3.5, e.color});
            items.push_back(text(x0 + kPad + kSample + 8, cy, e.label, Anchor::Start));
        }
    }
    return d;
}

// ---------------------------------------------------------------------------
// SVG

std::string xmlEscape(const std::string& s) {
    std::string out;
    out.reserve(s.size());
    for (char c : s) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&apos;"; break;
            default:
                // Control characters are not allowed in XML 1.0 at all.
                if (static_cast<unsigned char>(c) >= 0x20 || c == '\t' || c == '\n') out += c;
        }
    }
    return out;
}

std::string num(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f", v);
    return buf;
}

// The colours are linear like rad::Image; SVG wants sRGB.
std::string hex(const Rgb& c) {
    char buf[8];
    std::snprintf(buf, sizeof buf, "#%02x%02x%02x", encodeSrgb(c[0]), encodeSrgb(c[1]), encodeSrgb(c[2]));
    return buf;
}

void svgItem(std::string& out, const Stroke& s) {
    std::string attrs = " fill=\"none\" stroke=\"" + hex(s.color) + "\" stroke-width=\"" + num(s.width) + "\"";
    if (s.dash > 0) attrs += " stroke-dasharray=\"" + num(s.dash) + " " + num(s.dash) + "\"";
    if (s.clip) attrs += " clip-path=\"url(#plot-area)\"";
    if (s.seriesPath) {
        out += "<path d=\"";
        for (const auto& part : s.parts)
            for (std::size_t i = 0; i < part.size(); ++i)
            {
                // Appended piecewise: GCC 12 gives a false -Wrestrict on "literal" + std::string.
                out += i == 0 ? "M" : " L";
                out += num(part[i].x);
                out += ',';
                out += num(part[i].y);
                if (i + 1 == part.size()) out += ' ';
            }
        out += "\"" + attrs + " stroke-linejoin=\"round\" stroke-linecap=\"round\"/>\n";
        return;
    }
    for (const auto& part : s.parts) {
        if (part.size() == 2) {
            out += "<line x1=\"" + num(part[0].x) + "\" y1=\"" + num(part[0].y) + "\" x2=\"" + num(part[1].x) +
                   "\" y2=\"" + num(part[1].y) + "\"" + attrs + "/>\n";
        } else if (part.size() > 2) {
            out += "<polyline points=\"";
            for (std::size_t i = 0; i < part.size(); ++i)
            {
                if (i) out += ' ';
                out += num(part[i].x);
                out += ',';
                out += num(part[i].y);
            }
            out += "\"" + attrs + "/>\n";
        }
    }
}

void svgItem(std::string& out, const Dot& d) {
    out += "<circle cx=\"" + num(d.c.x) + "\" cy=\"" + num(d.c.y) + "\" r=\"" + num(d.r) + "\" fill=\"" +
           hex(d.color) + "\"/>\n";
}

void svgItem(std::string& out, const Box& b) {
    out += "<rect x=\"" + num(b.x0) + "\" y=\"" + num(b.y0) + "\" width=\"" + num(b.x1 - b.x0) + "\" height=\"" +
           num(b.y1 - b.y0) + "\" fill=\"" + hex(b.fill) + "\"/>\n";
}

void svgItem(std::string& out, const Text& t) {
    const char* anchor = t.anchor == Anchor::Start ? "start" : t.anchor == Anchor::Middle ? "middle" : "end";
    out += "<text x=\"" + num(t.at.x) + "\" y=\"" + num(t.at.y) + "\" text-anchor=\"" + anchor +
           "\" dominant-baseline=\"central\" fill=\"" + hex(t.color) + "\"";
    if (t.bold) out += " font-weight=\"bold\"";
    if (t.vertical) out += " transform=\"rotate(-90 " + num(t.at.x) + " " + num(t.at.y) + ")\"";
    out += '>';
    out += xmlEscape(t.s);
    out += "</text>\n";
}

// ---------------------------------------------------------------------------
// Raster

struct PixelRect {
    int x0, y0, x1, y1;  // half-open
};

PixelRect intersect(PixelRect a, PixelRect b) {
    return {std::max(a.x0, b.x0), std::max(a.y0, b.y0), std::min(a.x1, b.x1), std::min(a.y1, b.y1)};
}

void blend(Image& img, int x, int y, const Rgb& c, float a) {
    float* p = img.pixel(x, y);
    for (int k = 0; k < 3; ++k) p[k] += (c[k] - p[k]) * a;
}

// Antialiased by coverage from each pixel centre's distance to the segments
// (round joins and caps). Coverage is collected per stroke, taking the
// maximum, so joints of a polyline are not blended twice and look darker.
void rasterize(Image& img, const Stroke& s, PixelRect bounds) {
    const double hw = s.width / 2;
    double minX = INFINITY, minY = INFINITY, maxX = -INFINITY, maxY = -INFINITY;
    for (const auto& part : s.parts)
        for (const Pt& p : part) {
            minX = std::min(minX, p.x);
            minY = std::min(minY, p.y);
            maxX = std::max(maxX, p.x);
            maxY = std::max(maxY, p.y);
        }
    if (!(minX <= maxX)) return;
    const PixelRect r = intersect(bounds, {static_cast<int>(std::floor(std::max(minX - hw - 1, -1.0))),
                                           static_cast<int>(std::floor(std::max(minY - hw - 1, -1.0))),
                                           static_cast<int>(std::ceil(std::min(maxX + hw + 1, 1e6))),
                                           static_cast<int>(std::ceil(std::min(maxY + hw + 1, 1e6)))});
    if (r.x0 >= r.x1 || r.y0 >= r.y1) return;
    const int rw = r.x1 - r.x0;
    std::vector<float> cov(static_cast<std::size_t>(rw) * (r.y1 - r.y0), 0.0f);
    for (const auto& part : s.parts) {
        double along = 0;  // dash phase runs on across segments
        for (std::size_t i = 0; i + 1 < part.size(); ++i) {
            const Pt a = part[i], b = part[i + 1];
            const double dx = b.x - a.x, dy = b.y - a.y, len2 = dx * dx + dy * dy, len = std::sqrt(len2);
            const int x0 = std::max(r.x0, static_cast<int>(std::floor(std::min(a.x, b.x) - hw - 1)));
            const int x1 = std::min(r.x1, static_cast<int>(std::ceil(std::max(a.x, b.x) + hw + 1)));
            const int y0 = std::max(r.y0, static_cast<int>(std::floor(std::min(a.y, b.y) - hw - 1)));
            const int y1 = std::min(r.y1, static_cast<int>(std::ceil(std::max(a.y, b.y) + hw + 1)));
            for (int y = y0; y < y1; ++y)
                for (int x = x0; x < x1; ++x) {
                    const double px = x + 0.5 - a.x, py = y + 0.5 - a.y;
                    const double t = len2 > 0 ? std::clamp((px * dx + py * dy) / len2, 0.0, 1.0) : 0.0;
                    const double ex = px - t * dx, ey = py - t * dy;
                    double c = std::clamp(hw + 0.5 - std::sqrt(ex * ex + ey * ey), 0.0, 1.0);
                    if (c > 0 && s.dash > 0 && std::fmod(along + t * len, 2 * s.dash) >= s.dash) c = 0;
                    float& dst = cov[static_cast<std::size_t>(y - r.y0) * rw + (x - r.x0)];
                    dst = std::max(dst, static_cast<float>(c));
                }
            along += len;
        }
    }
    for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x) {
            const float c = cov[static_cast<std::size_t>(y - r.y0) * rw + (x - r.x0)];
            if (c > 0) blend(img, x, y, s.color, c);
        }
}

void rasterize(Image& img, const Dot& d, PixelRect bounds) {
    const PixelRect r = intersect(bounds, {static_cast<int>(std::floor(d.c.x - d.r - 1)),
                                           static_cast<int>(std::floor(d.c.y - d.r - 1)),
                                           static_cast<int>(std::ceil(d.c.x + d.r + 1)),
                                           static_cast<int>(std::ceil(d.c.y + d.r + 1))});
    for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x) {
            const double c = std::clamp(d.r + 0.5 - std::hypot(x + 0.5 - d.c.x, y + 0.5 - d.c.y), 0.0, 1.0);
            if (c > 0) blend(img, x, y, d.color, static_cast<float>(c));
        }
}

void rasterize(Image& img, const Box& b, PixelRect bounds) {
    const PixelRect r = intersect(bounds, {static_cast<int>(std::lround(b.x0)), static_cast<int>(std::lround(b.y0)),
                                           static_cast<int>(std::lround(b.x1)), static_cast<int>(std::lround(b.y1))});
    for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x) blend(img, x, y, b.fill, 1.0f);
}

void rasterize(Image& img, const Text& t, PixelRect bounds) {
    const int w = textWidth(t.s);
    const double start = t.anchor == Anchor::Start ? 0.0 : t.anchor == Anchor::Middle ? -w / 2.0 : -w;
    const int ox = static_cast<int>(std::lround(t.at.x)), oy = static_cast<int>(std::lround(t.at.y));
    const int u0 = static_cast<int>(std::lround(start));
    auto put = [&](int u, int v) {
        // u runs along the text, v down across it (top of the glyphs at v = -kTextH/2).
        const int x = t.vertical ? ox + v : ox + u;
        const int y = t.vertical ? oy - u - 1 : oy + v;
        if (x >= bounds.x0 && x < bounds.x1 && y >= bounds.y0 && y < bounds.y1) blend(img, x, y, t.color, 1.0f);
    };
    for (std::size_t i = 0; i < t.s.size(); ++i) {
        const unsigned char ch = static_cast<unsigned char>(t.s[i]);
        const auto& glyph = kFont[(ch >= 32 && ch <= 126 ? ch : '?') - 32];
        for (int col = 0; col < 5; ++col)
            for (int row = 0; row < 8; ++row) {
                if (!((glyph[col] >> row) & 1)) continue;
                for (int sy = 0; sy < kScale; ++sy)
                    for (int sx = 0; sx < kScale + (t.bold ? 1 : 0); ++sx)
                        put(u0 + static_cast<int>(i) * kAdvance + col * kScale + sx, -kTextH / 2 + row * kScale + sy);
            }
    }
}

}  // namespace

std::string toSvg(const Chart& chart, int width, int height) {
    const Drawing d = build(chart, width, height);
    std::string out;
    out += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + std::to_string(d.width) + "\" height=\"" +
           std::to_string(d.height) + "\" viewBox=\"0 0 " + std::to_string(d.width) + " " + std::to_string(d.height) +
           "\" font-family=\"DejaVu Sans Mono, Menlo, Consolas, monospace\" font-size=\"" +
           std::to_string(kSvgFontPx) + "\">\n";
    if (!chart.title.empty()) out += "<title>" + xmlEscape(chart.title) + "</title>\n";
    out += "<defs><clipPath id=\"plot-area\"><rect x=\"" + std::to_string(d.left) + "\" y=\"" + std::to_string(d.top) +
           "\" width=\"" + std::to_string(d.right - d.left) + "\" height=\"" + std::to_string(d.bottom - d.top) +
           "\"/></clipPath></defs>\n";
    out += "<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n";
    for (const auto& item : d.items) std::visit([&](const auto& v) { svgItem(out, v); }, item);
    out += "</svg>\n";
    return out;
}

Image toImage(const Chart& chart, int width, int height) {
    const Drawing d = build(chart, width, height);
    Image img;
    img.width = d.width;
    img.height = d.height;
    img.rgb.assign(static_cast<std::size_t>(d.width) * d.height * 3, 1.0f);
    const PixelRect all{0, 0, d.width, d.height};
    const PixelRect plot = intersect(all, {d.left, d.top, d.right, d.bottom});
    for (const auto& item : d.items)
        std::visit(
            [&](const auto& v) {
                PixelRect bounds = all;
                if constexpr (std::is_same_v<std::decay_t<decltype(v)>, Stroke>)
                    if (v.clip) bounds = plot;
                rasterize(img, v, bounds);
            },
            item);
    return img;
}

void writeChart(const Chart& chart, const std::string& pathWithoutExtension) {
    cli::writeFileAtomically(pathWithoutExtension + ".svg", toSvg(chart));
    writeImage(toImage(chart), pathWithoutExtension + ".png");
}

void writeCharts(const std::vector<Chart>& charts, const std::string& pathWithoutExtension, int width, int height) {
    // SVG: each chart nested at its offset, with its own clip-path id.
    std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + std::to_string(width * int(charts.size())) +
                      "\" height=\"" + std::to_string(height) + "\">\n";
    Image image;
    image.width = width * int(charts.size());
    image.height = height;
    image.rgb.assign(std::size_t(image.width) * height * 3, 1.0f);
    for (std::size_t i = 0; i < charts.size(); ++i) {
        std::string one = toSvg(charts[i], width, height);
        const std::string id = "plot-area-" + std::to_string(i);
        for (std::size_t at; (at = one.find("\"plot-area\"")) != std::string::npos;) one.replace(at, 11, "\"" + id + "\"");
        for (std::size_t at; (at = one.find("url(#plot-area)")) != std::string::npos;) one.replace(at, 15, "url(#" + id + ")");
        one.insert(4, " x=\"" + std::to_string(width * int(i)) + "\"");
        svg += one;
        const Image part = toImage(charts[i], width, height);
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x)
                for (int c = 0; c < 3; ++c) image.pixel(int(i) * width + x, y)[c] = part.pixel(x, y)[c];
    }
    svg += "</svg>\n";
    cli::writeFileAtomically(pathWithoutExtension + ".svg", svg);
    writeImage(image, pathWithoutExtension + ".png");
}

std::optional<std::array<double, 2>> dataToPixel(const Chart& chart, double x, double y, int width, int height) {
    const Layout l = computeLayout(chart, width, height);
    const auto tx = l.x.transform(x), ty = l.y.transform(y);
    if (!tx || !ty) return std::nullopt;
    return std::array<double, 2>{l.x.toPixel(*tx), l.y.toPixel(*ty)};
}

}  // namespace rad::plot
