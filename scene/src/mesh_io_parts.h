#pragma once
/// Pieces shared by the mesh and height-field loaders (mesh_checks.cpp, obj_loader.cpp,
/// stl_loader.cpp, png_loader.cpp).

#include <string>
#include <string_view>
#include <vector>

#include "tumble/scene/mesh_io.h"

namespace tumble::mesh_io {

/// The whole file as bytes; refuses a missing or unreadable file naming it.
std::string readFile(const std::string& path);

/// A coordinate written as text ("1.5", "+2", "-3e-4"): refuses, naming `where`, anything that
/// is not wholly a number or is not finite (NaN and infinities are refused, not read as 0).
double readCoordinate(std::string_view text, const std::string& where);

/// Appends "<source>: dropped N degenerate triangles ..., the first <first>" to `warnings` when
/// `dropped` holds any and `warnings` is given.
void warnDropped(std::vector<std::string>* warnings, const std::string& source,
                 const DroppedTriangles& dropped, const std::string& first);

/// Runs checkTriangleMesh; a refused element is re-thrown as "<where(element, index)>: rule",
/// a refused mesh as "<source>: message".
template <typename Where>
DroppedTriangles checkNamed(TriangleMeshData& mesh, const std::string& source, Where&& where) {
    try {
        return checkTriangleMesh(mesh);
    } catch (const MeshElementError& e) {
        fail(where(e.element(), e.index()), ": ", e.rule());
    } catch (const InvalidArgument& e) {
        fail(source, ": ", e.what());
    }
}

}  // namespace tumble::mesh_io
