// SPDX-License-Identifier: MIT
// Loading out-of-tree scenes.
#include <dlfcn.h>
#include <elf.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "emergent/error.hpp"
#include "emergent/plugin.hpp"

namespace emergent {

namespace {

/// Why the file at `path` cannot be a whole 64-bit ELF shared library, or "" where it may be one.
/// The loader maps segments past the end of a truncated file and dies of SIGBUS when it touches
/// them, so a file shorter than its own headers and segments say is refused before dlopen.
std::string damaged_library(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return "";  // dlopen says why
    Elf64_Ehdr header{};
    in.read(reinterpret_cast<char*>(&header), sizeof header);
    if (!in || std::memcmp(header.e_ident, ELFMAG, SELFMAG) != 0 || header.e_ident[EI_CLASS] != ELFCLASS64)
        return "";  // not a 64-bit ELF file: dlopen's own message names that
    const auto size = static_cast<std::uint64_t>(std::filesystem::file_size(path));
    if (header.e_phoff + std::uint64_t(header.e_phnum) * header.e_phentsize > size ||
        header.e_shoff + std::uint64_t(header.e_shnum) * header.e_shentsize > size)
        return "its headers reach past its end";
    for (int k = 0; k < header.e_phnum; ++k) {
        Elf64_Phdr segment{};
        in.seekg(static_cast<std::streamoff>(header.e_phoff + std::uint64_t(k) * header.e_phentsize));
        in.read(reinterpret_cast<char*>(&segment), sizeof segment);
        if (!in) return "its program headers cannot be read";
        if (segment.p_type == PT_LOAD && segment.p_offset + segment.p_filesz > size)
            return "a segment reaches past its end";
    }
    return "";
}

}  // namespace

void load_plugin(const std::string& given) {
    if (given.empty()) throw InputError("--plugin: the path is empty");
    // A bare name would be looked up in the library path only: one that names a file here
    // means that file.
    const std::string path =
        given.find('/') == std::string::npos && std::filesystem::exists(given) ? "./" + given : given;
    const std::string damage = damaged_library(path);
    if (!damage.empty())
        throw InputError("cannot load plugin '" + given + "': a truncated or damaged shared library (" +
                         damage + ")");
    // RTLD_NOW: unresolved symbols fail here, with dlerror's explanation, not mid-run.
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) throw InputError("cannot load plugin '" + path + "': " + dlerror());
    using AbiFunction = const char* (*)();
    using InitFunction = void (*)(ProblemRegistry&);
    auto abi = reinterpret_cast<AbiFunction>(dlsym(handle, "emergent_plugin_abi"));
    auto init = reinterpret_cast<InitFunction>(dlsym(handle, "emergent_plugin_init"));
    if (!abi || !init)
        throw InputError("plugin '" + path + "' has no EMERGENT_PLUGIN entry points");
    if (std::strcmp(abi(), EMERGENT_PLUGIN_ABI) != 0)
        throw InputError("plugin '" + path + "' was built for " + abi() + ", this emergent is " +
                         EMERGENT_PLUGIN_ABI + ": rebuild it against these headers");
    try {
        init(ProblemRegistry::instance());
    } catch (const std::logic_error& e) {
        throw InputError("plugin '" + path + "': " + e.what());
    }
    // The library stays loaded for the life of the process: its scenes are in the registry.
}

}  // namespace emergent
