#include "plot/Plot.h"

#include <cairo-svg.h>
#include <cairo.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <new>
#include <numbers>
#include <stdexcept>

#include "image/AtomicFile.h"
#include "image/Image.h"

namespace rad::plot {
namespace {

using Rgb = std::array<float, 3>;

struct Pt {
    double x = 0, y = 0;
};

// ---------------------------------------------------------------------------
// Cairo objects, owned.

struct CairoDelete {
    void operator()(cairo_t* cr) const { cairo_destroy(cr); }
    void operator()(cairo_surface_t* s) const { cairo_surface_destroy(s); }
    void operator()(cairo_font_options_t* o) const { cairo_font_options_destroy(o); }
};
using Context = std::unique_ptr<cairo_t, CairoDelete>;
using Surface = std::unique_ptr<cairo_surface_t, CairoDelete>;
using FontOptions = std::unique_ptr<cairo_font_options_t, CairoDelete>;

// Cairo reports failure through sticky status codes rather than return values.
void check(cairo_status_t status, const std::string& path) {
    if (status != CAIRO_STATUS_SUCCESS)
        throw std::runtime_error(path +
                                 ": cannot draw the chart: " + cairo_status_to_string(status));
}

// ---------------------------------------------------------------------------
// Colours and text

const Rgb kBlack = {0.0f, 0.0f, 0.0f};
const Rgb kDark = {0.03f, 0.03f, 0.03f};
const Rgb kGrid = {0.78f, 0.78f, 0.78f};
const Rgb kMid = {0.25f, 0.25f, 0.25f};
const Rgb kWhite = {1.0f, 1.0f, 1.0f};

// Chart colours are linear like rad::Image; Cairo takes them as sRGB values.
void setColor(cairo_t* cr, const Rgb& c) {
    cairo_set_source_rgb(cr, encodeSrgb(c[0]) / 255.0, encodeSrgb(c[1]) / 255.0,
                         encodeSrgb(c[2]) / 255.0);
}

constexpr const char* kFontFamily = "DejaVu Sans";
constexpr double kFontSize = 14;   // numbers, axis labels, legend
constexpr double kTitleSize = 16;  // bold

// Unhinted metrics: text then measures the same on the image and the SVG
// surface (and in dataToPixel's scratch context), so all lay out alike.
void prepare(cairo_t* cr) {
    const FontOptions options(cairo_font_options_create());
    cairo_font_options_set_hint_metrics(options.get(), CAIRO_HINT_METRICS_OFF);
    cairo_font_options_set_hint_style(options.get(), CAIRO_HINT_STYLE_SLIGHT);
    cairo_font_options_set_antialias(options.get(), CAIRO_ANTIALIAS_GRAY);
    cairo_set_font_options(cr, options.get());
}

void useFont(cairo_t* cr, bool title = false) {
    cairo_select_font_face(cr, kFontFamily, CAIRO_FONT_SLANT_NORMAL,
                           title ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, title ? kTitleSize : kFontSize);
}

double textWidth(cairo_t* cr, const std::string& s) {
    cairo_text_extents_t e;
    cairo_text_extents(cr, s.c_str(), &e);
    return e.x_advance;
}

// Height of one line of text (ascent + descent) in the current font.
double lineHeight(cairo_t* cr) {
    cairo_font_extents_t e;
    cairo_font_extents(cr, &e);
    return e.ascent + e.descent;
}

enum class Anchor { Start, Middle, End };

// Vertically the text is centred on y by its capitals, so numbers line up
// with the ticks they label.
void drawText(cairo_t* cr, double x, double y, const std::string& s, Anchor anchor,
              const Rgb& color = kDark) {
    cairo_text_extents_t capital;
    cairo_text_extents(cr, "H", &capital);
    const double w = textWidth(cr, s);
    const double start = anchor == Anchor::Start ? 0.0 : anchor == Anchor::Middle ? -w / 2 : -w;
    cairo_move_to(cr, x + start, y - capital.y_bearing / 2);
    setColor(cr, color);
    cairo_show_text(cr, s.c_str());
}

// Reads bottom to top, centred on (x, y).
void drawVerticalText(cairo_t* cr, double x, double y, const std::string& s) {
    cairo_save(cr);
    cairo_translate(cr, x, y);
    cairo_rotate(cr, -std::numbers::pi / 2);
    drawText(cr, 0, 0, s, Anchor::Middle);
    cairo_restore(cr);
}

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
    for (int guard = 0;
         guard < 8 && std::floor(a.hi / step) - std::ceil(a.lo / step) + 1 > maxCount; ++guard)
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

double widestLabel(cairo_t* cr, const Axis& a) {
    double w = 0;
    for (const auto& s : a.labels) w = std::max(w, textWidth(cr, s));
    return w;
}

// ---------------------------------------------------------------------------
// Layout: where the plot area, ticks and labels go. It depends on how wide the
// tick numbers are, so it is measured with the font on a Cairo context.

constexpr double kTickLen = 5;
constexpr double kOuter = 12;  // blank border around everything

struct Layout {
    double width = 0, height = 0;
    double left = 0, top = 0, right = 0, bottom = 0;  // plot area, on whole pixels
    double textH = 0, titleH = 0;
    Axis x, y;

