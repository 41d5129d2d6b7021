// SPDX-License-Identifier: MIT
// One line for a failure, and no rank left waiting.
#include "app/failure_report.hpp"

#include <cstdio>

#include "decomposition/ranks_meet.hpp"

namespace emergent::app {

namespace {
void print_line(const std::string& line) {
    std::fprintf(stderr, "%s\n", line.c_str());
    std::fflush(stderr);
}
}  // namespace

int report_failure(MPI_Comm errors, int code, const std::string& line, bool rank_local,
                   double wait_seconds) {
    int rank = 0, size = 1;
    MPI_Comm_rank(errors, &rank);
    MPI_Comm_size(errors, &size);
    if (size == 1) {
        print_line(line);
        return code;
    }
    // A barrier nobody else joins stays pending; the abort below ends it with the job.
    const bool everyone = !rank_local && decomp::ranks_meet(errors, wait_seconds);
    if (everyone) {
        int worst = code;
        MPI_Allreduce(&code, &worst, 1, MPI_INT, MPI_MAX, errors);
        if (rank == 0) print_line(line);
        return worst;
    }
    // Name the rank (a rank-local fault's line already does): the line may hold for that node only.
    const std::string marker = "emergent: ";
    print_line(!rank_local && line.compare(0, marker.size(), marker) == 0
                   ? marker + "rank " + std::to_string(rank) + ": " + line.substr(marker.size())
                   : line);
    MPI_Abort(MPI_COMM_WORLD, code);
    return code;
}

}  // namespace emergent::app
