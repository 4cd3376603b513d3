// Placeholder: benchmarks come with the collision work in progress.
