// Ray casts on a height field: the grid walk (a 2D DDA over the cells the ray's shadow crosses,
// what `raycast` does) against the reference scan of every cell under the box of the ray's
// stretch (detail::raycastCellsUnderBox, kept for the tests). Long rays descending across the
// terrain scenes' 64 x 64-cell bowl (bench/harness/terrain.h): the walk's cost grows with the
// cells crossed, the scan's with their square. ns_per_ray is the cost of one cast; the two
// benchmarks cast the same rays, and `hits` shows they find the same number.

#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "harness/terrain.h"
#include "mesh_queries.h"
#include "tumble/collision/raycast.h"

namespace {

using namespace tumble;

struct LongRays {
    HeightField field = HeightField::fromData(bench::rollingTerrain());
    std::vector<Ray> rays;

    LongRays() {
        const HeightFieldData& grid = field.data->grid;
        const Real side = (grid.columns - 1) * grid.spacingX;
        std::mt19937 rng(7);
        std::uniform_real_distribution<Real> u(0, 1);
        for (int k = 0; k < 512; ++k) {
            // From above one side, descending gently to below the far side's bowl rim.
            const Vec3 from(side * u(rng), -0.5, 3), to(side * u(rng), side + 0.5, -u(rng));
            rays.push_back(Ray{from, to - from, 1});
        }
    }
};

const LongRays& longRays() {
    static const LongRays r;
    return r;
}

template <typename Cast>
void runRays(benchmark::State& state, Cast&& cast) {
    const LongRays& r = longRays();
    int hits = 0;
    for (auto _ : state) {
        hits = 0;
        for (const Ray& ray : r.rays) {
            const std::optional<RayHit> hit = cast(r.field, ray);
            hits += hit ? 1 : 0;
            benchmark::DoNotOptimize(hit);
        }
    }
    state.counters["hits"] = hits;
    state.counters["ns_per_ray"] =
        benchmark::Counter(static_cast<double>(state.iterations() * r.rays.size()),
                           benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_HeightFieldRayGridWalk(benchmark::State& state) {
    runRays(state, [](const HeightField& field, const Ray& ray) {
        return raycast(field, Transform{}, ray);
    });
}

void BM_HeightFieldRayScanUnderBox(benchmark::State& state) {
    runRays(state, [](const HeightField& field, const Ray& ray) {
        return detail::raycastCellsUnderBox(*field.data, Transform{}, ray.origin, ray.direction,
                                            ray);
    });
}

}  // namespace

BENCHMARK(BM_HeightFieldRayGridWalk);
BENCHMARK(BM_HeightFieldRayScanUnderBox);
