#include "grade/child_process.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <thread>

#include "core/timer.h"

namespace pt {

namespace {

/// setrlimit is async-signal-safe: callable between fork and exec.
void limit(int resource, double value) {
    if (!(value > 0)) return;
    rlimit r{rlim_t(value), rlim_t(value)};
    setrlimit(resource, &r);
}

}  // namespace

ChildOutcome run_child(const std::vector<std::string>& argv, const std::string& log_path,
                       double timeout, const ChildLimits& limits) {
    ChildOutcome out;
    if (argv.empty()) return out;
    // Everything the child needs is prepared before fork: between fork and
    // exec a multithreaded process may only make async-signal-safe calls.
    std::vector<char*> args;
    for (const std::string& a : argv)
        args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    const int null_in = open("/dev/null", O_RDONLY | O_CLOEXEC);
    const int log = log_path.empty()
                        ? open("/dev/null", O_WRONLY | O_CLOEXEC)
                        : open(log_path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (null_in < 0 || log < 0) {
        if (null_in >= 0) close(null_in);
        if (log >= 0) close(log);
        return out;
    }
    const pid_t parent = getpid();
    const pid_t pid = fork();
    if (pid == 0) {
        setpgid(0, 0);
        prctl(PR_SET_PDEATHSIG, SIGKILL);  // a killed `grade --class` leaves no build behind
        if (getppid() != parent) _exit(127);
        limit(RLIMIT_AS, limits.memory_bytes);
        limit(RLIMIT_FSIZE, limits.file_bytes);
        limit(RLIMIT_CPU, limits.cpu_seconds);
        dup2(null_in, 0);
        dup2(log, 1);
        dup2(log, 2);
        execvp(args[0], args.data());  // a path, or a name on PATH (bwrap)
        _exit(127);
    }
    close(null_in);
    close(log);
    if (pid < 0) return out;
    setpgid(pid, pid);  // also from this side: no race with the kill below
    out.started = true;
    Timer timer;
    int status = 0;
    for (;;) {
        pid_t w = waitpid(pid, &status, WNOHANG);
        if (w == pid) break;
        if (w < 0 && errno != EINTR) return out;
        if (timeout > 0 && timer.seconds() > timeout && !out.timed_out) {
            out.timed_out = true;
            kill(-pid, SIGKILL);
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    if (!out.timed_out) kill(-pid, SIGKILL);  // whatever it left in its group
    if (WIFEXITED(status)) out.exit_code = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) out.signal = WTERMSIG(status);
    if (WIFEXITED(status) && out.exit_code == 127 && timer.seconds() < 0.5) {
        // execv failed (or the program itself said 127 at once): treat as not started
        // only when the program does not exist.
        if (access(argv[0].c_str(), X_OK) != 0) out.started = false;
    }
    return out;
}

}  // namespace pt
