"""Receivers' shader edits: assembling them, applying them to VTK's shaders, checking them."""
