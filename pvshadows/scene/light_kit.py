"""Which lights cast shadows when ``enable()`` is not given ``lights=[...]``.

PyVista's default lighting (``pv.Plotter()``, ``lighting="light kit"``) is
VTK's light kit: five lights that follow the camera. A photographer's
reading of it: the *key* light (the brightest, above and to one side) makes
the shadows; the *fill* light and the two *back* lights, softer and from
below and behind, only open up what the key leaves dark, and a shadow from
each of them would darken the undersides of objects from lights the user
never chose and swing as the camera orbits. So, by default:

- every scene light casts (``pv.Light(..., light_type="scene light")``,
  what ``pl.add_light`` adds unless told otherwise);
- of the lights that follow the camera (camera lights), only the brightest
  casts: the light kit's key light;
- the headlight casts nothing: a light on the camera's own axis hides each
  shadow behind the object that casts it (see :mod:`pvshadows.pipeline.planner`).

``pl.shadows.enable(lights=[...])`` casts from exactly the lights named
(a headlight still casts nothing).
"""

from __future__ import annotations

from pvshadows import _vtk as vtk
from pvshadows.scene.triangles import vtk_id


def key_light(renderer: vtk.vtkRenderer) -> vtk.vtkLight | None:
    """Return the brightest switched-on camera light of a renderer (the light kit's key light).

    Parameters
    ----------
    renderer : vtk.vtkRenderer
        The renderer.

    Returns
    -------
    vtk.vtkLight or None
        The first of the strongest camera lights, or ``None`` without any.

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.scene.light_kit import key_light
    >>> pl = pv.Plotter(off_screen=True)  # the light kit
    >>> key_light(pl.renderer).GetIntensity()
    0.75
    """
    # VTK's own methods, called on the class: PyVista's wrappers check every attribute, and
    # this runs for each camera light at every frame.
    best, brightest = None, 0.0
    lights = vtk.vtkRenderer.GetLights(renderer)
    item = lights.GetItemAsObject  # not GetNextItem: callers may be traversing
    for index in range(lights.GetNumberOfItems()):
        light = item(index)
        if not (vtk.vtkLight.LightTypeIsCameraLight(light) and vtk.vtkLight.GetSwitch(light)):
            continue
        intensity = vtk.vtkLight.GetIntensity(light)
        if best is None or intensity > brightest:
            best, brightest = light, intensity
    return best


def casts_by_default(
    light: vtk.vtkLight, renderer: vtk.vtkRenderer, keys: KeyLights | None = None
) -> bool:
    """Return whether a light casts shadows when ``enable()`` names no lights.

    Parameters
    ----------
    light : vtk.vtkLight
        A light of ``renderer``.
    renderer : vtk.vtkRenderer
        Its renderer.
    keys : KeyLights, optional
        The key lights this frame has found so far; without it, the key
        light is looked for.

    Returns
    -------
    bool
        ``False`` for a camera light that is not the key light; ``True``
        otherwise (the planner itself skips headlights).

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.scene.light_kit import casts_by_default
    >>> pl = pv.Plotter(off_screen=True)
    >>> [casts_by_default(light, pl.renderer) for light in pl.renderer.lights]
    [True, True, False, False, False]
    """
    if not vtk.vtkLight.LightTypeIsCameraLight(light):
        return True
    key = key_light(renderer) if keys is None else keys.key_of(renderer)
    return key is not None and vtk_id(key) == vtk_id(light)


class KeyLights:
    """Each renderer's key light (:func:`key_light`), looked for once: kept for one frame.

    A frame asks of each light whether it casts by default
    (:func:`casts_by_default`): with the light kit, four lights follow the
    camera and each would look for the key light among all of them. No
    light changes while a frame is planned, so one frame's lights share one
    look; the next frame makes a new object.

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.scene.light_kit import KeyLights, casts_by_default, key_light
    >>> pl = pv.Plotter(off_screen=True)  # the light kit
    >>> keys = KeyLights()
    >>> [casts_by_default(light, pl.renderer, keys) for light in pl.renderer.lights]
    [True, True, False, False, False]
    >>> keys.key_of(pl.renderer) is key_light(pl.renderer)
    True
    """

    def __init__(self) -> None:
        self._found: dict[str, vtk.vtkLight | None] = {}

    def key_of(self, renderer: vtk.vtkRenderer) -> vtk.vtkLight | None:
        """Return :func:`key_light` of a renderer, looked for on the first call only.

        Parameters
        ----------
        renderer : vtk.vtkRenderer
            The renderer.

        Returns
        -------
        vtk.vtkLight or None
            Its key light.
        """
        place = vtk_id(renderer)
        if place not in self._found:
            self._found[place] = key_light(renderer)
        return self._found[place]


def unshadowed_reason(
    light: vtk.vtkLight, renderer: vtk.vtkRenderer, keys: KeyLights | None = None
) -> str:
    """Return why a light without shadow settings casts nothing, for ``last_frame``.

    Parameters
    ----------
    light : vtk.vtkLight
        The light.
    renderer : vtk.vtkRenderer
        Its renderer.
    keys : KeyLights, optional
        As for :func:`casts_by_default`.

    Returns
    -------
    str
        The note.
    """
    if not casts_by_default(light, renderer, keys):
        return (
            "a camera light other than the key light (the brightest light that follows "
            "the camera): fill and back lights stay unshadowed unless named in "
            "enable(lights=[...])"
        )
    return "shadows are not enabled for this light"
