#pragma once
/// Replay files: a recorded run (the scene's static description and, per frame, every body's
/// pose) for the browser viewer (viewer/) and the glTF export. The layout is in docs/replay.md.
///
/// Writing reads the world through its public API only; an application records a run with
///     ReplayWriter replay(file, world);   // the description, from the world as it is now
///     replay.addFrame(world);             // after each step it wants to keep
///     replay.finish();                    // the end record; without it the file is truncated

#include <array>
#include <cstdint>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include "tumble/world.h"

namespace tumble {

/// What a replay holds besides every body's pose. The lists default to the whole world.
struct ReplayContent {
    /// Bodies in the order the file lists them; empty: World::bodies().
    std::vector<BodyId> bodies;
    /// Names of `bodies` (the same length), or empty.
    std::vector<std::string> names;
    /// Springs and threads; empty: every spring attached to a listed body.
    std::vector<SpringId> springs;
    /// Joints; empty: every joint attached to a listed body.
    std::vector<JointId> joints;
    /// Per body, its gravity scale for the potential energy (-m s g.c); empty: 1 for all.
    std::vector<Real> gravityScale;
    std::string title;     ///< shown by the viewer (a scene name)
    bool contacts = true;  ///< per frame: touching contact points with their normal force
    bool tensions = true;  ///< per frame: every spring's tension (N)
};

/// Writes a replay file, frame by frame. Setup problems (a file that cannot be written, an id
/// that is not valid, lists of different lengths) are refused with InvalidArgument.
class ReplayWriter {
public:
    /// Opens `path` and writes the description of `world` as it is now (shapes, masses,
    /// springs, joints); frames follow with addFrame.
    ReplayWriter(const std::string& path, const World& world, ReplayContent content = {});
    /// Writes to `out` (a file or a string stream) instead; `out` must outlive the writer.
    ReplayWriter(std::ostream& out, const World& world, ReplayContent content = {});
    ~ReplayWriter();
    ReplayWriter(const ReplayWriter&) = delete;
    ReplayWriter& operator=(const ReplayWriter&) = delete;

    /// Appends the world's state: time, poses, velocities, energies, tensions and contacts.
    void addFrame(const World& world);
    /// Writes the end record (frame count); a file without it is refused as truncated.
    /// Called by the destructor when not called before.
    void finish();
    int frameCount() const { return frames_; }

private:
    void writeDescription(const World& world);

    std::ostream* out_ = nullptr;
    std::unique_ptr<std::ostream> file_;
    ReplayContent content_;
    std::vector<float> buffer_;
    int frames_ = 0;
    bool finished_ = false;
};

/// A contact point of one frame: where, the normal (from body A to body B) and the normal
/// force of the last step (N).
struct ReplayContact {
    std::array<float, 3> point{};
    std::array<float, 3> normal{};
    float force = 0;
};

/// One body's state in a frame.
struct ReplayPose {
    std::array<float, 3> position{};     ///< body origin (m)
    std::array<float, 4> orientation{};  ///< quaternion x, y, z, w
    std::array<float, 3> velocity{};     ///< of the centre of mass (m/s)
    float kineticEnergy = 0;             ///< (J)
};

struct ReplayFrame {
    double time = 0;                      ///< (s)
    std::array<float, 3> energy{};        ///< kinetic, potential, elastic (J)
    std::vector<ReplayPose> poses;        ///< one per body, in the description's order
    std::vector<float> tensions;          ///< one per spring (N), or none
    std::vector<ReplayContact> contacts;  ///< touching points, or none
};

/// A replay read back: the description (JSON text, docs/replay.md) and the frames.
struct Replay {
    std::uint32_t version = 0;
    std::string description;
    int bodyCount = 0;
    int springCount = 0;
    std::vector<ReplayFrame> frames;
};

constexpr std::uint32_t kReplayVersion = 1;  ///< the version this build writes and reads

/// Reads a replay file. A file that is not a replay, of another version, or truncated is
/// refused with InvalidArgument naming the file and what is wrong.
Replay readReplay(const std::string& path);
/// Reads replay bytes (`name` names them in messages).
Replay readReplayBytes(const std::string& bytes, const std::string& name);

/// Writes the replay as an animated binary glTF 2.0 (.glb): a node per body with translation
/// and rotation channels, a mesh per shape, threads as a line mesh skinned to their bodies.
/// +Z up in Tumble becomes glTF's +Y up through a root node. Refuses an unwritable path.
void writeGltf(const Replay& replay, const std::string& path);

}  // namespace tumble
