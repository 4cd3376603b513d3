// Placeholder: tests come with the collision work in progress.
