// Shared pieces of the bench subcommands: argument parsing, Markdown
// tables, the ray sets the kernels are timed on, timing loops, and a
// least-squares line fit for growth rates.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "core/counters.h"
#include "core/ray.h"

namespace pt {
struct Scene;
class Accelerator;
}  // namespace pt

namespace pt::bench {

// ---------------------------------------------------------------------------
// Arguments

/// A subcommand's arguments: flags (with a fixed number of values each) and
/// positionals. Unknown flags and missing values throw InputError naming
/// the subcommand.
class Args {
  public:
    /// `arity` gives every accepted flag and how many values follow it.
    Args(const std::string& command, const std::vector<std::string>& args,
         const std::map<std::string, int>& arity);

    bool has(const std::string& flag) const { return values_.count(flag) > 0; }
    /// The flag's first value, or `fallback` when the flag is absent.
    std::string get(const std::string& flag, const std::string& fallback) const;
    /// The flag's values (empty when absent or when it takes none).
    const std::vector<std::string>& values(const std::string& flag) const;
    int get_int(const std::string& flag, int fallback, int lo, int hi) const;
    double get_double(const std::string& flag, double fallback, double lo) const;
    const std::vector<std::string>& positionals() const { return positionals_; }

  private:
    std::string command_;
    std::map<std::string, std::vector<std::string>> values_;
    std::vector<std::string> positionals_;
};

/// `text` as a whole number in [lo, hi]; InputError naming `what` otherwise.
int parse_int(const std::string& what, const std::string& text, int lo, int hi);

// ---------------------------------------------------------------------------
// Output

/// A Markdown table, printed with aligned columns: the first `text_columns`
/// columns left-aligned (names), the others right-aligned (numbers).
class Table {
  public:
    explicit Table(std::vector<std::string> header, size_t text_columns = 1)
        : header_(std::move(header)), text_columns_(text_columns) {}
    void add(std::vector<std::string> row) { rows_.push_back(std::move(row)); }
    std::string markdown() const;

  private:
    std::vector<std::string> header_;
    size_t text_columns_;
    std::vector<std::vector<std::string>> rows_;
};

/// `value` with `digits` decimals ("12.35").
std::string fixed(double value, int digits);
/// A count with thousands separators ("69,451").
std::string count(uint64_t value);
/// A compact count for sizes: "1k", "100k", "4.1M".
std::string short_count(uint64_t value);

// ---------------------------------------------------------------------------
// Scenes and rays

/// The scenes of assets/scenes (found from the current directory, else from
/// the source tree), sorted by name.
std::vector<std::string> asset_scenes();
/// The .obj files in `directory`, sorted; empty when it does not exist.
std::vector<std::string> obj_files(const std::string& directory);

/// The three ray kinds the kernels are timed on, all from the scene's camera.
struct RaySets {
    std::vector<Ray> primary;  ///< one camera ray through each pixel centre
    std::vector<Ray> diffuse;  ///< from each primary hit, a cosine-weighted bounce (incoherent)
    std::vector<Ray> shadow;   ///< from each primary hit to a point on a light (finite t_max)
};

/// Ray sets at width x height pixels. Shadow rays aim at the scene's
/// emitters, or, when nothing emits, at a square light above the scene's
/// bounding box (y up) as large as its top face. Secondary rays start
/// 10^-5 scene diagonals off the surface, and all coordinates are
/// representable in float, so that a float kernel traces the same rays.
RaySets make_ray_sets(const Scene& scene, const Accelerator& accel, int width, int height,
                      uint64_t seed = 1);

// ---------------------------------------------------------------------------
// Timing

/// One timed pass over a ray set.
struct KernelPass {
    double seconds = 0;    ///< wall-clock time of the pass
    RayCounters counters;  ///< nodes visited and primitive tests during it
    uint64_t hits = 0;     ///< rays that hit (keeps the work observable)
};

/// Traces every ray once (closest hit, or any hit when `any_hit`).
KernelPass trace_pass(const Accelerator& accel, const std::vector<Ray>& rays, bool any_hit);

/// Traces every ray once for its closest hit, in packets of kPacketSize
/// consecutive rays (Accelerator::intersect_packet).
KernelPass trace_packets(const Accelerator& accel, const std::vector<Ray>& rays);

/// Runs the passes in turn, round after round, until every one has run at
/// least `min_rounds` times and `min_seconds` have passed in total; returns
/// each pass's fastest time. Interleaving spreads the noise of other
/// processes over all contenders alike.
std::vector<double> best_times(const std::vector<std::function<double()>>& passes,
                               double min_seconds, int min_rounds = 3);

/// Least-squares line y = a + b x, with the coefficient of determination.
struct LineFit {
    double a = 0, b = 0, r2 = 0;
};
LineFit fit_line(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace pt::bench
