#pragma once
/// Dense storage of spring-dampers and of per-body drag, behind value handles.
///
/// Springs live in parallel contiguous arrays (definition, last-step state) indexed by the dense
/// index of a HandlePool (handle_pool.h). Destroying a spring moves the last one
/// into its place, so the order (which is the order the solver sweeps them in) depends only on the
/// sequence of create and destroy calls. A net of thousands of threads costs one push_back each.

#include <cstdint>
#include <span>
#include <vector>

#include "body_store.h"
#include "handle_pool.h"
#include "tumble/spring.h"

namespace tumble {

/// The per-step result of a spring, kept for reporting and warm starting.
struct SpringStepState {
    Real tension = 0;    ///< (N), positive pulls
    bool slack = false;  ///< tension-only and carrying nothing
    /// A discrete-gradient thread's half impulse of the step, applied again in the next (N s).
    Vec3 carried = Vec3::Zero();
};

/// An undamped implicit thread: one that may take the discrete gradient (spring_row.h).
inline bool isUndampedThread(const SpringDef& def) {
    return def.formulation == SpringFormulation::Implicit && def.tensionOnly &&
           def.numericalDamping == 0;
}

class SpringStore : public DenseStore<SpringId> {
    friend struct CheckpointAccess;  ///< checkpoint.cpp saves and restores the private state
public:
    SpringStore() : DenseStore("SpringId", "spring") {}
    SpringId add(const SpringDef& def);
    void remove(SpringId id);
    void reserve(std::size_t count);

    /// Removes every spring attached to the body (its id is about to die).
    void removeAttachedTo(BodyId body);

    /// state -> previousState at the start of a step, and back if the step fails.
    void saveState() { previousState = state; }
    void restoreState() { state = previousState; }

    /// The spring attached to `body` with the largest |tension| in the step just taken (a
    /// non-finite tension counts as the largest); null when none is attached.
    SpringId strongestOn(BodyId body) const;

    /// The largest stiffness of an undamped thread (isUndampedThread), 0 without one (N/m):
    /// found again only after springs were added or removed (the step asks it every time, and
    /// looking over a net's threads was 2 % of its step).
    Real stiffestThread() const;
    /// Forgets stiffestThread(): defs were written other than through add() and remove().
    void forgetStiffest() { stiffestThread_ = -1; }

    std::vector<SpringDef> defs;
    std::vector<SpringStepState> state;
    std::vector<SpringStepState> previousState;
    std::uint32_t implicitCount = 0;  ///< how many are solver rows (not Explicit)
    std::uint32_t contactCount = 0;   ///< how many touch shapes (contactRadius > 0)

private:
    mutable Real stiffestThread_ = -1;  ///< stiffestThread(), -1 until found (N/m)
};

/// Drag of the bodies that have any, in the order drag was first set.
class DragStore {
    friend struct CheckpointAccess;  ///< checkpoint.cpp saves and restores the private state
public:
    /// Sets (or with all-zero coefficients, clears) the body's drag.
    void set(BodyId body, const Drag& drag);
    Drag get(BodyId body) const;
    void remove(BodyId body);
    bool empty() const { return bodies.empty(); }

    std::vector<BodyId> bodies;
    std::vector<Drag> drags;

private:
    std::uint32_t find(BodyId body) const;  ///< dense index or kNone
    static constexpr std::uint32_t kNone = 0xFFFFFFFF;
    std::vector<std::uint32_t> denseOfSlot_;  ///< by BodyId::index
};

}  // namespace tumble
