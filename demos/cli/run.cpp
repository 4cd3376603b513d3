// The headless step loop. Output files are opened before the first step so that a bad path is
// bad input (status 2) rather than a lost run; the summary and picture are written at the end,
// also after a failed step, because a failure is exactly when a person wants to look.

#include "run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <ostream>

#include "replay_output.h"
#include "svg.h"
#include "tumble/checkpoint.h"

namespace tumble::cli {
namespace {

using Clock = std::chrono::steady_clock;

std::unique_ptr<std::ofstream> openOutput(const std::string& path, const char* what) {
    if (path.empty())
        return nullptr;
    auto file = std::make_unique<std::ofstream>(path);
    if (!*file)
        fail(what, " file \"", path, "\" cannot be written");
    return file;
}

void writeCsvHeader(std::ostream& csv) {
    csv << "time,body,name,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz\n";
}

/// One row per recorded body: `selected`, or every non-static body when it is empty.
void writeCsvRows(std::ostream& csv, const Scene& scene, const BuiltScene& built,
                  const std::vector<int>& selected) {
    const World& w = built.world;
    char line[512];
    const std::size_t count = selected.empty() ? built.bodies.size() : selected.size();
    for (std::size_t k = 0; k < count; ++k) {
        const std::size_t i = selected.empty() ? k : static_cast<std::size_t>(selected[k]);
        const BodyId b = built.bodies[i];
        if (selected.empty() && w.bodyType(b) == BodyType::Static)
            continue;
        const Vec3 p = w.position(b);
        const Quat q = w.orientation(b);
        const Vec3 v = w.linearVelocity(b);
        const Vec3 a = w.angularVelocity(b);
        std::snprintf(line, sizeof line,
                      "%.6f,%zu,%s,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,"
                      "%.9g\n",
                      w.time(), i, scene.bodies[i].name.c_str(), p.x(), p.y(), p.z(), q.w(), q.x(),
                      q.y(), q.z(), v.x(), v.y(), v.z(), a.x(), a.y(), a.z());
        csv << line;
    }
}

/// "[#####.....]  45%  t = 1.35 s" on one terminal line, redrawn in place.
class Progress {
public:
    Progress(bool enabled, Real duration) : enabled_(enabled), duration_(duration) {}
    void update(Real time, double elapsed) {
        // Only runs long enough to wait for (> ~2 s expected) get a bar, redrawn at 10 Hz.
        if (!enabled_ || elapsed < 0.5 || elapsed < lastDraw_ + 0.1)
            return;
        const double fraction = std::clamp(time / duration_, 0.0, 1.0);
        if (!shown_ && elapsed / std::max(fraction, 1e-9) < 2)
            return;
        shown_ = true;
        lastDraw_ = elapsed;
        const int filled = static_cast<int>(fraction * 30);
        std::printf("\r[%s%s] %3d%%  t = %.2f s", std::string(filled, '#').c_str(),
                    std::string(30 - filled, '.').c_str(), static_cast<int>(fraction * 100), time);
        std::fflush(stdout);
    }
    void clear() {
        if (shown_) {
            std::printf("\r\033[K");
            std::fflush(stdout);
        }
    }

private:
    bool enabled_;
    Real duration_;
    bool shown_ = false;
    double lastDraw_ = 0;
};

void printSummary(std::ostream& out, const Summary& s) {
    char buf[160];
    auto row = [&](const char* name, const char* fmt, auto value) {
        std::snprintf(buf, sizeof buf, fmt, value);
        out << "  " << name << std::string(24 - std::string(name).size(), ' ') << buf << "\n";
    };
    out << "scene " << s.scene << ": " << s.status << "\n";
    row("steps", "%llu", static_cast<unsigned long long>(s.steps));
    row("simulated time (s)", "%.4g", s.simulatedTime);
    row("wall time (s)", "%.4g", s.wallTime);
    row("real-time factor", "%.4g", s.realTimeFactor);
    row("bodies", "%d", s.bodies);
    row("asleep at the end", "%d", s.bodiesAsleep);
    std::snprintf(buf, sizeof buf, "  %-24s%12s %12s %12s %12s\n", "energy (J)", "kinetic",
                  "potential", "elastic", "total");
    out << buf;
    for (const auto& [label, e] : {std::pair{"  start", s.start}, std::pair{"  end", s.end}}) {
        std::snprintf(buf, sizeof buf, "  %-24s%12.5g %12.5g %12.5g %12.5g\n", label, e.kinetic,
                      e.potential, e.elastic, e.total());
        out << buf;
    }
    row("deepest penetration (m)", "%.3g", s.deepestPenetration);
    row("last residual (m/s)", "%.3g", s.lastResidual);
}

}  // namespace

Energy energyOf(const BuiltScene& built) {
    const World& w = built.world;
    Energy e;
    e.kinetic = w.kineticEnergy();
    e.elastic = w.springPotentialEnergy();
    const Vec3 g = w.settings().gravity;
    for (std::size_t i = 0; i < built.bodies.size(); ++i) {
        const BodyId b = built.bodies[i];
        if (w.bodyType(b) == BodyType::Dynamic)
            e.potential -=
                w.massProperties(b).mass * built.gravityScale[i] * g.dot(w.centerOfMass(b));
    }
    return e;
}

std::vector<std::string> nonFiniteFigures(const Summary& s) {
    std::vector<std::pair<std::string, Real>> figures{{"simulatedTime", s.simulatedTime},
                                                      {"wallTime", s.wallTime},
                                                      {"realTimeFactor", s.realTimeFactor},
                                                      {"deepestPenetration", s.deepestPenetration},
                                                      {"lastSolverResidual", s.lastResidual}};
    for (const auto& [name, e] : {std::pair{"start", s.start}, std::pair{"end", s.end}}) {
        const std::string at = std::string("energy.") + name + ".";
        figures.insert(figures.end(), {{at + "kinetic", e.kinetic},
                                       {at + "potential", e.potential},
                                       {at + "elastic", e.elastic},
                                       {at + "total", e.total()}});
    }
    std::vector<std::string> out;
    for (const auto& [name, value] : figures) {
        if (!std::isfinite(value))
            out.push_back(name);
    }
    return out;
}

std::string summaryJson(const Summary& s) {
    auto energy = [](const Energy& e) {
        return nlohmann::ordered_json{{"kinetic", e.kinetic},
                                      {"potential", e.potential},
                                      {"elastic", e.elastic},
                                      {"total", e.total()}};
    };
    nlohmann::ordered_json j{{"scene", s.scene},
                             {"status", s.status},
                             {"steps", s.steps},
                             {"timeStep", s.timeStep},
                             {"simulatedTime", s.simulatedTime},
                             {"wallTime", s.wallTime},
                             {"realTimeFactor", s.realTimeFactor},
                             {"bodies", s.bodies},
                             {"bodiesAsleep", s.bodiesAsleep},
                             {"energy", {{"start", energy(s.start)}, {"end", energy(s.end)}}},
                             {"deepestPenetration", s.deepestPenetration},
                             {"lastSolverResidual", s.lastResidual},
                             {"lastSolverIterations", s.lastIterations}};
    if (s.failedBody >= 0)
        j["failedBody"] = s.failedBody;
    j["warnings"] = s.warnings;
    return j.dump(2) + "\n";
}

namespace {

/// Refuses a scene whose energy at the start is no finite number (a position or velocity so
/// large that m g z or m v^2 / 2 overflows a double): every figure of the run would be
/// meaningless. Names the body and the key; what overflows only later is warned of instead.
void checkFiniteStart(const Scene& scene, const BuiltScene& built, const Energy& start) {
    if (std::isfinite(start.total()))
        return;
    const World& w = built.world;
    for (std::size_t i = 0; i < built.bodies.size(); ++i) {
        const BodyId b = built.bodies[i];
        if (w.bodyType(b) != BodyType::Dynamic)
            continue;
        const MassProperties mass = w.massProperties(b);
        const Vec3 v = w.linearVelocity(b);
        const Vec3 turn = w.orientation(b).conjugate() * w.angularVelocity(b);  // body frame
        const Real potential =
            -mass.mass * built.gravityScale[i] * w.settings().gravity.dot(w.centerOfMass(b));
        const Real kinetic = mass.mass * v.squaredNorm() / 2;
        const Real spin = turn.dot(mass.inertia * turn) / 2;
        const char* key = !std::isfinite(potential) ? "position"
                          : !std::isfinite(kinetic) ? "linearVelocity"
                          : !std::isfinite(spin)    ? "angularVelocity"
                                                    : nullptr;
        if (key == nullptr)
            continue;
        const BodySpec& spec = scene.bodies[i];
        const std::string path = spec.path + "." + key;
        fail(located(scene, scene.lines.count(path) != 0 ? path : spec.path), " (\"", spec.name,
             "\"): the body's energy at the start is not a finite number (potential ", potential,
             " J, kinetic ", kinetic + spin, " J): too large for the run's figures");
    }
    fail(scene.source, ": the energy at the start is not a finite number (kinetic ", start.kinetic,
         " J, potential ", start.potential, " J, elastic ", start.elastic,
         " J): too large for the run's figures");
}

/// The first multiple of `period` after `time` (within a fraction of a step h); `period` for a
/// period of 0 (every step).
Real nextMultiple(Real period, Real time, Real h) {
    if (period <= 0)
        return period;
    return period * (std::floor((time + 1e-9 * h) / period) + 1);
}

/// Loads the checkpoint into the world built from the scene, which must be the one it was
/// written from: the same bodies, springs and joints, and the same time step.
void resume(World& world, const BuiltScene& built, const Scene& scene, const std::string& file) {
    const int bodies = world.bodyCount(), springs = world.springCount();
    const int joints = world.jointCount();
    const Real h = world.settings().timeStep;
    loadCheckpoint(world, file);
    bool valid = true;
    for (const BodyId b : built.bodies)
        valid = valid && world.isValid(b);
    if (!valid || world.bodyCount() != bodies || world.springCount() != springs ||
        world.jointCount() != joints)
        fail("--resume ", file, ": the checkpoint holds ", world.bodyCount(), " bodies, ",
             world.springCount(), " springs and ", world.jointCount(), " joints; scene ",
             scene.name, " builds ", bodies, ", ", springs, " and ", joints,
             ": it was written from another scene");
    if (world.settings().timeStep != h)
        fail("--resume ", file, ": the checkpoint's time step ", world.settings().timeStep,
             " s is not the scene's ", h, " s (--dt or world.timeStep)");
}

}  // namespace

int runScene(const Scene& scene, const RunOptions& options, std::ostream& out, std::ostream& err,
             Summary* result) {
    for (const std::vector<int>* list : {&options.trace, &options.recordBodies}) {
        for (const int t : *list) {
            if (t < 0 || t >= static_cast<int>(scene.bodies.size()))
                fail("body ", t, " to trace or record: the scene has bodies 0 to ",
                     scene.bodies.size() - 1);
        }
    }
    const View view = parseView(options.view);
    BuiltScene built = buildScene(scene);
    World& world = built.world;
    if (!options.resume.empty())
        resume(world, built, scene, options.resume);
    // Every output is opened before the first step: a bad path is bad input, not a lost run.
    const Energy startEnergy = energyOf(built);
    checkFiniteStart(scene, built, startEnergy);
    auto csv = openOutput(options.record, "record");
    auto summaryFile = openOutput(options.summary, "summary");
    auto pictureFile = openOutput(options.picture, "picture");
    ReplayOutput replay(options.replay, options.gltf, options.replayRate, scene, built);
    const bool checkpointing = !options.checkpoint.empty();
    if (checkpointing)  // the state at the start; a path that cannot be written fails here
        saveCheckpoint(world, options.checkpoint);

    Summary s;
    s.scene = scene.name;
    s.timeStep = world.settings().timeStep;
    s.bodies = static_cast<int>(built.bodies.size());
    s.start = startEnergy;
    const auto steps = static_cast<std::uint64_t>(std::ceil(scene.duration / s.timeStep - 1e-9));
    SvgPicture picture(view,
                       scene.name + (scene.description.empty() ? "" : ": " + scene.description));
    const bool drawing = pictureFile != nullptr;
    const std::uint64_t traceStride = std::max<std::uint64_t>(1, steps / 1000);
    // The steps drawn: start, middle and end, or the steps nearest the chosen times.
    std::vector<std::uint64_t> panelSteps{0, steps / 2, steps};
    if (!options.pictureTimes.empty()) {
        panelSteps.clear();
        for (const Real t : options.pictureTimes)
            panelSteps.push_back(std::min<std::uint64_t>(
                steps,
                static_cast<std::uint64_t>(std::llround(std::max<Real>(t, 0) / s.timeStep))));
    }
    std::sort(panelSteps.begin(), panelSteps.end());
    panelSteps.erase(std::unique(panelSteps.begin(), panelSteps.end()), panelSteps.end());
    auto sample = [&](std::uint64_t step) {
        replay.sample(world);
        if (!drawing)
            return;
        if (std::binary_search(panelSteps.begin(), panelSteps.end(), step))
            picture.addPanel(world, built.shapes, built.springs, built.joints, world.time());
        if (step % traceStride == 0 || step == steps) {
            for (const int t : options.trace)
                picture.addTracePoint(t, world.time(), world.centerOfMass(built.bodies[t]));
        }
    };
    if (csv) {
        writeCsvHeader(*csv);
        writeCsvRows(*csv, scene, built, options.recordBodies);
    }
    const Real recordPeriod = options.recordRate > 0 ? 1 / options.recordRate : 0;
    Real nextRecord = nextMultiple(recordPeriod, world.time(), s.timeStep);
    Real nextCheckpoint = nextMultiple(options.checkpointEvery, world.time(), s.timeStep);
    const std::uint64_t first = world.stepCount();  // 0, or the step a resumed run starts from
    s.steps = first;
    sample(first);
    if (options.observe)
        options.observe(built, false);

    Progress progress(options.terminal && !options.quiet, scene.duration);
    const auto begin = Clock::now();
    for (std::uint64_t i = first + 1; i <= steps; ++i) {
        const StepStatus status = world.step();
        if (!status.ok()) {
            s.status = status.code == StepStatus::Code::Overflow ? "overflow" : "non-finite state";
            for (std::size_t b = 0; b < built.bodies.size(); ++b) {
                if (built.bodies[b] == status.body)
                    s.failedBody = static_cast<int>(b);
            }
            break;
        }
        s.steps = i;
        const SolverStats& stats = world.solverStats();
        s.deepestPenetration = std::max(s.deepestPenetration, stats.deepestPenetration);
        if (csv && world.time() >= nextRecord - 1e-9 * s.timeStep) {
            writeCsvRows(*csv, scene, built, options.recordBodies);
            nextRecord += recordPeriod;
        }
        if (checkpointing && options.checkpointEvery > 0 &&
            world.time() >= nextCheckpoint - 1e-9 * s.timeStep) {
            saveCheckpoint(world, options.checkpoint);
            nextCheckpoint += options.checkpointEvery;
        }
        sample(i);
        if (options.observe)
            options.observe(built, false);
        progress.update(world.time(), std::chrono::duration<double>(Clock::now() - begin).count());
    }
    progress.clear();
    if (options.observe)
        options.observe(built, true);
    // After a failed step the world holds the last finite state: that is what is saved.
    if (checkpointing)
        saveCheckpoint(world, options.checkpoint);
    s.wallTime = std::chrono::duration<double>(Clock::now() - begin).count();
    s.simulatedTime = world.time();
    s.realTimeFactor = s.wallTime > 0 ? s.simulatedTime / s.wallTime : 0;
    s.end = energyOf(built);
    s.lastResidual = world.solverStats().maxResidual;
    s.lastIterations = world.solverStats().iterations;
    for (const BodyId b : built.bodies) {
        if (world.bodyType(b) == BodyType::Dynamic && !world.isAwake(b))
            ++s.bodiesAsleep;
    }
    s.warnings = scene.warnings;  // loading's (mesh files), then the world's
    for (const Warning& w : world.warnings())
        s.warnings.push_back(describe(w));
    if (world.droppedWarnings() > 0)
        s.warnings.push_back(std::to_string(world.droppedWarnings()) + " more warnings not kept");
    for (const std::string& figure : nonFiniteFigures(s))
        s.warnings.push_back("summary: " + figure +
                             " is not a finite number (written as null): it overflowed a double");
    // A crowded scene can raise dozens; the summary keeps them all.
    constexpr std::size_t kPrinted = 5;
    for (std::size_t i = 0; i < s.warnings.size() && i < kPrinted; ++i)
        err << "tumble: warning: " << s.warnings[i] << "\n";
    if (s.warnings.size() > kPrinted) {
        err << "tumble: warning: ... and " << s.warnings.size() - kPrinted
            << " more (all in the --summary JSON)\n";
    }
    if (s.status != "ok" && drawing)
        picture.addPanel(world, built.shapes, built.springs, built.joints, world.time());
    if (summaryFile)
        *summaryFile << summaryJson(s);
    replay.finish();
    if (pictureFile)
        *pictureFile << picture.render();
    if (!options.quiet)
        printSummary(out, s);
    if (result != nullptr)
        *result = s;
    if (s.status != "ok") {
        err << "tumble: step " << s.steps + 1 << " failed: " << s.status << " (body "
            << s.failedBody << ")\n";
        return 1;
    }
    return 0;
}

}  // namespace tumble::cli
