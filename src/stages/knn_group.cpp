// Building the quantised groups and the filter's range (stages/knn_group.h).
#include "stages/knn_group.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pt {
namespace {

/// The largest coordinate the quantised filter accepts (of a point, of a
/// query): squared distances stay far inside float's range.
constexpr double kFilterRange = 1e18;

}  // namespace

/// Quantises the group [lo, hi) into `bucket` (see KnnGroup); false when
/// a coordinate is out of the filter's range or a point is not within
/// 0.75 steps of its code on each axis (then the index holds no groups).
bool quantise_group(const KdTree& tree, size_t lo, size_t hi, KnnGroup& bucket) {
    double low[3], high[3];
    for (int a = 0; a < 3; ++a) low[a] = high[a] = tree.points[lo][a];
    for (size_t i = lo; i < hi; ++i)
        for (int a = 0; a < 3; ++a) {
            const double x = tree.points[i][a];
            if (!(std::fabs(x) <= kFilterRange)) return false;
            low[a] = std::min(low[a], x);
            high[a] = std::max(high[a], x);
        }
    double extent = 0;
    for (int a = 0; a < 3; ++a) {
        float origin = float(low[a]);
        if (double(origin) > low[a]) origin = std::nextafter(origin, -std::numeric_limits<float>::infinity());
        bucket.origin[a] = origin;
        extent = std::max(extent, high[a] - double(origin));
    }
    float step = float(extent / 255);
    if (double(step) < extent / 255) step = std::nextafter(step, std::numeric_limits<float>::infinity());
    bucket.step = step;
    for (size_t i = lo; i < hi; ++i)
        for (int a = 0; a < 3; ++a) {
            const double offset = tree.points[i][a] - double(bucket.origin[a]);
            const double code = step > 0 ? std::clamp(std::nearbyint(offset / double(step)), 0.0, 255.0) : 0.0;
            bucket.code[a][i - lo] = uint8_t(code);
            if (!(std::fabs(offset - code * double(step)) <= 0.75 * double(step))) return false;
        }
    return true;
}

bool knn_group_filter_applies(const Vec3& p, double bound) {
    return std::fabs(p.x) <= kFilterRange && std::fabs(p.y) <= kFilterRange && std::fabs(p.z) <= kFilterRange &&
           bound >= 0 && bound <= kFilterRange * kFilterRange;
}

}  // namespace pt
