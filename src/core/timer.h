// Timer: wall-clock seconds since construction (steady clock).
// CpuTimer: CPU seconds this process has used since construction, summed
// over its threads (POSIX CLOCK_PROCESS_CPUTIME_ID): unlike wall-clock time
// it does not grow while other processes hold the cores.
// ThreadCpuTimer: the same for the calling thread only
// (CLOCK_THREAD_CPUTIME_ID): a measurement that other threads of this
// process do not disturb.
#pragma once

#include <chrono>
#include <ctime>

namespace pt {

class Timer {
public:
    Timer() : start_(std::chrono::steady_clock::now()) {}
    double seconds() const {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    }
    void reset() { start_ = std::chrono::steady_clock::now(); }

private:
    std::chrono::steady_clock::time_point start_;
};

class CpuTimer {
public:
    CpuTimer() : start_(now()) {}
    double seconds() const { return now() - start_; }

private:
    static double now() {
        timespec t{};
        clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
        return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
    }
    double start_;
};

class ThreadCpuTimer {
public:
    ThreadCpuTimer() : start_(now()) {}
    double seconds() const { return now() - start_; }

private:
    static double now() {
        timespec t{};
        clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
        return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
    }
    double start_;
};

}  // namespace pt
