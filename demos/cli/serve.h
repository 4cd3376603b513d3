#pragma once
/// `tumble view FILE`: serves the viewer page (viewer/) and a replay file on 127.0.0.1.

#include <iosfwd>
#include <string>

namespace tumble::cli {

struct ServeOptions {
    std::string replay;     ///< the replay file, served as /replay.tumble
    std::string viewerDir;  ///< the folder holding index.html and node_modules/three
    int port = 0;           ///< 0: a free port the system picks
};

/// $TUMBLE_VIEWER_DIR, else share/tumble/viewer beside the executable, else the source tree's.
std::string viewerDirectory(const std::string& argv0);

/// Checks the replay and the viewer's set-up (InvalidArgument naming what is wrong), prints the
/// address to `out` and serves until the process is stopped.
[[noreturn]] int serveViewer(const ServeOptions& options, std::ostream& out);

}  // namespace tumble::cli
