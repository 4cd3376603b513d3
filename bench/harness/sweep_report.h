#pragma once
/// The sweep's output (sweep.h): each engine's Pareto front among its runs that stayed sound, and
/// the CSV and Markdown files.

#include <string>
#include <vector>

#include "sweep_scenes.h"

namespace tumble::bench {

/// What a scene is and how its error is measured (and against what reference, how well
/// converged), for the files' headers.
struct SceneNote {
    std::string scene;
    std::string text;
};

/// Marks the Ok points of each (scene, engine) that no other Ok point of it beats in both cost
/// and error.
void markFronts(std::vector<Point>& points);

/// Every run, one a line, after '#' comment lines holding `preamble` and the notes.
void writeCsv(const std::string& path, const std::vector<Point>& points,
              const std::string& preamble, const std::vector<SceneNote>& notes);

/// Per scene: the note, each engine's front, the least cost each engine needs to reach an error
/// (Tumble against each peer), and the runs that collapsed or blew up.
void writeMarkdown(const std::string& path, const std::vector<Point>& points,
                   const std::string& preamble, const std::vector<SceneNote>& notes);

/// "1/240".
std::string fraction(double h);

}  // namespace tumble::bench
