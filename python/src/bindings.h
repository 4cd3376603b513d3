#pragma once
/// Shared by the binding sources: the Python-side World (the engine's world plus what keeps the
/// numpy views safe), the quaternion caster and the helper that binds a plain struct.

#include <pybind11/eigen.h>
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <string>
#include <vector>

#include "tumble/lumped.h"
#include "tumble/tumble.h"

namespace py = pybind11;

/// Quaternions cross the boundary as 4 floats (x, y, z, w): scalar last, as Quat::coeffs() stores
/// them and as the state views show them (and as scipy's Rotation.from_quat reads them).
namespace pybind11::detail {
template <>
struct type_caster<tumble::Quat> {
    PYBIND11_TYPE_CASTER(tumble::Quat, const_name("numpy.ndarray[4] (x, y, z, w)"));
    bool load(handle src, bool convert) {
        if (!convert && !array_t<double>::check_(src))
            return false;
        auto a = array_t<double, array::forcecast>::ensure(src);
        if (!a || a.ndim() != 1 || a.size() != 4)
            return false;
        auto r = a.unchecked<1>();
        value = tumble::Quat(r(3), r(0), r(1), r(2));
        return true;
    }
    static handle cast(const tumble::Quat& q, return_value_policy, handle) {
        array_t<double> a(4);
        auto w = a.mutable_unchecked<1>();
        w(0) = q.x();
        w(1) = q.y();
        w(2) = q.z();
        w(3) = q.w();
        return a.release();
    }
};
}  // namespace pybind11::detail

namespace tumble::python {

/// The World a Python program holds. Raw numpy arrays of the state (np.asarray of a view) point
/// into the engine's storage, which creating or destroying a body may move: `exports` counts
/// the live ones, and such a change is refused while any lives (BufferError, as a bytearray
/// refuses to resize under a memoryview). The checked views (tumble.StateView) compare
/// `structure` instead and refuse to read after a change.
struct PyWorld {
    World world;
    std::uint64_t structure = 0;  ///< bumped by every change of the bodies' dense storage
    int exports = 0;              ///< live raw arrays of the state

    explicit PyWorld(const WorldDef& def) : world(def) {}
    explicit PyWorld(World&& w) : world(std::move(w)) {}

    /// Refuses (BufferError) a change of the dense storage while raw arrays of it live.
    void guard(const char* what) const;
    /// Runs `change` (which may move the storage) under guard(), then invalidates the views.
    template <typename F>
    auto restructure(const char* what, F&& change) {
        guard(what);
        struct Bump {
            PyWorld& w;
            ~Bump() { ++w.structure; }
        } bump{*this};
        return change();
    }
};

/// Binds a plain struct: a default constructor, and fields by Python name with a docstring
/// (units and rules). `_fields` lists them: tumble/__init__.py gives every such class keyword
/// arguments (the C++ defaults for those not given) and a repr.
template <typename T>
class Struct {
public:
    Struct(py::module_& m, const char* name, const char* doc) : c_(m, name, doc) {
        c_.def(py::init<>());
    }
    ~Struct() { c_.attr("_fields") = py::tuple(py::cast(fields_)); }
    template <typename M>
    Struct& field(const char* name, M T::*member, const char* doc) {
        c_.def_readwrite(name, member, doc);
        fields_.emplace_back(name);
        return *this;
    }
    py::class_<T>& cls() { return c_; }

private:
    py::class_<T> c_;
    std::vector<std::string> fields_;
};

void bindIds(py::module_& m);
void bindTypes(py::module_& m);
/// TriangleMesh and HeightField (before ShapeDef, whose geometry may hold them).
void bindSurfaces(py::module_& m);
void bindWorld(py::module_& m);
void bindState(py::module_& m, py::class_<PyWorld>& world);
void bindScene(py::module_& m);

}  // namespace tumble::python
