#include "stages/stage_set.h"

#include <sstream>

#include "core/error.h"

namespace pt {

const char* to_string(Stage stage) {
    switch (stage) {
        case Stage::camera: return "camera";
        case Stage::intersect: return "intersect";
        case Stage::bvh: return "bvh";
        case Stage::direct: return "direct";
        case Stage::global: return "global";
        case Stage::adaptive: return "adaptive";
        case Stage::sampler: return "sampler";
        case Stage::photon: return "photon";
        case Stage::media: return "media";
        case Stage::bdpt: return "bdpt";
    }
    return "?";
}

int part_of(Stage stage) {
    switch (stage) {
        case Stage::camera:
        case Stage::intersect: return 1;
        case Stage::bvh: return 2;
        case Stage::direct: return 3;
        case Stage::global: return 4;
        case Stage::adaptive: return 5;
        case Stage::sampler: return 6;
        case Stage::photon: return 8;
        case Stage::media: return 9;
        case Stage::bdpt: return 7;
    }
    return 0;
}

StageSet StageSet::of_part(int part) {
    StageSet set;
    for (int i = 0; i < kStageCount; ++i)
        if (part_of(Stage(i)) == part) set = set.with(Stage(i));
    return set;
}

StageSet StageSet::parse(const std::string& list, const std::string& flag) {
    if (list == "all") return all();
    if (list == "none") return none();
    StageSet set;
    std::stringstream in(list);
    std::string name;
    while (std::getline(in, name, ',')) {
        bool found = false;
        for (int i = 0; i < kStageCount; ++i) {
            if (name == pt::to_string(Stage(i))) {
                set = set.with(Stage(i));
                found = true;
            }
        }
        if (!found)
            throw InputError(flag + ": unknown stage '" + name +
                             "' (expected a comma-separated list of camera, intersect, bvh, direct, "
                             "global, adaptive, sampler, photon, media, bdpt, or 'all' or 'none')");
    }
    if (set.empty()) throw InputError(flag + ": empty stage list (use 'none' for no student stages)");
    return set;
}

std::string StageSet::to_string() const {
    std::string out;
    for (int i = 0; i < kStageCount; ++i)
        if (contains(Stage(i))) out += (out.empty() ? "" : ",") + std::string(pt::to_string(Stage(i)));
    return out.empty() ? "none" : out;
}

}  // namespace pt
