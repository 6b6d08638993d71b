#pragma once
// The small argument parser every radiosity-cli command shares.
//
// A command declares its options, parses, then reads typed values:
//   const std::vector<OptionSpec> options{
//       {"--image", "OUT", "output image, .png or .pfm"},
//       {"--force", "", "overwrite OUT if it exists"}};
//   const ParsedArgs args = parseArgs(argv, options);   // throws UsageError
//   if (args.has("--help")) { printHelp(...); return 0; }
//   const ImageSize size = parseSize("--size", args.value("--size").value_or("512x512"));
//
// Usage problems throw UsageError; main prints "radiosity-cli: <problem>" and
// exits with kExitUsage.

#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace rad::cli {

constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;  // the command ran and failed (bad scene, existing output...)
constexpr int kExitUsage = 2;    // the command line itself is wrong

struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct OptionSpec {
    std::string name;       // "--image"
    std::string valueName;  // "OUT"; empty for a flag without a value
    std::string help;       // one line
};

struct ParsedArgs {
    std::vector<std::string> positionals;
    std::map<std::string, std::string> values;  // options with a value (the last one wins)
    std::set<std::string> flags;                // options without a value, and --help
    std::vector<std::pair<std::string, std::string>> ordered;  // every valued option, in order

    // Every value of a repeatable option, in command-line order.
    std::vector<std::string> all(const std::string& name) const;
    bool has(const std::string& name) const {
        return flags.count(name) > 0 || values.count(name) > 0;
    }
    std::optional<std::string> value(const std::string& name) const;
};

// Accepts "--name VALUE", "--name=VALUE", flags, "--help"/"-h" (always), and
// "--" to end options. Throws UsageError for an unknown option, a missing
// value, or a value given to a flag.
ParsedArgs parseArgs(const std::vector<std::string>& args, const std::vector<OptionSpec>& options);

// Aligned "  --name VALUE  help" lines, one per option, plus --help.
std::string formatOptions(const std::vector<OptionSpec>& options);

// Typed values. Errors name the option: "--size: expected WxH, got '12'".
double parseDouble(const std::string& option, const std::string& text);
long long parseInteger(const std::string& option, const std::string& text, long long lo,
                       long long hi);

struct ImageSize {
    int width = 0;
    int height = 0;
};
// "WxH", each in [lo, hi].
// "X,Y,Z" (count 3) or "AX,AY,AZ,DEG" (count 4): finite numbers.
std::vector<double> parseNumbers(const std::string& option, const std::string& text, std::size_t count);

ImageSize parseSize(const std::string& option, const std::string& text, int lo = 1, int hi = 8192);

// Exactly one positional per name; errors name the missing one ("missing SCENE", "unexpected
// argument 'x'").
void requirePositionals(const ParsedArgs& args, const std::vector<std::string>& names);

}  // namespace rad::cli
