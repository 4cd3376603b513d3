// The trajectory hash of a few contact scenes on the coloured wide rows and on the scalar sweep
// (SweepRows), printed as hex. Built twice (tests/CMakeLists.txt): with the lane kernels as the
// library has them -- on GCC for x86-64 an AVX2 and a baseline copy, the AVX2 one picked on a
// machine that has it -- and with the files that have kernels compiled again under
// TUMBLE_NO_LANE_CLONES, the baseline copy alone. The test solver.lane-clone-bits compares the
// two prints: contact_rows.h and lane_kernel.h promise the same bits.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "testkit/scenes.h"
#include "testkit/state_hash.h"

namespace {

using namespace tumble;

WorldDef colouredDef(bool coloured = true) {
    WorldDef def;
    def.solver.colouredContacts = coloured;
    return def;
}

void run(World& world, const std::vector<BodyId>& bodies, int steps, testkit::Hash& trajectory) {
    for (int i = 0; i < steps; ++i) {
        if (!world.step().ok()) {
            std::fprintf(stderr, "step %d failed\n", i);
            std::exit(1);
        }
        trajectory.add(testkit::stateHash(world, bodies));
    }
}

}  // namespace

int main() {
    testkit::Hash trajectory;
    {
        // A tall column: two colours alternating up the stack, full bundles.
        World world(colouredDef());
        testkit::addGround(world);
        run(world, testkit::buildStack(world, 35), 60, trajectory);
    }
    {
        // Spinning, rolling and sliding mixed shapes landing in a pile: the exact disc, the
        // angular rows and the normal blocks whose active set changes (the lanes solved alone).
        World world(colouredDef());
        testkit::Rain rain;
        rain.half = 1.2;
        rain.material.spinningFriction = 0.01;
        rain.material.rollingFriction = 0.005;
        rain.addContainer(world);
        std::vector<BodyId> bodies;
        for (int i = 0; i < 3 * rain.perWave(); ++i)
            bodies.push_back(rain.addBody(world, i));
        run(world, bodies, 120, trajectory);
    }
    {
        // The same pile on the scalar sweep (SweepRows::sweepPlain, one- and two-point
        // manifolds among the others).
        World world(colouredDef(false));
        testkit::Rain rain;
        rain.half = 1.2;
        rain.addContainer(world);
        std::vector<BodyId> bodies;
        for (int i = 0; i < 3 * rain.perWave(); ++i)
            bodies.push_back(rain.addBody(world, i));
        run(world, bodies, 120, trajectory);
    }
    std::printf("%016llx\n", static_cast<unsigned long long>(trajectory.value()));
    return 0;
}
