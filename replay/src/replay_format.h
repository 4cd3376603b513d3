#pragma once
// The replay file's fixed words (docs/replay.md), shared by the writer and the reader. The file
// is little-endian, as the hosts Tumble builds on and the browsers reading it are.

#include <bit>
#include <cstdint>
#include <ostream>

namespace tumble::replay {

static_assert(std::endian::native == std::endian::little, "replay files are little-endian");

inline constexpr char kMagic[8] = {'T', 'U', 'M', 'B', 'L', 'E', 'R', 'P'};
inline constexpr std::uint32_t kFrameTag = 0x4D415246;  // "FRAM" in the file
inline constexpr std::uint32_t kEndTag = 0x21444E45;    // "END!"
inline constexpr int kPoseFloats = 11;    // position 3, quaternion x y z w, velocity 3, energy
inline constexpr int kContactFloats = 7;  // point 3, normal 3, normal force
inline constexpr int kFrameHeaderBytes = 4 + 8 + 12 + 4;  // tag, time, energy, contact count

inline void writeWord(std::ostream& out, std::uint32_t word) {
    out.write(reinterpret_cast<const char*>(&word), sizeof word);
}

}  // namespace tumble::replay
