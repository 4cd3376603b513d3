#include "tumble/checkpoint.h"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <system_error>
#include <utility>

#include "checkpoint_io.h"
#include "checkpoint_surfaces.h"
#include "checks.h"
#include "tumble/solver/contact_solver.h"  // checkSolverSettings
#include "world_impl.h"

namespace tumble {
namespace checkpoint_io {

// --- public records ---------------------------------------------------------------------------
// Each lists every field, in declaration order: a field added to a record must be added here
// (and kCheckpointVersion bumped).

// An id is saved without its world tag (a tag is not state: two worlds stepping alike save alike)
// and read back with the tag of the world being loaded.
template <typename Ar, typename Id>
requires(std::is_same_v<Id, BodyId> || std::is_same_v<Id, ShapeId> || std::is_same_v<Id, JointId> ||
         std::is_same_v<Id, SpringId>) void field(Ar& a, Id& x) {
    fields(a, x.index, x.generation);
    if constexpr (Ar::kReading)
        x.world = x.isNull() ? 0 : a.world;
}
template <typename Ar>
void field(Ar& a, Transform& x) {
    fields(a, x.position, x.rotation);
}
template <typename Ar>
void field(Ar& a, Aabb& x) {
    fields(a, x.lower, x.upper);
}
template <typename Ar>
void field(Ar& a, MassProperties& x) {
    fields(a, x.mass, x.localCenter, x.inertia);
}
template <typename Ar>
void field(Ar& a, SolverSettings& x) {
    fields(a, x.iterations, x.relaxIterations, x.linkIterations, x.linkRelaxIterations, x.tolerance,
           x.relaxation, x.friction, x.stabilisation, x.baumgarte, x.splitImpulseFactor, x.slop,
           x.restitutionThreshold, x.warmStart, x.springSolve, x.projectSprings,
           x.jointGeometricStiffness, x.jointSolve, x.frictionAnchors, x.colouredContacts,
           x.softSubsteps, x.contactHertz, x.contactDampingRatio, x.maxPushOutSpeed);
}
template <typename Ar>
void field(Ar& a, WorldDef& x) {
    fields(a, x.gravity, x.timeStep, x.maxStepsPerAdvance, x.substeps, x.contactMargin,
           x.aabbMargin, x.solver, x.enableSleep, x.linearSleepVelocity, x.angularSleepVelocity,
           x.timeToSleep, x.impactSpeedThreshold);
}
template <typename Ar>
void field(Ar& a, SolverStats& x) {
    fields(a, x.iterations, x.maxResidual, x.deepestPenetration);
}

template <typename Ar>
void field(Ar& a, BodyMotion& x) {
    fields(a, x.center, x.orientation, x.linearVelocity, x.angularVelocity);
}
template <typename Ar>
void field(Ar& a, BodyInertia& x) {
    fields(a, x.inverseMass, x.localCenter, x.inertiaLocal, x.inverseInertiaLocal);
}
template <typename Ar>
void field(Ar& a, BodyForces& x) {
    fields(a, x.force, x.torque);
}
template <typename Ar>
void field(Ar& a, BodyInfo& x) {
    fields(a, x.type, x.linearDamping, x.angularDamping, x.gravityScale, x.mass, x.userData,
           x.firstShape, x.firstContact, x.awakeIndex, x.sleepTime, x.allowSleep, x.pushed,
           x.builtAsleep, x.massFromShapes, x.fixedRotation);
}

template <typename Ar>
void field(Ar& a, HullFace& x) {
    fields(a, x.normal, x.offset, x.first, x.count);
}

template <typename Ar>
void field(Ar& a, Shape& shape) {
    std::uint8_t type = static_cast<std::uint8_t>(shape.index());
    field(a, type);
    if constexpr (Ar::kReading) {
        switch (static_cast<ShapeType>(type)) {
            case ShapeType::Sphere:
                shape = Sphere{};
                break;
            case ShapeType::Capsule:
                shape = Capsule{};
                break;
            case ShapeType::Box:
                shape = Box{};
                break;
            case ShapeType::Cylinder:
                shape = Cylinder{};
                break;
            case ShapeType::ConvexHull:
                shape = ConvexHull{std::make_shared<HullData>()};
                break;
            case ShapeType::HalfSpace:
                shape = HalfSpace{};
                break;
            case ShapeType::TriangleMesh:
                shape = TriangleMesh{};
                break;
            case ShapeType::HeightField:
                shape = HeightField{};
                break;
            default:
                a.corrupt("shape type ", int{type});
        }
    }
    if (isTriangleSurface(shape)) {
        surfaceReference(a, shape);
        return;
    }
    std::visit(
        [&](auto& s) {
            using S = std::decay_t<decltype(s)>;
            if constexpr (std::is_same_v<S, Sphere>) {
                fields(a, s.radius);
            } else if constexpr (std::is_same_v<S, Capsule> || std::is_same_v<S, Cylinder>) {
                fields(a, s.radius, s.halfLength);
            } else if constexpr (std::is_same_v<S, Box>) {
                fields(a, s.halfExtents);
            } else if constexpr (std::is_same_v<S, HalfSpace>) {
                fields(a, s.normal, s.offset);
            } else if constexpr (std::is_same_v<S, ConvexHull>) {
                bool present = s.data != nullptr;
                field(a, present);
                if constexpr (Ar::kReading)
                    s.data = present ? std::make_shared<HullData>() : nullptr;
                if (!present)
                    return;
                // Hull data is shared and immutable once built; the writer only reads it, and
                // the reader fills the fresh copy it just made.
                auto& data = const_cast<HullData&>(*s.data);
                fields(a, data.vertices, data.faces, data.faceVertices, data.edges, data.centroid);
            } else {
                static_assert(std::is_same_v<S, TriangleMesh> || std::is_same_v<S, HeightField>);
            }
        },
        shape);
}
template <typename Ar>
void field(Ar& a, ShapeDef& x) {
    fields(a, x.geometry, x.localPose, x.material.friction, x.material.restitution,
           x.material.density, x.material.spinningFriction, x.material.rollingFriction,
           x.filter.category, x.filter.mask, x.updateBodyMass);
}
template <typename Ar>
void field(Ar& a, ShapeRecord& x) {
    fields(a, x.def, x.body, x.proxy, x.fatBounds, x.bounds, x.nextInBody);
}

template <typename Ar>
void field(Ar& a, Manifold& x) {
    fields(a, x.normal, x.pointCount);
    if constexpr (Ar::kReading) {
        if (x.pointCount < 0 || x.pointCount > Manifold::kMaxPoints)
            a.corrupt("manifold point count ", x.pointCount);
    }
    for (ContactPoint& p : x.points)
        fields(a, p.position, p.separation, p.featureId);
}
template <typename Ar>
void field(Ar& a, Contact& x) {
    fields(a, x.shapeA, x.shapeB, x.bodyA, x.bodyB, x.manifold, x.normalImpulse, x.tangentImpulse,
           x.angularImpulse);
}

template <typename Ar>
void field(Ar& a, JointDef& x) {
    fields(a, x.type, x.bodyA, x.bodyB, x.anchor, x.anchorB, x.axis, x.length, x.rope,
           x.enableLimit, x.lower, x.upper, x.enableMotor, x.motorSpeed, x.maxMotorForce,
           x.breakForce, x.breakTorque, x.collideConnected);
}
template <typename Ar>
void field(Ar& a, JointRecord& x) {
    fields(a, x.def, x.localAnchorA, x.localAnchorB, x.localAxisA, x.localAxisB, x.localReferenceA,
           x.localReferenceB, x.relativeOrientation, x.length);
}
template <typename Ar>
void field(Ar& a, JointStepState& x) {
    fields(a, x.linearForce, x.previousLinearForce, x.angularTorque, x.motorForce, x.lowerForce,
           x.upperForce, x.force, x.torque, x.broken);
}
template <typename Ar>
void field(Ar& a, SpringDef& x) {
    fields(a, x.bodyA, x.bodyB, x.localAnchorA, x.localAnchorB, x.restLength, x.stiffness,
           x.damping, x.tensionOnly, x.formulation, x.numericalDamping, x.contactRadius,
           x.contactFriction);
}
template <typename Ar>
void field(Ar& a, SpringStepState& x) {
    fields(a, x.tension, x.slack, x.carried);
}
template <typename Ar>
void field(Ar& a, Drag& x) {
    fields(a, x.linear, x.quadratic, x.projection);
}
template <typename Ar>
void field(Ar& a, ControllerDef& x) {
    fields(a, x.mode, x.target, x.targetVelocity, x.kp, x.ki, x.kd, x.maxForce);
}
template <typename Ar>
void field(Ar& a, ControllerState& x) {
    fields(a, x.error, x.integral, x.output);
}
template <typename Ar>
void field(Ar& a, ControllerRecord& x) {
    fields(a, x.joint, x.def, x.state, x.previousState, x.started, x.previousStarted);
}

template <typename Ar>
void field(Ar& a, ContactEvent& x) {
    fields(a, x.shapeA, x.shapeB, x.bodyA, x.bodyB);
}
template <typename Ar>
void field(Ar& a, ImpactEvent& x) {
    fields(a, x.shapeA, x.shapeB, x.bodyA, x.bodyB, x.point, x.normal, x.approachSpeed,
           x.normalImpulse);
}
template <typename Ar>
void field(Ar& a, JointBreakEvent& x) {
    fields(a, x.joint, x.bodyA, x.bodyB, x.force, x.torque);
}
template <typename Ar>
void field(Ar& a, SleepEvent& x) {
    fields(a, x.body, x.asleep);
}
template <typename Ar>
void field(Ar& a, EventLog& x) {
    fields(a, x.contactBegin, x.contactEnd, x.impact, x.jointBreak, x.sleep);
}
template <typename Ar>
void field(Ar& a, ProxyFilter& x) {
    fields(a, x.category, x.mask, x.isStatic);
}
template <typename Ar>
void field(Ar& a, ProxyPair& x) {
    fields(a, x.first, x.second);
}

}  // namespace checkpoint_io

using checkpoint_io::fields;
using checkpoint_io::sequence;
using checkpoint_io::surfaceSection;

/// Friend of World and of the stores: lists their private state.
struct CheckpointAccess {
    using Impl = World::Impl;

