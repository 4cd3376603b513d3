// A minimal application against the installed package: drop a body for one second.
#include <cstdio>

#include <tumble/tumble.h>

int main() {
    tumble::World world(tumble::WorldDef{.timeStep = 1.0 / 1000});
    const tumble::BodyId body = world.createBody({});
    for (int i = 0; i < 1000; ++i)
        world.step();
    std::printf("fell %.3f m\n", -world.position(body).z());
    return 0;
}