    std::optional<Pt> toPixel(double vx, double vy) const {
        const auto tx = x.transform(vx), ty = y.transform(vy);
        if (!tx || !ty) return std::nullopt;
        return Pt{x.toPixel(*tx), y.toPixel(*ty)};
    }
};

Layout computeLayout(cairo_t* cr, const Chart& chart, int width, int height) {
    Layout l;
    l.width = std::max(1, width);
    l.height = std::max(1, height);
    l.x.log = chart.logX;
    l.y.log = chart.logY;
    useFont(cr, true);
    l.titleH = lineHeight(cr);
    useFont(cr);
    l.textH = lineHeight(cr);

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
    l.top = std::round(chart.title.empty() ? kOuter + l.textH / 2 : kOuter + l.titleH + 10);
    const double below = kTickLen + 4 + l.textH + (chart.xLabel.empty() ? 0 : 6 + l.textH) + kOuter;
    l.bottom = std::max(l.top + 1, std::round(l.height - below));
    l.y.pixLo = l.bottom;
    l.y.pixHi = l.top;
    makeTicks(l.y, std::min(10, static_cast<int>(l.bottom - l.top) / 50 + 1));

    // The left band depends on the y numbers' width.
    l.left = std::round(kOuter + (chart.yLabel.empty() ? 0 : l.textH + 8) + widestLabel(cr, l.y) +
                        6 + kTickLen);
    l.right = std::max(l.left + 1, l.width - 2 * kOuter);
    l.x.pixLo = l.left;
    l.x.pixHi = l.right;
    // Fewer x ticks until their numbers fit side by side.
    const double plotW = l.right - l.left;
    for (int n = std::min(12, static_cast<int>(plotW) / 70 + 1); n >= 2; --n) {
        makeTicks(l.x, n);
        if (static_cast<double>(l.x.labels.size()) * (widestLabel(cr, l.x) + 16) <= plotW) break;
    }
    return l;
}

// ---------------------------------------------------------------------------
// Drawing one chart, at the origin of cr.

// Pixel-centred so 1px lines are crisp in the PNG; harmless in the SVG.
double crisp(double p) { return std::floor(p) + 0.5; }

void strokeLine(cairo_t* cr, Pt a, Pt b, const Rgb& color, double width = 1) {
    cairo_move_to(cr, a.x, a.y);
    cairo_line_to(cr, b.x, b.y);
    setColor(cr, color);
    cairo_set_line_width(cr, width);
    cairo_stroke(cr);
}

// Polylines broken into parts where points could not be drawn.
using Parts = std::vector<std::vector<Pt>>;

void strokeParts(cairo_t* cr, const Parts& parts) {
    for (const auto& part : parts)
        for (std::size_t i = 0; i < part.size(); ++i)
            i == 0 ? cairo_move_to(cr, part[i].x, part[i].y)
                   : cairo_line_to(cr, part[i].x, part[i].y);
    cairo_stroke(cr);
}

// Points every few pixels along the parts, for finding an empty corner.
void sampleParts(const Parts& parts, std::vector<Pt>& samples) {
    for (const auto& part : parts)
        for (std::size_t i = 0; i + 1 < part.size(); ++i) {
            const Pt a = part[i], b = part[i + 1];
            const int n =
                static_cast<int>(std::min(std::hypot(b.x - a.x, b.y - a.y) / 4, 1000.0)) + 1;
            for (int k = 0; k < n; ++k) {
                const double f = static_cast<double>(k) / n;
                samples.push_back({a.x + (b.x - a.x) * f, a.y + (b.y - a.y) * f});
            }
        }
}

void clipToPlot(cairo_t* cr, const Layout& l) {
    cairo_rectangle(cr, l.left, l.top, l.right - l.left, l.bottom - l.top);
    cairo_clip(cr);
}

constexpr double kDotRadius = 3.5;
constexpr double kDiagonalDash = 6;

void drawAxes(cairo_t* cr, const Chart& chart, const Layout& l) {
    const double L = l.left, T = l.top, R = l.right, B = l.bottom;
    // Frame, over the data so lines at the edge of the range do not hide it.
    cairo_rectangle(cr, L + 0.5, T + 0.5, R - L - 1, B - T - 1);
    setColor(cr, kDark);
    cairo_set_line_width(cr, 1);
    cairo_stroke(cr);

    useFont(cr);
    for (std::size_t i = 0; i < l.x.ticks.size(); ++i) {
        const double px = crisp(l.x.toPixel(l.x.ticks[i]));
        strokeLine(cr, {px, B}, {px, B + kTickLen}, kDark);
        // Keep the outermost numbers inside the chart.
        const double half = textWidth(cr, l.x.labels[i]) / 2;
        const double cx = std::clamp(px, half + 2, std::max(half + 2, l.width - half - 2));
        drawText(cr, cx, B + kTickLen + 4 + l.textH / 2, l.x.labels[i], Anchor::Middle);
    }
    for (double t : l.x.minor) {
        const double px = crisp(l.x.toPixel(t));
        strokeLine(cr, {px, B}, {px, B + kTickLen - 2}, kDark);
    }
    for (std::size_t i = 0; i < l.y.ticks.size(); ++i) {
        const double py = crisp(l.y.toPixel(l.y.ticks[i]));
        strokeLine(cr, {L - kTickLen, py}, {L, py}, kDark);
        drawText(cr, L - kTickLen - 6, py, l.y.labels[i], Anchor::End);
    }
    for (double t : l.y.minor) {
        const double py = crisp(l.y.toPixel(t));
        strokeLine(cr, {L - kTickLen + 2, py}, {L, py}, kDark);
    }

    if (!chart.xLabel.empty())
        drawText(cr, (L + R) / 2, l.height - kOuter - l.textH / 2, chart.xLabel, Anchor::Middle);
    if (!chart.yLabel.empty())
        drawVerticalText(cr, kOuter + l.textH / 2, (T + B) / 2, chart.yLabel);
    if (!chart.title.empty()) {
        useFont(cr, true);
        drawText(cr, l.width / 2, kOuter + l.titleH / 2, chart.title, Anchor::Middle, kBlack);
    }
}

// Legend, in whichever inner corner of the plot covers the fewest of the
// sampled points where data was drawn.
void drawLegend(cairo_t* cr, const Chart& chart, const Layout& l, const std::vector<Pt>& occupied) {
    struct Entry {
        std::string label;
        Rgb color;
        bool lines, points, dashed;
    };
    std::vector<Entry> entries;
    for (const auto& s : chart.series)
        if (!s.label.empty()) entries.push_back({s.label, s.color, s.lines, s.points, false});
    if (chart.diagonal && !entries.empty()) entries.push_back({"y = x", kMid, true, false, true});
    if (entries.empty()) return;

    useFont(cr);
    constexpr double kPad = 6, kSample = 28, kInset = 8;
    const double row = l.textH + 4;
    double labelW = 0;
    for (const auto& e : entries) labelW = std::max(labelW, textWidth(cr, e.label));
    const double w = std::ceil(kPad + kSample + 8 + labelW + kPad);
    const double h = std::ceil(row * static_cast<double>(entries.size()) + kPad);
    const Pt corners[] = {{l.right - kInset - w, l.top + kInset},
                          {l.left + kInset, l.top + kInset},
                          {l.right - kInset - w, l.bottom - kInset - h},
                          {l.left + kInset, l.bottom - kInset - h}};
    Pt best = corners[0];
    std::size_t bestCount = SIZE_MAX;
    for (const Pt& c : corners) {
        std::size_t count = 0;
        for (const Pt& p : occupied)
            count += p.x >= c.x - 4 && p.x <= c.x + w + 4 && p.y >= c.y - 4 && p.y <= c.y + h + 4;
        if (count < bestCount) {
            bestCount = count;
            best = c;
        }
    }

    const double x0 = std::round(best.x), y0 = std::round(best.y);
    cairo_rectangle(cr, x0, y0, w, h);
    setColor(cr, kWhite);
    cairo_fill(cr);
    cairo_rectangle(cr, x0 + 0.5, y0 + 0.5, w - 1, h - 1);
    setColor(cr, kGrid);
    cairo_set_line_width(cr, 1);
    cairo_stroke(cr);
    for (std::size_t i = 0; i < entries.size(); ++i) {
        const Entry& e = entries[i];
        const double cy = y0 + kPad + l.textH / 2 + row * static_cast<double>(i);
        if (e.lines) {
            const double dash = kDiagonalDash;
            cairo_set_dash(cr, &dash, e.dashed ? 1 : 0, 0);
            strokeLine(cr, {x0 + kPad, cy}, {x0 + kPad + kSample, cy}, e.color, e.dashed ? 1.5 : 2);
            cairo_set_dash(cr, nullptr, 0, 0);
        }
        if (e.points) {
            cairo_arc(cr, x0 + kPad + kSample / 2, cy, kDotRadius, 0, 2 * std::numbers::pi);
            setColor(cr, e.color);
            cairo_fill(cr);
        }
        drawText(cr, x0 + kPad + kSample + 8, cy, e.label, Anchor::Start);
    }
}

void drawChart(cairo_t* cr, const Chart& chart, int width, int height) {
    const Layout l = computeLayout(cr, chart, width, height);
    const double L = l.left, T = l.top, R = l.right, B = l.bottom;

    setColor(cr, kWhite);
    cairo_paint(cr);

    // Grid first so everything else lies on top.
    for (double t : l.x.ticks)
        strokeLine(cr, {crisp(l.x.toPixel(t)), T}, {crisp(l.x.toPixel(t)), B}, kGrid);
    for (double t : l.y.ticks)
        strokeLine(cr, {L, crisp(l.y.toPixel(t))}, {R, crisp(l.y.toPixel(t))}, kGrid);

    std::vector<Pt> occupied;  // where data went, for placing the legend

    cairo_save(cr);
    clipToPlot(cr, l);
    // Reference diagonal; sampled along x so it stays straight in data terms
    // when only one axis is logarithmic.
    if (chart.diagonal && std::isfinite(chart.diagonal->first) &&
        std::isfinite(chart.diagonal->second)) {
        const auto [a, b] = *chart.diagonal;
        Parts parts(1);
        const int n = chart.logX == chart.logY ? 1 : 128;
        const bool geometric = chart.logX && a > 0 && b > 0;
        for (int i = 0; i <= n; ++i) {
            const double f = static_cast<double>(i) / n;
            const double v = geometric ? a * std::pow(b / a, f) : a + (b - a) * f;
            if (const auto p = l.toPixel(v, v))
                parts.back().push_back(*p);
            else if (!parts.back().empty())
                parts.emplace_back();
        }
        const double dash = kDiagonalDash;
        cairo_set_dash(cr, &dash, 1, 0);
        setColor(cr, kMid);
        cairo_set_line_width(cr, 1.5);
        strokeParts(cr, parts);
        cairo_set_dash(cr, nullptr, 0, 0);
        sampleParts(parts, occupied);
    }

    // All series' lines, then all markers, so no line hides another
    // series' points.
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
    cairo_set_line_width(cr, 2);
    for (const auto& series : chart.series) {
        Parts parts(1);
        for (std::size_t i = 0; i < std::min(series.x.size(), series.y.size()); ++i) {
            if (const auto p = l.toPixel(series.x[i], series.y[i])) {
                parts.back().push_back(*p);
                occupied.push_back(*p);
            } else if (!parts.back().empty()) {
                parts.emplace_back();
            }
        }
        if (!series.lines) continue;
        setColor(cr, series.color);
        strokeParts(cr, parts);
        sampleParts(parts, occupied);
    }
    for (const auto& series : chart.series) {
        if (!series.points) continue;
        for (std::size_t i = 0; i < std::min(series.x.size(), series.y.size()); ++i)
            if (const auto p = l.toPixel(series.x[i], series.y[i])) {
                cairo_new_sub_path(cr);
                cairo_arc(cr, p->x, p->y, kDotRadius, 0, 2 * std::numbers::pi);
            }
        setColor(cr, series.color);
        cairo_fill(cr);
    }

    // Point labels beside their point, at whichever of eight spots around it
    // overlaps least with the plot's edge, the markers and the labels placed
    // before (points close together would otherwise mix their labels).
    useFont(cr);
    struct Box {
        double x0, y0, x1, y1;
        double overlap(const Box& o) const {
            return std::max(0.0, std::min(x1, o.x1) - std::max(x0, o.x0)) *
                   std::max(0.0, std::min(y1, o.y1) - std::max(y0, o.y0));
        }
        double area() const { return (x1 - x0) * (y1 - y0); }
    };
    const Box plotArea{L + 2, T + 2, R - 2, B - 2};
    std::vector<Box> taken;  // markers, then labels as they are placed
    for (const auto& series : chart.series)
        for (std::size_t i = 0; i < std::min(series.x.size(), series.y.size()); ++i)
            if (const auto p = l.toPixel(series.x[i], series.y[i]); p && series.points)
                taken.push_back(
                    {p->x - kDotRadius, p->y - kDotRadius, p->x + kDotRadius, p->y + kDotRadius});
    for (const auto& series : chart.series)
        for (std::size_t i = 0;
             i < std::min({series.x.size(), series.y.size(), series.pointLabels.size()}); ++i) {
            const std::string& text = series.pointLabels[i];
            const auto p = l.toPixel(series.x[i], series.y[i]);
            if (text.empty() || !p) continue;
            const double w = textWidth(cr, text), h = l.textH;
            // Left edge and vertical centre of each spot, the first preferred.
            const Pt spots[] = {{p->x + 7, p->y - 9},      {p->x - 7 - w, p->y - 9},
                                {p->x + 7, p->y + 9},      {p->x - 7 - w, p->y + 9},
                                {p->x + 8, p->y},          {p->x - 8 - w, p->y},
                                {p->x - w / 2, p->y - 13}, {p->x - w / 2, p->y + 13}};
            Box best{};
            double bestCost = INFINITY;
            for (const Pt& spot : spots) {
                const Box b{spot.x, spot.y - h / 2, spot.x + w, spot.y + h / 2};
                double cost = b.area() - b.overlap(plotArea);
                for (const Box& t : taken) cost += b.overlap(t);
                if (cost < bestCost) {
                    bestCost = cost;
                    best = b;
                }
            }
            taken.push_back(best);
            drawText(cr, best.x0, (best.y0 + best.y1) / 2, text, Anchor::Start);
            for (double u = 0; u <= w; u += 4)
                occupied.push_back({best.x0 + u, (best.y0 + best.y1) / 2});
        }
    cairo_restore(cr);

    drawAxes(cr, chart, l);
    drawLegend(cr, chart, l, occupied);
}

// The charts side by side, each in its own width x height cell.
void drawCharts(cairo_surface_t* surface, const std::vector<Chart>& charts, int width, int height,
                const std::string& path) {
    const Context cr(cairo_create(surface));
    check(cairo_status(cr.get()), path);
    prepare(cr.get());
    for (std::size_t i = 0; i < charts.size(); ++i) {
        cairo_save(cr.get());
        cairo_translate(cr.get(), static_cast<double>(i) * width, 0);
        cairo_rectangle(cr.get(), 0, 0, width, height);
        cairo_clip(cr.get());
        drawChart(cr.get(), charts[i], width, height);
        cairo_restore(cr.get());
    }
    check(cairo_status(cr.get()), path);
}

// ---------------------------------------------------------------------------
// Encoding to bytes, then files

// Cairo's stream writer: appends to the std::string passed as closure.
cairo_status_t appendTo(void* closure, const unsigned char* data, unsigned int length) {
    try {
        static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
        return CAIRO_STATUS_SUCCESS;
    } catch (const std::bad_alloc&) {
        return CAIRO_STATUS_NO_MEMORY;  // no exceptions through Cairo's C frames
    }
}

std::string renderPng(const std::vector<Chart>& charts, int width, int height,
                      const std::string& path) {
    const Surface surface(cairo_image_surface_create(
        CAIRO_FORMAT_RGB24, width * static_cast<int>(charts.size()), height));
    check(cairo_surface_status(surface.get()), path);
    drawCharts(surface.get(), charts, width, height, path);
    std::string png;
    check(cairo_surface_write_to_png_stream(surface.get(), appendTo, &png), path);
    return png;
}

std::string xmlEscape(const std::string& s) {
    std::string out;
    for (char c : s) {
        switch (c) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            default:
                // Control characters are not allowed in XML 1.0 at all.
                if (static_cast<unsigned char>(c) >= 0x20 || c == '\t' || c == '\n') out += c;
        }
    }
    return out;
}

// Cairo draws text into SVG as glyph outlines, so the file holds no words.
// A <title> and <desc> (the SVG elements meant for this) carry the titles,
// axis labels and legend as text, for search and for screen readers.
std::string withTextEquivalent(std::string svg, const std::vector<Chart>& charts) {
    std::string title, desc;
    for (const Chart& c : charts) {
        title += (title.empty() ? "" : " | ") + c.title;
        desc += c.title + ". x: " + c.xLabel + (c.logX ? " (log)" : "") + ". y: " + c.yLabel +
                (c.logY ? " (log)" : "") + ".";
        for (const Series& s : c.series)
            if (!s.label.empty()) desc += " Legend: " + s.label + ".";
        desc += "\n";
    }
    const std::size_t root = svg.find("<svg");
    const std::size_t end = root == std::string::npos ? root : svg.find('>', root);
    if (end != std::string::npos)
        svg.insert(end + 1, "\n<title>" + xmlEscape(title) + "</title>\n<desc>" + xmlEscape(desc) +
                                "</desc>");
    return svg;
}

std::string renderSvg(const std::vector<Chart>& charts, int width, int height,
                      const std::string& path) {
    std::string svg;
    {
        const Surface surface(cairo_svg_surface_create_for_stream(
            appendTo, &svg, static_cast<double>(width) * static_cast<double>(charts.size()),
            height));
        check(cairo_surface_status(surface.get()), path);
        cairo_svg_surface_set_document_unit(surface.get(), CAIRO_SVG_UNIT_PX);
        drawCharts(surface.get(), charts, width, height, path);
        cairo_surface_finish(surface.get());  // flushes the document into svg
        check(cairo_surface_status(surface.get()), path);
    }
    return withTextEquivalent(std::move(svg), charts);
}

}  // namespace