    template <typename Ar>
    static void io(Ar& a, SweepAndPrune& x) {
        sequence(a, x.proxies_, [&](SweepAndPrune::Proxy& p) {
            fields(a, p.box, p.filter, p.endpoint, p.moveSlot, p.activeSlot, p.state, p.isIndexed,
                   p.isNew, p.isLarge);
        });
        for (auto& list : x.endpoints_)
            sequence(a, list, [&](SweepAndPrune::Endpoint& e) { fields(a, e.value, e.tag); });
        sequence(a, x.moves_, [&](SweepAndPrune::Move& m) { fields(a, m.proxy, m.box); });
        fields(a, x.pending_, x.removing_, x.freeIds_, x.large_, x.excluded_, x.candidates_,
               x.pairs_, x.added_, x.removed_, x.liveCount_, x.axis_, x.structureChanged_,
               x.sweepNeeded_, x.centreSum_, x.centreSquareSum_, x.centreReference_,
               x.largeThreshold_, x.reach_);
    }

    /// The grid: its cells' sweep-and-prunes and the pair counts. The cell index is rebuilt
    /// from the cells' keys; scratch buffers are not saved.
    template <typename Ar>
    static void io(Ar& a, GridBroadphase& x) {
        sequence(a, x.proxies_, [&](GridBroadphase::Proxy& p) {
            fields(a, p.box, p.publishedBox, p.filter, p.range.lower, p.range.upper,
                   p.publishedRange.lower, p.publishedRange.upper, p.oversizedLocal, p.state,
                   p.isOversized, p.wasOversized, p.isDirty, p.wasLive);
            sequence(a, p.cells,
                     [&](GridBroadphase::Membership& m) { fields(a, m.cell, m.local); });
        });
        sequence(a, x.cells_, [&](GridBroadphase::Cell& c) {
            io(a, c.sap);
            fields(a, c.globalId, c.key, c.isDirty);
        });
        io(a, x.oversized_);
        sequence(a, x.counts_, [&](GridBroadphase::PairCount& c) { fields(a, c.pair, c.count); });
        fields(a, x.oversizedGlobal_, x.oversizedList_, x.oversizedPublished_, x.oversizedDirty_,
               x.dirtyCells_, x.dirty_, x.freeIds_, x.excluded_, x.toggled_, x.crossPairs_,
               x.pairs_, x.added_, x.removed_, x.liveCount_);
        if constexpr (Ar::kReading) {
            x.cellIndex_.clear();
            for (std::uint32_t i = 0; i < x.cells_.size(); ++i) {
                if (!x.cellIndex_.emplace(x.cells_[i].key, i).second)
                    a.corrupt("two grid cells with one key");
            }
            x.visitMark_.clear();
            x.rayStamp_ = 0;
        }
    }

