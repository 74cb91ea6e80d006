// CSG by span lists (scene/csg.h, stages/csg_accelerator.h): the span
// arithmetic by hand (touching, coincident and tangent cases, spans that
// start before the ray), the crossings of a closed mesh (shared edges, rays
// starting inside), and whole CSG objects against a point-membership oracle:
// for random rays from inside and outside, the first hit is where the
// analytic solid's membership changes, its geometric normal points out of
// the solid, and a miss changes nothing along the ray. The loader's errors.
#include <doctest/doctest.h>

#include <cmath>
#include <functional>
#include <string>

#include "core/error.h"
#include "core/rng.h"
#include "render/integrators.h"
#include "scene/csg.h"
#include "scene/scene_loader.h"
#include "stages/render_context.h"
#include "stages/stages.h"
#include "render_fixture.h"
#include "test_util.h"

using namespace pt;

namespace {

CsgEnd end_at(double t, uint32_t primitive) {
    CsgEnd e;
    e.t = t;
    e.primitive = primitive;
    return e;
}

CsgSpan span(double t0, double t1, uint32_t p0, uint32_t p1) { return {end_at(t0, p0), end_at(t1, p1)}; }

/// "[t0 p0, t1 p1] ..." for readable failures.
std::string str(const CsgSpans& spans) {
    std::string s;
    for (const CsgSpan& x : spans)
        s += "[" + std::to_string(x.in.t) + " p" + std::to_string(int(x.in.primitive)) + ", " +
             std::to_string(x.out.t) + " p" + std::to_string(int(x.out.primitive)) + "] ";
    return s;
}

const uint32_t A = 1, B = 2, C = 3, D = 4;

}  // namespace

TEST_CASE("CSG spans: union, intersection and difference of overlapping spans keep each end's surface") {
    CsgSpans a = {span(0, 2, A, A)}, b = {span(1, 3, B, B)};
    CHECK(str(csg_combine(CsgOp::union_op, a, b)) == str({span(0, 3, A, B)}));
    CHECK(str(csg_combine(CsgOp::intersection, a, b)) == str({span(1, 2, B, A)}));
    CHECK(str(csg_combine(CsgOp::difference, a, b)) == str({span(0, 1, A, B)}));
    CHECK(str(csg_combine(CsgOp::difference, b, a)) == str({span(2, 3, A, B)}));
    // A hole through the middle leaves two spans.
    CsgSpans hole = csg_combine(CsgOp::difference, {span(0, 4, A, A)}, {span(1, 2, B, B)});
    CHECK(str(hole) == str({span(0, 1, A, B), span(2, 4, B, A)}));
    // Several spans on each side.
    CsgSpans many = csg_combine(CsgOp::intersection, {span(0, 2, A, A), span(3, 5, C, C)}, {span(1, 4, B, D)});
    CHECK(str(many) == str({span(1, 2, B, A), span(3, 4, C, D)}));
}

TEST_CASE("CSG spans: regularised sets: touching spans merge or vanish, no slivers of zero length") {
    CsgSpans a = {span(0, 1, A, A)}, b = {span(1, 2, B, B)};
    CHECK(str(csg_combine(CsgOp::union_op, a, b)) == str({span(0, 2, A, B)}));  // one solid, no inner surface
    CHECK(csg_combine(CsgOp::intersection, a, b).empty());
    CHECK(str(csg_combine(CsgOp::difference, a, b)) == str(a));
    // Coincident surfaces: a solid minus itself is empty, with itself it is itself.
    CHECK(csg_combine(CsgOp::difference, a, a).empty());
    CHECK(csg_combine(CsgOp::intersection, a, a).size() == 1);
    CHECK(csg_combine(CsgOp::union_op, a, a).size() == 1);
    // One end coincident: [0, 2] - [1, 2] is [0, 1], not [0, 1] and a sliver at 2.
    CHECK(str(csg_combine(CsgOp::difference, {span(0, 2, A, A)}, {span(1, 2, B, B)})) == str({span(0, 1, A, B)}));
    CHECK(str(csg_combine(CsgOp::intersection, {span(0, 2, A, A)}, {span(0, 1, B, B)})) == str({span(0, 1, A, B)}));
    // Empty operands.
    CHECK(csg_combine(CsgOp::intersection, a, {}).empty());
    CHECK(str(csg_combine(CsgOp::union_op, {}, b)) == str(b));
}

