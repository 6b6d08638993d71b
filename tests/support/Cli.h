#pragma once
// Running radiosity-cli as a user would: a separate process, validation on.

#include <string>

namespace rad::test {

struct RunResult {
    int exitCode = -1;
    std::string output;  // stdout and stderr together
};

std::string shellQuote(const std::string& s);
// Runs `radiosity-cli ARGUMENTS` with RADIOSITY_VALIDATION=1.
RunResult runCli(const std::string& arguments);
std::string readFile(const std::string& path);
// The number after "key": in a JSON text (first occurrence), or NaN.
double jsonNumber(const std::string& json, const std::string& key, std::size_t from = 0);

}  // namespace rad::test
