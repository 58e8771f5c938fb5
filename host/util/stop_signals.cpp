// stop_signals.cpp — graceful stops on Ctrl-C, SIGTERM, SIGHUP (stop_signals.h).
#include "util/stop_signals.h"

#include <csignal>
#include <unistd.h>

namespace fen {

namespace {

std::atomic<bool> gStop{false};
std::atomic<bool> gQuiet{false};
int gDepth = 0;  // StopSignals alive (single-threaded: constructed and destroyed on the main thread)

// Only async-signal-safe calls here.
extern "C" void onStopSignal(int sig)
{
    if (gStop.exchange(true)) {
        std::signal(sig, SIG_DFL);
        std::raise(sig);
        return;
    }
    if (gQuiet.load())
        return;
    static const char msg[] =
        "\nfenestra: interrupted: finishing the paths in flight and writing the image (again to quit now)\n";
    const ssize_t ignored = ::write(STDERR_FILENO, msg, sizeof msg - 1);
    (void)ignored;
}

}  // namespace

StopSignals::StopSignals()
{
    outermost_ = gDepth++ == 0;
    if (!outermost_)
        return;
    gStop = false;
    oldInt_ = std::signal(SIGINT, onStopSignal);
    oldTerm_ = std::signal(SIGTERM, onStopSignal);
    oldHup_ = std::signal(SIGHUP, onStopSignal);
    oldPipe_ = std::signal(SIGPIPE, SIG_IGN);
}

StopSignals::~StopSignals()
{
    --gDepth;
    if (!outermost_)
        return;
    std::signal(SIGINT, oldInt_);
    std::signal(SIGTERM, oldTerm_);
    std::signal(SIGHUP, oldHup_);
    std::signal(SIGPIPE, oldPipe_);
}

void StopSignals::setQuiet(bool quiet)
{
    gQuiet = quiet;
}

std::atomic<bool>* StopSignals::flag()
{
    return &gStop;
}

}  // namespace fen
