#pragma once
/// The engine's side of joints: the frames stored at creation, the rows built for each step, the
/// results written back (reaction, breaking), and the islands joints hold together.

#include <cstdint>
#include <span>
#include <vector>

#include "body_store.h"
#include "contact_manager.h"
#include "island.h"
#include "joint_store.h"
#include "shape_store.h"
#include "step_context.h"
#include "tumble/solver/joint_row.h"

namespace tumble {

/// A joint measured at the current poses and velocities.
struct JointFrame {
    std::uint32_t a = 0;  ///< dense body index of A
    std::uint32_t b = 0;  ///< of B; meaningless when world
    bool world = false;   ///< B is the world (null bodyB)
    Vec3 rA = Vec3::Zero();
    Vec3 rB = Vec3::Zero();
    Vec3 separation = Vec3::Zero();  ///< anchor B - anchor A (m)
    Vec3 axis = Vec3::UnitZ();       ///< A's axis, world
    Vec3 angularError = Vec3::Zero();
    Real position = 0;  ///< angle, translation or distance
    Real speed = 0;     ///< its rate
};

/// The body-frame record of a definition checked by the caller, at the bodies' current poses.
JointRecord makeJointRecord(const JointDef& def, const BodyStore& bodies);

JointFrame jointFrame(const JointRecord& record, const BodyStore& bodies);

/// Rows of the joints that are not broken and have an awake dynamic body at either end, warm-
/// started from last step's forces.
void buildJointRows(const JointStore& joints, const BodyStore& bodies, Real h,
                    std::vector<JointRow>& rows, std::vector<std::uint32_t>& rowJoint);

/// Writes the solved impulses back as forces and reactions; a joint whose reaction exceeds its
/// break force or torque is marked broken and its index appended to `broken`.
void storeJointResults(JointStore& joints, std::span<const JointRow> rows,
                       std::span<const std::uint32_t> rowJoint, Real h,
                       std::vector<std::uint32_t>& broken);

/// Excludes from collision (or lets collide again) every shape pair of joint `index`'s two
/// bodies. Allowing them again leaves excluded what another unbroken joint with
/// collideConnected = false still joins.
void setJointedPairsExcluded(const JointStore& joints, const ShapeStore& shapes,
                             const BodyStore& bodies, ContactManager& contacts, std::uint32_t index,
                             bool excluded);
/// A new shape on a jointed body: excluded from the shapes of the bodies it is joined to.
void excludeJointedPairs(const JointStore& joints, const ShapeStore& shapes,
                         const BodyStore& bodies, ContactManager& contacts,
                         std::uint32_t shapeSlot);

/// A joint keeps both its bodies in one island: wakes every sleeping dynamic body joined to an
/// awake dynamic or moving kinematic body, until nothing more wakes. `midStep` as for
/// Islands::wake.
void wakeJointLinked(const JointStore& joints, BodyStore& bodies, ContactManager& contacts,
                     Islands& islands, const StepContext* midStep = nullptr);

}  // namespace tumble
