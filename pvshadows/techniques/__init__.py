"""One module per shadow technique: its maps, its passes, and the shading it asks for."""

from pvshadows.techniques.cubemap import CubemapTechnique
from pvshadows.techniques.volume import VolumeTechnique

#: The class that runs each technique, by name.
TECHNIQUE_CLASSES = {CubemapTechnique.name: CubemapTechnique, VolumeTechnique.name: VolumeTechnique}
