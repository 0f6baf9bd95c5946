"""Geometry in numpy, trimesh and manifold3d only: matrices, closed meshes, silhouettes."""
