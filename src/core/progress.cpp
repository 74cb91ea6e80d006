#include "core/progress.h"

#include <unistd.h>

#include <cstdio>

namespace pt {

Progress::Progress(std::string label, uint64_t total, bool enabled)
    : label_(std::move(label)), total_(total ? total : 1), enabled_(enabled) {}

Progress::~Progress() {
    if (enabled_ && !finished_) std::fputs("\n", stderr);
}

bool Progress::stderr_is_terminal() { return isatty(STDERR_FILENO) == 1; }

void Progress::advance(uint64_t work) {
    done_ += work;
    if (!enabled_) return;
    std::unique_lock<std::mutex> lock(draw_mutex_, std::try_to_lock);
    if (!lock.owns_lock()) return;  // another thread is drawing; skip
    if (timer_.seconds() - last_draw_ < 0.1) return;
    draw(false);
}

void Progress::finish() {
    if (!enabled_ || finished_) return;
    std::lock_guard<std::mutex> lock(draw_mutex_);
    draw(true);
    std::fputs("\n", stderr);
    finished_ = true;
}

void Progress::draw(bool final) {
    const int width = 30;
    double elapsed = timer_.seconds();
    last_draw_ = elapsed;
    double fraction = final ? 1.0 : double(done_.load()) / double(total_);
    if (fraction > 1) fraction = 1;
    int filled = int(fraction * width);
    char bar[width + 1];
    for (int i = 0; i < width; ++i) bar[i] = i < filled ? '#' : '-';
    bar[width] = '\0';
    if (final) {
        std::fprintf(stderr, "\r%s [%s] 100%% %.1fs          ", label_.c_str(), bar, elapsed);
    } else {
        double eta = fraction > 0 ? elapsed * (1 - fraction) / fraction : 0;
        std::fprintf(stderr, "\r%s [%s] %3d%% %.1fs ETA %.1fs   ", label_.c_str(), bar, int(fraction * 100),
                     elapsed, eta);
    }
    std::fflush(stderr);
}

}  // namespace pt
