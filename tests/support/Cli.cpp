#include "support/Cli.h"

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <iterator>

namespace rad::test {

std::string shellQuote(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

RunResult runCli(const std::string& arguments) {
    const std::string command = "RADIOSITY_VALIDATION=1 " + shellQuote(RADIOSITY_CLI) + " " + arguments + " 2>&1";
    RunResult result;
    FILE* pipe = popen(command.c_str(), "r");
    if (!pipe) return result;
    std::array<char, 4096> buffer;
    std::size_t n;
    while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) result.output.append(buffer.data(), n);
    const int status = pclose(pipe);
    result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return result;
}

std::string readFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

nlohmann::json readJson(const std::string& path) { return nlohmann::json::parse(readFile(path)); }

nlohmann::json jsonAt(const nlohmann::json& json, const std::string& pointer) {
    const nlohmann::json::json_pointer at(pointer);
    return json.contains(at) ? json.at(at) : nlohmann::json();
}

}  // namespace rad::test
