// SPDX-License-Identifier: MIT
// A run asked to stop early (SIGUSR1, SIGTERM: a batch system's time limit; SIGINT: Ctrl-C)
// checkpoints and ends with its own exit code, so that a job script can continue it.
#pragma once

#include <mpi.h>

#include <csignal>
#include <stdexcept>
#include <string>

namespace emergent::app {

/// Catches SIGUSR1 and SIGTERM while it lives, and a first SIGINT from catch_interrupt() on (the
/// previous handlers come back after), and lets every rank agree on the step at which to stop.
/// Signals reach the ranks at different steps (srun and mpirun forward them one task at a time),
/// so the ranks vote: each step completes the previous step's non-blocking reduction of "a
/// signal arrived here" and starts the next one. All ranks therefore see a request at the same
/// step, one step after the last rank was signalled, and the reduction is overlapped with a
/// whole step of work.
class StopRequest {
public:
    /// Inactive (installs nothing, never stops) when `active` is false: a run with nowhere to
    /// write a checkpoint keeps the default actions of these signals.
    StopRequest(MPI_Comm comm, bool active);
    ~StopRequest();
    StopRequest(const StopRequest&) = delete;
    StopRequest& operator=(const StopRequest&) = delete;

    /// Ctrl-C too, from here on: called once the set-up is done. During a set-up (which can be
    /// long, and has written nothing yet) Ctrl-C ends the process at once; SIGUSR1 and SIGTERM,
    /// a batch system's, wait for the first step and its checkpoint.
    void catch_interrupt();
    /// Called by every rank once per step, in step: true on all ranks alike when any rank has
    /// been signalled.
    bool agreed();
    /// The signal the ranks agreed on (the highest number any rank received; 0 before then).
    int signal() const;

private:
    bool active_ = false;
    MPI_Comm comm_ = MPI_COMM_NULL;
    int ranks_ = 1;
    MPI_Request pending_ = MPI_REQUEST_NULL;
    int vote_ = 0, result_ = 0;
    bool interrupt_caught_ = false;
    struct sigaction previous_usr1_ {}, previous_term_ {}, previous_int_ {};
};

/// "SIGUSR1", "SIGTERM", "SIGINT", or "signal N".
std::string signal_name(int sig);

/// Thrown after a run stopped on request has written its checkpoint and closed its files; main()
/// prints its line and exits with exit_code::stopped.
class RunStopped : public std::runtime_error {
public:
    explicit RunStopped(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace emergent::app
