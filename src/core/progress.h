// Progress: a progress bar with elapsed time and ETA on stderr, for long
// renders. Drawn only when enabled (stderr is a terminal and -q is absent),
// at most ten times a second, by whichever thread reports progress.
#pragma once

#include <atomic>
#include <cstdint>
#include <mutex>
#include <string>

#include "core/timer.h"

namespace pt {

class Progress {
public:
    Progress(std::string label, uint64_t total, bool enabled);
    ~Progress();
    /// Adds `work` units done; thread-safe.
    void advance(uint64_t work);
    /// Draws the final state and ends the line.
    void finish();

    /// Whether stderr is a terminal (the default for showing progress).
    static bool stderr_is_terminal();

private:
    void draw(bool final);

    std::string label_;
    uint64_t total_;
    bool enabled_;
    bool finished_ = false;
    std::atomic<uint64_t> done_{0};
    std::mutex draw_mutex_;
    double last_draw_ = -1.0;
    Timer timer_;
};

}  // namespace pt
