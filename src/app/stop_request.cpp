// SPDX-License-Identifier: MIT
#include "app/stop_request.hpp"

#include <exception>

namespace emergent::app {

namespace {
volatile std::sig_atomic_t g_signal = 0;

extern "C" void note_signal(int sig) { g_signal = sig; }

/// The action that notes a signal for the next vote; an interrupted write or MPI call carries on.
struct sigaction noting(int extra_flags) {
    struct sigaction action {};
    action.sa_handler = note_signal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESTART | extra_flags;
    return action;
}

}  // namespace

StopRequest::StopRequest(MPI_Comm comm, bool active) : active_(active) {
    if (!active_) return;
    g_signal = 0;
    MPI_Comm_dup(comm, &comm_);  // the votes never meet the step's own collectives
    MPI_Comm_size(comm_, &ranks_);
    const struct sigaction action = noting(0);
    sigaction(SIGUSR1, &action, &previous_usr1_);
    sigaction(SIGTERM, &action, &previous_term_);
}

void StopRequest::catch_interrupt() {
    if (!active_ || interrupt_caught_) return;
    // Once: the handler gives way to the default action, so a second Ctrl-C ends the process
    // at once (a checkpoint being written is a temporary file until renamed: the last one
    // stays whole). A SIGINT ignored from the start (a non-interactive shell's background job,
    // meant to be immune to the terminal's Ctrl-C) stays ignored.
    sigaction(SIGINT, nullptr, &previous_int_);
    interrupt_caught_ = true;
    if (previous_int_.sa_handler == SIG_IGN) return;
    const struct sigaction action = noting(SA_RESETHAND);
    sigaction(SIGINT, &action, nullptr);
}

StopRequest::~StopRequest() {
    if (!active_) return;
    // Leaving on an exception, other ranks may not come to these collectives: the process ends
    // soon, so the vote and its communicator are left as they are.
    if (std::uncaught_exceptions() == 0) {
        if (pending_ != MPI_REQUEST_NULL) MPI_Wait(&pending_, MPI_STATUS_IGNORE);
        MPI_Comm_free(&comm_);
    }
    sigaction(SIGUSR1, &previous_usr1_, nullptr);
    sigaction(SIGTERM, &previous_term_, nullptr);
    if (interrupt_caught_) sigaction(SIGINT, &previous_int_, nullptr);
}

bool StopRequest::agreed() {
    if (!active_) return false;
    if (ranks_ == 1) {
        result_ = g_signal;
        return result_ != 0;
    }
    if (pending_ != MPI_REQUEST_NULL) {
        MPI_Wait(&pending_, MPI_STATUS_IGNORE);
        if (result_ != 0) return true;
    }
    vote_ = g_signal;  // the signal's number: every rank learns which one came
    MPI_Iallreduce(&vote_, &result_, 1, MPI_INT, MPI_MAX, comm_, &pending_);
    return false;
}

int StopRequest::signal() const { return result_; }

std::string signal_name(int sig) {
    if (sig == SIGUSR1) return "SIGUSR1";
    if (sig == SIGTERM) return "SIGTERM";
    if (sig == SIGINT) return "SIGINT";
    return "signal " + std::to_string(sig);
}

}  // namespace emergent::app
