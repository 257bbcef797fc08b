#pragma once
// The six sides of the "bent thin cuboid" a facial soft-tissue model resembles (paper 3.1, 3.3).
// Each parameterization field runs from 0 on one side to 1 on the opposite side:
//   u: u0 = lateral side at -x of the model frame,  u1 = lateral side at +x
//   v: v0 = bottom cut (below the chin),             v1 = top cut (forehead)
//   w: w0 = inner side (on the bone),                w1 = outer side (the skin)
// In the CT default frame (+y anterior, +z superior) and in the bundled standard's frame, -x and +x are the two
// lateral ends of the face; which one is the patient's anatomical left depends on the scan's handedness, so the
// names never claim it.
//
// A vertex may lie on several sides (on the crease between two sides, or a corner): side membership is a bitmask,
// stored on meshes as the point-data array "side_mask" (bit s set <=> the vertex is on side s).
#include <array>
#include <optional>
#include <string>

namespace facehex {

enum Side : int { U0 = 0, U1 = 1, V0 = 2, V1 = 3, W0 = 4, W1 = 5, kNumSides = 6 };

constexpr std::array<const char*, kNumSides> kSideNames = {"u0", "u1", "v0", "v1", "w0", "w1"};
constexpr std::array<const char*, kNumSides> kSideDescriptions = {
    "lateral end at -x", "lateral end at +x", "bottom cut", "top cut", "inner side (bone)", "outer side (skin)"};

// Field index (0=u, 1=v, 2=w) and the Dirichlet value (0 or 1) a side imposes.
inline int side_field(Side s) { return static_cast<int>(s) / 2; }
inline double side_value(Side s) { return static_cast<double>(static_cast<int>(s) % 2); }
inline int side_bit(Side s) { return 1 << static_cast<int>(s); }

std::optional<Side> side_from_name(const std::string& name);

constexpr const char* kSideMaskArray = "side_mask";

}  // namespace facehex
