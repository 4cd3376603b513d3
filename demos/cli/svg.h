#pragma once
/// The picture: a scene drawn orthographically from one view at several times, side by side, with
/// the trajectories of chosen bodies, as an SVG document. Built on DebugDraw: each panel is what
/// describeWorld reports at that moment.

#include <array>
#include <span>
#include <string>
#include <vector>

#include "tumble/debug_draw.h"
#include "tumble/world.h"

namespace tumble::cli {

/// Orthographic views, +Z up in the world: side looks along +y (x right, z up), front along -x
/// (y right, z up), top down along -z (x right, y up).
enum class View { Side, Top, Front };

/// "side", "top" or "front"; anything else is refused (InvalidArgument).
View parseView(const std::string& name);

class SvgPicture {
public:
    SvgPicture(View view, std::string title);

    /// A panel showing the listed shapes, springs and joints (and touching contacts) as they
    /// are now.
    void addPanel(const World& world, std::span<const ShapeId> shapes,
                  std::span<const SpringId> springs, std::span<const JointId> joints, Real time);
    /// A point of a traced body's trajectory (its centre of mass, m) at `time` (s).
    void addTracePoint(int body, Real time, const Vec3& point);
    /// The SVG document.
    std::string render() const;

    /// What a panel holds, in view coordinates (u right, v up, m); depth grows away from the
    /// viewer.
    struct Item {
        enum class Kind { Polygon, Circle, Plane, Contact, Rectangle, Line, Joint };
        Kind kind = Kind::Polygon;
        /// Polygon outline; circle centre + rim point; line ends; joint anchors A and B.
        std::vector<std::array<double, 2>> points;
        /// Plane: n.q = offset; contact: direction; joint: its axis as seen (hinge, slider).
        std::array<double, 2> normal{};
        double offset = 0;
        double depth = 0;
        std::string fill;     ///< shapes; a line's or joint's stroke colour
        bool dashed = false;  ///< a slack thread
        JointType joint = JointType::Ball;
    };
    struct Panel {
        Real time = 0;
        std::vector<Item> items;
    };
    struct TracePoint {
        Real time = 0;
        std::array<double, 2> point{};
    };

private:
    View view_;
    std::string title_;
    std::vector<Panel> panels_;
    std::vector<std::pair<int, std::vector<TracePoint>>> traces_;
};

}  // namespace tumble::cli
