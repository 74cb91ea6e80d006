// Constructive solid geometry by interval lists along the ray (Roth,
// "Ray casting for modeling solids", CGIP 18(2), 1982; pbrt-v1's and
// Glassner's "An Introduction to Ray Tracing", section 2.7, give the same
// scheme). Every solid (a sphere, a closed mesh, or a CSG node) is, along
// one ray, a sorted list of disjoint spans [t_in, t_out] where the ray is
// inside it. Union, intersection and difference of two solids are the
// union, intersection and difference of their span lists, computed by one
// sweep over the span ends; the first span end at or after t_min is the
// surface the ray meets.
//
// The sets are regularised (Requicha 1980): a piece of zero length never
// exists. So a ray tangent to a sphere misses it, two spans that touch
// merge in a union, two that touch have no intersection, and a solid minus
// itself (coincident surfaces) is empty. Spans keep the primitive of each
// end, so a hit knows which surface it is on.
//
// Orientation: a surface of B seen through A - B bounds the empty inside of
// B, so its outward normal is B's inward one. A leaf's orientation is
// therefore fixed when the tree is read: flipped when an odd number of its
// ancestors hold it as a subtracted operand. The loader stores such a leaf
// turned round (a mesh's winding reversed, a sphere marked `inward`), so the
// shading code needs no CSG knowledge.
//
// Tests: tests/unit/test_csg.cpp (the span arithmetic: touching, coincident
// and tangent cases, rays starting inside; the loader's errors; rendered
// hits against the analytic answer).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/ray.h"
#include "scene/geometry.h"

namespace pt {

enum class CsgOp { leaf, union_op, intersection, difference };

/// One end of a span: where the ray crosses a surface of the solid.
struct CsgEnd {
    double t = 0;
    uint32_t primitive = kNoIndex;  ///< kNoIndex: no surface (the span began before the ray did)
    double b1 = 0, b2 = 0;          ///< barycentrics on a triangle
};

/// Where the ray is inside the solid: in.t < out.t.
struct CsgSpan {
    CsgEnd in, out;
};

/// Sorted, disjoint spans of positive length.
using CsgSpans = std::vector<CsgSpan>;

/// The spans of `op` (union, intersection or difference a - b) of two solids.
CsgSpans csg_combine(CsgOp op, const CsgSpans& a, const CsgSpans& b);

/// Spans from the crossings of a closed surface, sorted by t, each +1 where
/// the ray enters (against the outward normal), -1 where it leaves; only the
/// crossings at t >= t_min of the ray are given. Crossings within a relative
/// 1e-9 of each other are one (a ray through a shared edge crosses the
/// surface once, however many of the edge's triangles report it; a ray
/// grazing a fold enters and leaves at once: no crossing). The ray starts
/// inside when the crossings ahead of it leave more than they enter.
struct CsgCrossing {
    CsgEnd end;
    int direction = 0;  ///< +1 enters, -1 leaves
};
CsgSpans csg_spans_of_crossings(std::vector<CsgCrossing> crossings);

/// The spans of a sphere along `ray`: [t0, t1] from the two roots, the start
/// dropped (no surface) when t0 < t_min, nothing when t1 < t_min or the ray
/// is tangent (a span of zero length). `primitive` names the sphere.
CsgSpans csg_sphere_spans(const Sphere& sphere, const Ray& ray, uint32_t primitive);

/// A CSG tree over the primitives of one shape (Scene): node 0 is the root.
struct CsgNode {
    CsgOp op = CsgOp::leaf;
    std::vector<uint32_t> children;  ///< inner nodes: >= 2; a difference is the first minus all others
    bool sphere = false;             ///< leaf: a sphere (spheres[first]) or triangles [first, first + count)
    uint32_t first = 0, count = 0;
    bool inverted = false;           ///< leaf: stored turned round (its outward normal is the stored one negated)
};

struct CsgTree {
    std::vector<CsgNode> nodes;
};

/// "union", "intersection", "difference"; false for anything else.
bool parse_csg_op(const std::string& name, CsgOp& op);

}  // namespace pt
