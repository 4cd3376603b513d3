#pragma once
/// Impact events (see ImpactEvent in tumble/events.h for the definition): after each successful
/// step's solve, the contacts whose normal impulse stopped an approach of at least the threshold
/// open an impact; the impact takes the next step's impulse too (a speculative contact stops the
/// bodies over two steps) and is then reported.
///
/// Cost: one pass over the active touching contacts per step, a few products per point; none
/// when the threshold is infinite. Per-contact state is a side array indexed by contact slot,
/// grown with the contact pool, so a warm step allocates nothing.

#include <cstdint>
#include <vector>

#include "body_store.h"
#include "contact_manager.h"
#include "tumble/events.h"

namespace tumble {

class ImpactTracker {
    friend struct CheckpointAccess;  ///< checkpoint.cpp saves and restores the private state
public:
    /// After the solve of a step that succeeded: closes the impacts opened by the previous step
    /// (appending them to `out`) and opens this step's.
    void update(const ContactManager& contacts, const BodyStore& bodies, Real threshold,
                std::vector<ImpactEvent>& out);

private:
    struct Open {
        ImpactEvent event;
        bool open = false;
    };
    std::vector<Open> bySlot_;
    std::vector<std::uint32_t> opened_;  ///< slots opened by the previous step
    std::vector<std::uint32_t> next_;    ///< slots opened by this step
};

}  // namespace tumble
