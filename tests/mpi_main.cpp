// SPDX-License-Identifier: MIT
// GoogleTest main for all suites: initialises MPI and lets only rank 0 print results; a
// failure on any rank fails the process on every rank.
// Exit 77 (ctest's SKIP_RETURN_CODE) only when the program itself finds its tests cannot run
// here: EMERGENT_TESTS_NEED_DEVICE=1 on a machine without a CUDA device or driver (or a build
// without the CUDA back end), or every selected test skipped itself. Any failure exits 1.
#include <gtest/gtest.h>
#include <mpi.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "emergent/gpu.hpp"

namespace {
constexpr int kSkipped = 77;
}

int main(int argc, char** argv) {
    // As the engine's main: no X display probed for GPUs by hwloc (src/app/main.cpp).
    setenv("HWLOC_COMPONENTS", "-gl", 0);
    MPI_Init(&argc, &argv);
    ::testing::InitGoogleTest(&argc, argv);
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    const char* need_device = std::getenv("EMERGENT_TESTS_NEED_DEVICE");
    if (need_device && std::strcmp(need_device, "1") == 0 && !emergent::gpu::device_present()) {
        if (rank == 0)
            std::printf("SKIPPED: no CUDA device or driver on this machine, or a build without "
                        "the CUDA back end\n");
        MPI_Finalize();
        return kSkipped;
    }
    if (rank != 0) {
        auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
        delete listeners.Release(listeners.default_result_printer());
    }
    int failed = RUN_ALL_TESTS();
    int any_failed = 0;
    MPI_Allreduce(&failed, &any_failed, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    const ::testing::UnitTest& run = *::testing::UnitTest::GetInstance();
    const bool all_skipped = run.test_to_run_count() > 0 &&
                             run.skipped_test_count() == run.test_to_run_count();
    MPI_Finalize();
    if (any_failed) return 1;
    return all_skipped ? kSkipped : 0;
}
