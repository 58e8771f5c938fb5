// stop_signals.h — Ctrl-C, SIGTERM and SIGHUP ask a render (or a batch of them) to stop
// gracefully: the first signal sets a flag the render loop polls (the paths in flight finish, none
// start, the outputs are written); a second one ends the process at once (the default action).
// SIGPIPE is ignored meanwhile: with the terminal gone, a progress line must not kill the render.
//
// StopSignals installs the handlers for its lifetime. Instances nest: only the outermost installs,
// clears the flag and restores, so a batch (host/batch/) holds one across all its jobs and a stop
// that arrives between two jobs, or while one writes its outputs, is still seen by the batch.
#pragma once

#include <atomic>

namespace fen {

class StopSignals {
public:
    StopSignals();
    ~StopSignals();
    StopSignals(const StopSignals&) = delete;
    StopSignals& operator=(const StopSignals&) = delete;
    // The flag the first signal sets (what the render loop polls).
    static std::atomic<bool>* flag();
    static bool requested() { return flag()->load(); }
    // Quiet: the first signal stops as ever but prints nothing (the ranks of a team but the root,
    // so that a Ctrl-C to mpirun prints one line, not one per rank).
    static void setQuiet(bool quiet);

private:
    bool outermost_ = false;
    void (*oldInt_)(int) = nullptr;
    void (*oldTerm_)(int) = nullptr;
    void (*oldHup_)(int) = nullptr;
    void (*oldPipe_)(int) = nullptr;
};

}  // namespace fen
