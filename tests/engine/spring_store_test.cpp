// SpringStore::stiffestThread(), the cached bound belowBand() (springs.cpp) takes: it must follow
// every add and remove exactly, or a net could skip the discrete gradient's substeps it needs.

#include "spring_store.h"

#include <gtest/gtest.h>

namespace tumble {
namespace {

SpringDef thread(Real stiffness) {
    SpringDef def;
    def.bodyA = BodyId{1, 1};
    def.tensionOnly = true;
    def.stiffness = stiffness;
    return def;
}

TEST(SpringStore, StiffestThreadFollowsAddAndRemove) {
    SpringStore springs;
    EXPECT_EQ(springs.stiffestThread(), 0);
    const SpringId soft = springs.add(thread(10));
    EXPECT_EQ(springs.stiffestThread(), 10);
    const SpringId stiff = springs.add(thread(400));
    EXPECT_EQ(springs.stiffestThread(), 400);

    // Neither a damped thread nor a spring that pushes counts.
    SpringDef damped = thread(1e4);
    damped.numericalDamping = 0.1;
    springs.add(damped);
    SpringDef pushes = thread(2e4);
    pushes.tensionOnly = false;
    springs.add(pushes);
    EXPECT_EQ(springs.stiffestThread(), 400);

    springs.remove(stiff);
    EXPECT_EQ(springs.stiffestThread(), 10);
    springs.remove(soft);
    EXPECT_EQ(springs.stiffestThread(), 0);
}

}  // namespace
}  // namespace tumble
