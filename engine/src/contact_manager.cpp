#include "contact_manager.h"

#include <algorithm>
#include <iterator>

#include "tumble/collision/narrowphase.h"

namespace tumble {
namespace {

// A persisting point whose feature id changed (e.g. a clip vertex renamed) still inherits its
// impulse when it lies this close to a point of the last step (m).
constexpr Real kMatchDistance = 0.01;

Transform bodyTransform(const BodyStore& bodies, std::uint32_t index) {
    const BodyMotion& m = bodies.motion[index];
    return {m.center - m.orientation * bodies.inertia[index].localCenter, m.orientation};
}

// The tight box, grown along the motion expected over the next step so fast bodies find their
// pairs before they reach them.
Aabb sweptBounds(const Aabb& tight, const Vec3& velocity, Real h) {
    const Vec3 displacement = h * velocity;
    return {tight.lower + displacement.cwiseMin(Vec3::Zero()),
            tight.upper + displacement.cwiseMax(Vec3::Zero())};
}

// Gives `contact` the manifold `next`, with the impulses of its points that persist. Written in
// place (no copy of the whole record), with the values a fresh copy would get: the impulses of
// points beyond next.pointCount are zero.
void carryImpulses(Contact& contact, const Manifold& next) {
    const Manifold& previous = contact.manifold;
    std::array<Real, Manifold::kMaxPoints> normalImpulse{};
    std::array<Vec3, Manifold::kMaxPoints> tangentImpulse{Vec3::Zero(), Vec3::Zero(), Vec3::Zero(),
                                                          Vec3::Zero()};
    bool matched = false;
    for (int i = 0; i < next.pointCount; ++i) {
        const ContactPoint& point = next.points[i];
        int match = -1;
        for (int j = 0; j < previous.pointCount && match < 0; ++j) {
            if (previous.points[j].featureId == point.featureId)
                match = j;
        }
        for (int j = 0; j < previous.pointCount && match < 0; ++j) {
            if ((previous.points[j].position - point.position).norm() < kMatchDistance)
                match = j;
        }
        if (match >= 0) {
            normalImpulse[i] = contact.normalImpulse[match];
            tangentImpulse[i] = contact.tangentImpulse[match];
        }
        matched = matched || match >= 0;
    }
    contact.normalImpulse = normalImpulse;
    contact.tangentImpulse = tangentImpulse;
    // The manifold's torsion and rolling impulse is a torque on the pair, carried as it is, in
    // world coordinates, while a point persists; the solver splits it along this step's normal
    // and clamps each part to this step's limits. In a settled pile, 1-point manifolds' normals
    // were measured to jump by 20-40 deg from one step to the next while the torque the bodies
    // need does not (why was not pinned down; no small scene shows it): dropping the impulse
    // past 18 deg left the 5,000-body soak's settled pile awake for good, and carrying its parts
    // onto the new normal (spin about it, rolling turned across it) woke it after a drop.
    if (!matched)
        contact.angularImpulse.setZero();
    contact.manifold = next;
}

// Merges the sorted `added` into the sorted `list` in place, in std::merge's order (a list
// element before an equal added one). When few are added, each finds its place by a binary
// search and the list's elements after it move as a block: std::merge into a scratch list
// compared every element of the list, ~33,000 a step on pile-1000 for the few pairs activated.
template <class Less>
void mergeInto(std::vector<std::uint32_t>& list, const std::vector<std::uint32_t>& added,
               std::vector<std::uint32_t>& scratch, Less less) {
    if (added.size() * 16 > list.size()) {  // many: the binary searches would cost more
        scratch.clear();
        std::merge(list.begin(), list.end(), added.begin(), added.end(),
                   std::back_inserter(scratch), less);
        list.swap(scratch);
        return;
    }
    std::size_t end = list.size();  // list[0, end) is not yet in its final place
    list.resize(end + added.size());
    std::size_t out = list.size();  // list[out, size) is
    for (std::size_t j = added.size(); j-- > 0;) {
        const auto at = std::upper_bound(
            list.begin(), list.begin() + static_cast<std::ptrdiff_t>(end), added[j], less);
        const std::size_t from = static_cast<std::size_t>(at - list.begin());
        std::move_backward(at, list.begin() + static_cast<std::ptrdiff_t>(end),
                           list.begin() + static_cast<std::ptrdiff_t>(out));
        out -= end - from;
        list[--out] = added[j];
        end = from;
    }
}

ContactEvent touchEvent(const Contact& contact) {
    return {contact.shapeA, contact.shapeB, contact.bodyA, contact.bodyB};
}

}  // namespace

// A shape's body is live while the shape is (destroying a body destroys its shapes, and their
// contacts): the step's passes look it up unchecked (BodyStore::checkedIndexOf), where the
// refusal's tests were ~1 % of a pile's step.
Transform shapePose(const ShapeRecord& shape, const BodyStore& bodies) {
    const Transform body = bodyTransform(bodies, bodies.checkedIndexOf(shape.body));
    const Transform& local = shape.def.localPose;
    return {body.apply(local.position), body.rotation * local.rotation};
}

void ContactManager::addShape(ShapeStore& shapes, std::uint32_t slot, const BodyStore& bodies,
                              Real h) {
    ShapeRecord& shape = shapes.records[slot];
    const std::uint32_t bodyIndex = bodies.indexOf(shape.body);
    shape.bounds = boundsOf(shape.def.geometry, shapePose(shape, bodies));
    shape.fatBounds = proxyBounds(shape.bounds, bodies.motion[bodyIndex].linearVelocity, h);
    ProxyFilter filter;
    filter.category = shape.def.filter.category;
    filter.mask = shape.def.filter.mask;
    filter.isStatic = bodies.info[bodyIndex].type == BodyType::Static;
    shape.proxy = broadphase_.add(shape.fatBounds, filter);
    if (proxyToShape_.size() <= shape.proxy)
        proxyToShape_.resize(shape.proxy + 1);
    proxyToShape_[shape.proxy] = slot;
}

void ContactManager::removeShape(ShapeStore& shapes, std::uint32_t slot, BodyStore& bodies) {
    const ShapeRecord& shape = shapes.records[slot];
    broadphase_.remove(shape.proxy);
    const ShapeId id = shapes.idAt(slot);
    const std::uint32_t bodyIndex = bodies.indexOf(shape.body);
    std::uint32_t edge = bodies.info[bodyIndex].firstContact;
    while (edge != kNone) {
        const std::uint32_t contactSlot = edge >> 1;
        edge = pool_[contactSlot].next[edge & 1];  // before destroy() unlinks it
        const SlotState& state = state_[contactSlot];
        if (state.shapeA == id.index || state.shapeB == id.index)
            destroy(contactSlot, bodies);
    }
}

void ContactManager::refreshShape(ShapeStore& shapes, std::uint32_t slot, const BodyStore& bodies,
                                  Real h) {
    ShapeRecord& shape = shapes.records[slot];
    shape.bounds = boundsOf(shape.def.geometry, shapePose(shape, bodies));
    moveProxy(shape, bodies, h);
}

// Moves the proxy when the tight box, swept over the next step, left the fat box.
void ContactManager::moveProxy(ShapeRecord& shape, const BodyStore& bodies, Real h) {
    const Vec3& velocity = bodies.motion[bodies.checkedIndexOf(shape.body)].linearVelocity;
    const Aabb swept = sweptBounds(shape.bounds, velocity, h);
    if (!shape.fatBounds.contains(swept)) {
        shape.fatBounds = swept.fattened(aabbMargin);
        broadphase_.move(shape.proxy, shape.fatBounds);
    }
}

Aabb ContactManager::proxyBounds(const Aabb& tight, const Vec3& velocity, Real h) const {
    return sweptBounds(tight, velocity, h).fattened(aabbMargin);
}

bool ContactManager::boundsFinite(const ShapeStore& shapes, const BodyStore& bodies,
                                  std::uint32_t index, Real h) const {
    for (std::uint32_t slot = bodies.info[index].firstShape; slot != BodyInfo::kNoShape;
         slot = shapes.records[slot].nextInBody) {
        const ShapeRecord& shape = shapes.records[slot];
        const Aabb tight = boundsOf(shape.def.geometry, shapePose(shape, bodies));
        if (!proxyBounds(tight, bodies.motion[index].linearVelocity, h).allFinite())
            return false;
    }
    return true;
}

// Two passes, so that a body whose box overflows leaves the broadphase as it was: the tight
// boxes first (each computed once), then the proxies.
std::uint32_t ContactManager::refreshBounds(ShapeStore& shapes, const BodyStore& bodies,
                                            const StepContext& context) {
    for (const std::uint32_t index : bodies.awake) {
        const Vec3& velocity = bodies.motion[index].linearVelocity;
        for (std::uint32_t slot = bodies.info[index].firstShape; slot != BodyInfo::kNoShape;
             slot = shapes.records[slot].nextInBody) {
            ShapeRecord& shape = shapes.records[slot];
            shape.bounds = boundsOf(shape.def.geometry, shapePose(shape, bodies));
            if (!proxyBounds(shape.bounds, velocity, context.h).allFinite())
                return index;
        }
    }
    for (const std::uint32_t index : bodies.awake) {
        for (std::uint32_t slot = bodies.info[index].firstShape; slot != BodyInfo::kNoShape;
             slot = shapes.records[slot].nextInBody)
            moveProxy(shapes.records[slot], bodies, context.h);
    }
    return kNoBody;
}

void ContactManager::link(std::uint32_t slot, int side, BodyInfo& body) {
    Record& record = pool_[slot];
    const std::uint32_t edge = slot * 2 + static_cast<std::uint32_t>(side);
    record.previous[side] = kNone;
    record.next[side] = body.firstContact;
    if (body.firstContact != kNone)
        pool_[body.firstContact >> 1].previous[body.firstContact & 1] = edge;
    body.firstContact = edge;
}

void ContactManager::unlink(std::uint32_t slot, int side, BodyInfo& body) {
    Record& record = pool_[slot];
    const std::uint32_t previous = record.previous[side];
    const std::uint32_t next = record.next[side];
    if (previous != kNone)
        pool_[previous >> 1].next[previous & 1] = next;
    else
        body.firstContact = next;
    if (next != kNone)
        pool_[next >> 1].previous[next & 1] = previous;
}

std::uint32_t ContactManager::allocateSlot() {
    if (freeSlots_.empty()) {
        pool_.emplace_back();
        state_.emplace_back();
        return static_cast<std::uint32_t>(pool_.size() - 1);
    }
    const std::uint32_t slot = freeSlots_.back();
    freeSlots_.pop_back();
    return slot;
}

void ContactManager::create(const ProxyPair& pair, const ShapeStore& shapes, BodyStore& bodies) {
    const std::uint32_t slotA = proxyToShape_[pair.first];
    const std::uint32_t slotB = proxyToShape_[pair.second];
    const ShapeRecord& shapeA = shapes.records[slotA];
    const ShapeRecord& shapeB = shapes.records[slotB];
    if (shapeA.body == shapeB.body)
        return;  // parts of one compound never collide
    const std::uint32_t indexA = bodies.indexOf(shapeA.body);
    const std::uint32_t indexB = bodies.indexOf(shapeB.body);
    if (bodies.info[indexA].type != BodyType::Dynamic &&
        bodies.info[indexB].type != BodyType::Dynamic)
        return;

    const std::uint32_t slot = allocateSlot();
    Record& record = pool_[slot];
    record = Record{};
    record.contact.shapeA = shapes.idAt(slotA);
    record.contact.shapeB = shapes.idAt(slotB);
    record.contact.bodyA = shapeA.body;
    record.contact.bodyB = shapeB.body;
    state_[slot] =
        SlotState{.key = pair, .shapeA = slotA, .shapeB = slotB, .alive = true, .cleared = true};
    link(slot, 0, bodies.info[indexA]);
    link(slot, 1, bodies.info[indexB]);
    if (bodies.isAwake(indexA) || bodies.isAwake(indexB))
        activate(slot);
    // A static or kinematic shape teleported next to sleeping bodies wakes them: it may overlap
    // them, and a static one would otherwise never be collided with them. Other new pairs wake
    // nothing (a body created asleep stays asleep on the ground; an awake dynamic body wakes a
    // sleeper once it touches it, in collideActive).
    if (std::binary_search(placedProxies_.begin(), placedProxies_.end(), pair.first) ||
        std::binary_search(placedProxies_.begin(), placedProxies_.end(), pair.second)) {
        for (const std::uint32_t index : {indexA, indexB}) {
            if (bodies.isSleeping(index))
                wakeRequests_.push_back(index);
        }
    }
}

void ContactManager::markPlaced(std::uint32_t proxy) {
    const auto at = std::lower_bound(placedProxies_.begin(), placedProxies_.end(), proxy);
    if (at == placedProxies_.end() || *at != proxy)
        placedProxies_.insert(at, proxy);
}

// A pair's further records go with it (removeShape may reach them first: they are then skipped
// here), and its end is reported once.
void ContactManager::destroy(std::uint32_t slot, BodyStore& bodies) {
    if (!state_[slot].alive)
        return;
    Record& record = pool_[slot];
    if (state_[slot].part == 0) {
        if (events != nullptr && pairTouches(slot))
            events->contactEnd.push_back(touchEvent(record.contact));
        for (std::uint32_t part = record.nextPart; part != kNone; part = pool_[part].nextPart)
            destroy(part, bodies);
    }
    unlink(slot, 0, bodies.info[bodies.indexOf(record.contact.bodyA)]);
    unlink(slot, 1, bodies.info[bodies.indexOf(record.contact.bodyB)]);
    state_[slot].alive = false;
    state_[slot].active = false;
    dead_.push_back(slot);
    viewStale_ = true;
}

std::uint32_t ContactManager::find(const ProxyPair& pair, const ShapeStore& shapes,
                                   const BodyStore& bodies) const {
    // A destroyed shape's contacts went with it; its slot may already hold a new shape.
    const std::uint32_t slotA = proxyToShape_[pair.first];
    const std::uint32_t slotB = proxyToShape_[pair.second];
    const ShapeRecord& shapeA = shapes.records[slotA];
    const ShapeRecord& shapeB = shapes.records[slotB];
    if (!(shapes.isAlive(slotA) && shapeA.proxy == pair.first && shapes.isAlive(slotB) &&
          shapeB.proxy == pair.second))
        return kNone;
    // Walk the list of a non-static body: a static body (the ground) may have thousands.
    std::uint32_t index = bodies.indexOf(shapeA.body);
    if (bodies.info[index].type == BodyType::Static)
        index = bodies.indexOf(shapeB.body);
    for (std::uint32_t edge = bodies.info[index].firstContact; edge != kNone;
         edge = pool_[edge >> 1].next[edge & 1]) {
        if (state_[edge >> 1].key == pair && state_[edge >> 1].part == 0)
            return edge >> 1;
    }
    return kNone;
}

void ContactManager::activate(std::uint32_t slot) {
    SlotState& state = state_[slot];
    state.active = true;
    if (!state.listed && !state.queued) {
        state.queued = true;
        activated_.push_back(slot);
    }
}

void ContactManager::flushActivations() {
    if (activated_.empty())
        return;
    std::erase_if(activated_, [this](std::uint32_t slot) {
        SlotState& state = state_[slot];
        state.queued = false;
        return !(state.alive && state.active && !state.listed);
    });
    const auto byKey = [this](std::uint32_t a, std::uint32_t b) { return precedes(a, b); };
    std::sort(activated_.begin(), activated_.end(), byKey);
    for (const std::uint32_t slot : activated_)
        state_[slot].listed = true;
    mergeInto(active_, activated_, scratch_, byKey);
    // The touching ones among them (a woken island's parked manifolds) join touching_ likewise.
    std::erase_if(activated_, [this](std::uint32_t slot) {
        return pool_[slot].contact.manifold.pointCount == 0;
    });
    if (!activated_.empty())
        mergeInto(touching_, activated_, touchingScratch_, byKey);
    activated_.clear();
}

void ContactManager::compactActive() {
    std::erase_if(active_, [this](std::uint32_t slot) {
        SlotState& state = state_[slot];
        state.listed = state.active;
        return !state.active;
    });
}

void ContactManager::updateContacts(const ShapeStore& shapes, BodyStore& bodies,
                                    const StepContext& context) {
    for (const ProxyPair& pair : broadphase_.removedPairs()) {
        const std::uint32_t slot = find(pair, shapes, bodies);
        if (slot != kNone)
            destroy(slot, bodies);
    }
    compactActive();
    touching_.clear();  // not merged into below: collideActive lists every touching pair
    for (const ProxyPair& pair : broadphase_.addedPairs())
        create(pair, shapes, bodies);
    placedProxies_.clear();
    flushActivations();
    // Nothing lists a destroyed contact any more: its slot may be reused.
    for (const std::uint32_t slot : dead_)
        freeSlots_.push_back(slot);
    dead_.clear();
    collideActive(shapes, bodies, context);
    viewStale_ = true;
}

// Two passes over the active pairs. The first decides each from compact data (the slot's hot
// state, the shapes' boxes, the bodies' velocities) and lists those that need their record;
// the second collides them and rewrites their records, fetching each record a few pairs ahead:
// the records are 400 bytes each, and the walk over them was a cache miss per pair.
void ContactManager::collideActive(const ShapeStore& shapes, BodyStore& bodies,
                                   const StepContext& context) {
    constexpr std::size_t kAhead = 8;  // pairs fetched ahead (about the misses a core overlaps)
    work_.clear();
    touching_.clear();
    ++narrowphaseCount_;
    stepLength_ = context.h;
    if (poses_.size() < shapes.records.size())
        poses_.resize(shapes.records.size());
    // Held in locals: the stores below (a slot's flag, work_) might alias the vectors' and the
    // context's fields for the compiler, which then reloaded them for each of the ~11,000 pairs.
    SlotState* const states = state_.data();
    const ShapeRecord* const records = shapes.records.data();
    const BodyMotion* const motion = bodies.motion.data();
    const Real h = context.h;
    const Real baseMargin = contactMargin;
    for (std::size_t i = 0; i < active_.size(); ++i) {
        if (i + kAhead < active_.size())
            __builtin_prefetch(&states[active_[i + kAhead]]);
        const std::uint32_t slot = active_[i];
        SlotState& state = states[slot];
        if (state.part != 0)
            continue;  // collided with its pair's own record
        const ShapeRecord& shapeA = records[state.shapeA];
        const ShapeRecord& shapeB = records[state.shapeB];
        const std::uint32_t indexA = bodies.checkedIndexOf(shapeA.body);  // see shapePose
        const std::uint32_t indexB = bodies.checkedIndexOf(shapeB.body);
        const Vec3 relativeVelocity = motion[indexB].linearVelocity - motion[indexA].linearVelocity;
        const Real margin = baseMargin + h * relativeVelocity.norm();
        // Shapes whose tight boxes (at the current poses) lie more than the margin apart are
        // farther apart than that, so the manifold is empty: no GJK. In a settled pile most
        // broadphase pairs are such neighbours of neighbours (2,000 of the soak's bodies: 48,070
        // pairs, 7,895 touching; narrowphase 95 -> 66 ms per step, trajectories bitwise the same).
        // A record already cleared for such a pair would be written with what it holds.
        const bool near = shapeA.bounds.fattened(margin).overlaps(shapeB.bounds);
        if (!near && state.cleared)
            continue;
        state.cleared = !near;
        work_.push_back({slot, indexA, indexB, margin, near});
    }
    for (std::size_t i = 0; i < work_.size(); ++i) {
        if (i + kAhead < work_.size()) {
            const char* ahead = reinterpret_cast<const char*>(&pool_[work_[i + kAhead].slot]);
            for (std::size_t line = 0; line < sizeof(Record); line += 64)
                __builtin_prefetch(ahead + line);
        }
        // The pairs skipped above hold no points: the touching ones are all here, in pair order.
        collidePair(work_[i], shapes, bodies);
    }
    if (!addedParts_.empty()) {  // into active_ as flushActivations would; touching_ has them
        std::sort(addedParts_.begin(), addedParts_.end(),
                  [this](std::uint32_t a, std::uint32_t b) { return precedes(a, b); });
        scratch_.clear();
        std::merge(active_.begin(), active_.end(), addedParts_.begin(), addedParts_.end(),
                   std::back_inserter(scratch_),
                   [this](std::uint32_t a, std::uint32_t b) { return precedes(a, b); });
        active_.swap(scratch_);
        addedParts_.clear();
    }
}

void ContactManager::collidePair(const PairWork& work, const ShapeStore& shapes,
                                 BodyStore& bodies) {
    ManifoldSet& set = manifolds_;
    set.count = 0;
    if (work.near) {
        const SlotState& state = state_[work.slot];
        const ShapeRecord& shapeA = shapes.records[state.shapeA];
        const ShapeRecord& shapeB = shapes.records[state.shapeB];
        collide(shapeA.def.geometry, posedShape(state.shapeA, shapes, bodies), shapeB.def.geometry,
                posedShape(state.shapeB, shapes, bodies), work.margin, set);
    } else {
        set.manifolds[0] = Manifold{};
    }
    if (set.count > 1 || pool_[work.slot].nextPart != kNone) {
        spreadParts(work, bodies);
        return;
    }
    Contact& contact = pool_[work.slot].contact;
    const bool was = contact.manifold.pointCount > 0;
    const bool is = set.count > 0;
    carryImpulses(contact, set.manifolds[0]);
    if (was != is)
        reportTouch(contact, is, bodies, work.indexA, work.indexB);
    if (is) {
        wakeTouched(bodies, work.indexA, work.indexB,
                    std::span<const Manifold>(set.manifolds.data(), 1));
        touching_.push_back(work.slot);
    }
}

// Each new manifold goes to the record whose last normal is nearest (within kPartCos), so its
// points find their impulses; the others take the records left, in order, and records left over
// are emptied. A record holds its manifold's points in one frame of reference only when its
// normal stays put: a box shifting in a crease keeps each face's impulses on that face.
void ContactManager::spreadParts(const PairWork& work, BodyStore& bodies) {
    constexpr Real kPartCos = 0.7;  // about 45 degrees
    constexpr int kMax = ManifoldSet::kMaxManifolds;
    const ManifoldSet& set = manifolds_;
    std::array<std::uint32_t, kMax> slots;
    int parts = 0;
    for (std::uint32_t s = work.slot; s != kNone; s = pool_[s].nextPart)
        slots[static_cast<std::size_t>(parts++)] = s;
    for (; parts < set.count; ++parts)
        slots[static_cast<std::size_t>(parts)] = addPart(slots[static_cast<std::size_t>(parts - 1)],
                                                         static_cast<std::uint8_t>(parts), bodies);
    std::array<int, kMax> source;  // per record: the manifold it takes, or -1
    source.fill(-1);
    const auto previous = [&](int part) -> const Manifold& {
        return pool_[slots[static_cast<std::size_t>(part)]].contact.manifold;
    };
    for (int k = 0; k < set.count; ++k) {
        const Vec3& normal = set.manifolds[static_cast<std::size_t>(k)].normal;
        int best = -1;
        Real bestCos = kPartCos;
        for (int p = 0; p < parts; ++p) {
            if (source[static_cast<std::size_t>(p)] < 0 && previous(p).pointCount > 0 &&
                previous(p).normal.dot(normal) > bestCos) {
                best = p;
                bestCos = previous(p).normal.dot(normal);
            }
        }
        if (best >= 0)
            source[static_cast<std::size_t>(best)] = k;
    }
    for (int k = 0; k < set.count; ++k) {
        if (std::find(source.begin(), source.end(), k) != source.end())
            continue;
        *std::find(source.begin(), source.begin() + parts, -1) = k;
    }
    const bool was = pairTouches(work.slot);
    static const Manifold kEmpty{};
    for (int p = 0; p < parts; ++p) {
        const int k = source[static_cast<std::size_t>(p)];
        const std::uint32_t slot = slots[static_cast<std::size_t>(p)];
        carryImpulses(pool_[slot].contact,
                      k >= 0 ? set.manifolds[static_cast<std::size_t>(k)] : kEmpty);
        if (k >= 0)
            touching_.push_back(slot);
    }
    const bool is = set.count > 0;
    if (was != is)
        reportTouch(pool_[work.slot].contact, is, bodies, work.indexA, work.indexB);
    if (is) {
        wakeTouched(
            bodies, work.indexA, work.indexB,
            std::span<const Manifold>(set.manifolds.data(), static_cast<std::size_t>(set.count)));
    }
}

std::uint32_t ContactManager::addPart(std::uint32_t last, std::uint8_t part, BodyStore& bodies) {
    const std::uint32_t slot = allocateSlot();  // may move pool_: nothing is held across it
    Record& record = pool_[slot];
    record = Record{};
    const Contact& pair = pool_[last].contact;
    record.contact.shapeA = pair.shapeA;
    record.contact.shapeB = pair.shapeB;
    record.contact.bodyA = pair.bodyA;
    record.contact.bodyB = pair.bodyB;
    const SlotState& owner = state_[last];
    state_[slot] = SlotState{.key = owner.key,
                             .shapeA = owner.shapeA,
                             .shapeB = owner.shapeB,
                             .alive = true,
                             .active = true,
                             .listed = true,
                             .part = part};
    link(slot, 0, bodies.info[bodies.indexOf(pair.bodyA)]);
    link(slot, 1, bodies.info[bodies.indexOf(pair.bodyB)]);
    pool_[last].nextPart = slot;
    addedParts_.push_back(slot);
    return slot;
}

bool ContactManager::pairTouches(std::uint32_t slot) const {
    for (; slot != kNone; slot = pool_[slot].nextPart)
        if (pool_[slot].contact.manifold.pointCount > 0)
            return true;
    return false;
}

const Transform& ContactManager::posedShape(std::uint32_t slot, const ShapeStore& shapes,
                                            const BodyStore& bodies) {
    CachedPose& cached = poses_[slot];
    if (cached.narrowphase != narrowphaseCount_) {
        cached.pose = shapePose(shapes.records[slot], bodies);
        cached.narrowphase = narrowphaseCount_;
    }
    return cached.pose;
}

void ContactManager::reportTouch(const Contact& contact, bool began, const BodyStore& bodies,
                                 std::uint32_t indexA, std::uint32_t indexB) {
    if (events != nullptr)
        (began ? events->contactBegin : events->contactEnd).push_back(touchEvent(contact));
    if (warnings != nullptr && began) {
        warnings->checkMassRatio(contact.bodyA, bodies.inertia[indexA].inverseMass, contact.bodyB,
                                 bodies.inertia[indexB].inverseMass);
    }
}

// Touching a sleeping body wakes it -- unless the toucher is a kinematic body at rest (a resting
// pile on a parked platform stays asleep), or the pair's points are only speculative ones that
// cannot close this step (pushes, below).
void ContactManager::wakeTouched(const BodyStore& bodies, std::uint32_t indexA,
                                 std::uint32_t indexB, std::span<const Manifold> manifolds) {
    const bool wakeA =
        bodies.isSleeping(indexA) &&
        (bodies.info[indexB].type == BodyType::Dynamic || bodies.isMovingKinematic(indexB));
    const bool wakeB =
        bodies.isSleeping(indexB) &&
        (bodies.info[indexA].type == BodyType::Dynamic || bodies.isMovingKinematic(indexA));
    if (!(wakeA || wakeB) || !pushes(bodies, indexA, indexB, manifolds))
        return;
    if (wakeA)
        wakeRequests_.push_back(indexA);
    if (wakeB)
        wakeRequests_.push_back(indexB);
}

// Whether a pair with a sleeping side may push it this step: a point nearer than half the
// contact margin, or one the bodies' approach along the normal closes within the step. Not
// "has points": the margin is contactMargin + h |v_rel|, and v_rel here already holds the awake
// body's gravity for the step (g h = 0.16 m/s at 1/60) but not the sleeper's (it gets none), so
// a pair 2.0-2.27 cm apart had no points while both were awake (two islands: one fell asleep)
// and points once one slept (woken the next step). The 5,000-body soak's lone body by the wall
// blinked so every 0.52 s, and woke the whole settled pile once it slept (docs/ARCHITECTURE.md,
// "Islands and sleeping"). Islands still join every pair with points, so a body this wakes
// was within the island margin of nothing awake when it fell asleep: only motion of the other
// side by about half the margin, or a real approach, wakes it. Whatever is not woken is not
// solved either (buildConstraints skips sleepers), which costs nothing: such points demand
// v_n >= -s / h, met by the velocities the step starts with.
bool ContactManager::pushes(const BodyStore& bodies, std::uint32_t indexA, std::uint32_t indexB,
                            std::span<const Manifold> manifolds) const {
    const BodyMotion& a = bodies.motion[indexA];
    const BodyMotion& b = bodies.motion[indexB];
    const Real reach = 0.5 * contactMargin;
    for (const Manifold& manifold : manifolds) {
        for (int k = 0; k < manifold.pointCount; ++k) {
            const ContactPoint& point = manifold.points[static_cast<std::size_t>(k)];
            const Vec3 velocityA =
                a.linearVelocity + a.angularVelocity.cross(point.position - a.center);
            const Vec3 velocityB =
                b.linearVelocity + b.angularVelocity.cross(point.position - b.center);
            const Real approach = std::max<Real>(0, (velocityA - velocityB).dot(manifold.normal));
            if (point.separation <= reach + stepLength_ * approach)
                return true;
        }
    }
    return false;
}

std::span<const Contact> ContactManager::contacts() const {
    if (!viewStale_)
        return view_;
    viewOrder_.clear();
    for (std::uint32_t slot = 0; slot < pool_.size(); ++slot) {
        if (state_[slot].alive)
            viewOrder_.push_back(slot);
    }
    std::sort(viewOrder_.begin(), viewOrder_.end(),
              [this](std::uint32_t a, std::uint32_t b) { return precedes(a, b); });
    view_.clear();
    for (const std::uint32_t slot : viewOrder_)
        view_.push_back(pool_[slot].contact);
    viewStale_ = false;
    return view_;
}

}  // namespace tumble
