#include "grade/isolation.h"

#include <dirent.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>

#include "core/error.h"
#include "core/timer.h"
#include "grade/grader.h"
#include "grade/sandbox.h"
#include "grade/student_calls.h"

namespace pt {
namespace {

void write_all(int fd, const std::string& text) {
    size_t done = 0;
    while (done < text.size()) {
        ssize_t n = write(fd, text.data() + done, text.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return;
        done += size_t(n);
    }
}

TaskResult failed(const TaskSpec& spec, const std::string& message, double seconds) {
    TaskResult r;
    r.part = spec.part;
    r.id = spec.id;
    r.name = spec.name;
    r.check = spec.check;
    r.type = spec.type;
    r.status = TaskStatus::fail;
    r.max_points = spec.points;
    r.value = NAN;
    r.message = message;
    r.seconds = seconds;
    return r;
}

void limit(int resource, double value) {
    if (!(value > 0)) return;
    rlim_t v = value >= 1.8e19 ? RLIM_INFINITY : rlim_t(value);
    rlimit r{v, v};
    setrlimit(resource, &r);
}

/// The child's side before it runs anything of the student's.
void enter_child(const Isolation& iso) {
    setsid();  // its own session and process group: killed as a whole
    // Never run the sandbox as root when it was set up for another user.
    if (!become(iso.uid, iso.gid)) _exit(126);
    prctl(PR_SET_PDEATHSIG, SIGKILL);  // after the user changes, which clears it
    limit(RLIMIT_CORE, 0);  // a crash leaves no core file
    limit(RLIMIT_AS, iso.memory_bytes);
    limit(RLIMIT_FSIZE, iso.file_bytes);
    limit(RLIMIT_NOFILE, iso.open_files);
    limit(RLIMIT_CPU, std::ceil(iso.timeout) * 4 + 10);  // all threads' CPU time; the wall clock is the parent's
    signal(SIGPIPE, SIG_DFL);
}

/// This process's session id, and its children's (pid, session) from /proc.
std::vector<pid_t> foreign_children() {
    std::vector<pid_t> out;
    const pid_t self = getpid(), session = getsid(0);
    DIR* dir = opendir("/proc");
    if (!dir) return out;
    while (dirent* e = readdir(dir)) {
        char* end = nullptr;
        long pid = std::strtol(e->d_name, &end, 10);
        if (*end != '\0' || pid <= 0) continue;
        std::ifstream stat("/proc/" + std::string(e->d_name) + "/stat");
        std::string line;
        if (!std::getline(stat, line)) continue;
        size_t close = line.rfind(')');  // the name may hold spaces and parentheses
        if (close == std::string::npos) continue;
        char state = 0;
        long ppid = 0, pgrp = 0, sid = 0;
        if (std::sscanf(line.c_str() + close + 1, " %c %ld %ld %ld", &state, &ppid, &pgrp, &sid) != 4)
            continue;
        if (ppid == self && sid != session) out.push_back(pid_t(pid));
    }
    closedir(dir);
    return out;
}

/// User + system seconds of a reaped process and of the children it reaped.
double cpu_seconds(const rusage& use) {
    return double(use.ru_utime.tv_sec) + 1e-6 * double(use.ru_utime.tv_usec) +
           double(use.ru_stime.tv_sec) + 1e-6 * double(use.ru_stime.tv_usec);
}

std::string signal_name(int sig) {
    return std::string(strsignal(sig)) + " (signal " + std::to_string(sig) + ")";
}

}  // namespace

double kill_leftover_children() {
    double cpu = 0;
    for (int round = 0; round < 50; ++round) {
        std::vector<pid_t> left = foreign_children();
        if (left.empty()) break;
        for (pid_t p : left) {
            kill(-p, SIGKILL);  // its group, if it leads one
            kill(p, SIGKILL);
        }
        for (pid_t p : left) {
            rusage use{};
            while (wait4(p, nullptr, 0, &use) < 0 && errno == EINTR) {
            }
            cpu += cpu_seconds(use);
        }
    }
    return cpu;
}

TaskResult grade_task_isolated(const TaskSpec& spec, const GradeEnvironment& env,
                               double timeout_seconds) {
    Isolation iso;
    iso.timeout = timeout_seconds;
    return grade_task_isolated(spec, env, iso);
}

TaskResult grade_task_isolated(const TaskSpec& spec, const GradeEnvironment& env,
                               const Isolation& iso) {
    // Orphans of the task (a setsid grandchild) become our children, so
    // that kill_leftover_children finds them.
    prctl(PR_SET_CHILD_SUBREAPER, 1);
    std::vector<std::string> command;
    if (iso.runner) {
        command = iso.sandbox_prefix;
        for (const std::string& a : iso.runner(spec))
            command.push_back(a);
    }
    int fds[2];
    if (pipe2(fds, O_CLOEXEC) != 0)
        throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
    std::fflush(stdout);
    std::fflush(stderr);
    Timer timer;
    pid_t pid = fork();
    if (pid < 0) throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
    if (pid == 0) {
        close(fds[0]);
        enter_child(iso);
        if (!command.empty()) {
            // The runner reads its task from the arguments and writes its log to fd 3.
            if (dup2(fds[1], 3) < 0) _exit(127);
            std::vector<char*> argv;
            for (std::string& a : command)
                argv.push_back(a.data());
            argv.push_back(nullptr);
            execvp(argv[0], argv.data());
            _exit(127);
        }
        std::string log;
        try {
            Stages recording = start_recording(env.student);
            GradeEnvironment child{recording, env.reference, env.seed, env.threads,
                                   env.assets_dir, "", ""};
            grade_task(spec, child);
        } catch (...) {
            // The parent finds the same problem when it replays.
        }
        log = finish_recording();
        write_all(fds[1], log);
        close(fds[1]);
        _exit(0);
    }

    close(fds[1]);
    // Read until the runner exits (not until end of file: a process it
    // started may hold the pipe open), the deadline, or the size limit.
    std::string received;
    bool timed_out = false, too_large = false, exited = false;
    int status = 0;
    // The runner's CPU time as the kernel counts it (with every process it
    // reaped, and those reaped here): what the performance task times.
    rusage use{};
    std::vector<char> buffer(1 << 20);
    auto drain = [&](int wait_ms) {
        pollfd p{fds[0], POLLIN, 0};
        if (poll(&p, 1, wait_ms) <= 0) return false;
        ssize_t n = read(fds[0], buffer.data(), buffer.size());
        if (n <= 0) {  // end of file: wait for the exit without spinning
            if (wait_ms > 0) usleep(useconds_t(wait_ms) * 1000);
            return false;
        }
        if (double(received.size()) + double(n) > iso.max_log_bytes) {
            too_large = true;
            return false;
        }
        received.append(buffer.data(), size_t(n));
        return true;
    };
    while (!too_large) {
        if (timer.seconds() > iso.timeout) {
            timed_out = true;
            break;
        }
        pid_t w = wait4(pid, &status, WNOHANG, &use);
        if (w == pid) {
            exited = true;
            while (drain(0)) {
            }
            break;
        }
        drain(20);
    }
    close(fds[0]);
    if (!exited) {
        kill(-pid, SIGKILL), kill(pid, SIGKILL);
        while (wait4(pid, &status, 0, &use) < 0 && errno == EINTR) {
        }
    }
    kill(-pid, SIGKILL);
    const double runner_cpu = cpu_seconds(use) + kill_leftover_children();
    double seconds = timer.seconds();

    if (timed_out) {
        char msg[128];
        std::snprintf(msg, sizeof msg, "timed out after %.0f s (an endless loop?) and was stopped",
                      iso.timeout);
        return failed(spec, msg, seconds);
    }
    if (too_large)
        return failed(spec,
                      "the runner's output exceeded " + std::to_string(long(iso.max_log_bytes / 1e6)) +
                          " MB and was stopped",
                      seconds);
    if (WIFSIGNALED(status)) {
        int sig = WTERMSIG(status);
        std::string why = sig == SIGXCPU ? " (the CPU time limit)" : "";
        return failed(spec, "the student code crashed: " + signal_name(sig) + why, seconds);
    }
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    // bwrap exits with 128 + the signal that killed the runner.
    if (!iso.sandbox_prefix.empty() && code > 128 && code < 128 + 32 && received.empty())
        return failed(spec, "the student code crashed: " + signal_name(code - 128), seconds);
    if (code == 126 && received.empty() && iso.uid >= 0)
        return failed(spec, "the runner could not be started as the sandbox's user", seconds);
    if (code == 127 && received.empty())
        return failed(spec, "the runner for this task could not be started (is it built?)", seconds);
    if (code != 0 || received.empty() || uint8_t(received.back()) != 255)
        return failed(spec,
                      "the student code ended the grading process (exit status " +
                          std::to_string(code) + ")",
                      seconds);
    TaskResult r;
    try {
        set_runner_cpu_seconds(runner_cpu);
        Stages student = start_replay(std::move(received));
        GradeEnvironment e{student, env.reference, env.seed, env.threads,
                           env.assets_dir, env.cache_dir, env.out_dir};
        r = grade_task(spec, e);
    } catch (...) {
        stop_replay();
        throw;  // InputError: the grader's own problem, found again by the grader
    }
    stop_replay();
    r.seconds = seconds;
    return r;
}

}  // namespace pt
