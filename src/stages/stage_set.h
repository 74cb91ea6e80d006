// StageSet: which of the staged modules run student code.
//
// `--student LIST` takes a comma-separated list of stage names, or `all` or
// `none`. Part N's executable defaults to the stages of part N.
#pragma once

#include <cstdint>
#include <string>

namespace pt {

enum class Stage : uint8_t { camera, intersect, bvh, direct, global, adaptive, sampler, photon, media, bdpt };
constexpr int kStageCount = 10;

const char* to_string(Stage stage);
/// The course part (1 to 9) a stage belongs to.
int part_of(Stage stage);

class StageSet {
public:
    StageSet() = default;
    static StageSet none() { return {}; }
    static StageSet all() { return StageSet(uint16_t((1u << kStageCount) - 1)); }
    /// The stages of course part `part` (1 to 9; none for a part without a stage).
    static StageSet of_part(int part);
    /// Parses "camera,intersect", "all" or "none"; throws InputError naming `flag`.
    static StageSet parse(const std::string& list, const std::string& flag = "--student");

    bool contains(Stage s) const { return bits_ & bit(s); }
    StageSet with(Stage s) const { return StageSet(uint16_t(bits_ | bit(s))); }
    bool empty() const { return bits_ == 0; }
    bool operator==(const StageSet& o) const { return bits_ == o.bits_; }
    /// "camera,intersect", or "none".
    std::string to_string() const;

private:
    explicit StageSet(uint16_t bits) : bits_(bits) {}
    static uint16_t bit(Stage s) { return uint16_t(1u << unsigned(s)); }
    uint16_t bits_ = 0;  ///< one bit per Stage (room for 16)
};

}  // namespace pt
