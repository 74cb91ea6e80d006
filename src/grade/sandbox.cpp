#include "grade/sandbox.h"

#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>

namespace pt {
namespace {

/// Runs `argv` with its output discarded; true when it exits with 0.
bool runs(const std::vector<std::string>& argv) {
    pid_t pid = fork();
    if (pid < 0) return false;
    if (pid == 0) {
        std::vector<char*> a;
        for (const std::string& s : argv)
            a.push_back(const_cast<char*>(s.c_str()));
        a.push_back(nullptr);
        freopen("/dev/null", "w", stdout);
        freopen("/dev/null", "w", stderr);
        execvp(a[0], a.data());
        _exit(127);
    }
    int status = 0;
    while (waitpid(pid, &status, 0) < 0) {
    }
    return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

/// bwrap's namespaces and the read-only system every sandbox needs.
std::vector<std::string> base_prefix() {
    return {"bwrap", "--unshare-pid", "--unshare-net", "--unshare-ipc",
            "--unshare-uts", "--die-with-parent", "--ro-bind", "/usr",
            "/usr", "--ro-bind-try", "/lib", "/lib", "--ro-bind-try",
            "/lib64", "/lib64", "--ro-bind-try", "/bin", "/bin",
            "--ro-bind-try", "/etc/ld.so.cache", "/etc/ld.so.cache",
            "--proc", "/proc", "--dev", "/dev", "--tmpfs", "/tmp"};
}

/// Appends `--BIND path path` for each path that exists (canonical).
void bind_all(std::vector<std::string>& p, const std::vector<std::string>& paths,
              const std::string& bind) {
    for (const std::string& r : paths) {
        std::error_code ec;
        std::string path = std::filesystem::weakly_canonical(r, ec).string();
        if (ec || path.empty() || !std::filesystem::exists(path, ec)) continue;
        p.insert(p.end(), {bind, path, path});
    }
}

}  // namespace

std::vector<std::string> build_sandbox_prefix(
    const std::vector<std::string>& readable, const std::vector<std::string>& writable,
    bool use_bwrap, const std::vector<std::pair<std::string, std::string>>& mapped) {
    static const bool bwrap_runs = [] {
        std::vector<std::string> probe = base_prefix();
        probe.insert(probe.end(), {"--", "/bin/true"});
        return runs(probe);
    }();
    if (!use_bwrap || !bwrap_runs) return {};
    std::vector<std::string> p = base_prefix();
    p.insert(p.end(), {"--ro-bind-try", "/etc/alternatives", "/etc/alternatives", "--setenv",
                       "CCACHE_DISABLE", "1"});
    bind_all(p, readable, "--ro-bind");
    // Later binds cover earlier ones: the view hides src/ even if a
    // readable folder holds it.
    for (const auto& [from, to] : mapped) {
        std::error_code ec;
        const std::string a = std::filesystem::weakly_canonical(from, ec).string();
        const std::string b = std::filesystem::weakly_canonical(to, ec).string();
        p.insert(p.end(), {"--ro-bind", a, b});
    }
    bind_all(p, writable, "--bind");
    p.push_back("--");
    return p;
}

Sandbox make_sandbox(const std::vector<std::string>& readable, bool use_bwrap) {
    Sandbox s;
    const std::string limits = "setrlimit (address space, CPU, file size, open files), own session "
                               "and process group, killed with every leftover process after each task";
    if (!use_bwrap) {
        s.description = limits + " (bubblewrap switched off: --no-sandbox)";
        return s;
    }
    std::vector<std::string> p = base_prefix();
    p.insert(p.end(), {"--chdir", "/tmp"});
    bind_all(p, readable, "--ro-bind");
    std::vector<std::string> probe = p;
    probe.insert(probe.end(), {"--", "/bin/true"});
    if (!runs(probe)) {
        s.description = limits + " (bubblewrap could not start here)";
        return s;
    }
    p.push_back("--");
    s.prefix = p;
    s.description = "bubblewrap (new PID, network, IPC and UTS namespaces; read-only system and "
                    "inputs; empty /tmp; no cache, reports or sources) and " +
                    limits;
    return s;
}

}  // namespace pt
