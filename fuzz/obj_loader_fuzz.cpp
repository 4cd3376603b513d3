// libFuzzer target: the OBJ mesh loader (scene/mesh_io.h, tinyobjloader behind it) on arbitrary
// text. A refusal (InvalidArgument with a message) is the expected answer to bad input; a crash,
// undefined behaviour, a leak, another exception, a refusal without a message, or an accepted mesh
// that its own checks would change (an index out of range, a non-finite vertex, a degenerate
// triangle left in) is a finding.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "tumble/scene/mesh_io.h"

namespace {

const std::string& scratchFile() {
    static const std::string path = (std::filesystem::temp_directory_path() /
                                     ("tumble_obj_fuzz_" + std::to_string(getpid()) + ".obj"))
                                        .string();
    return path;
}

[[noreturn]] void finding(const char* what) {
    std::fprintf(stderr, "obj_loader_fuzz: %s\n", what);
    std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    {
        std::ofstream out(scratchFile(), std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    }
    tumble::TriangleMeshData mesh;
    try {
        mesh = tumble::loadObj(scratchFile());
    } catch (const tumble::InvalidArgument& e) {
        if (std::string(e.what()).empty())
            finding("a refusal without a message");
        return 0;
    }
    const std::size_t triangles = mesh.triangles.size();
    try {
        if (tumble::checkTriangleMesh(mesh).count != 0 || mesh.triangles.size() != triangles)
            finding("an accepted mesh kept a degenerate triangle");
    } catch (const tumble::InvalidArgument& e) {
        finding(e.what());  // accepted, yet its own checks refuse it
    }
    return 0;
}
