"""The few OpenGL objects VTK does not wrap for Python, made in VTK's own context."""
