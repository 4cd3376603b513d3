// The module `tumble._tumble` (tumble/__init__.py re-exports it with the checked state views),
// and the state's raw numpy arrays and batch setters.
#include <cmath>
#include <optional>

#include "bindings.h"
#include "tumble/core/error.h"

namespace tumble::python {

void PyWorld::guard(const char* what) const {
    if (exports > 0)
        throw py::buffer_error(std::string(what) + ": " + std::to_string(exports) +
                               " numpy array(s) of this world's state (np.asarray of a view) "
                               "are alive and would dangle; delete or copy them first");
}

namespace {

using Rows3 = Eigen::Matrix<Real, Eigen::Dynamic, 3, Eigen::RowMajor>;
using Rows4 = Eigen::Matrix<Real, Eigen::Dynamic, 4, Eigen::RowMajor>;

/// The base object of a raw array: keeps the world alive and counted in PyWorld::exports.
struct Export {
    py::object owner;
    PyWorld* world;
    explicit Export(py::object o) : owner(std::move(o)), world(owner.cast<PyWorld*>()) {
        ++world->exports;
    }
    ~Export() { --world->exports; }
    Export(const Export&) = delete;
    Export& operator=(const Export&) = delete;
};

/// A read-only (count, 3 or 4) array over bodies [first, first + count) of one field.
py::array rawArray(py::object self, int field, std::size_t first, std::size_t count) {
    PyWorld& w = self.cast<PyWorld&>();
    const DenseState s = w.world.denseState();
    if (field < 0 || field > 3)
        fail("state field ", field, " must be 0..3");
    if (first + count > s.count)
        fail("state range [", first, ", ", first + count, ") beyond the ", s.count, " bodies");
    const Real* bases[] = {s.center, s.orientation, s.linearVelocity, s.angularVelocity};
    const py::ssize_t width = field == 1 ? 4 : 3;
    static Real empty[4] = {};
    const Real* base = s.count == 0
                           ? empty
                           : reinterpret_cast<const Real*>(
                                 reinterpret_cast<const char*>(bases[field]) + first * s.stride);
    py::object owner = py::cast(new Export(self), py::return_value_policy::take_ownership);
    const py::ssize_t stride =
        s.count == 0 ? py::ssize_t(width * sizeof(Real)) : py::ssize_t(s.stride);
    py::array a(py::dtype::of<Real>(), {py::ssize_t(count), width},
                {stride, py::ssize_t(sizeof(Real))}, base, owner);
    a.attr("setflags")(py::arg("write") = false);
    return a;
}

/// Dense indices [first, first + count) of `bodies` when they are consecutive and in order.
std::pair<std::size_t, std::size_t> denseRange(const PyWorld& w,
                                               const std::vector<BodyId>& bodies) {
    const std::vector<BodyId> all = w.world.bodies();
    if (bodies.empty())
        return {0, 0};
    std::size_t first = all.size();
    for (std::size_t i = 0; i < all.size(); ++i)
        if (all[i] == bodies.front())
            first = i;
    if (first == all.size())
        fail("bodies[0] is not a live body of this world");
    for (std::size_t k = 0; k < bodies.size(); ++k)
        if (first + k >= all.size() || !(all[first + k] == bodies[k]))
            fail("bodies[", k, "] does not follow bodies[", k - 1,
                 "] in dense order (a destroyed body moved another into its place): "
                 "no single view covers these bodies");
    return {first, bodies.size()};
}

std::vector<BodyId> targets(const PyWorld& w, const std::optional<std::vector<BodyId>>& bodies,
                            Eigen::Index rows, const char* what) {
    std::vector<BodyId> ids = bodies ? *bodies : w.world.bodies();
    if (static_cast<std::size_t>(rows) != ids.size())
        fail(what, ": ", rows, " rows for ", ids.size(), " bodies");
    return ids;
}

template <typename Rows>
void requireFinite(const Rows& rows, const char* what) {
    for (Eigen::Index i = 0; i < rows.rows(); ++i)
        if (!rows.row(i).allFinite())
            fail(what, "[", i, "] = (", rows.row(i), ") must be finite");
}

// Each row goes through the engine's setter (its checks, its waking). Static bodies are skipped
// when their row is zero, so the whole-world arrays can be written back.
void setVelocities(PyWorld& w, const Rows3& v, const std::optional<std::vector<BodyId>>& bodies,
                   bool angular) {
    const char* what = angular ? "set_angular_velocities" : "set_linear_velocities";
    const std::vector<BodyId> ids = targets(w, bodies, v.rows(), what);
    requireFinite(v, what);
    for (std::size_t i = 0; i < ids.size(); ++i) {
        const Vec3 row = v.row(static_cast<Eigen::Index>(i)).transpose();
        if (w.world.bodyType(ids[i]) == BodyType::Static && row.isZero(0))
            continue;
        angular ? w.world.setAngularVelocity(ids[i], row) : w.world.setLinearVelocity(ids[i], row);
    }
}

void setPoses(PyWorld& w, const Rows3& p, const Rows4& q,
              const std::optional<std::vector<BodyId>>& bodies) {
    const std::vector<BodyId> ids = targets(w, bodies, p.rows(), "set_poses");
    if (q.rows() != p.rows())
        fail("set_poses: ", q.rows(), " orientations for ", p.rows(), " positions");
    requireFinite(p, "set_poses positions");
    requireFinite(q, "set_poses orientations");
    for (std::size_t i = 0; i < ids.size(); ++i) {
        const auto r = static_cast<Eigen::Index>(i);
        w.world.setTransform(ids[i], p.row(r).transpose(),
                             Quat(q(r, 3), q(r, 0), q(r, 1), q(r, 2)));
    }
}

}  // namespace

void bindState(py::module_& m, py::class_<PyWorld>& c) {
    py::class_<Export>(m, "_Export");
    const auto bodies = py::arg("bodies") = py::none();
    c.def("_raw", &rawArray, py::arg("field"), py::arg("first"), py::arg("count"))
        .def_property_readonly("_structure", [](const PyWorld& w) { return w.structure; })
        .def_property_readonly("_exports", [](const PyWorld& w) { return w.exports; })
        .def("_dense_range", &denseRange, py::arg("bodies"))
        .def(
            "body_positions",
            [](const PyWorld& w) {
                const std::vector<BodyId> ids = w.world.bodies();
                Rows3 out(static_cast<Eigen::Index>(ids.size()), 3);
                for (std::size_t i = 0; i < ids.size(); ++i)
                    out.row(static_cast<Eigen::Index>(i)) = w.world.position(ids[i]).transpose();
                return out;
            },
            "Body origins (m), dense order, as a new (n, 3) array (the views show centres of "
            "mass).")
        .def("set_poses", &setPoses, py::arg("positions"), py::arg("orientations"), bodies,
             "Body origins (m) and orientations (x, y, z, w) of `bodies` (default: all, dense "
             "order), each through World.set_transform (checked, wakes). Rows are checked finite "
             "before any is set.")
        .def(
            "set_linear_velocities",
            [](PyWorld& w, const Rows3& v, const std::optional<std::vector<BodyId>>& b) {
                setVelocities(w, v, b, false);
            },
            py::arg("velocities"), bodies,
            "(m/s) of `bodies` (default: all, dense order; zero rows of static bodies skipped).")
        .def(
            "set_angular_velocities",
            [](PyWorld& w, const Rows3& v, const std::optional<std::vector<BodyId>>& b) {
                setVelocities(w, v, b, true);
            },
            py::arg("velocities"), bodies, "(rad/s); as set_linear_velocities.");
}

}  // namespace tumble::python

PYBIND11_MODULE(_tumble, m) {
    using namespace tumble::python;
    m.doc() = "Tumble rigid-body, string and net physics (SI units, double precision).";
    py::register_exception<tumble::InvalidArgument>(m, "InvalidArgument", PyExc_ValueError);
    bindIds(m);
    bindSurfaces(m);
    bindTypes(m);
    bindWorld(m);
    bindScene(m);
}
