#include "grade/class_build.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/timer.h"
#include "grade/child_process.h"
#include "grade/sandbox.h"

namespace fs = std::filesystem;

namespace pt {
namespace {

std::string read_text(const std::string& path, size_t max_bytes) {
    std::ifstream in(path, std::ios::binary);
    std::string text(max_bytes, '\0');
    in.read(&text[0], std::streamsize(max_bytes));
    text.resize(size_t(in.gcount()));
    return text;
}

std::string join(const std::vector<std::string>& items, char sep) {
    std::string out;
    for (const std::string& s : items)
        out += (out.empty() ? "" : std::string(1, sep)) + s;
    return out;
}

std::string why(const ChildOutcome& c, const std::string& what, double timeout) {
    if (!c.started) return what + " could not be started";
    if (c.timed_out) return what + " took longer than " + std::to_string(long(timeout)) + " s";
    if (c.signal) return what + " was killed by signal " + std::to_string(c.signal);
    return what + " failed (exit " + std::to_string(c.exit_code) + ")";
}

}  // namespace

std::string first_build_error(const std::string& log, const std::vector<std::string>& strip) {
    std::istringstream in(log);
    std::string line, found;
    while (std::getline(in, line)) {
        if (line.find("error:") != std::string::npos ||
            line.find("out of memory") != std::string::npos ||
            line.find("undefined reference") != std::string::npos ||
            line.find("multiple definition") != std::string::npos ||
            line.rfind("CMake Error", 0) == 0) {
            found = line;
            break;
        }
    }
    for (const std::string& prefix : strip) {
        if (prefix.empty()) continue;
        for (size_t at; (at = found.find(prefix)) != std::string::npos;)
            found.erase(at, prefix.size());
    }
    // Printable ASCII only, and one line of reasonable length.
    std::string out;
    for (char c : found)
        if (c >= 32 && c < 127) out += c;
    if (out.size() > 300) out = out.substr(0, 297) + "...";
    return out;
}

ClassBuildResult build_submission(const ClassBuildTools& tools, const std::string& work_dir,
                                  const Submission& s, const std::vector<std::string>& keys,
                                  const std::string& log_path) {
    Timer timer;
    ClassBuildResult r;
    std::error_code ec;
    fs::create_directories(work_dir, ec);
    fs::remove(log_path, ec);
    // No runner of the previous submission of this folder may be graded as this one's.
    const fs::path bin = fs::path(work_dir) / "bin";
    for (const fs::directory_entry& e : fs::directory_iterator(bin, ec))
        if (e.path().filename().string().rfind("grade_runner_", 0) == 0) fs::remove(e.path(), ec);

    const std::vector<std::string> sources = submission_sources(s, tools.handout_dir);
    std::vector<std::string> configure = {tools.cmake,
                                          "-S", tools.project_dir,
                                          "-B", work_dir,
                                          "-C", tools.initial_cache,
                                          "-DPT_STUDENT_SOURCES=" + join(sources, ';'),
                                          "-DPT_KEYS=" + join(keys, ';')};
    if (!fs::exists(fs::path(work_dir) / "CMakeCache.txt", ec))
        configure.insert(configure.begin() + 1, {"-G", tools.generator});
    ChildOutcome c = run_child(configure, log_path, tools.timeout);
    // The compiler names a file as the generator spelled it: absolute, or
    // relative to the build folder when the submissions lie below it.
    std::vector<std::string> strip = {s.dir + "/", tools.handout_dir + "/", work_dir + "/"};
    for (const std::string& d : {s.dir, tools.handout_dir}) {
        const std::string rel = fs::path(d).lexically_relative(fs::absolute(work_dir)).string();
        if (!rel.empty() && rel != ".") strip.insert(strip.begin(), rel + "/");
    }
    if (c.exit_code != 0) {
        std::string e = first_build_error(read_text(log_path, 1 << 20), strip);
        r.first_error = e.empty() ? why(c, "the configure step", tools.timeout) : e;
        r.internal = e.empty() || e.rfind("CMake Error", 0) == 0;
        r.seconds = timer.seconds();
        return r;
    }
    // The compile reads the student's sources: sandboxed and limited. The
    // configure step above reads only their names.
    std::vector<std::string> build = build_sandbox_prefix(
        [&] {
            std::vector<std::string> r = tools.readable;
            r.insert(r.end(), {tools.project_dir, tools.handout_dir, s.dir});
            return r;
        }(),
        {work_dir}, tools.sandbox);
    r.sandboxed = !build.empty();
    for (const std::string& a : {tools.cmake, std::string("--build"), work_dir, std::string("--parallel"),
                                 std::to_string(std::max(1, tools.jobs))})
        build.push_back(a);
    ChildOutcome b = run_child(build, log_path, tools.timeout, tools.limits);
    if (b.exit_code != 0) {
        std::string e = first_build_error(read_text(log_path, 8 << 20), strip);
        if (e.find("out of memory") != std::string::npos)
            e += " (each compiler process may use " +
                 std::to_string(long(tools.limits.memory_bytes / 1e9)) + " GB)";
        if (e.find("Killed signal") != std::string::npos ||
            e.find("CPU time limit") != std::string::npos)
            e += " (each compiler process may use " +
                 std::to_string(long(tools.limits.cpu_seconds)) + " s of CPU time)";
        r.first_error = e.empty() ? why(b, "the build", tools.timeout) : e;
        r.internal = e.empty() && !b.timed_out;  // a compile that never ends is the student's
        r.seconds = timer.seconds();
        return r;
    }
    r.ok = true;
    r.runner_dir = bin.string();
    r.seconds = timer.seconds();
    return r;
}

}  // namespace pt
