// Placeholder: implemented by the collision work in progress.
