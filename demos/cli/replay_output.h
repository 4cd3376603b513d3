#pragma once
/// The run's replay and glTF outputs: frames recorded at a fixed rate into memory, written as a
/// replay file (docs/replay.md) and/or converted to an animated glTF at the end.

#include <memory>
#include <sstream>
#include <string>

#include "tumble/replay/replay.h"
#include "tumble/scene/scene.h"

namespace tumble::cli {

class ReplayOutput {
public:
    /// Nothing is recorded when both paths are empty. Refuses (InvalidArgument) a path that
    /// cannot be written or a rate that is not > 0, before the first step.
    ReplayOutput(const std::string& replayPath, const std::string& gltfPath, Real rate,
                 const Scene& scene, const BuiltScene& built);
    /// Records a frame when the world's time has reached the next multiple of 1 / rate.
    void sample(const World& world);
    /// Writes the files.
    void finish();

private:
    std::string replayPath_, gltfPath_;
    Real period_ = 0;
    Real next_ = 0;
    std::ostringstream bytes_;
    std::unique_ptr<ReplayWriter> writer_;
};

}  // namespace tumble::cli
