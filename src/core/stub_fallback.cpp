#include "core/stub_fallback.h"

#include <atomic>
#include <iostream>
#include <mutex>
#include <set>
#include <string>

#include "core/error.h"

namespace pt {
namespace {

std::atomic<int> strict_depth{0};

}  // namespace

StubFallbacksAreNotImplemented::StubFallbacksAreNotImplemented() {
    ++strict_depth;
}
StubFallbacksAreNotImplemented::~StubFallbacksAreNotImplemented() {
    --strict_depth;
}

void stub_fallback(int part, const char* task, const char* function, const char* fallback) {
    if (strict_depth.load(std::memory_order_relaxed) > 0)
        throw NotImplemented(part, task, function);
    // Called once per ray by the traversal stubs: each thread remembers what
    // it has already reported, so only the first call per thread takes the lock.
    thread_local std::set<const char*> reported_here;
    if (reported_here.count(function)) return;
    reported_here.insert(function);
    static std::mutex mutex;
    static std::set<std::string> reported;
    std::lock_guard<std::mutex> lock(mutex);
    if (reported.insert(function).second)
        std::cerr << "Part " << part << ": " << function << " is not implemented yet; using "
                  << fallback << "\n";
}

}  // namespace pt