    /// The id table of a store: slots, dense order, free list (not the world tag).
    template <typename Ar, typename Id>
    static void io(Ar& a, HandlePool<Id>& x) {
        sequence(a, x.slots_, [&](typename HandlePool<Id>::Slot& s) {
            fields(a, s.generation, s.dense, s.alive);
        });
        fields(a, x.slotOf_, x.freeSlots_);
    }

    template <typename Ar>
    static void io(Ar& a, ContactManager& x) {
        io(a, x.broadphase_);
        // Each slot's record and flags together, as when they were one struct (the format
        // stays); the flags' array grows with the records as they are read.
        sequence(a, x.pool_, [&](ContactManager::Record& r) {
            const auto slot = static_cast<std::size_t>(&r - x.pool_.data());
            if (x.state_.size() != x.pool_.size())
                x.state_.resize(x.pool_.size());
            ContactManager::SlotState& s = x.state_[slot];
            fields(a, r.contact, s.key, r.next, r.previous, s.alive, s.active, s.listed, s.queued,
                   r.nextPart, s.part);
            s.shapeA = r.contact.shapeA.index;
            s.shapeB = r.contact.shapeB.index;
            s.cleared = false;
        });
        x.state_.resize(x.pool_.size());
        fields(a, x.proxyToShape_, x.freeSlots_, x.dead_, x.active_, x.activated_, x.wakeRequests_,
               x.placedProxies_, x.contactMargin, x.aabbMargin);
        x.viewStale_ = true;
    }

