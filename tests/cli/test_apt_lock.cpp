// scripts/setup.sh waits for apt's lock instead of failing with apt's raw
// message (issue 22): scripts/wait_for_apt_lock.sh, on a lock file that a
// background flock holds for a while (apt takes fcntl locks, flock(1)
// flock locks; /proc/locks lists both, which is what the script reads).
#include <doctest/doctest.h>

#include <string>

#include "test_util.h"

using namespace pt::test;

namespace {

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

/// Holds `lock` for `seconds` in the background, then runs the wait script.
CommandResult wait_while_held(const std::string& dir, const std::string& lock, const char* seconds, int timeout) {
    // Until the background flock has the lock, flock -n gets it (exit 0).
    return run("touch '" + lock + "' && (flock '" + lock + "' sleep " + seconds + " >/dev/null 2>&1 &) && while flock -n '" +
                   lock + "' true; do sleep 0.02; done && '" + source_path("scripts/wait_for_apt_lock.sh") + "' " +
                   std::to_string(timeout) + " '" + lock + "'",
               dir);
}

}  // namespace

TEST_CASE("the wait for apt's lock says who holds it, waits, and gives up after its timeout") {
    std::string dir = scratch_dir("apt_lock");
    std::string lock = dir + "/lock-frontend";
    CommandResult r = wait_while_held(dir, lock, "1.5", 20);
    CHECK(r.exit_code == 0);
    CHECK(contains(r.err, "setup: waiting for apt's lock: " + lock + " is held by process "));
    CHECK(contains(r.err, " (flock) (another package manager, often unattended-upgrades on a fresh machine; "
                          "waiting up to 20 s)"));

    r = wait_while_held(dir, lock + "2", "5", 1);  // held well beyond the timeout
    CHECK(r.exit_code == 1);
    CHECK(contains(r.err, lock + "2 is held by process "));
    CHECK(contains(r.err, "still after 1 s; try again when it has finished"));

    // A free lock: no wait, no word.
    r = run("touch '" + lock + "3' && '" + source_path("scripts/wait_for_apt_lock.sh") + "' 5 '" + lock + "3'", dir);
    CHECK(r.exit_code == 0);
    CHECK(r.err.empty());
    // setup.sh runs it, and passes apt the same timeout.
    std::string setup = read_file(source_path("scripts/setup.sh"));
    CHECK(contains(setup, "wait_for_apt_lock.sh\" \"$lock_wait\""));
    CHECK(contains(setup, "apt-get -o DPkg::Lock::Timeout=\"$lock_wait\" install"));
}
