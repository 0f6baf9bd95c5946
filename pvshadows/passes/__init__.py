"""Passes that write shadow maps; the shading that reads them lives in :mod:`pvshadows.shading`."""
