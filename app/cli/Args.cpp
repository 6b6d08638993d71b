#include "cli/Args.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <utility>

namespace rad::cli {
namespace {

std::string shortNumber(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return text;
}

// A CLI::Validator from a check that throws CLI::ValidationError; CLI11
// catches it and names the option. No description: the option's help says
// what it accepts.
CLI::Validator validator(std::function<void(std::string&)> check) {
    return CLI::Validator(
        [check = std::move(check)](std::string& text) {
            check(text);
            return std::string();
        },
        std::string());
}

}  // namespace

void configure(CLI::App& app) {
    app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    app.get_formatter()->column_width(34);
}

CLI::Option* addFlag(CLI::App& app, const std::string& name, bool& value, const std::string& help) {
    return app.add_flag(name, value, help)->disable_flag_override();
}

double parseNumber(const std::string& text) {
    errno = 0;
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(v))
        throw CLI::ValidationError("expected a number, got '" + text + "'");
    return v;
}

long long parseInteger(const std::string& text, long long lo, long long hi) {
    errno = 0;
    char* end = nullptr;
    const long long v = std::strtoll(text.c_str(), &end, 10);
    if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE)
        throw CLI::ValidationError("expected an integer, got '" + text + "'");
    if (v < lo || v > hi)
        throw CLI::ValidationError(text + " is outside " + std::to_string(lo) + ".." + std::to_string(hi));
    return v;
}

std::vector<std::string> splitList(const std::string& text) {
    std::vector<std::string> out;
    std::size_t start = 0;
    while (true) {
        const std::size_t comma = text.find(',', start);
        out.push_back(text.substr(start, comma - start));
        if (comma == std::string::npos) return out;
        start = comma + 1;
    }
}

std::vector<double> parseNumbers(const std::string& text, std::size_t count) {
    std::vector<double> out;
    for (const std::string& item : splitList(text)) out.push_back(parseNumber(item));
    if (out.size() != count)
        throw CLI::ValidationError("expected " + std::to_string(count) + " comma-separated numbers, got '" + text +
                                   "'");
    return out;
}

std::size_t parseByteSize(const std::string& text) {
    const auto bad = [&text]() {
        return CLI::ValidationError("expected bytes with an optional K, M or G suffix (1K = 1024), got '" + text + "'");
    };
    std::string digits = text;
    int shift = 0;
    if (!digits.empty()) {
        switch (digits.back()) {
            case 'K': case 'k': shift = 10; break;
            case 'M': case 'm': shift = 20; break;
            case 'G': case 'g': shift = 30; break;
            default: break;
        }
        if (shift > 0) digits.pop_back();
    }
    // Digits only: strtoull would accept "-1" (as a huge number), "+5" or " 5".
    if (digits.empty() || !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
        throw bad();
    errno = 0;
    const unsigned long long value = std::strtoull(digits.c_str(), nullptr, 10);
    if (errno == ERANGE || value > (std::numeric_limits<std::size_t>::max() >> shift))
        throw CLI::ValidationError("'" + text + "' is more bytes than this machine can count");
    return static_cast<std::size_t>(value) << shift;
}

std::string byteSizeText(std::size_t bytes) {
    char text[32];
    if (bytes >= (std::size_t(1) << 30))
        std::snprintf(text, sizeof text, "%.1f GiB", double(bytes) / double(1 << 30));
    else
        std::snprintf(text, sizeof text, "%.0f MiB", double(bytes) / double(1 << 20));
    return text;
}

ImageSize parseSize(const std::string& text, int lo, int hi) {
    const std::size_t x = text.find_first_of("xX");
    const std::string w = text.substr(0, x);
    const std::string h = x == std::string::npos ? std::string() : text.substr(x + 1);
    // Digits only: strtoll would accept "+5" or " 5", which are not sizes.
    const auto digits = [](const std::string& s) {
        return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
    };
    if (!digits(w) || !digits(h)) throw CLI::ValidationError("expected WxH, got '" + text + "'");
    const auto side = [&](const std::string& s) {
        try {
            return static_cast<int>(parseInteger(s, lo, hi));
        } catch (const CLI::ValidationError&) {
            throw CLI::ValidationError(text + " has a side outside " + std::to_string(lo) + ".." +
                                       std::to_string(hi));
        }
    };
    return {side(w), side(h)};
}

CLI::Validator number() {
    return validator([](std::string& text) { parseNumber(text); });
}

CLI::Validator positiveNumber() {
    return validator([](std::string& text) {
        if (!(parseNumber(text) > 0.0)) throw CLI::ValidationError("must be > 0, got '" + text + "'");
    });
}

CLI::Validator numberIn(double lo, double hi) {
    return validator([lo, hi](std::string& text) {
        const double v = parseNumber(text);
        if (v < lo || v > hi)
            throw CLI::ValidationError("must be " + shortNumber(lo) + ".." + shortNumber(hi) + ", got '" + text + "'");
    });
}

CLI::Validator integerIn(long long lo, long long hi) {
    return validator([lo, hi](std::string& text) { text = std::to_string(parseInteger(text, lo, hi)); });
}

}  // namespace rad::cli