    template <typename Ar>
    static void io(Ar& a, World::Impl& w) {
        fields(a, w.settings, w.time, w.stepCount, w.accumulator, w.solverStats);
        BodyStore& b = w.bodies;
        fields(a, b.motion, b.previousMotion, b.inertia, b.forces, b.info, b.awake);
        io(a, b.pool_);
        surfaceSection(a, w.shapes.records);
        fields(a, w.shapes.records);
        io(a, w.shapes.pool_);
        io(a, w.contacts);
        AnchorTable& anchors = w.solve.anchors_;
        sequence(a, anchors.entries_, [&](AnchorTable::Entry& e) {
            fields(a, e.onA, e.onB, e.feature, e.count, e.solve, e.drift, e.reseated);
        });
        fields(a, anchors.solve_);
        // The thread contacts' warm start (thread_contacts.h): indices only compared, never used
        // to index, so a corrupt entry costs one step's warm start, nothing more.
        sequence(a, w.solve.threadContacts_.cache_, [&](ThreadContacts::Cached& c) {
            fields(a, c.spring, c.slot, c.t, c.normal, c.normalImpulse, c.tangentImpulse);
        });
        SpringStore& s = w.springs;
        fields(a, s.defs, s.state, s.previousState, s.implicitCount, s.contactCount);
        s.forgetStiffest();  // not saved: found again from the definitions read
        io(a, s.pool_);
        JointStore& j = w.joints;
        fields(a, j.records, j.state, j.previousState);
        io(a, j.pool_);
        fields(a, w.drag.bodies, w.drag.drags, w.drag.denseOfSlot_, w.controllers.records_);
        sequence(a, w.impacts.bySlot_, [&](ImpactTracker::Open& o) { fields(a, o.event, o.open); });
        fields(a, w.impacts.opened_, w.pendingEvents, w.events);
    }

