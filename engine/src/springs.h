#pragma once
/// The force elements of a step: explicit spring-dampers and drag (before the velocity update),
/// the rows of the implicit springs (for the solve stage), and the islands springs join.

#include <cstdint>
#include <vector>

#include "body_store.h"
#include "contact_manager.h"
#include "island.h"
#include "spring_store.h"
#include "step_context.h"
#include "tumble/solver/spring_row.h"

namespace tumble {

/// World position of a spring anchor: on the body, or the world point itself for a null body.
Vec3 anchorPosition(const BodyStore& bodies, BodyId body, const Vec3& localAnchor);

/// World position of the anchor of the body at dense `index` (no handle lookup). A lumped
/// node's anchor is its centre: no rotation.
inline Vec3 anchorAt(const BodyStore& bodies, std::uint32_t index, const Vec3& localAnchor) {
    const BodyMotion& m = bodies.motion[index];
    const Vec3 offset = localAnchor - bodies.inertia[index].localCenter;
    return offset.isZero() ? m.center : Vec3(m.center + m.orientation * offset);
}

/// Dense indices of an implicit spring row's bodies (b is meaningless for a world end).
struct RowBodies {
    std::uint32_t a = 0;
    std::uint32_t b = 0;
    bool world = false;  ///< B is the world point itself
    /// Both anchors at their bodies' centres of mass (not a world end), as anchorAt() finds
    /// them: the span is the centres' difference. A net's nodes; the end-of-step check of its
    /// slack threads (solve_stage.cpp) then reads neither the definition nor a rotation.
    bool centred = false;
};

/// Whether anchorAt() puts the anchor at the body's centre of mass (no rotation).
inline bool anchorCentred(const BodyStore& bodies, std::uint32_t index, const Vec3& localAnchor) {
    return (localAnchor - bodies.inertia[index].localCenter).isZero();
}

/// Anchor distance of spring `index` at the current poses (m).
Real springLength(const SpringStore& springs, const BodyStore& bodies, std::uint32_t index);

/// Elastic energy of every spring at the current poses (J): k (L - L0)^2 / 2, and nothing for a
/// tension-only element shorter than its rest length.
Real springPotentialEnergy(const SpringStore& springs, const BodyStore& bodies);

/// Substeps for a step of h in which undamped threads on the discrete gradient work (spring_row.h):
/// the most that keeps every such thread that is taut, or caught within the step, and whose length
/// changes, on the gradient (floor(omega h / 2)); 1 when none works. See docs/ARCHITECTURE.md.
int threadSubsteps(const SpringStore& springs, const BodyStore& bodies, Real h);

/// A spring keeps both its bodies in one island: wakes every sleeping dynamic body linked by a
/// spring to an awake dynamic or moving kinematic body, repeated until nothing more wakes.
void wakeSpringLinked(const SpringStore& springs, BodyStore& bodies, ContactManager& contacts,
                      Islands& islands);

/// The forces stage's share of springs and drag. apply() adds the explicit springs' forces and
/// drag to BodyStore::forces of the awake dynamic bodies (saving what the application had put
/// there), restore() puts the application's forces back after the velocity update, so a failed
/// step leaves them as they were.
class ForceElements {
public:
    void apply(SpringStore& springs, const DragStore& drag, BodyStore& bodies);
    void restore(BodyStore& bodies);

private:
    std::vector<std::uint32_t> savedBodies_;  ///< the bodies awake at apply()
    std::vector<BodyForces> saved_;           ///< their forces then, in the same order
    bool applied_ = false;
};

/// Rows of the implicit springs with an awake dynamic body at either end. `solverIndex` maps a
/// body's dense index to its solver body; rows are warm-started from last step's tension.
/// rowBodies: each row's dense body indices, for the step's later passes over the rows.
template <typename SolverIndex>
void buildSpringRows(const SpringStore& springs, const BodyStore& bodies, Real h,
                     SolverIndex&& solverIndex, std::vector<SpringRow>& rows,
                     std::vector<std::uint32_t>& rowSpring, std::vector<RowBodies>& rowBodies);

}  // namespace tumble

#include "springs_inl.h"
