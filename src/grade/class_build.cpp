#include "grade/class_build.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/timer.h"
#include "grade/child_process.h"
#include "grade/compile_deps.h"
#include "grade/header_view.h"
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

/// A name the student chose, as one line of printable ASCII for the reports.
std::string printable(const std::string& text) {
    std::string out;
    for (char c : text)
        if (c >= 32 && c < 127 && out.size() < 200) out += c;
    return out;
}

/// The project-relative spelling of `path` under `src` ("src/stages/x.cpp"), for messages.
std::string shown_in_project(const std::string& path, const std::string& src) {
    std::error_code ec;
    const fs::path real = fs::weakly_canonical(path, ec);
    const fs::path rel = real.lexically_relative(fs::weakly_canonical(src, ec));
    return rel.empty() || *rel.begin() == ".." ? path : "src/" + rel.string();
}

/// Whether `error` is GCC's "fatal error: NAME: No such file or directory"
/// for a NAME that is not a header: in the sandbox, most likely a .cpp of
/// the project's src/, which the headers-only view does not hold.
bool missing_non_header(const std::string& error) {
    const std::string head = "fatal error: ", tail = ": No such file or directory";
    const size_t a = error.find(head), b = error.rfind(tail);
    if (a == std::string::npos || b == std::string::npos || b < a + head.size()) return false;
    return !is_header(error.substr(a + head.size(), b - a - head.size()));
}

/// Whether the student's sources read only headers of the project's src/
/// (compile_deps.h): "" when they did, else the refusal. `complete` is set
/// false when a student source has no dependency list to check.
std::string check_includes(const ClassBuildTools& tools, const std::string& work_dir,
                           const Submission& s, const std::vector<std::string>& sources,
                           const std::string& log_path, bool& complete) {
    complete = true;
    if (tools.project_src.empty()) return "";
    std::vector<CompileDeps> deps;
    if (tools.generator.find("Ninja") != std::string::npos) {
        // Ninja keeps the lists in its log and deletes the .d files.
        const std::string out = work_dir + "/ninja_deps.txt";
        std::error_code ec;
        fs::remove(out, ec);
        run_child({tools.cmake, "--build", work_dir, "--", "-t", "deps"}, out, tools.timeout);
        deps = parse_ninja_deps(read_text(out, 64 << 20));
    } else {
        deps = read_make_deps(work_dir);
    }
    std::error_code ec;
    for (const std::string& source : sources) {
        const fs::path mine = fs::weakly_canonical(source, ec);
        if (fs::path(source).lexically_relative(s.dir).string().rfind("..", 0) == 0) continue;  // a stub
        const CompileDeps* found = nullptr;
        for (const CompileDeps& d : deps) {
            const fs::path p = fs::path(d.source).is_absolute() ? fs::path(d.source)
                                                                : fs::path(work_dir) / d.source;
            if (fs::weakly_canonical(p, ec) == mine) found = &d;
        }
        const std::string name = fs::path(source).lexically_relative(s.dir).string();
        if (!found) {
            complete = false;
            std::ofstream(log_path, std::ios::app) << "grade: no dependency list for " << source << "\n";
            continue;
        }
        const std::string bad = project_source_read(found->files, tools.project_src, work_dir);
        if (!bad.empty())
            return printable(name) + " includes " + shown_in_project(bad, tools.project_src) +
                   ", a source file of the project: only its headers may be included";
    }
    return "";
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
    auto remove_runners = [&] {
        for (const fs::directory_entry& e : fs::directory_iterator(bin, ec))
            if (e.path().filename().string().rfind("grade_runner_", 0) == 0) fs::remove(e.path(), ec);
    };
    remove_runners();

    const std::string link = first_symlink(s);
    if (!link.empty()) {
        r.first_error = "the submission holds a symbolic link, " + link +
                        ": only regular files are compiled";
        r.seconds = timer.seconds();
        return r;
    }
    const std::vector<std::string> sources = submission_sources(s, tools.handout_dir);
    std::vector<std::string> own;  // the submission's files, not the handout's stubs
    for (const std::string& f : sources)
        if (fs::path(f).lexically_relative(s.dir).string().rfind("..", 0) != 0) own.push_back(f);
    std::vector<std::string> configure = {tools.cmake,
                                          "-S", tools.project_dir,
                                          "-B", work_dir,
                                          "-C", tools.initial_cache,
                                          "-DPT_STUDENT_SOURCES=" + join(sources, ';'),
                                          "-DPT_SUBMITTED_SOURCES=" + join(own, ';'),
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
    // It sees the project's headers only: the view, bound at src/'s path.
    std::vector<std::pair<std::string, std::string>> mapped;
    if (!tools.header_view.empty()) mapped.push_back({tools.header_view, tools.project_src});
    std::vector<std::string> build = build_sandbox_prefix(
        [&] {
            std::vector<std::string> r = tools.readable;
            r.insert(r.end(), {tools.project_dir, tools.handout_dir, s.dir});
            return r;
        }(),
        {work_dir}, tools.sandbox, mapped);
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
        if (!tools.header_view.empty() && r.sandboxed && missing_non_header(e))
            e += " (the compile sees only the project's headers: a .cpp of src/ cannot be included)";
        r.first_error = e.empty() ? why(b, "the build", tools.timeout) : e;
        r.internal = e.empty() && !b.timed_out;  // a compile that never ends is the student's
        r.seconds = timer.seconds();
        return r;
    }
    // Inside the sandbox no .cpp of src/ was there to read; outside it (or
    // as a second look inside) the compiler's dependency lists say what was.
    bool complete = true;
    const std::string refused = check_includes(tools, work_dir, s, sources, log_path, complete);
    if (!refused.empty() || (!complete && !r.sandboxed)) {
        r.first_error = !refused.empty() ? refused
                                         : "the compiler's dependency lists of the submission's files "
                                           "were not found: what they include cannot be checked";
        r.internal = refused.empty();
        remove_runners();  // built, but not to be graded
        r.seconds = timer.seconds();
        return r;
    }
    r.ok = true;
    r.runner_dir = bin.string();
    r.seconds = timer.seconds();
    return r;
}

}  // namespace pt