    /// An id table that maps `count` dense elements to live slots and back, whose every other
    /// slot is free.
    template <typename Id>
    static void check(const checkpoint_io::Reader& r, const HandlePool<Id>& pool, std::size_t count,
                      const char* what) {
        if (pool.slotOf_.size() != count)
            r.corrupt(what, " ids: ", pool.slotOf_.size(), " for ", count, " elements");
        if (pool.freeSlots_.size() + count != pool.slots_.size())
            r.corrupt(what, " ids: free and live slots do not add up");
        for (std::uint32_t i = 0; i < count; ++i) {
            const std::uint32_t slot = pool.slotOf_[i];
            if (!(slot < pool.slots_.size() && pool.slots_[slot].alive &&
                  pool.slots_[slot].dense == i))
                r.corrupt(what, " slot ", slot, " does not point back at element ", i);
        }
        for (const std::uint32_t slot : pool.freeSlots_) {
            if (!(slot < pool.slots_.size() && !pool.slots_[slot].alive))
                r.corrupt("free ", what, " slot ", slot, " out of range or alive");
        }
    }

    /// Every index in `values` lands inside an array of `size` (or is kNoIndex, if allowed).
    template <typename Values>
    static void inRange(const checkpoint_io::Reader& r, const Values& values, std::size_t size,
                        bool noneAllowed, const char* what) {
        constexpr std::uint32_t kNoIndex = 0xFFFFFFFF;
        for (const auto v : values) {
            if (!(v < size || (noneAllowed && v == kNoIndex)))
                r.corrupt(what, " ", v, " out of range (", size, ")");
        }
    }

    static void check(const checkpoint_io::Reader& r, const SweepAndPrune& sap) {
        const std::size_t proxies = sap.proxies_.size();
        for (const SweepAndPrune::Proxy& proxy : sap.proxies_) {
            for (int axis = 0; axis < 3; ++axis) {
                if (proxy.isIndexed)
                    inRange(r, proxy.endpoint[axis], sap.endpoints_[axis].size(), false,
                            "endpoint");
            }
        }
        for (const auto& list : sap.endpoints_) {
            for (const SweepAndPrune::Endpoint& e : list)
                inRange(r, std::array{e.proxy()}, proxies, false, "endpoint's proxy");
        }
        for (const SweepAndPrune::Move& m : sap.moves_)
            inRange(r, std::array{m.proxy}, proxies, false, "moved proxy");
        for (const auto* list : {&sap.pending_, &sap.removing_, &sap.freeIds_, &sap.large_})
            inRange(r, *list, proxies, false, "proxy");
        for (const auto* list :
             {&sap.excluded_, &sap.candidates_, &sap.pairs_, &sap.added_, &sap.removed_}) {
            for (const ProxyPair& pair : *list) {
                inRange(r, std::array{pair.first, pair.second}, proxies, false, "paired proxy");
            }
        }
        if (sap.axis_ < 0 || sap.axis_ > 2)
            r.corrupt("sweep axis ", sap.axis_);
    }

