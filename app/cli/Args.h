#pragma once
// What radiosity-cli's commands and radiosity-viewer share on top of CLI11:
// exit codes, the parsers of option values, and the checks for options bound
// to a number.
//
// A value parser turns one argument into a value or throws
// CLI::ValidationError with a message saying what is wrong ("expected WxH,
// got '12'"); CLI11 puts the option's name in front, so the user reads
// "--size: expected WxH, got '12'". A command binds one like this:
//   command.add_option("--size", "image size")->type_name("WxH")
//       ->each([&size](const std::string& text) { size = parseSize(text); });
// and a number CLI11 reads itself, with its default shown in --help, like this:
//   command.add_option("--epsilon", settings.epsilon, "BF threshold")
//       ->type_name("E")->check(positiveNumber())->capture_default_str();

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace rad::cli {

constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;  // the command ran and failed (bad scene, existing output...)
constexpr int kExitUsage = 2;    // the command line itself is wrong

// A usage problem found after parsing, when it involves several options
// ("needs a motion"). The program prints it as one line and exits with kExitUsage.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// CLI11's settings for both programs: an option given twice keeps the last
// value (repeatable options say so), and the help's first column is wide
// enough for "--rotate AX,AY,AZ,DEG".
void configure(CLI::App& app);

// Flags take no value: "--force=0" is refused rather than read as "no".
CLI::Option* addFlag(CLI::App& app, const std::string& name, bool& value, const std::string& help);

// Value parsers (see the top of this file).
double parseNumber(const std::string& text);  // finite
long long parseInteger(const std::string& text, long long lo, long long hi);
// "X,Y,Z" (count 3) or "AX,AY,AZ,DEG" (count 4): finite numbers.
std::vector<double> parseNumbers(const std::string& text, std::size_t count);
// "a,b,c" -> {"a", "b", "c"}; "" -> {""}.
std::vector<std::string> splitList(const std::string& text);

// "SIZE": a count of bytes, digits only, with an optional K, M or G suffix
// (either case; binary: 1K = 1024). Throws CLI::ValidationError.
std::size_t parseByteSize(const std::string& text);
// The other way round, for messages: "512 MiB", "3.2 GiB".
std::string byteSizeText(std::size_t bytes);

struct ImageSize {
    int width = 0;
    int height = 0;
};
// "WxH" (or "WXH"), digits only, each side in [lo, hi].
ImageSize parseSize(const std::string& text, int lo = 1, int hi = 8192);

// Checks for options bound to a number. CLI11 runs them on the text before
// reading the number itself, so a bad value gets these messages, not CLI11's.
CLI::Validator number();          // finite
CLI::Validator positiveNumber();  // finite and > 0
CLI::Validator numberIn(double lo, double hi);
// An integer in [lo, hi]. Use it with ->transform(), not ->check(): it
// rewrites the text in base 10, which CLI11 alone would read "010" as octal 8.
CLI::Validator integerIn(long long lo, long long hi);

}  // namespace rad::cli
