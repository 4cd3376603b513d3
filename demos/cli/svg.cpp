// The SVG picture writer: a DebugDraw that projects every primitive into a panel (outlines as
// convex polygons, which is exact for the orthographic projection of a convex solid), and a
// renderer that lays the panels out side by side at one common scale.

#include "svg.h"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <limits>
#include <numbers>

#include "tumble/core/error.h"

namespace tumble::cli {
namespace {

using Point = std::array<double, 2>;
using Item = SvgPicture::Item;

/// (u, v, depth) of a world point in a view.
std::array<double, 3> project(View view, const Vec3& p) {
    switch (view) {
        case View::Side:
            return {p.x(), p.z(), p.y()};
        case View::Front:
            return {p.y(), p.z(), -p.x()};
        case View::Top:
            return {p.x(), p.y(), -p.z()};
    }
    return {};
}

double cross(const Point& o, const Point& a, const Point& b) {
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

/// Andrew's monotone chain: the convex hull, counter-clockwise.
std::vector<Point> hull(std::vector<Point> p) {
    std::sort(p.begin(), p.end());
    if (p.size() < 3)
        return p;
    std::vector<Point> h(2 * p.size());
    std::size_t k = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0)
            --k;
        h[k++] = p[i];
    }
    for (std::size_t i = p.size() - 1, t = k + 1; i > 0; --i) {
        while (k >= t && cross(h[k - 2], h[k - 1], p[i - 1]) <= 0)
            --k;
        h[k++] = p[i - 1];
    }
    h.resize(k - 1);
    return h;
}

/// A distinct colour per body (golden-angle hues); static grey, kinematic green, asleep pale.
// Appends printf-formatted text (up to 511 characters) to `out`; the attribute has the compiler
// check each call's literal format against its arguments.
[[gnu::format(printf, 2, 3)]] void appendf(std::string& out, const char* fmt, ...) {
    char buf[512];
    std::va_list args;
    va_start(args, fmt);
    std::vsnprintf(buf, sizeof buf, fmt, args);
    va_end(args);
    out += buf;
}

std::string colourOf(BodyId body, BodyType type, bool awake) {
    if (type == BodyType::Static)
        return "#b4b4b4";
    if (type == BodyType::Kinematic)
        return "#7fb27f";
    const double hue = std::fmod(body.index * 137.508, 360.0);
    char buf[48];
    std::snprintf(buf, sizeof buf, "hsl(%.0f,%d%%,%d%%)", hue, awake ? 65 : 25, awake ? 60 : 72);
    return buf;
}

class PanelRecorder final : public DebugDraw {
public:
    PanelRecorder(View view, SvgPicture::Panel& panel) : view_(view), panel_(panel) {}

    void beginBody(BodyId body, BodyType type, bool awake) override {
        fill_ = colourOf(body, type, awake);
    }
    void drawBox(const Transform& pose, const Vec3& h) override {
        std::vector<Vec3> corners;
        for (int i = 0; i < 8; ++i)
            corners.push_back(pose.apply(
                Vec3(i & 1 ? h.x() : -h.x(), i & 2 ? h.y() : -h.y(), i & 4 ? h.z() : -h.z())));
        addSolid(corners, pose.position);
    }
    void drawSphere(const Transform& pose, Real radius) override {
        const auto c = project(view_, pose.position);
        Item item;
        item.kind = Item::Kind::Circle;
        item.depth = c[2];
        item.fill = fill_;
        // The rim point marks the body's local x axis, so rolling shows between panels.
        const auto rim = project(view_, pose.apply(Vec3(radius, 0, 0)));
        item.points = {{c[0], c[1]}, {rim[0], rim[1]}};
        item.offset = radius;
        panel_.items.push_back(std::move(item));
    }
    void drawCapsule(const Transform& pose, Real radius, Real halfLength) override {
        // The projection of a capsule is the hull of two discs of its radius.
        std::vector<Point> points;
        for (const Real end : {-halfLength, halfLength}) {
            const auto c = project(view_, pose.apply(Vec3(0, 0, end)));
            for (int k = 0; k < 24; ++k) {
                const double a = 2 * std::numbers::pi * k / 24;
                points.push_back({c[0] + radius * std::cos(a), c[1] + radius * std::sin(a)});
            }
        }
        addPolygon(hull(points), project(view_, pose.position)[2]);
    }
    void drawCylinder(const Transform& pose, Real radius, Real halfLength) override {
        std::vector<Vec3> rim;
        for (const Real end : {-halfLength, halfLength}) {
            for (int k = 0; k < 24; ++k) {
                const double a = 2 * std::numbers::pi * k / 24;
                rim.push_back(pose.apply(Vec3(radius * std::cos(a), radius * std::sin(a), end)));
            }
        }
        addSolid(rim, pose.position);
    }
    void drawHull(const Transform& pose, const HullData& data) override {
        std::vector<Vec3> vertices;
        for (const Vec3& v : data.vertices)
            vertices.push_back(pose.apply(v));
        addSolid(vertices, pose.position);
    }
    void drawPlane(const Vec3& normal, Real offset) override {
        // The boundary seen edge-on where the plane crosses depth 0: n_uv . q = offset. A plane
        // facing the viewer (the ground from the top) covers everything and is left out.
        const auto n = project(view_, normal);
        if (std::hypot(n[0], n[1]) < 1e-6)
            return;
        Item item;
        item.kind = Item::Kind::Plane;
        item.normal = {n[0], n[1]};
        item.offset = offset;
        item.depth = std::numeric_limits<double>::infinity();  // drawn first, behind everything
        panel_.items.push_back(std::move(item));
    }
    void drawContact(const Vec3& point, const Vec3& normal, Real) override {
        const auto p = project(view_, point);
        const auto n = project(view_, normal);
        Item item;
        item.kind = Item::Kind::Contact;
        item.points = {{p[0], p[1]}};
        item.normal = {n[0], n[1]};
        item.depth = -std::numeric_limits<double>::infinity();  // drawn last, on top
        panel_.items.push_back(std::move(item));
    }

