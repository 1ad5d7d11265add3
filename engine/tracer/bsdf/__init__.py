"""Surface scattering: one file of per-path kernel functions per model, dispatched on an integer kind."""
