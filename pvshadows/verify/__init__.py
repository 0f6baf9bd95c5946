"""Exact visibility by ray casting, and what the renderer shows measured against it."""
