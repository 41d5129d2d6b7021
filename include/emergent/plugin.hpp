// SPDX-License-Identifier: MIT
// Out-of-tree scenes: a shared library that `emergent --plugin path.so` loads.
//
//   // my_scene.cpp, built as a shared library against these headers:
//   #include "emergent/plugin.hpp"
//   emergent::ProblemInfo my_scene_info() { ... }
//   EMERGENT_PLUGIN(my_scene_info)
//
// The library's undefined symbols resolve against the emergent executable, which exports the
// whole engine API. The ABI string is checked on load: a plugin built against other headers is
// refused with a clear error instead of crashing.
#pragma once

#include "emergent/problem.hpp"
#include "emergent/simulation.hpp"

/// Changes whenever the public headers change (tests/plugin/interface_digest.cmake enforces it);
/// what changed at each tag: docs/plugin_abi.md.
#define EMERGENT_PLUGIN_ABI "emergent-plugin-42"

#define EMERGENT_PLUGIN(info_function)                                               \
    extern "C" const char* emergent_plugin_abi() { return EMERGENT_PLUGIN_ABI; }     \
    extern "C" void emergent_plugin_init(::emergent::ProblemRegistry& registry) {    \
        registry.add(info_function());                                               \
    }

namespace emergent {

/// Loads a plugin and registers its scenes; InputError naming the file on any failure.
void load_plugin(const std::string& path);

}  // namespace emergent