TEST_CASE("CSG spans: a ray starting inside has a span without a first surface") {
    CsgSpans inside = {span(-kInfinity, 2, kNoIndex, A)};
    CHECK(str(csg_combine(CsgOp::difference, inside, {span(1, 3, B, B)})) == str({span(-kInfinity, 1, kNoIndex, B)}));
    // Starting inside the subtracted solid: the first surface is where it ends.
    CHECK(str(csg_combine(CsgOp::difference, {span(-kInfinity, 5, kNoIndex, A)}, {span(-kInfinity, 2, kNoIndex, B)})) ==
          str({span(2, 5, B, A)}));

    // Spheres: the ray from the centre has the far root only; behind, nothing.
    Sphere s{Vec3(0, 0, 0), 1};
    CsgSpans from_centre = csg_sphere_spans(s, Ray(Vec3(0), Vec3(1, 0, 0)), 7);
    REQUIRE(from_centre.size() == 1);
    CHECK(from_centre[0].in.primitive == kNoIndex);
    CHECK(from_centre[0].out.t == doctest::Approx(1));
    CHECK(csg_sphere_spans(s, Ray(Vec3(2, 0, 0), Vec3(1, 0, 0)), 7).empty());
    CsgSpans through = csg_sphere_spans(s, Ray(Vec3(-5, 0, 0), Vec3(1, 0, 0)), 7);
    REQUIRE(through.size() == 1);
    CHECK(through[0].in.t == doctest::Approx(4));
    CHECK(through[0].out.t == doctest::Approx(6));
}

TEST_CASE("CSG spans: a tangent ray meets a sphere in a span of zero length, which does not exist") {
    Sphere s{Vec3(0, 0, 0), 1};
    CHECK(csg_sphere_spans(s, Ray(Vec3(-5, 1, 0), Vec3(1, 0, 0)), 0).empty());
    CHECK(csg_sphere_spans(s, Ray(Vec3(-5, 0, 1), Vec3(1, 0, 0)), 0).empty());
    // Just inside the tangent, a short span.
    CHECK(csg_sphere_spans(s, Ray(Vec3(-5, 1 - 1e-6, 0), Vec3(1, 0, 0)), 0).size() == 1);
}

TEST_CASE("CSG crossings: shared edges count once, grazing folds not at all, inside starts open") {
    auto crossing = [](double t, int direction, uint32_t p) {
        CsgCrossing c;
        c.end = end_at(t, p);
        c.direction = direction;
        return c;
    };
    // Through an edge: both triangles report the entry (at t equal to rounding), both the exit.
    CHECK(str(csg_spans_of_crossings({crossing(1, +1, A), crossing(1 + 1e-15, +1, B), crossing(3, -1, C),
                                      crossing(3, -1, D)})) == str({span(1, 3, A, C)}));
    // A ray grazing a fold of the surface enters and leaves at once: nothing.
    CHECK(csg_spans_of_crossings({crossing(2, +1, A), crossing(2, -1, B)}).empty());
    // From inside: the first crossing leaves.
    CHECK(str(csg_spans_of_crossings({crossing(2, -1, A)})) == str({span(-kInfinity, 2, kNoIndex, A)}));
    // Unsorted input, two separate spans.
    CHECK(str(csg_spans_of_crossings({crossing(7, -1, D), crossing(1, +1, A), crossing(5, +1, C), crossing(2, -1, B)})) ==
          str({span(1, 2, A, B), span(5, 7, C, D)}));
}

