#include "scene/density_grid.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/error.h"
#include "core/files.h"

namespace pt {

namespace {
constexpr int kMaxPointsPerAxis = 512;
constexpr uint64_t kMaxGridFileBytes = uint64_t(1) << 30;
}  // namespace

DensityGrid::DensityGrid(int nx, int ny, int nz, const BBox& bounds, std::vector<float> values)
    : nx_(nx), ny_(ny), nz_(nz), bounds_(bounds), values_(std::move(values)) {
    for (float v : values_) max_density_ = std::max(max_density_, double(v));
}

double DensityGrid::density(const Vec3& p) const {
    if (!bounds_.contains(p)) return 0.0;
    // Continuous grid coordinates, then the cell and the position in it.
    Vec3 o = bounds_.offset(p);
    double x = o.x * (nx_ - 1), y = o.y * (ny_ - 1), z = o.z * (nz_ - 1);
    int i = std::min(int(x), nx_ - 2), j = std::min(int(y), ny_ - 2), k = std::min(int(z), nz_ - 2);
    double fx = x - i, fy = y - j, fz = z - k;
    auto lerp = [](double a, double b, double t) { return a + (b - a) * t; };
    double c00 = lerp(at(i, j, k), at(i + 1, j, k), fx), c10 = lerp(at(i, j + 1, k), at(i + 1, j + 1, k), fx);
    double c01 = lerp(at(i, j, k + 1), at(i + 1, j, k + 1), fx);
    double c11 = lerp(at(i, j + 1, k + 1), at(i + 1, j + 1, k + 1), fx);
    return lerp(lerp(c00, c10, fy), lerp(c01, c11, fy), fz);
}

DensityGrid load_density_grid(const std::string& path, const std::string& where) {
    std::string text = read_small_file(path, where, kMaxGridFileBytes, "a density grid");
    std::istringstream in(text);
    int line_number = 0;
    std::vector<std::string> tokens;  // with their line numbers, below
    std::vector<int> token_line;
    std::string line;
    while (std::getline(in, line)) {
        ++line_number;
        if (!line.empty() && line[0] == '#') continue;
        std::istringstream words(line);
        std::string w;
        while (words >> w) {
            tokens.push_back(w);
            token_line.push_back(line_number);
        }
    }
    size_t next = 0;
    auto fail = [&](const std::string& what) -> void {
        std::string at = next < token_line.size() ? ": line " + std::to_string(token_line[next]) : ": at the end";
        throw InputError(where + ": " + path + at + ": " + what);
    };
    auto number = [&](const char* what) {
        if (next >= tokens.size()) fail(std::string("expected ") + what);
        const std::string& s = tokens[next];
        char* end = nullptr;
        double v = std::strtod(s.c_str(), &end);
        if (end != s.c_str() + s.size() || !std::isfinite(v))
            fail(std::string("expected ") + what + ", got \"" + s + "\"");
        ++next;
        return v;
    };
    if (tokens.empty() || tokens[0] != "ptgrid") fail("expected the magic word \"ptgrid\" (scene/density_grid.h)");
    ++next;
    if (number("the format version 1") != 1.0) { --next; fail("expected format version 1"); }
    int n[3];
    for (int a = 0; a < 3; ++a) {
        double v = number("NX NY NZ, each an integer in [2, 512]");
        if (v != std::floor(v) || v < 2 || v > kMaxPointsPerAxis) {
            --next;
            fail("expected NX NY NZ, each an integer in [2, 512]");
        }
        n[a] = int(v);
    }
    double b[6];
    for (double& v : b) v = number("the box XMIN YMIN ZMIN XMAX YMAX ZMAX");
    if (!(b[3] > b[0] && b[4] > b[1] && b[5] > b[2])) {
        --next;
        fail("expected XMAX > XMIN, YMAX > YMIN and ZMAX > ZMIN");
    }
    const size_t count = size_t(n[0]) * n[1] * n[2];
    std::vector<float> values(count);
    for (size_t i = 0; i < count; ++i) {
        double v = number(("density " + std::to_string(i + 1) + " of " + std::to_string(count)).c_str());
        if (v < 0) {
            --next;
            fail("expected densities >= 0, got " + tokens[next]);
        }
        values[i] = float(v);
    }
    if (next != tokens.size()) fail("more values than NX*NY*NZ = " + std::to_string(count));
    return DensityGrid(n[0], n[1], n[2], BBox(Vec3(b[0], b[1], b[2]), Vec3(b[3], b[4], b[5])), std::move(values));
}

std::string density_grid_text(int nx, int ny, int nz, const BBox& bounds, const std::vector<float>& values,
                              const std::string& comment) {
    std::ostringstream out;
    out << "ptgrid 1\n";
    if (!comment.empty()) out << "# " << comment << "\n";
    out << nx << " " << ny << " " << nz << "\n";
    out << bounds.min.x << " " << bounds.min.y << " " << bounds.min.z << " " << bounds.max.x << " " << bounds.max.y
        << " " << bounds.max.z << "\n";
    char buffer[32];
    for (size_t i = 0; i < values.size(); ++i) {
        std::snprintf(buffer, sizeof buffer, "%.3g", double(values[i]));
        out << buffer << ((i + 1) % size_t(nx) == 0 ? "\n" : " ");
    }
    return out.str();
}

}  // namespace pt
