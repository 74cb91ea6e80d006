#include "apps/bench/bench_util.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "apps/number_flags.h"
#include "core/error.h"
#include "core/frame.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "core/timer.h"
#include "stages/render_context.h"
#include "scene/scene.h"
#include "stages/camera.h"

namespace pt::bench {

// ---------------------------------------------------------------------------
// Arguments

Args::Args(const std::string& command, const std::vector<std::string>& args,
           const std::map<std::string, int>& arity)
    : command_(command) {
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (a.size() > 1 && a[0] == '-') {
            auto it = arity.find(a);
            if (it == arity.end())
                throw InputError(command + ": unknown option " + a + " (see bench " + command +
                                 " --help)");
            if (i + size_t(it->second) >= args.size() && it->second > 0)
                throw InputError(command + ": " + a + " expects " + std::to_string(it->second) +
                                 " value" + (it->second > 1 ? "s" : ""));
            std::vector<std::string>& v = values_[a];
            v.assign(args.begin() + long(i) + 1, args.begin() + long(i) + 1 + it->second);
            i += size_t(it->second);
        } else {
            positionals_.push_back(a);
        }
    }
}

std::string Args::get(const std::string& flag, const std::string& fallback) const {
    auto it = values_.find(flag);
    return it == values_.end() || it->second.empty() ? fallback : it->second[0];
}

const std::vector<std::string>& Args::values(const std::string& flag) const {
    static const std::vector<std::string> none;
    auto it = values_.find(flag);
    return it == values_.end() ? none : it->second;
}

int parse_int(const std::string& what, const std::string& text, int lo, int hi) {
    return int(parse_whole_number(what, text, lo, hi));
}

int Args::get_int(const std::string& flag, int fallback, int lo, int hi) const {
    if (!has(flag)) return fallback;
    return parse_int(command_ + ": " + flag, get(flag, ""), lo, hi);
}

double Args::get_double(const std::string& flag, double fallback, double lo) const {
    if (!has(flag)) return fallback;
    return parse_real_number(command_ + ": " + flag, get(flag, ""), lo);
}

// ---------------------------------------------------------------------------
// Output

std::string Table::markdown() const {
    std::vector<size_t> width(header_.size(), 3);
    for (size_t c = 0; c < header_.size(); ++c)
        width[c] = std::max(width[c], header_[c].size());
    for (const auto& row : rows_)
        for (size_t c = 0; c < row.size() && c < width.size(); ++c)
            width[c] = std::max(width[c], row[c].size());
    std::ostringstream s;
    auto line = [&](const std::vector<std::string>& cells) {
        s << "|";
        for (size_t c = 0; c < width.size(); ++c) {
            std::string cell = c < cells.size() ? cells[c] : "";
            // Text left, numbers right, as Markdown renderers do with ---: .
            bool text = c < text_columns_;
            s << " " << (text ? cell : std::string(width[c] - cell.size(), ' ') + cell)
              << (text ? std::string(width[c] - cell.size(), ' ') : "") << " |";
        }
        s << "\n";
    };
    line(header_);
    s << "|";
    for (size_t c = 0; c < width.size(); ++c)
        s << (c < text_columns_ ? ":" : "-") << std::string(width[c], '-')
          << (c < text_columns_ ? "-" : ":") << "|";
    s << "\n";
    for (const auto& row : rows_)
        line(row);
    return s.str();
}

std::string fixed(double value, int digits) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", digits, value);
    return buf;
}

std::string count(uint64_t value) {
    std::string digits = std::to_string(value), out;
    for (size_t i = 0; i < digits.size(); ++i) {
        if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
        out += digits[i];
    }
    return out;
}

std::string short_count(uint64_t value) {
    if (value < 1000) return std::to_string(value);
    double v = double(value);
    const char* unit = "k";
    if (v >= 1e6) {
        v /= 1e6;
        unit = "M";
    } else {
        v /= 1e3;
    }
    return (std::fabs(v - std::round(v)) < 0.05 ? fixed(v, 0) : fixed(v, 1)) + unit;
}

// ---------------------------------------------------------------------------
// Scenes and rays

std::vector<std::string> asset_scenes() {
    namespace fs = std::filesystem;
    fs::path dir = "assets/scenes";
    if (!fs::is_directory(dir)) dir = fs::path(PT_SOURCE_DIR) / "assets" / "scenes";
    std::vector<std::string> out;
    if (fs::is_directory(dir))
        for (const auto& entry : fs::directory_iterator(dir))
            if (entry.path().extension() == ".json") out.push_back(entry.path().string());
    std::sort(out.begin(), out.end());
    return out;
}

std::vector<std::string> obj_files(const std::string& directory) {
    namespace fs = std::filesystem;
    std::vector<std::string> out;
    std::error_code ec;
    if (!fs::is_directory(directory, ec)) return out;
    for (const auto& entry : fs::directory_iterator(directory, ec))
        if (entry.path().extension() == ".obj") out.push_back(entry.path().string());
    std::sort(out.begin(), out.end());
    return out;
}

namespace {

/// A uniformly distributed point on primitive `prim` (pbrt-v3 section 13.6.5).
Vec3 sample_primitive(const Scene& scene, uint32_t prim, Rng& rng) {
    Vec2 u = rng.next_2d();
    if (scene.is_sphere(prim)) {
        const Sphere& s = scene.sphere_record(prim).sphere;
        return s.center + s.radius * sample_uniform_sphere(u);
    }
    Triangle t = scene.triangle(prim);
    double su = std::sqrt(u.x);
    double b0 = 1 - su, b1 = u.y * su;
    return b0 * t.p0 + b1 * t.p1 + (1 - b0 - b1) * t.p2;
}

/// The ray with origin and direction rounded to float: a single-precision
/// kernel (Embree) then traces exactly the same ray as the reference.
Ray float_exact(Ray r) {
    for (int a = 0; a < 3; ++a) {
        r.o[a] = double(float(r.o[a]));
        r.d[a] = double(float(r.d[a]));
    }
    return r;
}

}  // namespace

