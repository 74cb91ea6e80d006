// Options: the command line of pathtracer and part1..part5 (DESIGN.md
// "Command line", CS184-compatible), parsed strictly: a bad value gets one
// message naming the flag and what it expected, and exit code 2.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "image/tone_map.h"
#include "render/renderer.h"
#include "stages/settings.h"
#include "stages/stage_set.h"
#include "stages/stages.h"

namespace pt {

/// The sampler of pathtracer and partN when --sampler is not given: the
/// one that reached a given error soonest (docs/sampling.md).
constexpr SamplerKind kDefaultSampler = SamplerKind::zsobol;

struct Options {
    std::string scene_path;            ///< SCENE.json or MESH.obj
    RenderSettings render;             ///< -s -a -l -m -o -H --direct --integrator --seed --rr-depth --clamp
    AcceleratorSettings accelerator;   ///< --accel --bvh-split --max-leaf
    StageSet student;                  ///< --student
    int threads = 1;                   ///< -t (default: all hardware threads)
    std::string output;                ///< -f FILE.png|FILE.exr; empty = "<scene name>.png"
    std::string hdr_output;            ///< --hdr FILE.pfm|FILE.exr
    std::string bdpt_strategies;       ///< --bdpt-strategies DIR (bdpt); empty: none
    int bdpt_strategy_depth = -1;      ///< --bdpt-strategy-depth N; -1: min(-m, 3)
    DisplaySettings display;           ///< --tonemap, --exposure (the PNG only)
    std::string stats_output;          ///< --stats FILE.json
    std::string environment_map;       ///< -e FILE
    std::optional<std::pair<int, int>> resolution;  ///< -r W H
    std::optional<PixelRect> cell;     ///< -p X Y DX DY
    std::optional<double> lens_radius;     ///< -b
    std::optional<double> focal_distance;  ///< -d
    bool quiet = false;                ///< -q
    std::string triangle_test = "moller";  ///< --triangle moller|watertight
    std::optional<std::string> bvh_view;   ///< --bvh-view PATH
    std::string bvh_depth_image;           ///< --bvh-depth-image FILE.png
    bool packets = true;  ///< --packets on|off (render/camera_packets.h); on: faster where it applies (docs/accel.md)
    bool help = false;                 ///< -h / --help
};

/// Parses argv[1..]; `student` is the executable's default for --student.
/// Throws InputError for unknown flags, missing or bad values.
Options parse_options(const std::vector<std::string>& args, StageSet default_student);

/// The --help text of a renderer executable.
std::string usage(const std::string& program, StageSet default_student);

}  // namespace pt
