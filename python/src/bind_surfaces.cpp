// The triangle surfaces, TriangleMesh and HeightField, from numpy arrays (in a translation unit
// of their own: pybind11's Eigen casters compile slowly, and GCC's inlining across them is
// touchy about -Wmaybe-uninitialized).
#include <array>
#include <optional>

#include "bindings.h"
#include "tumble/collision/mesh_data.h"
#include "tumble/collision/mesh_shape.h"

namespace tumble::python {
namespace {

using Points = Eigen::Matrix<Real, Eigen::Dynamic, 3, Eigen::RowMajor>;
using Indices = Eigen::Matrix<std::int64_t, Eigen::Dynamic, 3, Eigen::RowMajor>;
using Grid = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using Flags = Eigen::Matrix<std::int64_t, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// Mesh data from numpy arrays; an index outside [0, 2^32) is refused here, one past the
/// vertices by TriangleMesh::fromData.
TriangleMeshData meshData(const Points& vertices, const Indices& triangles) {
    TriangleMeshData data;
    for (Eigen::Index i = 0; i < vertices.rows(); ++i)
        data.vertices.push_back(vertices.row(i).transpose());
    for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
        std::array<std::uint32_t, 3> triangle{};
        for (Eigen::Index k = 0; k < 3; ++k) {
            const std::int64_t v = triangles(t, k);
            if (v < 0 || v > std::int64_t{0xFFFFFFFF})
                fail("TriangleMesh: triangles[", t, ", ", k, "] = ", v,
                     " must be a vertex index >= 0");
            triangle[static_cast<std::size_t>(k)] = static_cast<std::uint32_t>(v);
        }
        data.triangles.push_back(triangle);
    }
    return data;
}

/// Height-field data from a (rows, columns) array of heights, row j at y = j spacing_y, and
/// optional (rows - 1, columns - 1) hole flags.
HeightFieldData fieldData(const Grid& heights, Real spacingX, Real spacingY,
                          const std::optional<Flags>& holes) {
    HeightFieldData data;
    data.rows = static_cast<std::uint32_t>(heights.rows());
    data.columns = static_cast<std::uint32_t>(heights.cols());
    data.spacingX = spacingX;
    data.spacingY = spacingY;
    data.heights.assign(heights.data(), heights.data() + heights.size());
    if (holes) {
        if (holes->rows() + 1 != heights.rows() || holes->cols() + 1 != heights.cols())
            fail("HeightField: holes has shape (", holes->rows(), ", ", holes->cols(),
                 "); it must be (rows - 1, columns - 1) = (", heights.rows() - 1, ", ",
                 heights.cols() - 1, ")");
        for (Eigen::Index k = 0; k < holes->size(); ++k)
            data.holes.push_back(holes->data()[k] != 0 ? 1 : 0);
    }
    return data;
}

}  // namespace

void bindSurfaces(py::module_& m) {
    py::class_<TriangleMesh>(m, "TriangleMesh",
                             "A static triangle mesh (two-sided surface); static and kinematic "
                             "bodies only.")
        .def_static(
            "from_arrays",
            [](const Points& vertices, const Indices& triangles) {
                return TriangleMesh::fromData(meshData(vertices, triangles));
            },
            py::arg("vertices"), py::arg("triangles"),
            "From an (n, 3) array of vertices (m) and an (m, 3) array of vertex indices, "
            "counter-clockwise seen from the normal's side; degenerate triangles are dropped.")
        .def_property_readonly("triangle_count",
                               [](const TriangleMesh& s) { return s.data->triangles.size(); })
        .def_property_readonly("dropped_triangles",
                               [](const TriangleMesh& s) { return s.data->droppedTriangles; })
        .def_property_readonly(
            "bounds", [](const TriangleMesh& s) { return localBounds(*s.data); }, "local box (m)");
    py::class_<HeightField>(m, "HeightField",
                            "A regular grid of heights over local x-y, z up; static and "
                            "kinematic bodies only.")
        .def_static(
            "from_grid",
            [](const Grid& heights, Real spacingX, Real spacingY,
               const std::optional<Flags>& holes) {
                return HeightField::fromData(fieldData(heights, spacingX, spacingY, holes));
            },
            py::arg("heights"), py::arg("spacing_x") = 1.0, py::arg("spacing_y") = 1.0,
            py::arg("holes") = py::none(),
            "From a (rows, columns) array: heights[j, i] (m) at (i spacing_x, j spacing_y); "
            "holes: optional (rows - 1, columns - 1) flags, nonzero marks a hole.")
        .def_property_readonly("rows", [](const HeightField& s) { return s.data->grid.rows; })
        .def_property_readonly("columns", [](const HeightField& s) { return s.data->grid.columns; })
        .def_property_readonly(
            "bounds", [](const HeightField& s) { return localBounds(*s.data); }, "local box (m)");
}

}  // namespace tumble::python
