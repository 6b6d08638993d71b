#pragma once
// Running radiosity-cli as a user would: a separate process, validation on.

#include <string>

#include <nlohmann/json.hpp>

namespace rad::test {

struct RunResult {
    int exitCode = -1;
    std::string output;  // stdout and stderr together
};

std::string shellQuote(const std::string& s);
// Runs `radiosity-cli ARGUMENTS` with RADIOSITY_VALIDATION=1.
RunResult runCli(const std::string& arguments);
std::string readFile(const std::string& path);
// A JSON file, parsed; throws nlohmann::json::parse_error (the test fails
// with it) when the file is missing or not JSON.
nlohmann::json readJson(const std::string& path);
// The value at a JSON pointer ("/seconds/total"), or null when there is none,
// so that a missing key fails the assertion on its value instead of throwing.
nlohmann::json jsonAt(const nlohmann::json& json, const std::string& pointer);

}  // namespace rad::test
