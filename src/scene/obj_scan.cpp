#include "scene/obj_scan.h"

#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <vector>

#include "core/error.h"

namespace pt {
namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }

/// Splits a line into whitespace-separated tokens, in place.
std::vector<char*> tokens_of(char* line) {
    std::vector<char*> tokens;
    char* p = line;
    while (*p) {
        while (*p && is_space(*p)) ++p;
        if (!*p) break;
        tokens.push_back(p);
        while (*p && !is_space(*p)) ++p;
        if (*p) *p++ = '\0';
    }
    return tokens;
}

class Scanner {
public:
    Scanner(const std::string& where) : where_(where) {}

    [[noreturn]] void fail(const std::string& message) const {
        throw InputError(where_ + ": line " + std::to_string(line_) + ": " + message);
    }

    void line(uint64_t number, char* text) {
        line_ = number;
        while (is_space(*text)) ++text;
        // Only v, vn, vt and f lines are checked; the rest goes to tinyobjloader.
        const bool face = text[0] == 'f' && is_space(text[1]);
        const bool vertex = text[0] == 'v' && (is_space(text[1]) || ((text[1] == 'n' || text[1] == 't') && is_space(text[2])));
        if (!face && !vertex) return;
        std::vector<char*> tokens = tokens_of(text);
        const std::string keyword = tokens[0];
        if (vertex) {
            for (size_t i = 1; i < tokens.size(); ++i) check_number(keyword, tokens[i]);
            if (keyword == "v") ++counts.vertices;
        } else {
            for (size_t i = 1; i < tokens.size(); ++i) check_corner(tokens[i]);
            if (tokens.size() >= 4) counts.triangles += tokens.size() - 3;
        }
    }

    ObjCounts counts;

private:
    void check_number(const std::string& keyword, const char* token) const {
        char* end = nullptr;
        double value = std::strtod(token, &end);
        if (end == token || *end != '\0' || !std::isfinite(value))
            fail("'" + std::string(token) + "' is not a finite number (in a '" + keyword + "' line)");
    }

    /// One face corner: "v", "v/t", "v//n" or "v/t/n", each a non-zero
    /// whole number that fits tinyobjloader's int.
    void check_corner(char* token) const {
        const std::string corner = token;
        int part = 0;
        for (char* field = token;; ++part) {
            char* slash = std::strchr(field, '/');
            if (slash) *slash = '\0';
            if (*field != '\0' || part == 0) check_index(field, corner, part);
            if (!slash) break;
            if (part == 2) fail("face corner '" + corner + "' has more than three parts");
            field = slash + 1;
        }
    }

    void check_index(const char* text, const std::string& corner, int part) const {
        static const char* kWhat[] = {"vertex", "texture coordinate", "normal"};
        const std::string what = kWhat[part];
        const char* digits = text + (*text == '-' || *text == '+');
        bool whole = *digits != '\0';
        for (const char* c = digits; *c; ++c) whole = whole && *c >= '0' && *c <= '9';
        if (!whole) fail("face corner '" + corner + "': '" + text + "' is not a " + what + " index");
        errno = 0;
        long long value = std::strtoll(text, nullptr, 10);
        if (errno == ERANGE || value > INT_MAX || value < -INT_MAX)
            fail("face corner '" + corner + "': " + what + " index " + text + " is out of range (OBJ indices here are at most " +
                 std::to_string(INT_MAX) + ")");
        if (value == 0) fail("face corner '" + corner + "': " + what + " index 0 (OBJ indices start at 1, or count back from -1)");
    }

    std::string where_;
    uint64_t line_ = 0;
};

}  // namespace

ObjCounts scan_obj(const std::string& path, const std::string& where) {
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), std::fclose);
    if (!file) throw InputError(where + ": cannot read " + path + ": " + std::strerror(errno));
    Scanner scanner(where);
    std::vector<char> buffer(kMaxObjLine + 2);
    // fgets fills the buffer to its last byte only for a line too long for
    // it; a marker there tells, even when the line holds NUL bytes.
    const size_t last = buffer.size() - 1;
    for (uint64_t number = 1;; ++number) {
        buffer[last] = 1;
        if (!std::fgets(buffer.data(), int(buffer.size()), file.get())) break;
        if (buffer[last] == '\0' && buffer[last - 1] != '\n')
            throw InputError(where + ": line " + std::to_string(number) + " is longer than " +
                             std::to_string(kMaxObjLine) + " bytes (not an OBJ file?)");
        scanner.line(number, buffer.data());
    }
    if (std::ferror(file.get())) throw InputError(where + ": cannot read " + path + ": " + std::strerror(errno));
    return scanner.counts;
}

}  // namespace pt