    void drawSpring(const Vec3& anchorA, const Vec3& anchorB, Real, bool slack) override {
        const auto a = project(view_, anchorA);
        const auto b = project(view_, anchorB);
        Item item;
        item.kind = Item::Kind::Line;
        item.points = {{a[0], a[1]}, {b[0], b[1]}};
        item.depth = 0.5 * (a[2] + b[2]);
        item.fill = slack ? "#8fa3c7" : "#1f3f7a";
        item.dashed = slack;
        panel_.items.push_back(std::move(item));
    }
    void drawJoint(JointType type, const Vec3& anchorA, const Vec3& anchorB, const Vec3& axis,
                   bool broken) override {
        const auto a = project(view_, anchorA);
        const auto b = project(view_, anchorB);
        const auto n = project(view_, axis);
        Item item;
        item.kind = Item::Kind::Joint;
        item.joint = type;
        item.points = {{a[0], a[1]}, {b[0], b[1]}};
        item.normal = {n[0], n[1]};
        item.fill = broken ? "#999" : "#c25a00";
        item.depth = -std::numeric_limits<double>::infinity();  // on top of the bodies it joins
        panel_.items.push_back(std::move(item));
    }

private:
    void addSolid(const std::vector<Vec3>& points, const Vec3& centre) {
        std::vector<Point> flat;
        for (const Vec3& p : points) {
            const auto q = project(view_, p);
            flat.push_back({q[0], q[1]});
        }
        addPolygon(hull(flat), project(view_, centre)[2]);
    }
    void addPolygon(std::vector<Point> outline, double depth) {
        Item item;
        item.points = std::move(outline);
        item.depth = depth;
        item.fill = fill_;
        panel_.items.push_back(std::move(item));
    }

    View view_;
    SvgPicture::Panel& panel_;
    std::string fill_ = "#999";
};

/// The half-plane n.q <= offset clipped to a rectangle (Sutherland-Hodgman against one line).
std::vector<Point> clipHalfPlane(const Point& n, double offset, double u0, double v0, double u1,
                                 double v1) {
    const std::vector<Point> box{{u0, v0}, {u1, v0}, {u1, v1}, {u0, v1}};
    std::vector<Point> out;
    for (std::size_t i = 0; i < box.size(); ++i) {
        const Point& a = box[i];
        const Point& b = box[(i + 1) % box.size()];
        const double da = n[0] * a[0] + n[1] * a[1] - offset;
        const double db = n[0] * b[0] + n[1] * b[1] - offset;
        if (da <= 0)
            out.push_back(a);
        if ((da < 0) != (db < 0) && da != db) {
            const double t = da / (da - db);
            out.push_back({a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])});
        }
    }
    return out;
}

/// A joint in pixels: a ring at A's anchor, a line to B's (a distance joint's rod or rope, or a
/// joint pulled apart), and a hinge's or slider's axis as seen (a slider's dashed).
void drawJointMark(std::string& svg, const Item& item, const Point& a, const Point& b) {
    char buf[256];
    const char* colour = item.fill.c_str();
    std::snprintf(buf, sizeof buf,
                  "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"2.5\" fill=\"none\" stroke=\"%s\" "
                  "stroke-width=\"1.2\"/>\n",
                  a[0], a[1], colour);
    svg += buf;
    if (std::hypot(b[0] - a[0], b[1] - a[1]) > 0.5) {
        std::snprintf(buf, sizeof buf,
                      "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"%s\" "
                      "stroke-width=\"1.2\"/>\n",
                      a[0], a[1], b[0], b[1], colour);
        svg += buf;
    }
    const double n = std::hypot(item.normal[0], item.normal[1]);
    if ((item.joint == JointType::Hinge || item.joint == JointType::Slider) && n > 1e-3) {
        const double du = 9 * item.normal[0] / n, dv = -9 * item.normal[1] / n;
        std::snprintf(buf, sizeof buf,
                      "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"%s\" "
                      "stroke-width=\"1.2\"%s/>\n",
                      a[0] - du, a[1] - dv, a[0] + du, a[1] + dv, colour,
                      item.joint == JointType::Slider ? " stroke-dasharray=\"2,2\"" : "");
        svg += buf;
    }
}

}  // namespace