namespace {

const std::string kHeader = R"({"camera": {"position": [0, 0, 10], "look_at": [0, 0, 0]},
    "materials": {"m": {"type": "diffuse"}, "lamp": {"type": "diffuse", "emission": [1, 1, 1]}}, "objects": [)";

Scene csg_scene(const std::string& objects) {
    return parse_json_scene(kHeader + objects + "]}", test::source_path("assets/scenes/csg_test.json"));
}

std::string error_of(const std::string& objects) {
    try {
        csg_scene(objects);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

struct Tracer {
    explicit Tracer(Scene s)
        : scene(std::move(s)), stages(make_stages(StageSet::none())), accel(build_accelerator(scene, stages, AcceleratorSettings{})),
          integrator(make_integrator(IntegratorKind::direct)), context{scene, *accel, stages, settings, *integrator} {}
    std::optional<SurfaceInteraction> hit(const Vec3& o, const Vec3& d) { return context.intersect(Ray(o, d)); }
    Scene scene;  // owned: the accelerator and the context refer to it
    Stages stages;
    std::unique_ptr<Accelerator> accel;
    RenderSettings settings;
    std::unique_ptr<Integrator> integrator;
    RenderContext context;
};

const std::string kCube = R"({"type": "mesh", "file": "../meshes/cube.obj"})";

}  // namespace

TEST_CASE("CSG objects: random rays from inside and outside meet the solid where its membership changes") {
    // (cube [-1,1]^3 intersected with the sphere of radius 1.3) minus a
    // sphere on a corner, minus the union of a sphere and a small cube (the
    // leaves of a subtracted union are turned round once).
    Scene scene = csg_scene(R"({"type": "csg", "op": "difference", "material": "m",
        "operands": [
          {"type": "csg", "op": "intersection", "operands": [)" + kCube + R"(,
             {"type": "sphere", "center": [0, 0, 0], "radius": 1.3}]},
          {"type": "sphere", "center": [1, 1, 1], "radius": 0.7},
          {"type": "csg", "op": "union", "operands": [
             {"type": "sphere", "center": [-1, 0, 0], "radius": 0.5},
             {"type": "mesh", "file": "../meshes/cube.obj", "transform": {"scale": 0.3, "translate": [0, -1, 0]}}]}]})");
    auto inside = [](const Vec3& p) {
        auto ball = [&](const Vec3& c, double r) { return (p - c).norm() < r; };
        auto box = [&](const Vec3& c, double h) {
            return std::fabs(p.x - c.x) < h && std::fabs(p.y - c.y) < h && std::fabs(p.z - c.z) < h;
        };
        return box(Vec3(0), 1) && ball(Vec3(0), 1.3) && !ball(Vec3(1, 1, 1), 0.7) &&
               !(ball(Vec3(-1, 0, 0), 0.5) || box(Vec3(0, -1, 0), 0.3));
    };
    Tracer tracer(scene);
    Rng rng(21, 0, 0);
    int hits = 0, from_inside = 0, misses = 0;
    for (int i = 0; i < 20000; ++i) {
        Vec3 o((rng.next_1d() - 0.5) * 5, (rng.next_1d() - 0.5) * 5, (rng.next_1d() - 0.5) * 5);
        Vec3 d = Vec3(rng.next_1d() - 0.5, rng.next_1d() - 0.5, rng.next_1d() - 0.5).unit();
        std::optional<SurfaceInteraction> h = tracer.hit(o, d);
        INFO("ray " << i);
        if (!h) {
            ++misses;
            // Nothing changes along the ray: sample it.
            for (double t = 0.01; t < 10; t += 0.01) REQUIRE(inside(o + t * d) == inside(o));
            continue;
        }
        ++hits;
        from_inside += inside(o);
        const double eps = 1e-7;
        REQUIRE(inside(o + (h->t - eps) * d) == inside(o));            // nothing before the hit
        REQUIRE(inside(o + (h->t + eps) * d) != inside(o));            // the membership changes at it
        REQUIRE((dot(h->ng, d) < 0) == !inside(o));                    // the normal points out of the solid
        REQUIRE(dot(h->n, h->ng) > 0.5);                               // the shading normal agrees
        REQUIRE(h->material->name == "m");
    }
    CHECK(hits > 2000);
    CHECK(from_inside > 100);
    CHECK(misses > 2000);
}

TEST_CASE("CSG objects: coincident surfaces, tangent rays, rays through mesh edges and from inside") {
    const Vec3 down(0, 0, -1);
    {  // A solid minus itself is empty; with itself it is itself.
        Tracer empty(csg_scene(R"({"type": "csg", "op": "difference", "material": "m", "operands": [)" + kCube + ", " +
                               kCube + "]}"));
        CHECK_FALSE(empty.hit(Vec3(0.3, 0.2, 5), down));
        CHECK_FALSE(empty.hit(Vec3(0.3, 0.2, 0), down));
        Tracer same(csg_scene(R"({"type": "csg", "op": "union", "material": "m", "operands": [)" + kCube + ", " + kCube +
                              "]}"));
        auto h = same.hit(Vec3(0.3, 0.2, 5), down);
        REQUIRE(h);
        CHECK(h->t == doctest::Approx(4));
        CHECK(h->ng.z == doctest::Approx(1));
    }
    {  // Cubes sharing the faces y = +-1 and z = +-1: the intersection is [0, 1] x [-1, 1]^2.
        Tracer half(csg_scene(R"({"type": "csg", "op": "intersection", "material": "m", "operands": [)" + kCube +
                              R"(, {"type": "mesh", "file": "../meshes/cube.obj", "transform": {"translate": [1, 0, 0]}}]})"));
        auto from_left = half.hit(Vec3(-5, 0.5, 0.25), Vec3(1, 0, 0));
        REQUIRE(from_left);
        CHECK(from_left->p.x == doctest::Approx(0));
        CHECK(from_left->ng.x == doctest::Approx(-1));
        auto from_above = half.hit(Vec3(0.5, 0.25, 5), down);  // onto the shared face z = 1
        REQUIRE(from_above);
        CHECK(from_above->t == doctest::Approx(4));
        CHECK_FALSE(half.hit(Vec3(-0.5, 0.25, 5), down));
    }
    {  // The cube minus a sphere in its middle, seen from inside the hole: the hole's wall faces the ray.
        Tracer hollow(csg_scene(R"({"type": "csg", "op": "difference", "material": "m", "operands": [)" + kCube +
                                R"(, {"type": "sphere", "center": [0, 0, 0], "radius": 0.5}]})"));
        auto h = hollow.hit(Vec3(0, 0, 0), Vec3(1, 0, 0));
        REQUIRE(h);
        CHECK(h->t == doctest::Approx(0.5));
        CHECK(h->ng.x == doctest::Approx(-1));  // out of the solid, into the hole
        auto through = hollow.hit(Vec3(-5, 0, 0), Vec3(1, 0, 0));
        REQUIRE(through);
        CHECK(through->t == doctest::Approx(4));
        // Tangent to the hole: the ray stays in the solid, meets no wall of the hole.
        auto tangent = hollow.hit(Vec3(-0.9, 0.5, 0), Vec3(1, 0, 0));
        REQUIRE(tangent);
        CHECK(tangent->t == doctest::Approx(1.9));
        // Through the diagonals of the cube's faces (the edges two triangles share) and from inside.
        auto diagonal = hollow.hit(Vec3(0.75, 0.75, 5), down);
        REQUIRE(diagonal);
        CHECK(diagonal->t == doctest::Approx(4));
        auto out = hollow.hit(Vec3(0.75, 0.75, 0), down);
        REQUIRE(out);
        CHECK(out->t == doctest::Approx(1));
        CHECK(out->ng.z == doctest::Approx(-1));
    }
    {  // A tangent ray misses a lone CSG sphere.
        Tracer ball(csg_scene(R"({"type": "csg", "op": "union", "material": "m", "operands": [
            {"type": "sphere", "center": [0, 0, 0], "radius": 1}, {"type": "sphere", "center": [5, 5, 5], "radius": 1}]})"));
        CHECK_FALSE(ball.hit(Vec3(-5, 1, 0), Vec3(1, 0, 0)));
        CHECK(ball.hit(Vec3(-5, 0.999, 0), Vec3(1, 0, 0)));
    }
}

