// The replay reader: checks the magic, the version and that every record lies wholly inside the
// file, so a cut-off file is refused by name rather than read as fewer frames.

#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "replay_format.h"
#include "tumble/core/error.h"
#include "tumble/replay/replay.h"

namespace tumble {
namespace {

class Cursor {
public:
    Cursor(const std::string& bytes, const std::string& name) : bytes_(bytes), name_(name) {}

    /// Copies `size` bytes to `to`, refusing a file that ends before them.
    void read(void* to, std::size_t size, const char* what) {
        if (size == 0)  // an empty vector's data() may be null, which memcpy must not see
            return;
        if (size > bytes_.size() - at_)
            fail(name_, ": truncated replay: ", what, " needs ", size, " bytes at byte ", at_,
                 ", the file has ", bytes_.size());
        std::memcpy(to, bytes_.data() + at_, size);
        at_ += size;
    }
    std::uint32_t word(const char* what) {
        std::uint32_t w = 0;
        read(&w, sizeof w, what);
        return w;
    }
    template <typename T>
    void read(std::vector<T>& to, std::size_t count, const char* what) {
        to.resize(count);
        read(to.data(), count * sizeof(T), what);
    }
    std::size_t at() const { return at_; }
    bool done() const { return at_ == bytes_.size(); }

private:
    const std::string& bytes_;
    const std::string& name_;
    std::size_t at_ = 0;
};

ReplayFrame readFrame(Cursor& in, const Replay& r, bool tensions) {
    ReplayFrame f;
    in.read(&f.time, sizeof f.time, "a frame's time");
    in.read(f.energy.data(), sizeof f.energy, "a frame's energy");
    const std::uint32_t contacts = in.word("a frame's contact count");
    std::vector<float> poses;
    in.read(poses, static_cast<std::size_t>(r.bodyCount) * replay::kPoseFloats, "a frame's poses");
    f.poses.resize(r.bodyCount);
    for (int i = 0; i < r.bodyCount; ++i) {
        const float* p = poses.data() + i * replay::kPoseFloats;
        ReplayPose& pose = f.poses[i];
        std::copy(p, p + 3, pose.position.begin());
        std::copy(p + 3, p + 7, pose.orientation.begin());
        std::copy(p + 7, p + 10, pose.velocity.begin());
        pose.kineticEnergy = p[10];
    }
    if (tensions)
        in.read(f.tensions, r.springCount, "a frame's tensions");
    std::vector<float> points;
    in.read(points, static_cast<std::size_t>(contacts) * replay::kContactFloats,
            "a frame's contacts");
    f.contacts.resize(contacts);
    for (std::uint32_t k = 0; k < contacts; ++k) {
        const float* p = points.data() + k * replay::kContactFloats;
        std::copy(p, p + 3, f.contacts[k].point.begin());
        std::copy(p + 3, p + 6, f.contacts[k].normal.begin());
        f.contacts[k].force = p[6];
    }
    return f;
}

}  // namespace

Replay readReplayBytes(const std::string& bytes, const std::string& name) {
    Cursor in(bytes, name);
    char magic[sizeof replay::kMagic];
    if (bytes.size() < sizeof magic || (in.read(magic, sizeof magic, "the magic"),
                                        std::memcmp(magic, replay::kMagic, sizeof magic) != 0))
        fail(name, ": not a Tumble replay file (it does not start with \"TUMBLERP\")");
    Replay r;
    r.version = in.word("the version");
    if (r.version != kReplayVersion)
        fail(name, ": replay version ", r.version, " is not supported: this build reads version ",
             kReplayVersion, " (write it again with this build's tumble run --replay)");
    r.description.resize(in.word("the description's length"));
    in.read(r.description.data(), r.description.size(), "the description");
    const nlohmann::json d = nlohmann::json::parse(r.description, nullptr, false);
    if (d.is_discarded() || !d.contains("bodies") || !d.contains("springs"))
        fail(name, ": the replay's description is not the JSON docs/replay.md describes");
    r.bodyCount = static_cast<int>(d["bodies"].size());
    r.springCount = static_cast<int>(d["springs"].size());
    const bool tensions = d["frame"].value("tensions", false);
    for (;;) {
        const std::uint32_t tag = in.word("a frame or the end record (the run was cut off?)");
        if (tag == replay::kEndTag)
            break;
        if (tag != replay::kFrameTag)
            fail(name, ": byte ", in.at() - 4, " holds neither a frame nor the end record");
        r.frames.push_back(readFrame(in, r, tensions));
    }
    const std::uint32_t count = in.word("the end record's frame count");
    if (count != r.frames.size() || !in.done())
        fail(name, ": the end record counts ", count, " frames; the file holds ", r.frames.size(),
             in.done() ? "" : " and bytes after the end record");
    return r;
}

Replay readReplay(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    if (!file)
        fail("replay file \"", path, "\" cannot be read");
    std::ostringstream bytes;
    bytes << file.rdbuf();
    return readReplayBytes(bytes.str(), path);
}

}  // namespace tumble
