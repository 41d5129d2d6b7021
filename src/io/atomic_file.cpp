// SPDX-License-Identifier: MIT
// Atomic file replacement.
#include "io/atomic_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>

#include "emergent/error.hpp"

namespace emergent::io {

void write_atomically(const std::string& path, const std::string& content) {
    const std::string tmp = path + ".tmp";
    errno = 0;
    bool written = false;
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        if (out) {
            out << content;
            out.close();  // a full disk may only show when the last block is written
            written = !out.fail();
        }
    }
    int cause = errno;
    if (written && std::rename(tmp.c_str(), path.c_str()) == 0) return;
    const std::string verb = written ? "cannot rename '" + tmp + "' to '" + path + "'"
                                     : "cannot write '" + tmp + "'";
    if (written) cause = errno;
    std::remove(tmp.c_str());  // the earlier file, if any, is still whole
    throw IoError(verb + (cause != 0 ? std::string(": ") + std::strerror(cause) : ""));
}

}  // namespace emergent::io