    static void check(const checkpoint_io::Reader& r, const GridBroadphase& grid) {
        const std::size_t proxies = grid.proxies_.size();
        const std::size_t cells = grid.cells_.size();
        check(r, grid.oversized_);
        for (const GridBroadphase::Cell& cell : grid.cells_) {
            check(r, cell.sap);
            if (cell.globalId.size() < cell.sap.proxies_.size())
                r.corrupt("a grid cell's id table is shorter than its proxies");
            inRange(r, cell.globalId, proxies, true, "grid cell's proxy");
        }
        for (const GridBroadphase::Proxy& proxy : grid.proxies_) {
            for (const GridBroadphase::Membership& m : proxy.cells) {
                inRange(r, std::array{m.cell}, cells, false, "proxy's cell");
                inRange(r, std::array{m.local}, grid.cells_[m.cell].sap.proxies_.size(), false,
                        "proxy's id in a cell");
            }
            inRange(r, std::array{proxy.oversizedLocal}, grid.oversized_.proxies_.size(), true,
                    "oversized id");
        }
        if (grid.oversizedGlobal_.size() < grid.oversized_.proxies_.size())
            r.corrupt("the oversized id table is shorter than its proxies");
        inRange(r, grid.oversizedGlobal_, proxies, true, "oversized proxy");
        for (const auto* list :
             {&grid.oversizedList_, &grid.oversizedPublished_, &grid.dirty_, &grid.freeIds_})
            inRange(r, *list, proxies, false, "grid proxy");
        inRange(r, grid.dirtyCells_, cells, false, "dirty cell");
        for (const auto* list : {&grid.excluded_, &grid.toggled_, &grid.crossPairs_, &grid.pairs_,
                                 &grid.added_, &grid.removed_}) {
            for (const ProxyPair& pair : *list)
                inRange(r, std::array{pair.first, pair.second}, proxies, false, "paired proxy");
        }
        for (const GridBroadphase::PairCount& count : grid.counts_)
            inRange(r, std::array{count.pair.first, count.pair.second}, proxies, false,
                    "counted proxy");
    }

