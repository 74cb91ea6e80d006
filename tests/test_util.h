// Helpers shared by the test suites: scratch files and running the apps.
#pragma once

#include <sys/stat.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

namespace pt::test {

/// A fresh scratch directory under the build tree for one test.
inline std::string scratch_dir(const std::string& name) {
    std::string dir = std::string(PT_TEST_OUTPUT_DIR) + "/" + name;
    std::string cmd = "rm -rf '" + dir + "' && mkdir -p '" + dir + "'";
    if (std::system(cmd.c_str()) != 0) throw std::runtime_error("cannot create " + dir);
    return dir;
}

inline void write_file(const std::string& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
}

inline std::string read_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

inline bool file_exists(const std::string& path) {
    struct stat st;
    return stat(path.c_str(), &st) == 0;
}

inline std::string source_path(const std::string& relative) { return std::string(PT_SOURCE_DIR) + "/" + relative; }
inline std::string bin_path(const std::string& program) { return std::string(PT_BIN_DIR) + "/" + program; }

struct CommandResult {
    int exit_code = -1;
    std::string out;  ///< stdout
    std::string err;  ///< stderr
};

/// Runs a shell command line, capturing stdout and stderr separately.
inline CommandResult run(const std::string& command, const std::string& scratch) {
    std::string err_path = scratch + "/stderr.txt";
    CommandResult r;
    FILE* pipe = popen((command + " 2>'" + err_path + "'").c_str(), "r");
    if (!pipe) return r;
    std::array<char, 4096> buffer;
    size_t n;
    while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) r.out.append(buffer.data(), n);
    int status = pclose(pipe);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.err = read_file(err_path);
    return r;
}

}  // namespace pt::test
