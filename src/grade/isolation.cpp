#include "grade/isolation.h"

#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "core/error.h"
#include "core/timer.h"
#include "grade/grader.h"
#include "grade/task_json.h"

namespace pt {
namespace {

/// Writes all of `text` to `fd` (the pipe may take it in pieces).
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

}  // namespace

TaskResult grade_task_isolated(const TaskSpec& spec, const GradeEnvironment& env,
                               double timeout_seconds) {
    int fds[2];
    if (pipe(fds) != 0) throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
    std::fflush(stdout);
    std::fflush(stderr);
    Timer timer;
    pid_t pid = fork();
    if (pid < 0) throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
    if (pid == 0) {
        // The child: grade, send, and leave without running the parent's atexit handlers.
        close(fds[0]);
        rlimit no_core{0, 0};
        setrlimit(RLIMIT_CORE, &no_core);  // a crashing submission leaves no core files behind
        nlohmann::json message;
        try {
            message["result"] = task_to_json(grade_task(spec, env));
        } catch (const InputError& e) {
            message["input_error"] = e.what();
        } catch (const std::exception& e) {
            message["error"] = e.what();
        }
        write_all(fds[1], message.dump());
        close(fds[1]);
        _exit(0);
    }

    close(fds[1]);
    std::string received;
    bool timed_out = false;
    char buffer[65536];
    for (;;) {
        double left = timeout_seconds - timer.seconds();
        if (left <= 0) {
            timed_out = true;
            break;
        }
        pollfd p{fds[0], POLLIN, 0};
        int ready = poll(&p, 1, int(std::min(left, 3600.0) * 1000) + 1);
        if (ready < 0 && errno == EINTR) continue;
        if (ready <= 0) continue;  // the deadline is checked at the top
        ssize_t n = read(fds[0], buffer, sizeof buffer);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;  // end of file: the child has finished or died
        received.append(buffer, size_t(n));
    }
    close(fds[0]);
    if (timed_out) kill(pid, SIGKILL);
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    double seconds = timer.seconds();

    if (timed_out) {
        char msg[128];
        std::snprintf(msg, sizeof msg, "timed out after %.0f s (an endless loop?) and was stopped",
                      timeout_seconds);
        return failed(spec, msg, seconds);
    }
    if (WIFSIGNALED(status)) {
        int sig = WTERMSIG(status);
        return failed(spec,
                      std::string("the student code crashed: ") + strsignal(sig) + " (signal " +
                          std::to_string(sig) + ")",
                      seconds);
    }
    nlohmann::json message;
    try {
        message = nlohmann::json::parse(received);
    } catch (const nlohmann::json::exception&) {
        return failed(spec,
                      "the student code ended the grading process (exit status " +
                          std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ")",
                      seconds);
    }
    if (message.contains("input_error"))
        throw InputError(message["input_error"].get<std::string>());
    if (message.contains("error")) throw std::runtime_error(message["error"].get<std::string>());
    return task_from_json(message.at("result"));
}

}  // namespace pt
