#include "grade/compile_deps.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "grade/header_view.h"

namespace fs = std::filesystem;

namespace pt {

CompileDeps parse_make_deps(const std::string& text) {
    CompileDeps d;
    std::string token;
    bool after_target = false;
    auto flush = [&] {
        if (token.empty()) return;
        if (!after_target && token.back() == ':') {
            after_target = true;
        } else if (after_target) {
            if (d.source.empty()) d.source = token;
            d.files.push_back(token);
        }
        token.clear();
    };
    for (size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (c == '\\' && i + 1 < text.size() && (text[i + 1] == ' ' || text[i + 1] == '#')) {
            token += text[++i];  // an escaped space or '#' belongs to the path
        } else if (c == '\\' && i + 1 < text.size() && text[i + 1] == '\n') {
            ++i, flush();  // a continued line
        } else if (c == '$' && i + 1 < text.size() && text[i + 1] == '$') {
            token += text[++i];
        } else if (c == ' ' || c == '\t' || c == '\n' || c == '\r') {
            flush();
        } else {
            token += c;
        }
    }
    flush();
    return d;
}

std::vector<CompileDeps> parse_ninja_deps(const std::string& text) {
    std::vector<CompileDeps> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        if (line.empty()) continue;
        if (line[0] != ' ' && line[0] != '\t') {
            out.emplace_back();  // "obj.o: #deps N, deps mtime M (VALID)"
            continue;
        }
        if (out.empty()) continue;
        const std::string path = line.substr(line.find_first_not_of(" \t"));
        if (out.back().source.empty()) out.back().source = path;
        out.back().files.push_back(path);
    }
    return out;
}

std::vector<CompileDeps> read_make_deps(const std::string& build_dir) {
    std::vector<CompileDeps> out;
    std::error_code ec;
    for (fs::recursive_directory_iterator it(fs::path(build_dir) / "CMakeFiles", ec), end;
         !ec && it != end; it.increment(ec)) {
        if (it->path().extension() != ".d" || !it->is_regular_file(ec)) continue;
        std::ifstream in(it->path(), std::ios::binary);
        std::stringstream text;
        text << in.rdbuf();
        CompileDeps d = parse_make_deps(text.str());
        if (!d.source.empty()) out.push_back(std::move(d));
    }
    return out;
}

std::string project_source_read(const std::vector<std::string>& files, const std::string& src,
                                const std::string& cwd) {
    std::error_code ec;
    const fs::path root = fs::weakly_canonical(src, ec);
    for (const std::string& f : files) {
        const fs::path p = fs::path(f).is_absolute() ? fs::path(f) : fs::path(cwd) / f;
        const fs::path real = fs::weakly_canonical(p, ec);  // symbolic links resolved
        if (ec) continue;
        const fs::path rel = real.lexically_relative(root);
        if (rel.empty() || *rel.begin() == "..") continue;  // not under src/
        if (!is_header(real)) return real.string();
    }
    return "";
}

}  // namespace pt
