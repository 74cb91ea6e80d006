// Stages: the switch between reference and student code, one function
// table per stage, filled once at start-up (DESIGN.md "The stages and the
// switch"). Every call from the engine into a staged function goes through
// this table, so `--student LIST` decides at run time whose code runs.
//
// On the all-reference path the table costs nothing measurable: its
// functions are called per pixel or per shading point, and the one call per
// primitive test (intersect) is bypassed by the reference accelerators,
// which call the reference routines directly when `intersect` is not a
// student stage.
#pragma once

#include "stages/accelerator.h"
#include "stages/adaptive.h"
#include "stages/bvh.h"
#include "stages/uniform_grid.h"
#include "stages/camera.h"
#include "stages/direct.h"
#include "stages/global.h"
#include "stages/intersect.h"
#include "stages/bdpt.h"
#include "stages/media.h"
#include "stages/photon.h"
#include "stages/sampler.h"
#include "stages/stage_set.h"

namespace pt {

struct Scene;

/// The acceleration structure (`--accel`).
enum class AccelKind {
    none,    ///< linear scan: every primitive for every ray
    grid,    ///< uniform grid, 3D-DDA (stages/uniform_grid.h)
    kdtree,  ///< SAH kd-tree (stages/kd_tree.h)
    bvh,     ///< the bvh stage: the reference BVH, or the student's (Part 2)
    embree,  ///< Embree 3, when built with -DPT_WITH_EMBREE=ON (stages/embree_accel.h)
};

/// "none", "grid", "kdtree", "bvh", "embree"; otherwise InputError naming `flag`.
AccelKind parse_accel_kind(const std::string& name, const std::string& flag = "--accel");
const char* to_string(AccelKind kind);

/// How the accelerator is built (`--accel`, `--bvh-split`, `--max-leaf`).
struct AcceleratorSettings {
    AccelKind kind = AccelKind::bvh;  ///< `--accel`
    std::string split = "sah";  ///< sah | median | middle
    int max_leaf = 4;          ///< at most this many primitives per leaf when a split is possible
    /// `--bvh-width`: children per node of the reference BVH: 2 (the binary
    /// tree), 4 (collapsed, SSE) or 8 (collapsed, AVX2 where the processor
    /// has it; stages/bvh_wide.h). The student's tree is binary. The default
    /// is the fastest measured (docs/bvh.md).
    int width = 8;
    /// Wide BVH box tests with SIMD instructions where available; false: the
    /// portable scalar loop, same answers (tests compare the two).
    bool simd = true;
};

using BuildAcceleratorFn = std::unique_ptr<Accelerator> (*)(const Scene& scene,
                                                            const IntersectStage& intersect,
                                                            const AcceleratorSettings& settings);

struct BvhStage {
    /// Builds the scene's BVH; its queries must use `intersect`'s routines.
    BuildAcceleratorFn build;
    /// The four handout functions of the same side (student or reference),
    /// one by one: the grader builds and queries student-style trees with
    /// them (make_tree_bvh), so that each is graded on its own.
    BvhFunctions tree;
    /// Part 2's optional task 6: the grid's closest-hit walk, used by
    /// `--accel grid` (stages/uniform_grid.h).
    GridIntersectFn grid_intersect = reference::grid_intersect;
};

struct Stages {
    StageSet student;  ///< the stages that run student code
    CameraStage camera;
    IntersectStage intersect;
    BvhStage bvh;
    AdaptiveStage adaptive;
    DirectStage direct;
    GlobalStage global;
    SamplerStage sampler;
    MediaStage media;
    PhotonStage photon;
    BdptStage bdpt;

    bool is_student(Stage s) const { return student.contains(s); }
};

/// The reference triangle test (`--triangle`): Moller-Trumbore, or the
/// watertight test of Woop et al. (stages/intersect_watertight.cpp).
enum class TriangleTest { moller, watertight };

/// The function tables with student code for the stages in `student`; the
/// reference intersect stage uses `triangle_test` for triangles.
Stages make_stages(StageSet student, TriangleTest triangle_test = TriangleTest::moller);

/// The scene's accelerator: the linear scan for `--accel none`, the grid,
/// the kd-tree, Embree, or (`--accel bvh`) the bvh stage's.
std::unique_ptr<Accelerator> build_accelerator(const Scene& scene, const Stages& stages,
                                               const AcceleratorSettings& settings);

}  // namespace pt
