// tumble: run Tumble's scenes headless. See `tumble --help` and docs/scene-format.md.

#include <unistd.h>

#include <iostream>
#include <string>
#include <vector>

#include "command.h"

int main(int argc, char** argv) {
    const std::vector<std::string> args(argv, argv + argc);
    return tumble::cli::runCommand(args, std::cout, std::cerr, isatty(STDOUT_FILENO) == 1);
}
