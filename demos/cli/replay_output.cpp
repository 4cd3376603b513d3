#include "replay_output.h"

#include <cmath>
#include <fstream>

namespace tumble::cli {
namespace {

void checkWritable(const std::string& path, const char* what) {
    if (!path.empty() && !std::ofstream(path, std::ios::binary))
        fail(what, " file \"", path, "\" cannot be written");
}

}  // namespace

ReplayOutput::ReplayOutput(const std::string& replayPath, const std::string& gltfPath, Real rate,
                           const Scene& scene, const BuiltScene& built)
    : replayPath_(replayPath), gltfPath_(gltfPath) {
    if (replayPath.empty() && gltfPath.empty())
        return;
    if (!(rate > 0) || !std::isfinite(rate))
        fail("--replay-rate = ", rate, " must be > 0 (Hz)");
    checkWritable(replayPath, "replay");
    checkWritable(gltfPath, "glTF");
    ReplayContent content;
    content.bodies = built.bodies;
    for (const BodySpec& body : scene.bodies)
        content.names.push_back(body.name);
    content.springs = built.springs;
    content.joints = built.joints;
    content.gravityScale = built.gravityScale;
    content.title = scene.name;
    writer_ = std::make_unique<ReplayWriter>(bytes_, built.world, std::move(content));
    period_ = 1 / rate;
    next_ = built.world.time();
}

void ReplayOutput::sample(const World& world) {
    // Within a fraction of a step of the frame's time, so 60 Hz of 1/240 s steps is every 4th.
    if (!writer_ || world.time() < next_ - 1e-6 * world.settings().timeStep)
        return;
    writer_->addFrame(world);
    next_ = period_ * (std::floor(world.time() / period_ + 1e-6) + 1);
}

void ReplayOutput::finish() {
    if (!writer_)
        return;
    writer_->finish();
    if (!replayPath_.empty()) {
        std::ofstream file(replayPath_, std::ios::binary);
        file << bytes_.str();
        if (!file)
            fail("replay file \"", replayPath_, "\" could not be written");
    }
    if (!gltfPath_.empty())
        writeGltf(readReplayBytes(bytes_.str(), "the run's replay"), gltfPath_);
}

}  // namespace tumble::cli
