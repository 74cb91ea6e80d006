#include "scene/csg.h"

#include <algorithm>
#include <cmath>

namespace pt {

namespace {

bool inside(CsgOp op, bool a, bool b) {
    switch (op) {
        case CsgOp::union_op:
            return a || b;
        case CsgOp::intersection:
            return a && b;
        case CsgOp::difference:
            return a && !b;
        case CsgOp::leaf:
            break;
    }
    return a;
}

struct Event {
    CsgEnd end;
    int operand;  ///< 0: a, 1: b
    int step;     ///< +1 a span begins, -1 it ends
};

}  // namespace

CsgSpans csg_combine(CsgOp op, const CsgSpans& a, const CsgSpans& b) {
    // Short cuts that the sweep would also find.
    if (op == CsgOp::union_op && b.empty()) return a;
    if (op == CsgOp::union_op && a.empty()) return b;
    if (op == CsgOp::difference && b.empty()) return a;
    if ((op == CsgOp::intersection || op == CsgOp::difference) && a.empty()) return {};
    if (op == CsgOp::intersection && b.empty()) return {};

    std::vector<Event> events;
    events.reserve(2 * (a.size() + b.size()));
    for (const CsgSpan& s : a) events.push_back({s.in, 0, +1}), events.push_back({s.out, 0, -1});
    for (const CsgSpan& s : b) events.push_back({s.in, 1, +1}), events.push_back({s.out, 1, -1});
    std::stable_sort(events.begin(), events.end(), [](const Event& x, const Event& y) { return x.end.t < y.end.t; });

    // Sweep: apply every event at one t together (a span of one operand that
    // ends where another begins, or ends of both operands at one t, change
    // nothing in between), then compare the result's state before and after.
    // Counts, not flags, so the order of the events at one t does not matter.
    CsgSpans out;
    int count[2] = {0, 0};
    bool was_inside = false;
    CsgEnd open;
    for (size_t i = 0; i < events.size();) {
        size_t j = i;
        bool before[2] = {count[0] > 0, count[1] > 0};
        for (; j < events.size() && events[j].end.t == events[i].end.t; ++j) count[events[j].operand] += events[j].step;
        bool after[2] = {count[0] > 0, count[1] > 0};
        bool now_inside = inside(op, after[0], after[1]);
        if (now_inside != was_inside) {
            // The surface here is an end of an operand whose state changed:
            // a's when it did (coincident surfaces: either is right), else b's.
            int who = before[0] != after[0] ? 0 : 1;
            const CsgEnd* end = &events[i].end;
            const int step = after[who] ? +1 : -1;
            for (size_t k = i; k < j; ++k)
                if (events[k].operand == who && events[k].step == step) {
                    end = &events[k].end;
                    break;
                }
            if (now_inside) {
                open = *end;
            } else {
                out.push_back({open, *end});
            }
            was_inside = now_inside;
        }
        i = j;
    }
    return out;
}

CsgSpans csg_spans_of_crossings(std::vector<CsgCrossing> crossings) {
    std::sort(crossings.begin(), crossings.end(),
              [](const CsgCrossing& x, const CsgCrossing& y) { return x.end.t < y.end.t; });
    // Merge the crossings of one point into one net crossing.
    std::vector<CsgCrossing> net;
    for (size_t i = 0; i < crossings.size();) {
        size_t j = i;
        int sum = 0;
        const double t0 = crossings[i].end.t, tolerance = 1e-9 * std::abs(t0);
        for (; j < crossings.size() && crossings[j].end.t - t0 <= tolerance; ++j) sum += crossings[j].direction;
        int direction = std::clamp(sum, -1, 1);
        if (direction != 0)
            for (size_t k = i; k < j; ++k)
                if (crossings[k].direction == direction) {
                    net.push_back(crossings[k]);
                    net.back().direction = direction;
                    break;
                }
        i = j;
    }
    // A closed surface is crossed as often inwards as outwards along the
    // whole line, so the winding number at the ray's start is minus the sum
    // of the crossings ahead of it.
    int winding = 0;
    for (const CsgCrossing& c : net) winding -= c.direction;
    CsgSpans out;
    CsgEnd open;
    open.t = -kInfinity;
    for (const CsgCrossing& c : net) {
        const bool was_inside = winding > 0;
        winding += c.direction;
        if (!was_inside && winding > 0) {
            open = c.end;
        } else if (was_inside && winding <= 0) {
            if (open.t < c.end.t) out.push_back({open, c.end});
        }
    }
    if (winding > 0) {  // an inconsistent surface: close at infinity, no surface
        CsgEnd end;
        end.t = kInfinity;
        out.push_back({open, end});
    }
    return out;
}

CsgSpans csg_sphere_spans(const Sphere& sphere, const Ray& ray, uint32_t primitive) {
    // The roots as the reference intersect_sphere computes them (Ray Tracing
    // Gems chapter 7): discriminant from the perpendicular distance, the
    // second root by Vieta.
    Vec3 f = ray.o - sphere.center;
    double a = dot(ray.d, ray.d);
    double b = -dot(f, ray.d);
    double c = dot(f, f) - sphere.radius * sphere.radius;
    Vec3 perp = f + (b / a) * ray.d;
    double disc = a * (sphere.radius * sphere.radius - dot(perp, perp));
    if (!(disc > 0.0)) return {};  // a miss, or tangent: a span of zero length
    double root = std::sqrt(disc);
    double q = b + std::copysign(root, b);
    double t0 = c / q, t1 = q / a;
    if (t0 > t1) std::swap(t0, t1);
    if (!(t1 >= ray.t_min) || !(t0 < t1)) return {};
    CsgSpan span;
    span.in.t = t0;
    span.in.primitive = primitive;
    if (!(t0 >= ray.t_min)) {
        span.in.t = -kInfinity;
        span.in.primitive = kNoIndex;
    }
    span.out.t = t1;
    span.out.primitive = primitive;
    return {span};
}

bool parse_csg_op(const std::string& name, CsgOp& op) {
    if (name == "union") op = CsgOp::union_op;
    else if (name == "intersection") op = CsgOp::intersection;
    else if (name == "difference") op = CsgOp::difference;
    else return false;
    return true;
}

}  // namespace pt
