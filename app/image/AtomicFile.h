#pragma once
// Writing a whole file so that readers never see half of it: the bytes go to a
// temporary beside the target, which is then renamed over it. A failed write
// leaves the old file (if any) as it was and removes the temporary.

#include <string>
#include <string_view>

namespace rad {

// Throws std::runtime_error("<path>: <what went wrong>"), one line.
void writeFileAtomically(const std::string& path, std::string_view bytes);

}  // namespace rad