TEST_CASE("CSG in the shapes table: instances of a CSG shape") {
    Scene scene = parse_json_scene(
        R"({"camera": {"position": [0, 0, 10], "look_at": [0, 0, 0]}, "materials": {"m": {"type": "diffuse"}},
            "shapes": {"lens": {"type": "csg", "op": "intersection", "operands": [
                {"type": "sphere", "center": [0, 0, -0.75], "radius": 1}, {"type": "sphere", "center": [0, 0, 0.75], "radius": 1}]}},
            "objects": [{"type": "instance", "shape": "lens", "material": "m", "transform": {"translate": [3, 0, 0]}},
                        {"type": "instance", "shape": "lens", "material": "m", "transform": {"scale": 2}}]})",
        "lens.json");
    Tracer tracer(scene);
    auto a = tracer.hit(Vec3(3, 0, 5), Vec3(0, 0, -1));
    REQUIRE(a);
    CHECK(a->t == doctest::Approx(5 - 0.25));  // the lens is 0.5 thick on its axis
    auto b = tracer.hit(Vec3(0, 0, 5), Vec3(0, 0, -1));
    REQUIRE(b);
    CHECK(b->t == doctest::Approx(5 - 0.5));
}

TEST_CASE("CSG: bad input is one error naming the JSON path") {
    struct Case {
        std::string object, expected;
    } cases[] = {
        {R"({"type": "csg", "op": "xor", "material": "m", "operands": []})", "objects[0].op: expected \"union\", \"intersection\" or \"difference\", got \"xor\""},
        {R"({"type": "csg", "op": "union", "material": "m", "operands": [)" + kCube + "]}", "objects[0].operands: expected at least two operands, got 1"},
        {R"({"type": "csg", "op": "union", "material": "m", "operands": [)" + kCube + R"(, {"type": "quad"}]})", "objects[0].operands[1].type: unknown CSG operand type \"quad\""},
        {R"({"type": "csg", "op": "union", "material": "lamp", "operands": [)" + kCube + ", " + kCube + "]}", "objects[0].material: a CSG object cannot emit light"},
        {R"({"type": "csg", "op": "union", "operands": [)" + kCube + ", " + kCube + "]}", "missing key 'material'"},
        {R"({"type": "csg", "op": "union", "material": "m", "operands": [)" + kCube + R"(, {"type": "sphere", "center": [0, 0, 0], "radius": -1}]})", "objects[0].operands[1].radius"},
        {R"({"type": "csg", "op": "union", "material": "m", "operands": [)" + kCube + R"(, {"type": "mesh", "file": "../meshes/cbox.obj"}]})", "a CSG operand must be a closed, consistently wound mesh, but the edge"},
        {R"({"type": "csg", "op": "union", "material": "m", "colour": 1, "operands": [)" + kCube + ", " + kCube + "]}", "colour"},
    };
    for (const Case& c : cases) {
        INFO(c.object);
        std::string error = error_of(c.object);
        CHECK(error.find(c.expected) != std::string::npos);
        CHECK(error.find("csg_test.json") != std::string::npos);
    }
}

