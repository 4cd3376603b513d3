#include "gltf_meshes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace tumble::gltf {
namespace {

using V3 = std::array<double, 3>;
constexpr int kSegments = 24;  // around a round shape's axis

V3 cross(const V3& a, const V3& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
V3 unit(const V3& a) {
    const double n = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    return {a[0] / n, a[1] / n, a[2] / n};
}

class Builder {
public:
    std::uint32_t vertex(const V3& p, const V3& n) {
        const V3 u = unit(n);
        for (int k = 0; k < 3; ++k) {
            mesh.positions.push_back(static_cast<float>(p[k]));
            mesh.normals.push_back(static_cast<float>(u[k]));
        }
        return static_cast<std::uint32_t>(mesh.positions.size() / 3 - 1);
    }
    /// Adds the triangle unless two of its corners coincide.
    void triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
        auto at = [&](std::uint32_t i) {
            return V3{mesh.positions[3 * i], mesh.positions[3 * i + 1], mesh.positions[3 * i + 2]};
        };
        const V3 pa = at(a), pb = at(b), pc = at(c);
        const V3 n = cross({pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]},
                           {pc[0] - pa[0], pc[1] - pa[1], pc[2] - pa[2]});
        if (n[0] * n[0] + n[1] * n[1] + n[2] * n[2] < 1e-18)
            return;
        mesh.indices.insert(mesh.indices.end(), {a, b, c});
    }
    /// A flat polygon, counter-clockwise about `normal`.
    void polygon(const std::vector<V3>& corners, const V3& normal) {
        const std::uint32_t first = vertex(corners[0], normal);
        for (std::size_t k = 1; k < corners.size(); ++k)
            vertex(corners[k], normal);
        for (std::uint32_t k = 1; k + 1 < corners.size(); ++k)
            triangle(first, first + k, first + k + 1);
    }
    /// A surface of revolution about z through rings of (radius, z, normal's radial part,
    /// normal's z part), top ring first.
    void lathe(const std::vector<std::array<double, 4>>& rings) {
        const auto first = static_cast<std::uint32_t>(mesh.positions.size() / 3);
        for (const auto& [r, z, nr, nz] : rings) {
            for (int s = 0; s <= kSegments; ++s) {
                const double a = 2 * std::numbers::pi * s / kSegments;
                vertex({r * std::cos(a), r * std::sin(a), z},
                       {nr * std::cos(a), nr * std::sin(a), nz});
            }
        }
        const std::uint32_t row = kSegments + 1;
        for (std::uint32_t i = 0; i + 1 < rings.size(); ++i) {
            for (std::uint32_t s = 0; s < kSegments; ++s) {
                const std::uint32_t a = first + i * row + s, b = a + row;
                triangle(a, b, b + 1);
                triangle(a, b + 1, a + 1);
            }
        }
    }
    /// A disc at height z facing +z (up = true) or -z.
    void disc(double radius, double z, bool up) {
        std::vector<V3> rim;
        for (int s = 0; s < kSegments; ++s) {
            const double a = 2 * std::numbers::pi * (up ? s : kSegments - s) / kSegments;
            rim.push_back({radius * std::cos(a), radius * std::sin(a), z});
        }
        polygon(rim, {0, 0, up ? 1.0 : -1.0});
    }
    Mesh mesh;
};

/// Rings of a sphere of `radius` whose upper half is raised by `half` and lower half lowered.
std::vector<std::array<double, 4>> roundRings(double radius, double half) {
    std::vector<std::array<double, 4>> rings;
    constexpr int kRows = 8;  // per hemisphere
    for (int i = kRows; i >= -kRows; --i) {
        const double phi = std::numbers::pi / 2 * i / kRows;
        const double c = std::cos(phi), s = std::sin(phi);
        const double offset = i > 0 ? half : i < 0 ? -half : 0;
        if (i == 0 && half > 0) {  // the equator twice: the capsule's cylinder between
            rings.push_back({radius, half, 1, 0});
            rings.push_back({radius, -half, 1, 0});
            continue;
        }
        rings.push_back({radius * c, radius * s + offset, c, s});
    }
    return rings;
}

V3 vec(const nlohmann::json& j) {
    return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()};
}

void box(Builder& b, const V3& h) {
    for (int axis = 0; axis < 3; ++axis) {
        for (const double sign : {-1.0, 1.0}) {
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            std::vector<V3> corners;
            for (const auto& [su, sv] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) {
                V3 p{};
                p[axis] = sign * h[axis];
                p[u] = su * h[u] * sign;  // mirrored on the negative side: still outward
                p[v] = sv * h[v];
                corners.push_back(p);
            }
            V3 n{};
            n[axis] = sign;
            b.polygon(corners, n);
        }
    }
}

/// Each face fanned from its first corner, wound counter-clockwise seen from outside (away from
/// the vertices' mean, which lies inside the convex hull).
void hull(Builder& b, const nlohmann::json& shape) {
    std::vector<V3> vertices;
    V3 mean{};
    for (const auto& v : shape["vertices"]) {
        vertices.push_back(vec(v));
        for (int k = 0; k < 3; ++k)
            mean[k] += vertices.back()[k] / static_cast<double>(shape["vertices"].size());
    }
    auto minus = [](const V3& a, const V3& c) { return V3{a[0] - c[0], a[1] - c[1], a[2] - c[2]}; };
    for (const auto& face : shape["faces"]) {
        std::vector<V3> corners;
        for (const auto& k : face)
            corners.push_back(vertices.at(k.get<std::size_t>()));
        if (corners.size() < 3)
            continue;
        V3 n = cross(minus(corners[1], corners[0]), minus(corners[2], corners[0]));
        const V3 out = minus(corners[0], mean);
        if (n[0] * out[0] + n[1] * out[1] + n[2] * out[2] < 0) {
            std::reverse(corners.begin(), corners.end());
            n = {-n[0], -n[1], -n[2]};
        }
        b.polygon(corners, n);
    }
}

}  // namespace

Mesh shapeMesh(const nlohmann::json& shape, float planeSize) {
    Builder b;
    const std::string type = shape["type"];
    if (type == "box") {
        box(b, vec(shape["halfExtents"]));
    } else if (type == "sphere") {
        b.lathe(roundRings(shape["radius"], 0));
    } else if (type == "capsule") {
        b.lathe(roundRings(shape["radius"], shape["halfLength"]));
    } else if (type == "cylinder") {
        const double r = shape["radius"], h = shape["halfLength"];
        b.lathe({{r, h, 1, 0}, {r, -h, 1, 0}});
        b.disc(r, h, true);
        b.disc(r, -h, false);
    } else if (type == "hull") {
        hull(b, shape);
    } else if (type == "plane") {
        const V3 n = unit(vec(shape["normal"]));
        const double d = shape["offset"];
        const V3 t = unit(std::abs(n[0]) < 0.9 ? cross(n, {1, 0, 0}) : cross(n, {0, 1, 0}));
        const V3 s = cross(n, t);
        const double h = planeSize / 2;
        std::vector<V3> corners;
        for (const auto& [a, c] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}})
            corners.push_back({n[0] * d + h * (a * t[0] + c * s[0]),
                               n[1] * d + h * (a * t[1] + c * s[1]),
                               n[2] * d + h * (a * t[2] + c * s[2])});
        b.polygon(corners, n);
    }
    return b.mesh;
}

}  // namespace tumble::gltf
