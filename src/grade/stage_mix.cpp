#include "grade/stage_mix.h"

#include "core/error.h"

namespace pt {
namespace {

// One entry per slot: which stage it belongs to and how to copy it. When a
// part lands with new stages or functions, add their slots here.
struct Slot {
    const char* name;
    Stage stage;
    void (*copy)(Stages& to, const Stages& from);
};

const Slot kSlots[] = {
    {"camera", Stage::camera, [](Stages& to, const Stages& from) { to.camera = from.camera; }},
    {"camera.generate_ray", Stage::camera,
     [](Stages& to, const Stages& from) { to.camera.generate_ray = from.camera.generate_ray; }},
    {"camera.raytrace_pixel", Stage::camera,
     [](Stages& to, const Stages& from) { to.camera.raytrace_pixel = from.camera.raytrace_pixel; }},
    {"intersect", Stage::intersect,
     [](Stages& to, const Stages& from) { to.intersect = from.intersect; }},
    {"intersect.intersect_triangle", Stage::intersect,
     [](Stages& to, const Stages& from) {
         to.intersect.intersect_triangle = from.intersect.intersect_triangle;
     }},
    {"intersect.intersect_sphere", Stage::intersect,
     [](Stages& to, const Stages& from) {
         to.intersect.intersect_sphere = from.intersect.intersect_sphere;
     }},
    {"bvh", Stage::bvh, [](Stages& to, const Stages& from) { to.bvh = from.bvh; }},
    {"global", Stage::global, [](Stages& to, const Stages& from) { to.global = from.global; }},
    {"global.at_least_one_bounce_radiance", Stage::global,
     [](Stages& to, const Stages& from) {
         to.global.at_least_one_bounce_radiance = from.global.at_least_one_bounce_radiance;
     }},
    {"global.est_radiance_global_illumination", Stage::global,
     [](Stages& to, const Stages& from) {
         to.global.est_radiance_global_illumination = from.global.est_radiance_global_illumination;
     }},
};

}  // namespace

std::vector<std::string> known_slots() {
    std::vector<std::string> names;
    for (const Slot& s : kSlots)
        names.push_back(s.name);
    return names;
}

Stages mix_stages(const Stages& reference, const Stages& student,
                  const std::vector<std::string>& slots, const std::string& where) {
    Stages mixed = reference;
    StageSet set = StageSet::none();
    for (const std::string& name : slots) {
        const Slot* found = nullptr;
        for (const Slot& s : kSlots)
            if (name == s.name) found = &s;
        if (!found) {
            std::string list;
            for (const std::string& n : known_slots())
                list += (list.empty() ? "" : ", ") + n;
            throw InputError(where + ": unknown student function \"" + name + "\" (known: " + list +
                             ")");
        }
        found->copy(mixed, student);
        set = set.with(found->stage);
    }
    mixed.student = set;
    return mixed;
}

}  // namespace pt
