#pragma once
/// The event arrays of tumble/events.h, as the world keeps them: the stages and the API append
/// to a pending log at any time; when a step returns, the pending log becomes the published one
/// (a swap, so the vectors keep their capacity and a warm step allocates nothing).

#include <vector>

#include "tumble/events.h"

namespace tumble {

struct EventLog {
    std::vector<ContactEvent> contactBegin;
    std::vector<ContactEvent> contactEnd;
    std::vector<ImpactEvent> impact;
    std::vector<JointBreakEvent> jointBreak;
    std::vector<SleepEvent> sleep;

    void clear() {
        contactBegin.clear();
        contactEnd.clear();
        impact.clear();
        jointBreak.clear();
        sleep.clear();
    }
    void swap(EventLog& other) noexcept {
        contactBegin.swap(other.contactBegin);
        contactEnd.swap(other.contactEnd);
        impact.swap(other.impact);
        jointBreak.swap(other.jointBreak);
        sleep.swap(other.sleep);
    }
};

}  // namespace tumble
