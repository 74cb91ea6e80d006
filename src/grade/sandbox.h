// The sandbox of a runner: bubblewrap (Debian package bubblewrap) with a
// new PID, network, IPC and UTS namespace, the system and the grading
// inputs bound read-only, an empty writable /tmp, and --die-with-parent.
// It sees neither the reference cache nor the reports nor the student's
// sources, and (with a user namespace) has at most N processes. Where bwrap cannot run (no user namespaces), the runner runs
// with setrlimit and its own process group only (isolation.h), and the
// report says so.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace pt {

struct Sandbox {
    std::vector<std::string> prefix;  ///< the bwrap command to put before the runner's; empty: none
    std::string description;          ///< for the report: which isolation is used
    /// Run the prefix as this user and group (grade run as root: `nobody`,
    /// so that the process limit holds; the kernel exempts user id 0 from
    /// RLIMIT_NPROC in every namespace); -1: as grade's own user.
    int uid = -1, gid = -1;
};

/// A bwrap sandbox that can read `readable` (folders or files), if bwrap
/// runs here (tried once, with /bin/true); otherwise an empty prefix and a
/// description saying why. `use_bwrap` false: the fallback on purpose.
/// Where it can, the sandbox has its own user namespace and the runner at
/// most `max_processes` processes and threads (`prlimit --nproc` inside
/// the sandbox, counted per namespace: a fork bomb stops there, and other
/// processes of the same user do not count); the description says whether.
Sandbox make_sandbox(const std::vector<std::string>& readable, bool use_bwrap,
                     int max_processes = 256);

/// Sets this process's groups, group and user (each only when not -1);
/// false when the system refused.
bool become(int uid, int gid);

/// The sandbox of a compile of student sources (grade --class): the same
/// namespaces, the system (and /etc/alternatives, where the compiler's
/// name points) and `readable` bound read-only, `writable` (the build
/// folder) read-write, an empty /tmp and no ccache (its cache is outside).
/// A source that includes a file the grader can read (/etc/..., another
/// student's folder, the reports) then fails to compile. `mapped` binds
/// folders read-only at another path (from, to), after `readable`: the
/// headers-only view of the project's src/ at src/'s path (header_view.h).
/// An empty prefix where bwrap cannot run (or `use_bwrap` is false).
std::vector<std::string> build_sandbox_prefix(
    const std::vector<std::string>& readable, const std::vector<std::string>& writable,
    bool use_bwrap, const std::vector<std::pair<std::string, std::string>>& mapped = {});

}  // namespace pt
