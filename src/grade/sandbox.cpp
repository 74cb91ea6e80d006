#include "grade/sandbox.h"

#include <grp.h>
#include <pwd.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>

namespace pt {

bool become(int uid, int gid) {
    if (gid >= 0 && (setgroups(0, nullptr) != 0 || setgid(gid_t(gid)) != 0)) return false;
    if (uid >= 0 && setuid(uid_t(uid)) != 0) return false;
    return true;
}

namespace {

/// Runs `argv` with its output discarded (as `uid`/`gid` when not -1);
/// true when it exits with 0.
bool runs(const std::vector<std::string>& argv, int uid = -1, int gid = -1) {
    pid_t pid = fork();
    if (pid < 0) return false;
    if (pid == 0) {
        if (!become(uid, gid)) _exit(126);
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

Sandbox make_sandbox(const std::vector<std::string>& readable, bool use_bwrap, int max_processes) {
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
    const std::string bwrap = "bubblewrap (new PID, network, IPC and UTS namespaces; read-only system and "
                              "inputs; empty /tmp; no cache, reports or sources) and " +
                              limits;

    // First choice: a user namespace of its own, with the process limit set
    // inside it. RLIMIT_NPROC counts per (namespace, user), so only the
    // runner's processes count; root is exempt from it, so grade run as
    // root runs the sandbox as nobody. The probe binds the same inputs as
    // that user: an input nobody may not read fails it here, not a task.
    if (max_processes > 0) {
        int uid = -1, gid = -1;
        if (geteuid() == 0) {
            const passwd* nobody = getpwnam("nobody");
            if (nobody) uid = int(nobody->pw_uid), gid = int(nobody->pw_gid);
        }
        if (geteuid() != 0 || uid > 0) {
            std::vector<std::string> q = p;
            const std::string nproc = std::to_string(max_processes);
            q.insert(q.begin() + 1, "--unshare-user");
            q.insert(q.end(), {"--", "prlimit", "--nproc=" + nproc + ":" + nproc});
            std::vector<std::string> probe = q;
            probe.push_back("/bin/true");
            if (runs(probe, uid, gid)) {
                s.prefix = q;
                s.uid = uid, s.gid = gid;
                s.description = bwrap + "; at most " + nproc + " processes and threads (prlimit in its own " +
                                "user namespace" + (uid > 0 ? ", as the user nobody" : "") + ")";
                return s;
            }
        }
    }
    std::vector<std::string> probe = p;
    probe.insert(probe.end(), {"--", "/bin/true"});
    if (!runs(probe)) {
        s.description = limits + " (bubblewrap could not start here)";
        return s;
    }
    p.push_back("--");
    s.prefix = p;
    s.description = bwrap + "; no process limit (no user namespace for it here)";
    return s;
}

}  // namespace pt