    /// Sizes that must agree for the stores to be usable; a payload that passed the checksum
    /// but breaks one was not written by this code.
    static void check(const checkpoint_io::Reader& r, const World::Impl& w) {
        constexpr std::uint32_t kNone = 0xFFFFFFFF;
        // Every index the stores follow must land inside its array: a crafted payload that
        // passed the checksum is refused here rather than read out of bounds by a step.
        const auto all = [&](const auto& values, std::size_t size, bool noneAllowed,
                             const char* what) {
            for (const auto v : values) {
                if (!(v < size || (noneAllowed && v == kNone)))
                    r.corrupt(what, " ", v, " out of range (", size, ")");
            }
        };
        const auto one = [&](std::uint32_t v, std::size_t size, bool noneAllowed,
                             const char* what) {
            all(std::array<std::uint32_t, 1>{v}, size, noneAllowed, what);
        };
        const BodyStore& b = w.bodies;
        const std::size_t n = b.motion.size();
        if (b.previousMotion.size() != n || b.inertia.size() != n || b.forces.size() != n ||
            b.info.size() != n || b.awake.size() > n)
            r.corrupt("body arrays of different sizes");
        all(b.awake, n, false, "awake body");
        for (std::size_t k = 0; k < b.awake.size(); ++k) {
            if (b.info[b.awake[k]].awakeIndex != k)
                r.corrupt("awake list and awake indices disagree");
        }
        check(r, b.pool_, n, "body");
        const std::size_t shapeSlots = w.shapes.records.size();
        if (w.shapes.pool_.slotCount() != shapeSlots)
            r.corrupt("shape records and shape slots of different sizes");
        check(r, w.shapes.pool_, w.shapes.pool_.size(), "shape");
        const ContactManager& c = w.contacts;
        const std::size_t edges = 2 * c.pool_.size();
        for (std::uint32_t i = 0; i < n; ++i) {
            const BodyInfo& info = b.info[i];
            one(info.firstShape, shapeSlots, true, "first shape");
            one(info.firstContact, edges, true, "first contact");
            one(info.awakeIndex, b.awake.size(), true, "awake index");
        }
        const std::size_t proxies = c.broadphase_.proxies_.size();
        for (std::uint32_t slot = 0; slot < shapeSlots; ++slot) {
            const ShapeRecord& shape = w.shapes.records[slot];
            one(shape.nextInBody, shapeSlots, true, "next shape");
            if (!w.shapes.isAlive(slot))
                continue;
            if (!b.isValid(shape.body) || shape.proxy >= proxies)
                r.corrupt("a shape's body or proxy is invalid");
            const bool staticOnly = isTriangleSurface(shape.def.geometry) ||
                                    std::holds_alternative<HalfSpace>(shape.def.geometry);
            if (staticOnly && b.info[b.indexOf(shape.body)].type == BodyType::Dynamic)
                r.corrupt("a dynamic body carries a half-space, mesh or height field");
        }
        for (std::size_t slot = 0; slot < c.pool_.size(); ++slot) {
            const ContactManager::Record& record = c.pool_[slot];
            all(record.next, edges, true, "contact edge");
            all(record.previous, edges, true, "contact edge");
            one(record.nextPart, c.pool_.size(), true, "contact part");
            const Contact& contact = record.contact;
            if (c.state_[slot].alive &&
                (!b.isValid(contact.bodyA) || !b.isValid(contact.bodyB) ||
                 contact.shapeA.index >= shapeSlots || contact.shapeB.index >= shapeSlots))
                r.corrupt("a contact's bodies or shapes are invalid");
        }
        for (const auto* list : {&c.freeSlots_, &c.dead_, &c.active_, &c.activated_})
            all(*list, c.pool_.size(), false, "contact slot");
        all(c.proxyToShape_, shapeSlots, true, "proxy's shape");
        all(c.wakeRequests_, n, false, "body to wake");
        all(c.placedProxies_, proxies, false, "placed proxy");
        check(r, c.broadphase_);
        const SpringStore& s = w.springs;
        if (s.state.size() != s.defs.size() || s.previousState.size() != s.defs.size())
            r.corrupt("spring arrays of different sizes");
        check(r, s.pool_, s.defs.size(), "spring");
        for (const SpringDef& def : s.defs) {
            if (!b.isValid(def.bodyA) || !(def.bodyB.isNull() || b.isValid(def.bodyB)))
                r.corrupt("a spring's bodies are invalid");
        }
        const JointStore& j = w.joints;
        if (j.state.size() != j.records.size() || j.previousState.size() != j.records.size())
            r.corrupt("joint arrays of different sizes");
        check(r, j.pool_, j.records.size(), "joint");
        for (const JointRecord& record : j.records) {
            const JointDef& def = record.def;
            if (!b.isValid(def.bodyA) || !(def.bodyB.isNull() || b.isValid(def.bodyB)))
                r.corrupt("a joint's bodies are invalid");
        }
        if (w.drag.drags.size() != w.drag.bodies.size())
            r.corrupt("drag arrays of different sizes");
        all(w.drag.denseOfSlot_, w.drag.drags.size(), true, "drag index");
        for (const BodyId body : w.drag.bodies) {
            if (!b.isValid(body))
                r.corrupt("a drag's body is invalid");
        }
        all(w.impacts.opened_, w.impacts.bySlot_.size(), false, "impact slot");
        if (!(w.settings.timeStep > 0))
            r.corrupt("time step ", w.settings.timeStep);
        if (w.settings.substeps < 1)
            r.corrupt("substeps ", w.settings.substeps);
        if (checks::twoSubstepCounts(w.settings.substeps, w.settings.solver.softSubsteps))
            r.corrupt("substeps ", w.settings.substeps, " with soft substeps");
        try {
            checkSolverSettings(w.settings.solver);  // a soft step of -1 substeps, a NaN hertz
        } catch (const InvalidArgument& e) {
            r.corrupt(e.what());
        }
    }