View parseView(const std::string& name) {
    if (name == "side")
        return View::Side;
    if (name == "top")
        return View::Top;
    if (name == "front")
        return View::Front;
    fail("view \"", name, "\" is not one of side, top, front");
}

SvgPicture::SvgPicture(View view, std::string title) : view_(view), title_(std::move(title)) {}

void SvgPicture::addPanel(const World& world, std::span<const ShapeId> shapes,
                          std::span<const SpringId> springs, std::span<const JointId> joints,
                          Real time) {
    panels_.push_back({time, {}});
    PanelRecorder recorder(view_, panels_.back());
    describeWorld(world, shapes, recorder, kDrawShapes | kDrawContacts);
    describeSprings(world, springs, recorder);
    describeJoints(world, joints, recorder);
    std::stable_sort(panels_.back().items.begin(), panels_.back().items.end(),
                     [](const Item& a, const Item& b) { return a.depth > b.depth; });
}

void SvgPicture::addTracePoint(int body, Real time, const Vec3& point) {
    auto it = std::find_if(traces_.begin(), traces_.end(),
                           [&](const auto& t) { return t.first == body; });
    if (it == traces_.end()) {
        traces_.push_back({body, {}});
        it = traces_.end() - 1;
    }
    const auto p = project(view_, point);
    it->second.push_back({time, {p[0], p[1]}});
}