TEST_CASE("CSG through the volume path tracer: a glass ball of milk united with a ball inside it is the ball, byte for byte") {
    std::string text = test::read_file(test::source_path("assets/scenes/cbox_milk.json"));
    const std::string ball = R"({"type": "sphere", "center": [278, 130, 280], "radius": 130, "material": "milk_glass"})";
    REQUIRE(text.find(ball) != std::string::npos);
    std::string csg = text;
    csg.replace(csg.find(ball), ball.size(),
                R"({"type": "csg", "op": "union", "material": "milk_glass", "operands": [
                    {"type": "sphere", "center": [278, 130, 280], "radius": 130},
                    {"type": "sphere", "center": [278, 100, 250], "radius": 60}]})");
    const std::string path = test::source_path("assets/scenes/cbox_milk.json");
    Scene plain = parse_json_scene(text, path), united = parse_json_scene(csg, path);
    plain.film_width = plain.film_height = united.film_width = united.film_height = 24;
    plain.camera.aspect = united.camera.aspect = 1;
    RenderSettings settings;
    settings.spp = 4;
    settings.max_depth = 16;
    Stages stages = make_stages(StageSet::none());
    auto integrator = make_volpath_integrator();
    RenderResult a = test::render_with(plain, *integrator, settings, stages, 2);
    RenderResult b = test::render_with(united, *integrator, settings, stages, 2);
    CHECK(a.image.data() == b.image.data());
    double sum = 0;
    for (float v : a.image.data()) sum += v;
    CHECK(sum > 0);  // light does reach the film
}
