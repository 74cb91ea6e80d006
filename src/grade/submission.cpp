#include "grade/submission.h"

#include <algorithm>
#include <filesystem>
#include <map>

#include "core/error.h"

namespace fs = std::filesystem;

namespace pt {
namespace {

/// partN -> N, or 0 when `name` is not a part folder's name.
int part_number(const std::string& name) {
    if (name.size() < 5 || name.compare(0, 4, "part") != 0) return 0;
    int n = 0;
    for (size_t i = 4; i < name.size(); ++i) {
        if (name[i] < '0' || name[i] > '9' || n > 1000) return 0;
        n = n * 10 + (name[i] - '0');
    }
    return n;
}

/// A real folder or file, not a symbolic link: a submission's links could
/// point the compiler (whose messages the student reads) anywhere.
bool is_real(const fs::directory_entry& e, fs::file_type type) {
    std::error_code ec;
    return e.symlink_status(ec).type() == type;
}

/// Relative path ("part1/camera.cpp") -> absolute path, of dir/part*/*.cpp.
std::map<std::string, std::string> part_sources(const std::string& dir) {
    std::map<std::string, std::string> out;
    std::error_code ec;
    for (const fs::directory_entry& p : fs::directory_iterator(dir, ec)) {
        if (!is_real(p, fs::file_type::directory) || part_number(p.path().filename().string()) == 0)
            continue;
        for (const fs::directory_entry& f : fs::directory_iterator(p.path(), ec))
            if (is_real(f, fs::file_type::regular) && f.path().extension() == ".cpp")
                out[p.path().filename().string() + "/" + f.path().filename().string()] =
                    fs::absolute(f.path()).lexically_normal().string();
    }
    return out;
}

bool has_part_folder(const std::string& dir) {
    std::error_code ec;
    for (const fs::directory_entry& p : fs::directory_iterator(dir, ec))
        if (is_real(p, fs::file_type::directory) && part_number(p.path().filename().string()) > 0)
            return true;
    return false;
}

}  // namespace

Submission inspect_submission(const std::string& name, const std::string& dir) {
    Submission s;
    s.name = name;
    s.dir = fs::absolute(dir).lexically_normal().string();
    std::error_code ec;
    if (!has_part_folder(s.dir)) {
        std::vector<std::string> subs;
        for (const fs::directory_entry& e : fs::directory_iterator(s.dir, ec))
            if (is_real(e, fs::file_type::directory) && e.path().filename().string()[0] != '.')
                subs.push_back(e.path().string());
        if (subs.size() == 1 && has_part_folder(subs[0])) s.dir = subs[0];
    }
    for (const auto& [relative, path] : part_sources(s.dir)) {
        (void)path;
        int part = part_number(relative.substr(0, relative.find('/')));
        if (std::find(s.parts.begin(), s.parts.end(), part) == s.parts.end()) s.parts.push_back(part);
    }
    std::sort(s.parts.begin(), s.parts.end());
    return s;
}

std::vector<Submission> list_submissions(const std::string& class_dir) {
    std::error_code ec;
    if (!fs::is_directory(class_dir, ec))
        throw InputError("--class: " + class_dir + " is not a folder");
    std::vector<std::string> names;
    for (const fs::directory_entry& e : fs::directory_iterator(class_dir, ec)) {
        const std::string name = e.path().filename().string();
        if (e.is_directory(ec) && !name.empty() && name[0] != '.') names.push_back(name);
    }
    if (names.empty())
        throw InputError("--class: " + class_dir + " holds no submission (one subfolder per student)");
    std::sort(names.begin(), names.end());
    std::vector<Submission> out;
    for (const std::string& n : names)
        out.push_back(inspect_submission(n, (fs::path(class_dir) / n).string()));
    return out;
}

std::string first_symlink(const Submission& s) {
    std::error_code ec;
    size_t seen = 0;
    for (fs::recursive_directory_iterator it(s.dir, ec), end; !ec && it != end; it.increment(ec)) {
        if (++seen > 100000) return "(more than 100,000 files)";
        if (it->is_symlink(ec)) {
            const fs::path rel = it->path().lexically_relative(s.dir);
            const std::string said =
                rel.string() + " (a link to " + fs::read_symlink(it->path(), ec).string() + ")";
            std::string out;  // the student's names: printable ASCII, one short line
            for (char c : said)
                if (c >= 32 && c < 127 && out.size() < 300) out += c;
            return out;
        }
    }
    return "";
}

std::vector<std::string> submission_sources(const Submission& s, const std::string& handout_dir) {
    std::map<std::string, std::string> files = part_sources(handout_dir);
    for (const auto& [relative, path] : part_sources(s.dir))
        files[relative] = path;
    std::vector<std::string> out;
    for (const auto& [relative, path] : files)
        out.push_back(path);
    std::sort(out.begin(), out.end());
    return out;
}

}  // namespace pt
