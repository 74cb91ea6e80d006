// grade_runner_KEY: the untrusted half of `grade` (docs/grading.md). It
// holds the student's code and the reference of every function except
// those it withholds (grade/runners.h), runs one task's check with
// recording student functions, and writes the raw log of their outputs to
// file descriptor 3. It computes no verdict: `grade` replays the log and
// grades. Not meant to be run by hand.
//   grade_runner_KEY --manifest FILE --task ID --seed N --threads N --assets DIR
#include <unistd.h>

#include <cstdio>
#include <string>

#include "grade/grader.h"
#include "grade/manifest.h"
#include "grade/runners.h"
#include "grade/stage_mix.h"
#include "grade/student_calls.h"

namespace {

void write_all(int fd, const std::string& text) {
    size_t done = 0;
    while (done < text.size()) {
        ssize_t n = write(fd, text.data() + done, text.size() - done);
        if (n <= 0) return;
        done += size_t(n);
    }
}

}  // namespace

// scripts/coverage.sh: _exit skips the atexit handler that writes the gcov
// counters of the student's objects (-DPT_STUDENT_COVERAGE=ON), so they are
// written here; weak, so null in every other build.
extern "C" void __gcov_dump(void) __attribute__((weak));

int main(int argc, char** argv) {
    using namespace pt;
    if (argc == 2 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h")) {
        std::printf("usage: grade_runner_%s --manifest FILE --task ID --seed N --threads N --assets DIR\n"
                    "The untrusted half of grade (docs/grading.md): runs one task's student code and\n"
                    "writes the raw log of its outputs to file descriptor 3. grade starts it.\n",
                    PT_RUNNER_KEY);
        return 0;
    }
    std::string manifest, task, assets;
    uint64_t seed = 1;
    int threads = 1;
    for (int i = 1; i + 1 < argc; i += 2) {
        std::string a = argv[i], v = argv[i + 1];
        if (a == "--manifest") manifest = v;
        if (a == "--task") task = v;
        if (a == "--assets") assets = v;
        if (a == "--seed") seed = std::stoull(v);
        if (a == "--threads") threads = std::stoi(v);
    }
    std::string log;
    try {
        TaskSpec spec;
        for (const TaskSpec& t : read_manifest(manifest).tasks)
            if (t.id == task) spec = t;
        const std::vector<std::string> withheld = withheld_slots(PT_RUNNER_KEY);
        Stages recording = start_recording(make_stages(StageSet::all()));
        Stages reference = stand_in_reference(make_stages(StageSet::none()), withheld);
        for (const std::string& w : withheld)
            if (w == "direct.one_bounce_radiance")
                reference.direct.one_bounce_radiance = one_bounce_through_table;
        GradeEnvironment env{recording, reference, seed, threads, assets, "", ""};
        grade_task(spec, env);
    } catch (...) {
        // `grade` meets the same problem when it replays the log.
    }
    log = finish_recording();
    write_all(3, log);
    std::fflush(stdout);
    if (__gcov_dump) __gcov_dump();
    _exit(0);
}
