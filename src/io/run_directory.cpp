// SPDX-License-Identifier: MIT
// A run's output directory.
#include "io/run_directory.hpp"

#include <hdf5.h>

#include <algorithm>
#include <filesystem>
#include <regex>

#include "emergent/error.hpp"

namespace emergent::io {

namespace fs = std::filesystem;

bool is_run_output(const std::string& name) {
    // Segments of a continued run carry ".from<STEP>"; sidecars name their particle group.
    static const std::regex names(
        R"(((trajectory|fields)(\.from[0-9]+)?(\.h5|(\.[A-Za-z_]+)?\.xmf))"
        R"(|snapshot\.h5|thermo\.dat|summary\.json|checkpoint\.h5|last_good\.h5)(\.tmp)?)");
    return std::regex_match(name, names);
}

std::vector<std::string> run_outputs_in(const std::string& dir) {
    std::vector<std::string> found;
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) return found;
    for (const fs::directory_entry& entry : fs::directory_iterator(dir, ec)) {
        const std::string name = entry.path().filename().string();
        if (is_run_output(name)) found.push_back(name);
    }
    std::sort(found.begin(), found.end());
    return found;
}

void remove_run_outputs(const std::string& dir) {
    for (const std::string& name : run_outputs_in(dir)) {
        const std::string path = (fs::path(dir) / name).string();
        std::error_code ec;
        fs::remove(path, ec);
        if (ec) throw IoError("cannot remove '" + path + "' of the earlier run: " + ec.message());
    }
}

bool trajectory_complete(const std::string& path) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) return false;
    long long complete = 0;
    // Read serially by the one rank that asks: the file belongs to no running job.
    H5E_BEGIN_TRY {
        const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
        if (file >= 0) {
            const hid_t group = H5Gopen2(file, "h5md", H5P_DEFAULT);
            if (group >= 0) {
                const hid_t attr = H5Aopen(group, "emergent_complete", H5P_DEFAULT);
                if (attr >= 0) {
                    if (H5Aread(attr, H5T_NATIVE_LLONG, &complete) < 0) complete = 0;
                    H5Aclose(attr);
                }
                H5Gclose(group);
            }
            H5Fclose(file);
        }
    }
    H5E_END_TRY;
    return complete == 1;
}

std::string list_names(const std::vector<std::string>& names, std::size_t shown) {
    std::string text;
    for (std::size_t k = 0; k < names.size() && k < shown; ++k)
        text += (k == 0 ? "" : ", ") + names[k];
    if (names.size() > shown) text += " and " + std::to_string(names.size() - shown) + " more";
    return text;
}

}  // namespace emergent::io