std::string SvgPicture::render() const {
    // One scale for every panel, from everything bounded that any panel shows.
    double u0 = 1e300, v0 = 1e300, u1 = -1e300, v1 = -1e300;
    auto grow = [&](const Point& p, double r) {
        u0 = std::min(u0, p[0] - r), u1 = std::max(u1, p[0] + r);
        v0 = std::min(v0, p[1] - r), v1 = std::max(v1, p[1] + r);
    };
    for (const Panel& panel : panels_) {
        for (const Item& item : panel.items) {
            if (item.kind == Item::Kind::Polygon || item.kind == Item::Kind::Line ||
                item.kind == Item::Kind::Joint)
                for (const Point& p : item.points)
                    grow(p, 0);
            else if (item.kind == Item::Kind::Circle)
                grow(item.points[0], item.offset);
        }
    }
    for (const auto& [body, points] : traces_)
        for (const TracePoint& t : points)
            grow(t.point, 0);
    if (u0 > u1)
        u0 = v0 = -1, u1 = v1 = 1;
    // Pad, and keep the aspect within 3:1 so a long row still leaves room to see its height.
    const double pad = 0.08 * std::max(u1 - u0, v1 - v0) + 0.01;
    u0 -= pad, u1 += pad, v0 -= pad, v1 += pad;
    const double minHeight = (u1 - u0) / 3, minWidth = (v1 - v0) / 3;
    if (v1 - v0 < minHeight)  // room above: what is low (the ground) stays at the bottom
        v1 = v0 + minHeight;
    if (u1 - u0 < minWidth) {
        const double c = (u0 + u1) / 2;
        u0 = c - minWidth / 2, u1 = c + minWidth / 2;
    }
    const double scale = std::min(360 / (u1 - u0), 360 / (v1 - v0));  // px per m
    const double pw = (u1 - u0) * scale, ph = (v1 - v0) * scale;
    const double margin = 16, header = 44, caption = 20;
    const double width = margin + static_cast<double>(panels_.size()) * (pw + margin);
    const double height = header + caption + ph + margin + 20;
    auto px = [&](const Point& p) { return Point{(p[0] - u0) * scale, (v1 - p[1]) * scale}; };
    std::string svg;
    auto polygon = [&](const std::vector<Point>& points, const std::string& fill,
                       const char* stroke) {
        svg += "<polygon points=\"";
        for (const Point& p : points) {
            const Point q = px(p);
            appendf(svg, "%.1f,%.1f ", q[0], q[1]);
        }
        appendf(svg, "\" fill=\"%s\" stroke=\"%s\" stroke-width=\"0.8\"/>\n", fill.c_str(), stroke);
    };
    appendf(svg,
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" "
            "font-family=\"sans-serif\" font-size=\"12\">\n",
            width, height);
    appendf(svg, "<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n");
    std::string title;
    for (const char c : title_)  // XML-escape the scene's own text
        title += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : std::string(1, c);
    appendf(svg, "<text x=\"%.0f\" y=\"18\" font-size=\"14\">%s</text>\n", margin, title.c_str());
    const char* axes = view_ == View::Side    ? "side view: x right, z up"
                       : view_ == View::Front ? "front view: y right, z up"
                                              : "top view: x right, y up";
    double bar = std::pow(10.0, std::floor(std::log10((u1 - u0) / 4)));
    if (bar * 5 <= (u1 - u0) / 4)
        bar *= 5;
    else if (bar * 2 <= (u1 - u0) / 4)
        bar *= 2;
    appendf(svg,
            "<text x=\"%.0f\" y=\"36\" fill=\"#555\">%s; scale bar %g m; red: contacts; blue: "
            "springs and threads (dashed: slack); orange: joints; dark lines: traced centres of "
            "mass</text>\n",
            margin, axes, bar);
    for (std::size_t k = 0; k < panels_.size(); ++k) {
        const Panel& panel = panels_[k];
        const double x0 = margin + static_cast<double>(k) * (pw + margin), y0 = header + caption;
        appendf(svg, "<text x=\"%.1f\" y=\"%.1f\">t = %.3f s</text>\n", x0, y0 - 6, panel.time);
        appendf(svg,
                "<defs><clipPath id=\"p%zu\"><rect width=\"%.1f\" height=\"%.1f\"/></clipPath>"
                "</defs>\n",
                k, pw, ph);
        appendf(svg, "<g transform=\"translate(%.1f,%.1f)\" clip-path=\"url(#p%zu)\">\n", x0, y0,
                k);
        appendf(svg, "<rect width=\"%.1f\" height=\"%.1f\" fill=\"#f7f9fc\"/>\n", pw, ph);
        for (const Item& item : panel.items) {
            if (item.kind == Item::Kind::Plane) {
                polygon(clipHalfPlane(item.normal, item.offset, u0 - 1, v0 - 1, u1 + 1, v1 + 1),
                        "#d9d4cc", "#8a8275");
            } else if (item.kind == Item::Kind::Polygon) {
                polygon(item.points, item.fill, "#333");
            } else if (item.kind == Item::Kind::Circle) {
                const Point c = px(item.points[0]), r = px(item.points[1]);
                appendf(svg,
                        "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"%.1f\" fill=\"%s\" stroke=\"#333\" "
                        "stroke-width=\"0.8\"/>\n",
                        c[0], c[1], item.offset * scale, item.fill.c_str());
                appendf(svg,
                        "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#333\" "
                        "stroke-width=\"0.8\"/>\n",
                        c[0], c[1], r[0], r[1]);
            } else if (item.kind == Item::Kind::Line) {
                const Point a = px(item.points[0]), b = px(item.points[1]);
                appendf(svg,
                        "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"%s\" "
                        "stroke-width=\"0.8\"%s/>\n",
                        a[0], a[1], b[0], b[1], item.fill.c_str(),
                        item.dashed ? " stroke-dasharray=\"2,2\"" : "");
            } else if (item.kind == Item::Kind::Joint) {
                drawJointMark(svg, item, px(item.points[0]), px(item.points[1]));
            } else if (item.kind == Item::Kind::Contact) {
                const Point p = px(item.points[0]);
                const double n = std::hypot(item.normal[0], item.normal[1]);
                appendf(svg, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"1.2\" fill=\"#d22\"/>\n", p[0],
                        p[1]);
                if (n > 1e-3)
                    appendf(svg,
                            "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#d22\" "
                            "stroke-width=\"0.8\"/>\n",
                            p[0], p[1], p[0] + 6 * item.normal[0] / n,
                            p[1] - 6 * item.normal[1] / n);
            }
        }
        for (std::size_t t = 0; t < traces_.size(); ++t) {
            svg += "<polyline fill=\"none\" stroke-width=\"1.2\" stroke=\"";
            appendf(svg, "hsl(%.0f,80%%,30%%)\" points=\"",
                    std::fmod(static_cast<double>(t) * 97.0 + 200, 360.0));
            for (const TracePoint& p : traces_[t].second) {
                if (p.time > panel.time + 1e-9)
                    break;
                const Point q = px(p.point);
                appendf(svg, "%.1f,%.1f ", q[0], q[1]);
            }
            svg += "\"/>\n";
        }
        if (k == 0)
            appendf(svg,
                    "<line x1=\"8\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"black\" "
                    "stroke-width=\"2\"/>\n",
                    ph - 8, 8 + bar * scale, ph - 8);
        appendf(svg,
                "</g>\n<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"none\" "
                "stroke=\"#888\"/>\n",
                x0, y0, pw, ph);
    }
    svg += "</svg>\n";
    return svg;
}

}  // namespace tumble::cli
