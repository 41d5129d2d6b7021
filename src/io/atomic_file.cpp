// SPDX-License-Identifier: MIT
// Atomic file replacement.
#include "io/atomic_file.hpp"

#include <cstdio>
#include <fstream>

#include "emergent/error.hpp"

namespace emergent::io {

void write_atomically(const std::string& path, const std::string& content) {
    const std::string tmp = path + ".tmp";
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        if (!out) throw IoError("cannot write '" + tmp + "'");
        out << content;
        out.flush();
        if (!out) throw IoError("cannot write '" + tmp + "'");
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0)
        throw IoError("cannot rename '" + tmp + "' to '" + path + "'");
}

}  // namespace emergent::io
