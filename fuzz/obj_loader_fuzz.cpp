// libFuzzer target: the OBJ mesh loader (scene/mesh_io.h, tinyobjloader behind it) on arbitrary
// text. A refusal (InvalidArgument with a message) is the expected answer to bad input; a crash,
// undefined behaviour, a leak, another exception, a refusal without a message, or an accepted mesh
// that its own checks would change (an index out of range, a non-finite vertex, a degenerate
// triangle left in) is a finding.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "scratch_file.h"
#include "tumble/scene/mesh_io.h"

namespace {

[[noreturn]] void finding(const char* what) {
    std::fprintf(stderr, "obj_loader_fuzz: %s\n", what);
    std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string file = tumble::fuzz::writeScratch("obj_fuzz", ".obj", data, size);
    tumble::TriangleMeshData mesh;
    try {
        mesh = tumble::loadObj(file);
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
