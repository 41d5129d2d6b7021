// SPDX-License-Identifier: MIT
// Files that appear complete or not at all.
#pragma once

#include <string>

namespace emergent::io {

/// Writes `content` to `path` through `path.tmp` and a rename, so a reader (or a crash) never
/// sees a half-written file and a previous version survives a failed write.
void write_atomically(const std::string& path, const std::string& content);

}  // namespace emergent::io
