// SPDX-License-Identifier: MIT
// A lower bound of a run's memory against its nodes'.
#include "app/memory_check.hpp"

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>

#include "emergent/error.hpp"
#include "emergent/vec3.hpp"

namespace emergent::app {

double particle_bytes_lower_bound() {
    // position, velocity, force; species, id, image, diameter
    const double fields = 3 * sizeof(Vec3) + sizeof(int) + sizeof(std::int64_t) + sizeof(Int3) + sizeof(Real);
    return 2 * fields;
}

double node_memory_bytes() {
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
    double bytes = pages > 0 && page > 0 ? double(pages) * double(page) : 0;
    // A container's limit (cgroup v2, then v1) may be lower than the machine's memory.
    for (const char* path : {"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"}) {
        std::ifstream in(path);
        double limit = 0;
        if (in >> limit && limit > 0 && (bytes == 0 || limit < bytes)) bytes = limit;
    }
    return bytes;
}

namespace {
std::string bytes_text(double b) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g GB", b / 1e9);
    return text;
}
}  // namespace

void check_memory(MPI_Comm comm, const std::string& scene, double particles,
                  const std::string& what, const std::vector<FieldGrid>& grids) {
    int ranks = 1, node_ranks = 1;
    MPI_Comm_size(comm, &ranks);
    MPI_Comm node;
    MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
    MPI_Comm_size(node, &node_ranks);
    MPI_Comm_free(&node);
    // Every rank holds a share of the particles; every rank holds each field grid whole
    // (accumulated sums, 6 doubles a cell), and one copy more is reduced for a frame.
    double cells = 0;
    for (const FieldGrid& g : grids) cells += double(g.n.x) * double(g.n.y) * double(g.n.z);
    const double per_rank_particles = particles / ranks * particle_bytes_lower_bound();
    const double per_rank_grids = cells * 6 * sizeof(double) * 2;
    const double need = node_ranks * (per_rank_particles + per_rank_grids);
    // The node's memory is the same for all of its ranks; agree on the smallest node.
    double have = node_memory_bytes();
    MPI_Allreduce(MPI_IN_PLACE, &have, 1, MPI_DOUBLE, MPI_MIN, comm);
    if (have <= 0 || need <= have) return;
    const bool grids_dominate = per_rank_grids > per_rank_particles;
    std::string item;
    if (grids_dominate) {
        for (const FieldGrid& g : grids) {
            const double n = double(g.n.x) * double(g.n.y) * double(g.n.z);
            const std::string shape =
                std::to_string(g.n.x) + "x" + std::to_string(g.n.y) + "x" + std::to_string(g.n.z);
            if (item.empty() || n * 2 > cells)
                item = g.name == "box" ? "fields.grid=" + shape
                                       : "field grid '" + g.name + "' (" + shape + " cells)";
        }
    } else {
        char count[32];
        std::snprintf(count, sizeof count, "%.3g", particles);
        item = what.empty() ? std::string("N = ") + count + " particles"
                            : what + " (N = " + count + " particles)";
    }
    throw InputError(scene + ": " + item + " needs at least " + bytes_text(need) + " on each node (" +
                     std::to_string(node_ranks) + " rank(s) there), more than its memory (" +
                     bytes_text(have) + "): make it smaller or use more nodes");
}

}  // namespace emergent::app
