"""Passes that write shadow maps (:mod:`pvshadows.shaders.shading` is what reads them)."""
