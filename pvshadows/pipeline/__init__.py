"""One frame: the planner that decides, the caches it keeps, the renderer observer."""
