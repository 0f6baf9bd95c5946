"""The scene as shadows see it: actors, lights, the camera's view, and their bounds."""
