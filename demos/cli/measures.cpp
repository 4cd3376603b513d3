#include "measures.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <utility>

namespace tumble::cli {
namespace {

using Figure = std::pair<std::string, std::function<Real(const Summary&)>>;
using Vec2 = Eigen::Matrix<Real, 2, 1>;

const std::vector<Figure>& summaryFigures() {
    static const std::vector<Figure> figures = [] {
        std::vector<Figure> f{
            {"steps", [](const Summary& s) { return Real(s.steps); }},
            {"simulatedTime", [](const Summary& s) { return s.simulatedTime; }},
            {"deepestPenetration", [](const Summary& s) { return s.deepestPenetration; }},
            {"lastSolverResidual", [](const Summary& s) { return s.lastResidual; }},
            {"lastSolverIterations", [](const Summary& s) { return Real(s.lastIterations); }},
            {"bodiesAsleep", [](const Summary& s) { return Real(s.bodiesAsleep); }},
            {"warnings", [](const Summary& s) { return Real(s.warnings.size()); }}};
        for (const auto& [when, member] :
             {std::pair{"start", &Summary::start}, std::pair{"end", &Summary::end}}) {
            const std::string at = std::string("energy.") + when + ".";
            for (const auto& [part, read] :
                 std::array<std::pair<const char*, Real (*)(const Energy&)>, 4>{
                     {{"kinetic", [](const Energy& e) { return e.kinetic; }},
                      {"potential", [](const Energy& e) { return e.potential; }},
                      {"elastic", [](const Energy& e) { return e.elastic; }},
                      {"total", [](const Energy& e) { return e.total(); }}}}) {
                f.emplace_back(at + part,
                               [m = member, r = read](const Summary& s) { return r(s.*m); });
            }
        }
        return f;
    }();
    return figures;
}

Real quantityOf(const World& world, BodyId body, const std::string& quantity) {
    const Vec3 c = world.centerOfMass(body);
    const Vec3 v = world.linearVelocity(body);
    static const std::vector<std::string> names = quantityNames();
    const std::array<Real, 7> values{c.x(), c.y(), c.z(), v.x(), v.y(), v.z(), v.norm()};
    return values[std::find(names.begin(), names.end(), quantity) - names.begin()];
}

Real cross(const Vec2& o, const Vec2& a, const Vec2& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

/// Is `p` strictly inside the convex hull of `points`? Andrew's monotone chain, then one side
/// test per hull edge (counter-clockwise: p left of every edge).
bool insideHull(std::vector<Vec2> points, const Vec2& p) {
    std::sort(points.begin(), points.end(), [](const Vec2& a, const Vec2& b) {
        return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
    });
    if (points.size() < 3)
        return false;
    std::vector<Vec2> hull(2 * points.size());
    std::size_t k = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {  // lower chain
        while (k >= 2 && cross(hull[k - 2], hull[k - 1], points[i]) <= 0)
            --k;
        hull[k++] = points[i];
    }
    for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {  // upper chain
        while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0)
            --k;
        hull[k++] = points[i];
    }
    if (k < 4)  // collinear points: no area to be inside
        return false;
    for (std::size_t i = 0; i + 1 < k; ++i) {
        if (cross(hull[i], hull[i + 1], p) <= 0)
            return false;
    }
    return true;
}

}  // namespace

bool summaryValue(const Summary& s, const std::string& key, Real& value) {
    for (const auto& [name, read] : summaryFigures()) {
        if (key == name) {
            value = read(s);
            return true;
        }
    }
    return false;
}

std::string summaryKeys() {
    std::string out;
    for (const auto& figure : summaryFigures())
        out += (out.empty() ? "" : ", ") + figure.first;
    return out;
}

std::vector<std::string> quantityNames() {
    return {"x", "y", "z", "vx", "vy", "vz", "speed"};
}

bool netCaptures(const BuiltScene& built, const std::vector<int>& nodes,
                 const std::vector<int>& corners, int target) {
    const World& world = built.world;
    const std::vector<ShapeId> shapes = world.bodyShapes(built.bodies[target]);
    if (shapes.empty())
        return false;
    Aabb box = world.shapeBounds(shapes.front());
    for (const ShapeId s : shapes) {
        box.lower = box.lower.cwiseMin(world.shapeBounds(s).lower);
        box.upper = box.upper.cwiseMax(world.shapeBounds(s).upper);
    }
    const Real top = box.upper.z();
    for (const int c : corners) {
        if (!(world.centerOfMass(built.bodies[c]).z() < top))
            return false;
    }
    std::vector<Vec2> over;
    for (const int n : nodes) {
        const Vec3 p = world.centerOfMass(built.bodies[n]);
        if (p.z() >= top)
            over.emplace_back(p.x(), p.y());
    }
    const Vec3 centre = (box.lower + box.upper) / 2;
    return insideHull(std::move(over), Vec2(centre.x(), centre.y()));
}

RunMeasures::RunMeasures(const Study& study, const Scene& scene) : study_(study) {
    for (const StudyOutput& o : study.outputs) {
        Track t;
        if (o.kind == StudyOutput::Kind::Captured) {
            t.corners = selectBodies(scene, {o.net + ".corners"}, o.name);
            const auto net = std::find_if(scene.lumped.begin(), scene.lumped.end(),
                                          [&](const LumpedSpec& l) { return l.name == o.net; });
            for (std::size_t i = 0; i < net->nodeCount; ++i)
                t.bodies.push_back(static_cast<int>(net->firstBody + i));
            t.bodies.push_back(selectBodies(scene, {o.target}, o.name).front());
        } else if (o.kind != StudyOutput::Kind::Summary) {
            t.bodies = selectBodies(scene, {o.body}, o.name);
        }
        tracks_.push_back(std::move(t));
    }
}

void RunMeasures::observe(const BuiltScene& built, bool end) {
    using Kind = StudyOutput::Kind;
    const Real time = built.world.time();
    for (std::size_t k = 0; k < tracks_.size(); ++k) {
        const StudyOutput& o = study_.outputs[k];
        Track& t = tracks_[k];
        if (o.kind == Kind::Summary || (o.kind == Kind::Captured && !end))
            continue;
        if (o.kind == Kind::Captured) {
            const std::vector<int> nodes(t.bodies.begin(), t.bodies.end() - 1);
            t.value = netCaptures(built, nodes, t.corners, t.bodies.back()) ? 1 : 0;
            continue;
        }
        const Real q = quantityOf(built.world, built.bodies[t.bodies.front()], o.quantity);
        if (o.kind == Kind::Final)
            t.value = q;
        else if (o.kind == Kind::Min || o.kind == Kind::Max)
            t.value = !t.started            ? q
                      : o.kind == Kind::Min ? std::min(t.value, q)
                                            : std::max(t.value, q);
        else if (std::isnan(t.value)) {
            const bool crossed = o.kind == Kind::FirstBelow ? q <= o.threshold : q >= o.threshold;
            // Linear between the two states around the crossing: a step's resolution is coarse.
            if (crossed)
                t.value = !t.started || q == t.previous
                              ? time
                              : t.previousTime + (o.threshold - t.previous) / (q - t.previous) *
                                                     (time - t.previousTime);
        }
        t.previous = q;
        t.previousTime = time;
        t.started = true;
    }
}

std::vector<Real> RunMeasures::values(const Summary& summary) const {
    std::vector<Real> out;
    for (std::size_t k = 0; k < tracks_.size(); ++k) {
        Real value = tracks_[k].value;
        if (study_.outputs[k].kind == StudyOutput::Kind::Summary)
            summaryValue(summary, study_.outputs[k].summaryKey, value);
        out.push_back(value);
    }
    return out;
}

}  // namespace tumble::cli
