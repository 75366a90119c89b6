"""Task shapes: what families of tasks share (a scene, success checks and an expert with hooks); a
task module in ``inventory/`` is a row of its shape plus its hooks."""
