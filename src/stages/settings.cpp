#include "stages/settings.h"

namespace pt {

const char* to_string(DirectStrategy s) {
    switch (s) {
        case DirectStrategy::light: return "light";
        case DirectStrategy::hemisphere: return "hemisphere";
        case DirectStrategy::mis: return "mis";
    }
    return "?";
}

const char* to_string(AdaptiveRule r) {
    switch (r) {
        case AdaptiveRule::split: return "split";
        case AdaptiveRule::cs184: return "cs184";
    }
    return "?";
}

const char* to_string(MisHeuristic h) {
    switch (h) {
        case MisHeuristic::power: return "power";
        case MisHeuristic::balance: return "balance";
    }
    return "?";
}

const char* to_string(IntegratorKind k) {
    switch (k) {
        case IntegratorKind::automatic: return "auto";
        case IntegratorKind::normals: return "normals";
        case IntegratorKind::depth: return "depth";
        case IntegratorKind::whitted: return "whitted";
        case IntegratorKind::direct: return "direct";
        case IntegratorKind::path: return "path";
        case IntegratorKind::volpath: return "volpath";
        case IntegratorKind::bdpt: return "bdpt";
        case IntegratorKind::pm: return "pm";
        case IntegratorKind::sppm: return "sppm";
    }
    return "?";
}

const char* to_string(PhotonKernel k) {
    switch (k) {
        case PhotonKernel::box: return "box";
        case PhotonKernel::cone: return "cone";
        case PhotonKernel::epanechnikov: return "epanechnikov";
    }
    return "?";
}

const char* to_string(PhotonView v) {
    switch (v) {
        case PhotonView::none: return "none";
        case PhotonView::caustic: return "caustic";
        case PhotonView::global: return "global";
    }
    return "?";
}

}  // namespace pt
