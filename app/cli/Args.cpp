#include "cli/Args.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace rad::cli {
namespace {

const OptionSpec* findOption(const std::vector<OptionSpec>& options, const std::string& name) {
    auto it = std::find_if(options.begin(), options.end(),
                           [&](const OptionSpec& o) { return o.name == name; });
    return it == options.end() ? nullptr : &*it;
}

}  // namespace

std::vector<std::string> ParsedArgs::all(const std::string& name) const {
    std::vector<std::string> out;
    for (const auto& [n, v] : ordered)
        if (n == name) out.push_back(v);
    return out;
}

std::optional<std::string> ParsedArgs::value(const std::string& name) const {
    auto it = values.find(name);
    if (it == values.end()) return std::nullopt;
    return it->second;
}

ParsedArgs parseArgs(const std::vector<std::string>& args, const std::vector<OptionSpec>& options) {
    ParsedArgs parsed;
    bool optionsEnded = false;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& arg = args[i];
        if (optionsEnded || arg.size() < 2 || arg[0] != '-') {
            parsed.positionals.push_back(arg);
            continue;
        }
        if (arg == "--") {
            optionsEnded = true;
            continue;
        }
        if (arg == "--help" || arg == "-h") {
            parsed.flags.insert("--help");
            continue;
        }
        const std::size_t eq = arg.find('=');
        const std::string name = arg.substr(0, eq);
        const OptionSpec* spec = findOption(options, name);
        if (!spec) throw UsageError("unknown option '" + name + "' (see --help)");
        if (spec->valueName.empty()) {
            if (eq != std::string::npos) throw UsageError(name + " takes no value");
            parsed.flags.insert(name);
        } else if (eq != std::string::npos) {
            parsed.values[name] = arg.substr(eq + 1);
            parsed.ordered.emplace_back(name, parsed.values[name]);
        } else {
            if (i + 1 >= args.size()) throw UsageError(name + " needs a value " + spec->valueName);
            parsed.values[name] = args[++i];
            parsed.ordered.emplace_back(name, parsed.values[name]);
        }
    }
    return parsed;
}

std::string formatOptions(const std::vector<OptionSpec>& options) {
    std::vector<OptionSpec> all = options;
    all.push_back({"--help", "", "show this help and exit"});
    std::size_t width = 0;
    for (const auto& o : all)
        width = std::max(width, o.name.size() + (o.valueName.empty() ? 0 : 1 + o.valueName.size()));
    std::string out;
    for (const auto& o : all) {
        std::string left = o.name + (o.valueName.empty() ? "" : " " + o.valueName);
        left.resize(width, ' ');
        out += "  " + left + "  " + o.help + "\n";
    }
    return out;
}

double parseDouble(const std::string& option, const std::string& text) {
    errno = 0;
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(v))
        throw UsageError(option + ": expected a number, got '" + text + "'");
    return v;
}

long long parseInteger(const std::string& option, const std::string& text, long long lo,
                       long long hi) {
    errno = 0;
    char* end = nullptr;
    const long long v = std::strtoll(text.c_str(), &end, 10);
    if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE)
        throw UsageError(option + ": expected an integer, got '" + text + "'");
    if (v < lo || v > hi)
        throw UsageError(option + ": " + text + " is outside " + std::to_string(lo) + ".." +
                         std::to_string(hi));
    return v;
}

std::vector<double> parseNumbers(const std::string& option, const std::string& text, std::size_t count) {
    std::vector<double> out;
    std::size_t start = 0;
    while (true) {
        const std::size_t comma = text.find(',', start);
        out.push_back(parseDouble(option, text.substr(start, comma - start)));
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    if (out.size() != count)
        throw UsageError(option + ": expected " + std::to_string(count) + " comma-separated numbers, got '" + text + "'");
    return out;
}

ImageSize parseSize(const std::string& option, const std::string& text, int lo, int hi) {
    const std::size_t x = text.find_first_of("xX");
    if (x == std::string::npos) throw UsageError(option + ": expected WxH, got '" + text + "'");
    const std::string w = text.substr(0, x);
    const std::string h = text.substr(x + 1);
    // Digits only: strtoll would accept "+5" or " 5", which are not sizes.
    const auto digits = [](const std::string& s) {
        return !s.empty() &&
               std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
    };
    if (!digits(w) || !digits(h)) throw UsageError(option + ": expected WxH, got '" + text + "'");
    const auto inRange = [&](const std::string& s) {
        try {
            return static_cast<int>(parseInteger(option, s, lo, hi));
        } catch (const UsageError&) {
            throw UsageError(option + ": " + text + " has a side outside " + std::to_string(lo) +
                             ".." + std::to_string(hi));
        }
    };
    return {inRange(w), inRange(h)};
}

void requirePositionals(const ParsedArgs& args, const std::vector<std::string>& names) {
    if (args.positionals.size() < names.size())
        throw UsageError("missing " + names[args.positionals.size()]);
    if (args.positionals.size() > names.size())
        throw UsageError("unexpected argument '" + args.positionals[names.size()] + "'");
}

}  // namespace rad::cli
