#include <cstdio>

#include "tumble/warnings.h"
#include "warning_log.h"

namespace tumble {
namespace {

bool sameCause(const Warning& a, const Warning& b) {
    const bool sameBodies =
        (a.bodyA == b.bodyA && a.bodyB == b.bodyB) || (a.bodyA == b.bodyB && a.bodyB == b.bodyA);
    return a.kind == b.kind && sameBodies && a.spring == b.spring && a.joint == b.joint;
}

std::string bodyName(BodyId id) {
    char text[48];
    std::snprintf(text, sizeof text, "body %u (generation %u)", id.index, id.generation);
    return text;
}

}  // namespace

void WarningLog::raise(const Warning& warning) {
    for (const Warning& kept : items_) {
        if (sameCause(kept, warning))
            return;
    }
    if (items_.size() == kCapacity) {
        ++dropped_;
        return;
    }
    items_.push_back(warning);
}

void WarningLog::checkMassRatio(BodyId a, double inverseMassA, BodyId b, double inverseMassB,
                                JointId joint) {
    if (!(inverseMassA > 0 && inverseMassB > 0))
        return;
    const bool aHeavier = inverseMassA < inverseMassB;
    const double ratio = aHeavier ? inverseMassB / inverseMassA : inverseMassA / inverseMassB;
    if (!(ratio > kMassRatioWarning))
        return;
    Warning warning;
    warning.kind = Warning::Kind::MassRatio;
    warning.bodyA = aHeavier ? a : b;
    warning.bodyB = aHeavier ? b : a;
    warning.joint = joint;
    warning.value = ratio;
    warning.limit = kMassRatioWarning;
    raise(warning);
}

std::string describe(const Warning& w) {
    char text[400];
    switch (w.kind) {
        case Warning::Kind::MassRatio:
            std::snprintf(text, sizeof text,
                          "%s is %.3g times heavier than %s, which it meets in a %s: above %g the "
                          "iterative solver cannot pass the load between them (the light body is "
                          "pushed through what holds it); keep mass ratios below %g",
                          bodyName(w.bodyA).c_str(), w.value, bodyName(w.bodyB).c_str(),
                          w.joint.isNull() ? "contact" : "joint", w.limit, w.limit);
            break;
        case Warning::Kind::SmallerThanSlop:
            std::snprintf(text, sizeof text,
                          "a shape of %s is %.3g m across, less than twice the contact slop (%g "
                          "m): its contacts may leave it sunk by half its size or more; scale "
                          "the solver's slop, the contact margins and the time step with the "
                          "bodies",
                          bodyName(w.bodyA).c_str(), w.value, 0.5 * w.limit);
            break;
        case Warning::Kind::ExplicitSpringUnstable:
            std::snprintf(text, sizeof text,
                          "explicit spring %u (generation %u) on %s%s%s has omega h = %.3g, at "
                          "or above %g: semi-implicit Euler amplifies its oscillation every step "
                          "and the state will overflow; make it implicit or shorten the step",
                          w.spring.index, w.spring.generation, bodyName(w.bodyA).c_str(),
                          w.bodyB.isNull() ? "" : " and ",
                          w.bodyB.isNull() ? "" : bodyName(w.bodyB).c_str(), w.value, w.limit);
            break;
    }
    return text;
}

}  // namespace tumble
