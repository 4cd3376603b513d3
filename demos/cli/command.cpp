#include "command.h"

#include <CLI/CLI.hpp>
#include <cmath>
#include <iostream>

#include "run.h"
#include "serve.h"
#include "sweep.h"
#include "tumble/scene/scene.h"

namespace tumble::cli {
namespace {

std::string number(double x) {
    std::ostringstream s;
    s.precision(17);
    s << x;
    return s.str();
}

/// `tumble scenes`: one line per built-in scene, its name and description.
int listScenes(const std::string& directory, std::ostream& out, std::ostream& err) {
    const std::vector<std::string> names = builtinScenes(directory);
    if (names.empty()) {
        err << "tumble: no scenes in " << directory << " (set TUMBLE_SCENE_DIR)\n";
        return 2;
    }
    for (const std::string& name : names) {
        try {
            const Scene scene = loadScene(name, {}, directory);
            out << name << std::string(name.size() < 10 ? 10 - name.size() : 1, ' ')
                << scene.description << "\n";
        } catch (const InvalidArgument& e) {
            err << "tumble: " << e.what() << "\n";
            return 2;
        }
    }
    return 0;
}

}  // namespace

int runCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& err,
               bool terminal) {
    CLI::App app{
        "tumble: run Tumble's rigid-body scenes headless (scene files: "
        "docs/scene-format.md)",
        "tumble"};
    app.set_version_flag("--version", std::string("tumble ") + TUMBLE_VERSION);
    app.require_subcommand(1);
    CLI::App* scenes = app.add_subcommand("scenes", "List the built-in scenes, one per line");
    CLI::App* run = app.add_subcommand("run", "Run a built-in scene or a scene file");
    CLI::App* sweep = app.add_subcommand(
        "sweep",
        "Run a study: a scene over parameter values, one CSV row per run (docs/sweeps.md)");
    SweepOptions sweepOptions;
    addSweepOptions(*sweep, sweepOptions, true);
    CLI::App* view = app.add_subcommand(
        "view", "Serve the viewer for a replay FILE (tumble run --replay) on 127.0.0.1");
    ServeOptions serve;
    view->add_option("file", serve.replay, "A replay file")->required();
    view->add_option("--port", serve.port, "TCP port (default: a free one, printed)");

    std::string scene;
    double time = 0, dt = 0, recordRate = -1;
    int iterations = 0;
    std::vector<std::string> sets;
    std::vector<std::string> trace, recordBodies;
    RunOptions options;
    run->add_option("scene", scene, "A built-in scene name (tumble scenes) or a FILE.json")
        ->required();
    run->add_option("--time", time, "Simulated time T (s), instead of the scene's duration");
    run->add_option("--dt", dt, "Time step H (s), instead of world.timeStep");
    run->add_option("--iterations", iterations,
                    "PGS iterations K, instead of world.solver.iterations and linkIterations");
    run->add_option("--set", sets,
                    "Override a scene value by its dotted path: key=value "
                    "(e.g. world.solver.iterations=20); repeatable")
        ->expected(1)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    run->add_option("--record", options.record, "Write trajectories as CSV to FILE");
    run->add_option("--record-rate", recordRate,
                    "Samples per second (Hz) for --record; "
                    "default: every step");
    run->add_option("--record-bodies", recordBodies,
                    "Bodies the CSV holds (default every non-static one): indices, names or "
                    "NET.corners, comma-separated")
        ->delimiter(',');
    run->add_option("--replay", options.replay,
                    "Write a replay for the viewer (tumble view FILE) to FILE (docs/replay.md)");
    run->add_option("--gltf", options.gltf, "Write the run as an animated glTF binary to FILE.glb");
    run->add_option("--replay-rate", options.replayRate,
                    "Frames per second (Hz) of --replay and --gltf (default 60)");
    run->add_option("--summary", options.summary, "Write the summary as JSON to FILE");
    run->add_option("--picture", options.picture,
                    "Draw start, middle and end (or outputs.pictureTimes) to FILE.svg");
    run->add_option("--view", options.view, "Picture view: side, top or front (default side)");
    run->add_option("--trace", trace,
                    "Bodies whose trajectories the picture draws: indices, names or NET.corners, "
                    "comma-separated")
        ->delimiter(',');
    run->add_flag("--quiet,-q", options.quiet, "Print nothing but errors");
    double checkpointEvery = 0;
    run->add_option("--checkpoint", options.checkpoint,
                    "Save the world's state to FILE at the start, every --checkpoint-every "
                    "and at the end (written to FILE.tmp, then renamed)");
    run->add_option("--checkpoint-every", checkpointEvery,
                    "Simulated time T (s) between checkpoints; needs --checkpoint");
    run->add_option("--resume", options.resume,
                    "Continue from a checkpoint FILE of this scene to --time (or the duration)");

    std::vector<const char*> argv;
    for (const std::string& a : args)
        argv.push_back(a.c_str());
    try {
        app.parse(static_cast<int>(argv.size()), argv.data());
    } catch (const CLI::ParseError& e) {
        const int status = app.exit(e, out, err);
        return status == 0 ? 0 : 2;
    }
    const std::string directory = sceneDirectory(args.empty() ? "" : args[0]);
    if (*scenes)
        return listScenes(directory, out, err);
    if (*sweep) {
        try {
            sweepOptions.terminal = terminal;
            return runSweep(sweepOptions, directory, out, err);
        } catch (const InvalidArgument& e) {
            err << "tumble sweep: error: " << e.what() << "\n";
            return 2;
        }
    }
    if (*view) {
        try {
            serve.viewerDir = viewerDirectory(args.empty() ? "" : args[0]);
            serveViewer(serve, out);
        } catch (const InvalidArgument& e) {
            err << "tumble: error: " << e.what() << "\n";
            return 2;
        }
    }

    try {
        // The command-line shortcuts are overrides like --set, applied last so they win.
        if (run->count("--dt") != 0)
            sets.push_back("world.timeStep=" + number(dt));
        if (run->count("--iterations") != 0) {
            sets.push_back("world.solver.iterations=" + std::to_string(iterations));
            sets.push_back("world.solver.linkIterations=" + std::to_string(iterations));
        }
        if (run->count("--time") != 0)
            sets.push_back("duration=" + number(time));
        const Scene loaded = loadScene(scene, sets, directory);
        const OutputSpec& defaults = loaded.outputs;
        if (options.record.empty())
            options.record = defaults.record;
        options.recordRate = recordRate >= 0 ? recordRate : defaults.recordRate;
        if (options.summary.empty())
            options.summary = defaults.summary;
        if (options.picture.empty())
            options.picture = defaults.picture;
        options.pictureTimes = defaults.pictureTimes;
        if (run->count("--view") == 0)
            options.view = defaults.view;
        options.trace =
            run->count("--trace") != 0 ? selectBodies(loaded, trace, "--trace") : defaults.trace;
        options.recordBodies = run->count("--record-bodies") != 0
                                   ? selectBodies(loaded, recordBodies, "--record-bodies")
                                   : defaults.recordBodies;
        options.terminal = terminal;
        if (run->count("--checkpoint-every") != 0) {
            if (options.checkpoint.empty())
                fail("--checkpoint-every needs --checkpoint FILE");
            if (!(checkpointEvery > 0) || !std::isfinite(checkpointEvery))
                fail("--checkpoint-every = ", checkpointEvery, " must be > 0 (s)");
            options.checkpointEvery = checkpointEvery;
        }
        if (recordRate < 0 && run->count("--record-rate") != 0)
            fail("--record-rate = ", recordRate, " must be >= 0");
        return runScene(loaded, options, out, err);
    } catch (const InvalidArgument& e) {
        err << "tumble: error: " << e.what() << "\n";
        return 2;
    }
}

}  // namespace tumble::cli
