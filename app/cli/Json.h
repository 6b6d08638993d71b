#pragma once
// A minimal streaming JSON writer for the CLI's reports: objects, arrays,
// strings (escaped), numbers (shortest round-trip form; NaN/Inf as null).

#include <string>
#include <vector>

namespace rad::cli {

class JsonWriter {
public:
    JsonWriter& beginObject(const std::string& key = {});
    JsonWriter& endObject();
    JsonWriter& beginArray(const std::string& key = {});
    JsonWriter& endArray();
    JsonWriter& value(const std::string& key, double v);
    JsonWriter& value(const std::string& key, long long v);
    JsonWriter& value(const std::string& key, std::size_t v) { return value(key, static_cast<long long>(v)); }
    JsonWriter& value(const std::string& key, int v) { return value(key, static_cast<long long>(v)); }
    JsonWriter& value(const std::string& key, bool v);
    JsonWriter& value(const std::string& key, const std::string& v);
    JsonWriter& value(const std::string& key, const char* v) { return value(key, std::string(v)); }
    JsonWriter& null(const std::string& key);
    // Array elements (no key).
    JsonWriter& element(double v) { return value(std::string(), v); }

    const std::string& str() const { return out_; }

private:
    void prefix(const std::string& key);
    void newline();
    std::string out_;
    std::vector<bool> first_;  // per open container: no element written yet
};

std::string jsonEscape(const std::string& s);

// Writes text to path atomically (temporary beside it, then rename).
void writeFileAtomically(const std::string& path, const std::string& text);

}  // namespace rad::cli
