#pragma once
/// Checkpoint and resume: the whole state of a World -- bodies, shapes, materials, joints,
/// springs, drag, controllers, the triangle meshes and height fields the shapes carry, the contact
/// cache with its warm-start impulses, the broadphase, sleep timers, pending events, settings, time
/// and step count -- written to a versioned binary file and read back. A world loaded from a
/// checkpoint steps bitwise-identically to the world that was saved (same build; see
/// docs/checkpoint.md for the format and its limits).
///
/// Not saved: the pre-step callback (the application's code; a loaded world keeps its own) and
/// the stage timings of the last step.

#include <cstdint>
#include <filesystem>
#include <span>
#include <string_view>
#include <vector>

#include "tumble/world.h"

namespace tumble {

/// Format version written by this build; files of any other version are refused.
inline constexpr std::uint32_t kCheckpointVersion = 14;

/// The checkpoint of `world` as bytes (header and payload, as written to a file).
std::vector<std::uint8_t> checkpointBytes(const World& world);

/// Replaces the state of `world` with the checkpoint in `bytes`. A truncated, corrupted or
/// wrong-version checkpoint is refused (InvalidArgument naming `source` and what is wrong) and
/// leaves `world` untouched: the state is read into a fresh world and swapped in only on
/// success. Refused from inside the pre-step callback.
void restoreCheckpoint(World& world, std::span<const std::uint8_t> bytes,
                       std::string_view source = "checkpoint");

/// Writes the checkpoint of `world` to `file`: to `file`.tmp first, flushed and closed, then
/// renamed onto `file`, so a crash mid-write leaves any previous checkpoint intact. Refuses
/// (InvalidArgument) a file that cannot be written.
void saveCheckpoint(const World& world, const std::filesystem::path& file);

/// Reads a checkpoint file into `world` (see restoreCheckpoint). Refuses (InvalidArgument) a
/// file that cannot be read.
void loadCheckpoint(World& world, const std::filesystem::path& file);

}  // namespace tumble
