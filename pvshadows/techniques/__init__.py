"""One module per shadow technique: its maps, its passes, and the shading it asks for."""

from pvshadows.techniques.cubemap import CubemapTechnique
from pvshadows.techniques.maps import MapTechnique
from pvshadows.techniques.planar import PlanarTechnique
from pvshadows.techniques.volume import VolumeTechnique

#: The class that runs each technique, by name.
TECHNIQUE_CLASSES = {
    technique.name: technique
    for technique in (CubemapTechnique, MapTechnique, VolumeTechnique, PlanarTechnique)
}
