#include "joint_store.h"

namespace tumble {

JointId JointStore::add(const JointRecord& record) {
    const JointId id = pool_.add();
    records.push_back(record);
    state.push_back({});
    previousState.push_back({});
    return id;
}

void JointStore::remove(JointId id) {
    moveLastInto(pool_.remove(id), records, state, previousState);
}

}  // namespace tumble
