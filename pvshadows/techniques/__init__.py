"""One module per shadow technique: its maps, its passes, and the shading it asks for."""