    static const World::Impl& impl(const World& world) { return *world.impl_; }
    static std::unique_ptr<World::Impl>& impl(World& world) { return world.impl_; }
    static std::unique_ptr<World::Impl> fresh() { return std::make_unique<World::Impl>(); }
};

namespace {

constexpr std::array<std::uint8_t, 8> kMagic{'T', 'U', 'M', 'B', 'C', 'K', 'P', 'T'};
// magic, u32 version, u32 reserved (0), u64 payload length, u64 FNV-1a of the payload.
constexpr std::size_t kHeaderSize = 8 + 4 + 4 + 8 + 8;

std::uint64_t readWord(std::span<const std::uint8_t> bytes, std::size_t at, int width) {
    std::uint64_t value = 0;
    for (int i = 0; i < width; ++i)
        value |= std::uint64_t{bytes[at + i]} << (8 * i);
    return value;
}

}  // namespace

std::vector<std::uint8_t> checkpointBytes(const World& world) {
    checkpoint_io::Writer payload;
    // The writer only reads: the same field lists serve both directions.
    CheckpointAccess::io(payload,
                         const_cast<CheckpointAccess::Impl&>(CheckpointAccess::impl(world)));
    checkpoint_io::Writer out;
    out.bytes.assign(kMagic.begin(), kMagic.end());
    out.word(kCheckpointVersion, 4);
    out.word(0, 4);
    out.word(payload.bytes.size(), 8);
    out.word(checkpoint_io::fnv1a(payload.bytes), 8);
    out.bytes.insert(out.bytes.end(), payload.bytes.begin(), payload.bytes.end());
    return std::move(out.bytes);
}

void restoreCheckpoint(World& world, std::span<const std::uint8_t> bytes, std::string_view source) {
    std::unique_ptr<CheckpointAccess::Impl>& current = CheckpointAccess::impl(world);
    if (current->inPreStep)
        fail("checkpoint ", source, ": cannot be loaded from the pre-step callback");
    if (bytes.size() < kHeaderSize)
        fail("checkpoint ", source, ": truncated: ", bytes.size(), " bytes, shorter than the ",
             kHeaderSize, "-byte header");
    if (!std::equal(kMagic.begin(), kMagic.end(), bytes.begin()))
        fail("checkpoint ", source, ": not a Tumble checkpoint (bad magic number)");
    const std::uint64_t version = readWord(bytes, 8, 4);
    if (version != kCheckpointVersion)
        fail("checkpoint ", source, ": format version ", version, ", this build reads version ",
             kCheckpointVersion);
    const std::uint64_t length = readWord(bytes, 16, 8);
    const std::size_t available = bytes.size() - kHeaderSize;
    if (length != available)
        fail("checkpoint ", source, ": ", length < available ? "trailing bytes" : "truncated",
             ": the header announces ", length, " payload bytes, the file holds ", available);
    const std::span<const std::uint8_t> payload = bytes.subspan(kHeaderSize);
    const std::uint64_t checksum = readWord(bytes, 24, 8);
    if (checkpoint_io::fnv1a(payload) != checksum)
        fail("checkpoint ", source, ": corrupted: the payload's checksum does not match");

    // The loaded state takes this world's tag: ids this world handed out stay good, another
    // world's ids stay foreign (docs/checkpoint.md, "Ids").
    std::unique_ptr<CheckpointAccess::Impl> loaded = CheckpointAccess::fresh();
    loaded->setWorldTag(current->worldTag);
    checkpoint_io::Reader reader(payload, std::string(source));
    reader.world = current->worldTag;
    CheckpointAccess::io(reader, *loaded);
    if (!reader.atEnd())
        reader.corrupt("bytes left after the last field");
    CheckpointAccess::check(reader, *loaded);

    for (std::uint32_t index = 0; index < loaded->bodies.count(); ++index)
        loaded->refreshExtent(index);  // derived, not saved
    loaded->connectLogs();
    loaded->preStep = std::move(current->preStep);
    current.swap(loaded);
}

void saveCheckpoint(const World& world, const std::filesystem::path& file) {
    const std::vector<std::uint8_t> bytes = checkpointBytes(world);
    std::filesystem::path temporary = file;
    temporary += ".tmp";
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        if (!out)
            fail("checkpoint ", file.string(), ": cannot open ", temporary.string(),
                 " for writing");
        out.write(reinterpret_cast<const char*>(bytes.data()),
                  static_cast<std::streamsize>(bytes.size()));
        out.flush();
        if (!out)
            fail("checkpoint ", file.string(), ": writing ", temporary.string(), " failed");
    }
    std::error_code error;
    std::filesystem::rename(temporary, file, error);
    if (error)
        fail("checkpoint ", file.string(), ": cannot rename ", temporary.string(), " onto it (",
             error.message(), ")");
}

void loadCheckpoint(World& world, const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in)
        fail("checkpoint ", file.string(), ": cannot open it for reading");
    const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                          std::istreambuf_iterator<char>());
    if (in.bad())
        fail("checkpoint ", file.string(), ": reading failed");
    restoreCheckpoint(world, bytes, file.string());
}

}  // namespace tumble