RaySets make_ray_sets(const Scene& scene, const Accelerator& accel, int width, int height,
                      uint64_t seed) {
    Camera camera = scene.camera;
    camera.aspect = double(width) / height;
    camera.finalize(scene.path + ": camera");
    // The fallback light: a square above the scene, as large as its top face.
    const BBox& b = scene.bounds;
    Vec3 light_corner(b.min.x, b.max.y + 0.5 * b.extent().y + 1e-3 * b.extent().norm(), b.min.z);
    // Secondary rays start this far off the surface, so that rounding their
    // origins to float (float_exact) cannot put them behind it: the renderer's
    // own offsets (interaction.h) are sized for double precision only.
    const double lift = 1e-5 * b.extent().norm();

    RaySets sets;
    sets.primary.reserve(size_t(width) * height);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            double u = (x + 0.5) / width, v = 1.0 - (y + 0.5) / height;
            Ray ray = reference::generate_ray(camera, u, v, Vec2(0.5, 0.5));
            ray = float_exact(ray);
            sets.primary.push_back(ray);
            std::optional<Hit> hit = accel.intersect(ray);
            if (!hit) continue;
            SurfaceInteraction si = make_interaction(scene, ray, *hit);
            Rng rng(seed, uint64_t(y) * width + x, 0);
            // Bounce on the side the ray came from.
            Vec3 n = dot(si.ng, si.wo) < 0 ? -si.ng : si.ng;
            Vec3 origin = si.p + lift * n;
            sets.diffuse.push_back(float_exact(
                Ray(origin, Frame(n).to_world(sample_cosine_hemisphere(rng.next_2d())))));
            Vec3 target;
            if (!scene.emitters.empty()) {
                target = sample_primitive(
                    scene, scene.emitters[rng.next_index(uint32_t(scene.emitters.size()))], rng);
            } else {
                Vec2 w = rng.next_2d();
                target = light_corner + Vec3(w.x * b.extent().x, 0, w.y * b.extent().z);
            }
            origin = float_exact(Ray(origin, Vec3())).o;
            sets.shadow.push_back(
                float_exact(Ray(origin, target - origin, 0.0, 1.0 - kShadowEpsilon)));
        }
    }
    return sets;
}

// ---------------------------------------------------------------------------
// Timing

KernelPass trace_pass(const Accelerator& accel, const std::vector<Ray>& rays, bool any_hit) {
    KernelPass pass;
    RayCounters before = thread_counters();
    // CPU time, not wall-clock: on a shared machine the kernel's own cost
    // (the pass runs on this one thread; core/timer.h).
    CpuTimer timer;
    uint64_t hits = 0;
    if (any_hit) {
        for (const Ray& r : rays)
            hits += accel.occluded(r) ? 1 : 0;
    } else {
        for (const Ray& r : rays)
            hits += accel.intersect(r).has_value() ? 1 : 0;
    }
    pass.seconds = timer.seconds();
    pass.counters = thread_counters() - before;
    pass.hits = hits;
    return pass;
}

KernelPass trace_packets(const Accelerator& accel, const std::vector<Ray>& rays) {
    KernelPass pass;
    RayCounters before = thread_counters();
    CpuTimer timer;
    uint64_t hits = 0;
    std::optional<Hit> packet[kPacketSize];
    for (size_t i = 0; i < rays.size(); i += kPacketSize) {
        int count = int(std::min<size_t>(kPacketSize, rays.size() - i));
        accel.intersect_packet(&rays[i], count, packet);
        for (int k = 0; k < count; ++k)
            hits += packet[k].has_value() ? 1 : 0;
    }
    pass.seconds = timer.seconds();
    pass.counters = thread_counters() - before;
    pass.hits = hits;
    return pass;
}

std::vector<double> best_times(const std::vector<std::function<double()>>& passes,
                               double min_seconds, int min_rounds) {
    std::vector<double> best(passes.size(), INFINITY);
    Timer total;
    for (int round = 0; round < min_rounds || total.seconds() < min_seconds; ++round)
        for (size_t i = 0; i < passes.size(); ++i)
            best[i] = std::min(best[i], passes[i]());
    return best;
}

LineFit fit_line(const std::vector<double>& x, const std::vector<double>& y) {
    const size_t n = x.size();
    LineFit fit;
    if (n < 2) return fit;
    double mx = 0, my = 0;
    for (size_t i = 0; i < n; ++i) {
        mx += x[i] / double(n);
        my += y[i] / double(n);
    }
    double sxx = 0, sxy = 0, syy = 0;
    for (size_t i = 0; i < n; ++i) {
        sxx += (x[i] - mx) * (x[i] - mx);
        sxy += (x[i] - mx) * (y[i] - my);
        syy += (y[i] - my) * (y[i] - my);
    }
    fit.b = sxx > 0 ? sxy / sxx : 0;
    fit.a = my - fit.b * mx;
    fit.r2 = sxx > 0 && syy > 0 ? (sxy * sxy) / (sxx * syy) : 1.0;
    return fit;
}

}  // namespace pt::bench