void writeCharts(const std::vector<Chart>& charts, const std::string& pathWithoutExtension,
                 bool overwrite, int width, int height) {
    const std::string png = pathWithoutExtension + ".png", svg = pathWithoutExtension + ".svg";
    if (charts.empty()) throw std::runtime_error(png + ": no charts to draw");
    // Both checked before either is written, so a refusal leaves no half pair.
    if (!overwrite)
        for (const std::string& path : {png, svg})
            if (std::filesystem::exists(path))
                throw std::runtime_error(path + ": exists, not overwritten");
    width = std::max(1, width);
    height = std::max(1, height);
    // Both drawn before either is written, for the same reason.
    const std::string pngBytes = renderPng(charts, width, height, png);
    const std::string svgBytes = renderSvg(charts, width, height, svg);
    writeFileAtomically(png, pngBytes);
    writeFileAtomically(svg, svgBytes);
}

std::optional<std::array<double, 2>> dataToPixel(const Chart& chart, double x, double y, int width,
                                                 int height) {
    // The layout measures text; any surface will do for that, as the font
    // metrics are unhinted (see prepare).
    const Surface scratch(cairo_image_surface_create(CAIRO_FORMAT_RGB24, 1, 1));
    const Context cr(cairo_create(scratch.get()));
    prepare(cr.get());
    const Layout l = computeLayout(cr.get(), chart, width, height);
    const auto p = l.toPixel(x, y);
    if (!p) return std::nullopt;
    return std::array<double, 2>{p->x, p->y};
}

}  // namespace rad::plot
