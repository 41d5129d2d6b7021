// SPDX-License-Identifier: MIT
// Loading out-of-tree scenes.
#include <dlfcn.h>

#include <cstring>
#include <stdexcept>

#include "emergent/error.hpp"
#include "emergent/plugin.hpp"

namespace emergent {

void load_plugin(const std::string& path) {
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
