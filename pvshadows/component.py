"""``pl.shadows``: the PyVista plotter component users call."""

from __future__ import annotations

import warnings
from collections.abc import Iterable
from dataclasses import replace
from functools import partial
from numbers import Integral, Real
from typing import cast

import numpy as np
import pyvista as pv

from pvshadows import _vtk as vtk
from pvshadows.gl.binding import check_window
from pvshadows.model.plan import AUTO_TECHNIQUE, SERVES, LightPlan
from pvshadows.model.report import FrameReport
from pvshadows.model.settings import ShadowSettings, preset, validated
from pvshadows.pipeline.frame import RendererShadows
from pvshadows.scene.actor_state import hides_what_is_behind
from pvshadows.scene.light_kit import KeyLights, casts_by_default
from pvshadows.scene.lights import light_kind, light_pose, renderer_lights
from pvshadows.scene.naming import ActorNames
from pvshadows.scene.planes import require_plane
from pvshadows.scene.reader import SceneReader
from pvshadows.scene.triangles import vtk_id, world_points
from pvshadows.verify.measure import Measurement, compare
from pvshadows.verify.probe import read_visibility, require_drawn
from pvshadows.verify.reference import (
    MAX_SAMPLES,
    SceneMesh,
    ViewSpec,
    require_traceable,
    trace_reference,
)


class ShadowsComponent:
    """Shadows from every light of a PyVista plotter: ``pl.shadows``.

    Installed as the ``shadows`` plotter component, so every
    :class:`pyvista.Plotter` has it once pvshadows is installed.

    Parameters
    ----------
    plotter : pyvista.Plotter
        The plotter.

    Examples
    --------
    >>> import pyvista as pv
    >>> import pvshadows
    >>> pl = pv.Plotter(off_screen=True, lighting="none")
    >>> _ = pl.add_mesh(pv.Plane(i_size=10, j_size=10))
    >>> _ = pl.add_mesh(pv.Sphere(center=(0, 0, 1)))
    >>> pl.add_light(pv.Light(position=(0, 0, 3), positional=True, cone_angle=180))
    >>> pl.shadows.enable()
    >>> image = pl.screenshot(return_img=True)
    >>> print(pl.shadows.last_frame.lights[0].technique)
    cubemap
    """

    def __init__(self, plotter: pv.Plotter) -> None:
        self._plotter = plotter
        self._defaults = ShadowSettings()
        self._per_light: dict[str, ShadowSettings] = {}
        self._lights: set[str] | None = None
        self._names = ActorNames(plotter)
        self._reader = SceneReader(self._actor_name)
        self._renderers: list[RendererShadows] = []
        self._traced: tuple | None = None
        self._show_volumes = False

    # -- enabling --------------------------------------------------------------------------

    @property
    def enabled(self) -> bool:
        """Whether shadows are on."""
        return bool(self._renderers)

    def enable(
        self,
        technique: str = "auto",
        *,
        quality: str = "balanced",
        lights: Iterable[vtk.vtkLight] | None = None,
        **settings: object,
    ) -> None:
        """Turn shadows on for every light (or the given ones).

        Parameters
        ----------
        technique : str, default: "auto"
            ``"auto"`` lets pvshadows choose per light and frame
            (``"cubemap"`` for point lights, ``"map"`` for spot and
            directional lights, ``"volume"`` for ``quality="exact"``,
            ``"planar"`` when the only receiver is one plane), or name one
            technique for all lights it can serve (``"cubemap"``, ``"map"``,
            ``"volume"``: stencil shadow volumes, pixel-exact hard shadows
            from every kind of light; ``"planar"``: casters flattened onto
            one receiving plane, the cheapest, every kind of light, but
            objects do not shadow each other). A light the named technique
            cannot serve (``"cubemap"`` and a directional light, ``"map"``
            and a point light) casts with auto's choice instead: one
            warning names those lights and :attr:`last_frame` says so
            (:meth:`configure` refuses the same request for one light).
        quality : {"draft", "balanced", "exact"}, default: "balanced"
            A point on the accuracy-cost frontier that ``pvshadows bench``
            measures: ``"draft"`` (512-texel maps, hard edges), ``"balanced"``
            (1024-texel maps, 4-tap PCF edges) or ``"exact"`` (pixel-exact
            shadow volumes; shadow maps of 2048 texels for open casters).
            Settings given explicitly win over the preset's.
        lights : iterable of pyvista.Light, optional
            Only these lights cast shadows. By default every scene light
            does and, of the lights that follow the camera (PyVista's light
            kit), only the brightest one, the key light: the fill and back
            lights stay unshadowed. A headlight never casts (its shadows
            hide behind the objects that cast them).
        **settings
            Defaults for every light: ``resolution``, ``filter``,
            ``pcf_taps``, ``samples``, ``filter_radius``, ``light_size``,
            ``passes``, ``bias``, ``slope_bias``, ``normal_offset``, and for
            volumes ``zmode``, ``extrude``, ``on_open``, and ``strength``
            (0 to 1: how much of a shadowed light's contribution is removed,
            1 by default; see :class:`pvshadows.model.settings.ShadowSettings`).
            ``bias=0, slope_bias=0, normal_offset=0`` compares each lit
            surface with its own depth in the map, so about half of it
            shadows itself in speckles (acne, 43 % of lit pixels in the
            standard scene); that warns, as it is only useful to see what the
            biases do.

        Raises
        ------
        ValueError, TypeError
            For a bad setting (naming it and what is allowed), a light that
            is not in this plotter, or a mesh that cannot cast shadows.
        pvshadows.gl.binding.OpenGLPlatformError
            If PyOpenGL was imported for a platform that cannot reach this
            plotter's window (``pvshadows info`` says the same).

        Examples
        --------
        >>> import pyvista as pv
        >>> import pvshadows
        >>> pl = pv.Plotter(off_screen=True)
        >>> pl.shadows.enable(filter="hard", resolution=512)
        >>> pl.shadows.enabled
        True
        """
        self._check_open("enable")
        defaults = validated(preset(quality), technique=technique, **settings)
        chosen = None
        if lights is not None:
            chosen = {vtk_id(self._check_light(light, "lights")) for light in _light_list(lights)}
        self._check_scene()
        self._warn_unserved(defaults, chosen)
        self._check_volumes(defaults)
        if self._plotter.render_window is not None:
            check_window(self._plotter.render_window)
        self._defaults, self._lights = defaults, chosen
        if not self._renderers:
            self._renderers = [
                RendererShadows(
                    renderer, partial(self._settings_for, renderer=renderer), self._reader
                )
                for renderer in self._plotter.renderers
            ]
            for renderer in self._renderers:
                renderer.show_debug = self._show_volumes
        self._plotter.render()

    def disable(self) -> None:
        """Turn shadows off and release every GPU resource they used.

        A screenshot afterwards is identical to one of a plotter that never
        had shadows.

        Examples
        --------
        >>> import pyvista as pv
        >>> import pvshadows
        >>> pl = pv.Plotter(off_screen=True)
        >>> pl.shadows.enable()
        >>> pl.shadows.disable()
        >>> pl.shadows.enabled
        False
        """
        for renderer in self._renderers:
            renderer.detach()
        self._renderers = []
        if self._plotter.render_window is not None:
            self._plotter.render()

    def configure(self, light: vtk.vtkLight, **settings: object) -> None:
        """Set the shadow settings of one light.

        Parameters
        ----------
        light : pyvista.Light
            A light of this plotter.
        **settings
            Any setting of :class:`pvshadows.model.settings.ShadowSettings`
            (``technique``, ``resolution``, ``filter``, ``pcf_taps``,
            ``samples``, ``light_size``, ``passes``, the biases, ``zmode``,
            ``extrude``, ``on_open``, ``strength``, ...); ``quality`` starts
            from that preset instead of the light's current settings.

        Raises
        ------
        ValueError, TypeError
            Naming the bad argument and the allowed values.

        Examples
        --------
        >>> import pyvista as pv
        >>> import pvshadows
        >>> pl = pv.Plotter(off_screen=True, lighting="none")
        >>> bulb = pv.Light(position=(0, 0, 3), positional=True, cone_angle=180)
        >>> pl.add_light(bulb)
        >>> pl.shadows.configure(bulb, filter="pcf", pcf_taps=4, resolution=2048)
        """
        self._check_light(light, "light")
        current = self._per_light.get(vtk_id(light), self._defaults)
        quality = settings.get("quality")
        if isinstance(quality, str):
            current = preset(quality)
        updated = validated(current, **settings)
        kind = light_kind(light)
        if updated.technique != "auto" and kind not in SERVES[updated.technique]:
            allowed = ", ".join(k.value for k in SERVES[updated.technique])
            msg = (
                f"technique={updated.technique!r} cannot serve this {kind.value} light; "
                f"it serves {allowed} lights"
            )
            raise ValueError(msg)
        self._check_volumes(updated)
        self._per_light[vtk_id(light)] = updated
        self._plotter.render()

    def settings(self, light: vtk.vtkLight) -> ShadowSettings:
        """Return the settings a light casts its shadows with.

        Parameters
        ----------
        light : pyvista.Light
            A light of this plotter.

        Returns
        -------
        ShadowSettings
            Its settings (the defaults of :meth:`enable` unless configured).
        """
        self._check_light(light, "light")
        return self._per_light.get(vtk_id(light), self._defaults)

    def set_caster(
        self, actor: vtk.vtkActor, cast: bool = True, *, transmittance: float | None = None
    ) -> None:
        """Choose whether an actor casts shadows (all do by default), and how much light it passes.

        Parameters
        ----------
        actor : pyvista.Actor
            The actor.
        cast : bool, default: True
            ``False`` to let light pass through it.
        transmittance : float, optional
            Share of the light each of its surfaces lets through, from 0
            (opaque) to 1 (casts nothing), in place of ``1 - opacity``; every
            technique and :meth:`reference` use it. ``None`` (the default)
            goes back to ``1 - opacity``.

        Raises
        ------
        TypeError
            If ``actor`` is not an actor, ``cast`` not a bool or
            ``transmittance`` not a number.
        ValueError
            If ``actor`` is not in this plotter or ``transmittance`` not from 0 to 1.

        Notes
        -----
        Shadows are physical about a caster's transmittance (``1 - opacity``
        unless set here): each of its surfaces a shadow ray crosses lets
        that share of the light through, so a closed body at ``opacity=0.3``
        passes ``0.7 ** 2 = 0.49`` (its two sides, as VTK's blending draws
        them). :meth:`reference` traces exactly that. ``technique="planar"``
        does the same, and so does ``"volume"`` (exactly for convex bodies;
        a ray through several parts of one translucent caster gets what one
        part lets through).

        ``"map"`` and ``"cubemap"`` draw the translucent casters of a light
        into a companion of its depth map, of the same size and projection:
        per texel, the product of the transmittances of every translucent
        surface over it and the depth of the nearest one. A receiver beyond
        that depth gets the product, read once at its own texel (unfiltered,
        whatever the light's filter), times what the opaque casters let
        through. The approximation: a receiver between two translucent
        surfaces (inside a translucent body, or between two translucent
        casters) gets all of them, not only those in front of it. A light
        whose casters are all opaque gets no companion and costs nothing
        more.

        Lower the light's ``strength`` (:meth:`configure`) to lighten all
        its shadows instead.

        Examples
        --------
        >>> import pyvista as pv
        >>> import pvshadows
        >>> pl = pv.Plotter(off_screen=True)
        >>> ground = pl.add_mesh(pv.Plane())
        >>> glass = pl.add_mesh(pv.Sphere(center=(0, 0, 1)), opacity=0.9)
        >>> pl.shadows.set_caster(ground, False)
        >>> pl.shadows.set_caster(glass, transmittance=0.5)  # lets half through each side
        """
        key = vtk_id(self._check_actor(actor, cast, "cast"))
        through = _check_transmittance(transmittance)
        self._reader.set_casting(key, bool(cast), through)

    def set_receiver(
        self, actor: vtk.vtkActor, receive: bool = True, *, plane: bool = False
    ) -> None:
        """Choose whether an actor shows shadows (all lit actors do by default).

        Parameters
        ----------
        actor : pyvista.Actor
            The actor.
        receive : bool, default: True
            ``False`` to draw it fully lit.
        plane : bool, default: False
            ``True`` names it the plane that ``technique="planar"`` flattens
            shadows onto (otherwise the largest flat receiver is found on
            its own). Its points must lie in one plane, within
            :data:`pvshadows.scene.planes.PLANE_TOLERANCE` of its size.

        Raises
        ------
        ValueError
            With ``plane=True``, for an actor that is not flat (saying how
            far off a plane its points are) or with ``receive=False``.

        Examples
        --------
        >>> import pyvista as pv
        >>> import pvshadows
        >>> pl = pv.Plotter(off_screen=True)
        >>> label = pl.add_mesh(pv.Sphere())
        >>> pl.shadows.set_receiver(label, False)
        >>> floor = pl.add_mesh(pv.Plane(i_size=10, j_size=10))
        >>> pl.shadows.set_receiver(floor, plane=True)
        """
        key = vtk_id(self._check_actor(actor, receive, "receive"))
        if not isinstance(plane, bool | np.bool_):
            msg = f"plane must be True or False, got {plane!r}"
            raise TypeError(msg)
        if plane:
            if not receive:
                msg = "plane=True names a receiver of planar shadows: it needs receive=True"
                raise ValueError(msg)
            name = self._actor_name(actor)
            require_plane(actor, self._reader.triangles_of(actor), name)
        self._reader.set_receiving(key, bool(receive), plane)

    def show_volumes(self, show: bool = True) -> None:
        """Draw the shadow volumes translucent over the scene, for debugging.

        Only lights using ``technique="volume"`` have volumes; the sides of
        each are drawn as counted in that frame, depth-tested against the
        scene (the caps lie on the casters and at infinity, so they are left
        out).

        Parameters
        ----------
        show : bool, default: True
            ``False`` to stop drawing them.

        Examples
        --------
        >>> import pyvista as pv
        >>> import pvshadows
        >>> pl = pv.Plotter(off_screen=True, lighting="none")
        >>> _ = pl.add_mesh(pv.Plane(i_size=10, j_size=10))
        >>> _ = pl.add_mesh(pv.Cube(center=(0, 0, 1)))
        >>> pl.add_light(pv.Light(position=(0, 0, 3), positional=True, cone_angle=180))
        >>> pl.shadows.enable(technique="volume")
        >>> pl.shadows.show_volumes(True)
        >>> image = pl.screenshot(return_img=True)
        """
        if not isinstance(show, bool | np.bool_):
            msg = f"show must be True or False, got {show!r}"
            raise TypeError(msg)
        self._show_volumes = bool(show)
        for renderer in self._renderers:
            renderer.show_debug = self._show_volumes
        if self._renderers:
            self._plotter.render()

    # -- what happened and how right it was ------------------------------------------------

    @property
    def last_frame(self) -> FrameReport:
        """What ran in the last frame: per light, its technique and each pass with its GPU time.

        Returns
        -------
        pvshadows.model.report.FrameReport
            Printable; ``passes_run`` counts the passes that ran. With
            subplots, each light says which subplot it lights. GPU times
            are read without stalling the GPU: a pass's ``ms`` arrives in
            this same report a frame or two later (``frame`` says which
            frame it is, ``gpu_ready`` whether every time is in).
        """
        report = FrameReport(frame=max((r.last_frame.frame for r in self._renderers), default=0))
        several = len(self._renderers) > 1
        for number, renderer in enumerate(self._renderers):
            report.failure = report.failure or renderer.last_frame.failure
            for light in renderer.last_frame.lights:
                report.lights.append(
                    replace(light, subplot=self._subplot(number)) if several else light
                )
            report.receivers.extend(renderer.last_frame.receivers)
            report.cpu_ms += renderer.last_frame.cpu_ms
        return report

    def visibility(self, light: vtk.vtkLight | None = None, *, scale: int = 1) -> np.ndarray:
        """Return how much of a light reaches the surface seen in each pixel.

        The frame is drawn once more with the receivers showing that light's
        visibility instead of their colour (the same maps, camera and
        window; SSAA included, image passes that only recolour the frame,
        such as eye-dome lighting or SSAO, left out), then drawn normally
        again.

        Parameters
        ----------
        light : pyvista.Light, optional
            A shadowed light; by default the first one of the frame.
        scale : int, default: 1
            Read the image ``pl.screenshot(scale=scale)`` produces: the
            frame drawn ``scale`` times larger each way, in tiles.

        Returns
        -------
        numpy.ndarray
            float32 ``(H, W)`` in [0, 1] (``H`` and ``W`` times ``scale``),
            row 0 at the top, NaN where the pixel shows no receiving
            surface. 0 where the visible side faces away from the light.

        Notes
        -----
        This is the geometric visibility, the same at every ``strength``:
        a receiver shows ``1 - strength * (1 - visibility)`` of the light's
        diffuse and specular terms, so :meth:`measure` judges the shadow
        test itself against :meth:`reference` whatever the strength.

        Raises
        ------
        TypeError
            If ``light`` is not a ``pyvista.Light``.
        ValueError
            If the light is not in this plotter or cast no shadow in the
            last frame, or ``scale`` is below 1.
        TypeError
            If ``scale`` is not an int.
        pvshadows.verify.probe.FrameFailedError
            If pvshadows failed in the frame, so it was drawn without
            shadows (:attr:`last_frame` says which light, which pass and
            the error).

        Examples
        --------
        >>> import pyvista as pv
        >>> import pvshadows
        >>> pl = pv.Plotter(off_screen=True, lighting="none", window_size=(200, 150))
        >>> _ = pl.add_mesh(pv.Plane(i_size=10, j_size=10))
        >>> _ = pl.add_mesh(pv.Sphere(center=(0, 0, 1)))
        >>> pl.add_light(pv.Light(position=(0, 0, 3), positional=True, cone_angle=180))
        >>> pl.shadows.enable()
        >>> pl.shadows.visibility(scale=2).shape
        (300, 400)
        """
        scale = _check_scale(scale)
        renderer, plan = self._plan_of(light)
        return read_visibility(
            self._plotter, renderer.renderer, plan.vtk_index, renderer, scale=scale
        )

    def reference(
        self,
        light: vtk.vtkLight | None = None,
        *,
        light_size: float = 0.0,
        samples: int = 1,
        scale: int = 1,
    ) -> np.ndarray:
        """Return the exact visibility of a light per pixel, by ray casting.

        Parameters
        ----------
        light : pyvista.Light, optional
            A light of this plotter; by default the first shadowed one.
        light_size : float, default: 0.0
            Radius of a spherical emitter (point and spot lights, world
            units) or angular radius in degrees (directional lights); 0 for
            hard shadows.
        samples : int, default: 1
            Shadow rays per pixel (more than one needs ``light_size > 0``).
        scale : int, default: 1
            Trace the image ``pl.screenshot(scale=scale)`` produces.

        Returns
        -------
        numpy.ndarray
            float32 ``(H, W)`` like :meth:`visibility`.
        """
        return self._trace(light, light_size=light_size, samples=samples, scale=scale).visibility

    def measure(
        self, light: vtk.vtkLight | None = None, *, scale: int = 1, **reference: object
    ) -> Measurement:
        """Compare :meth:`visibility` with :meth:`reference` on the current frame.

        Parameters
        ----------
        light : pyvista.Light, optional
            A shadowed light; by default the first one.
        scale : int, default: 1
            Compare the image ``pl.screenshot(scale=scale)`` produces.
        **reference
            ``light_size`` and ``samples`` for a soft-shadow reference.

        Returns
        -------
        pvshadows.verify.measure.Measurement
            Share of lit-side pixels whose shadow class disagrees, false and
            missed shadow shares, and the RMSE of visibility.

        Raises
        ------
        TypeError, ValueError, pvshadows.verify.probe.FrameFailedError
            As :meth:`visibility` does.
        """
        unknown = sorted(set(reference) - {"light_size", "samples"})
        if unknown:
            msg = f"unknown reference option(s) {', '.join(unknown)}; they are light_size, samples"
            raise TypeError(msg)
        _check_reference_options(**reference)
        shown = self.visibility(light, scale=scale)
        traced = self._trace(light, scale=scale, **reference)
        return compare(shown, traced)

    def __plotter_close__(self) -> None:
        self.disable()

    def __plotter_deep_clean__(self) -> None:
        self.disable()

    # -- helpers ---------------------------------------------------------------------------

    def _settings_for(
        self, light: vtk.vtkLight, renderer: vtk.vtkRenderer, keys: KeyLights
    ) -> ShadowSettings | None:
        key = vtk_id(light)
        if self._lights is not None and key not in self._lights:
            return None
        if self._lights is None and not casts_by_default(light, renderer, keys):
            return None
        return self._per_light.get(key, self._defaults)

    def _subplot(self, number: int) -> tuple[int, ...]:
        where = self._plotter.renderers.index_to_loc(number)
        return tuple(int(value) for value in np.atleast_1d(where))

    def _actor_name(self, actor: vtk.vtkActor) -> str:
        return self._names(actor)

    def _all_lights(self) -> list[tuple[vtk.vtkRenderer, vtk.vtkLight]]:
        return [
            (renderer, light)
            for renderer in self._plotter.renderers
            for light in renderer_lights(renderer)
        ]

    def _check_light(self, light: object, argument: str) -> vtk.vtkLight:
        if not isinstance(light, vtk.vtkLight):
            msg = f"{argument} must be a pyvista.Light of this plotter, got {type(light).__name__}"
            raise TypeError(msg)
        if vtk_id(light) not in {vtk_id(found) for _, found in self._all_lights()}:
            msg = (
                f"{argument}: this light is not in the plotter; "
                "add it first with pl.add_light(light)"
            )
            raise ValueError(msg)
        light_pose(light)
        return light

    def _check_actor(self, actor: object, flag: object, flag_name: str) -> vtk.vtkActor:
        if not isinstance(actor, vtk.vtkActor):
            msg = (
                f"actor must be a pyvista.Actor (what add_mesh returns), got {type(actor).__name__}"
            )
            raise TypeError(msg)
        if not any(renderer.HasViewProp(actor) for renderer in self._plotter.renderers):
            msg = (
                f"actor: this {type(actor).__name__} is not in this plotter (never added, "
                "removed, or added to another plotter); add it with pl.add_mesh() or "
                "pl.add_actor() first"
            )
            raise ValueError(msg)
        if not isinstance(flag, bool | np.bool_):
            msg = f"{flag_name} must be True or False, got {flag!r}"
            raise TypeError(msg)
        return actor

    def _check_open(self, call: str) -> None:
        if getattr(self._plotter, "_closed", False) or self._plotter.render_window is None:
            msg = (
                f"{call}(): this plotter is closed (close(), or show() or screenshot() "
                "closing it, ended it); create a new plotter to draw shadows"
            )
            raise RuntimeError(msg)

    def _warn_unserved(self, defaults: ShadowSettings, chosen: set[str] | None) -> None:
        """Warn once, in enable(), about lights the technique asked for cannot serve."""
        if defaults.technique == "auto":
            return
        unserved = []
        for renderer, light in self._all_lights():
            key = vtk_id(light)
            if (chosen is not None and key not in chosen) or key in self._per_light:
                continue
            kind = light_kind(light)
            if light.LightTypeIsHeadlight() or kind in SERVES[defaults.technique]:
                continue
            index = [vtk_id(found) for found in renderer_lights(renderer)].index(key)
            unserved.append(f"light {index} ({kind.value}, {AUTO_TECHNIQUE[kind]})")
        if unserved:
            msg = (
                f"technique={defaults.technique!r} cannot serve {len(unserved)} light(s); "
                f"they cast with auto's choice instead: {', '.join(unserved)} "
                "(pl.shadows.last_frame says the same)"
            )
            warnings.warn(msg, stacklevel=3)

    def _check_scene(self) -> None:
        for _, light in self._all_lights():
            if light.GetSwitch():
                light_pose(light)
        for renderer in self._plotter.renderers:
            actors = renderer.GetActors()
            actors.InitTraversal()
            for _ in range(actors.GetNumberOfItems()):
                actor = actors.GetNextActor()
                if actor.GetVisibility() and actor.GetMapper() is not None:
                    self._reader.triangles_of(actor)

    def _check_volumes(self, settings: ShadowSettings) -> None:
        """Ask for a stencil buffer before the first render; check casters for ``on_open="raise"``.

        Volumes are counted in pvshadows' own framebuffer, so a window that
        already rendered without a stencil buffer works too.
        """
        if settings.technique != "volume":
            return
        window = self._plotter.render_window
        if window is not None and not window.GetInitialized():
            window.SetStencilCapable(1)
        if settings.on_open == "raise":
            from pvshadows.techniques.volume_meshes import require_closed

            casters = []
            for renderer in self._plotter.renderers:
                for state in self._reader.read(renderer).casters:
                    casters.append((state.name, state.triangles))
            require_closed(casters)

    def _plan_of(self, light: vtk.vtkLight | None) -> tuple[RendererShadows, LightPlan]:
        if light is not None:
            self._check_light(light, "light")
        if not self._renderers:
            msg = "shadows are not enabled: call pl.shadows.enable() first"
            raise ValueError(msg)
        if all(r.snapshot is None and r.error is None for r in self._renderers):
            self._plotter.screenshot(return_img=True)
        require_drawn(self._renderers)
        for renderer in self._renderers:
            for plan in renderer.plans:
                if plan.technique is None:
                    continue
                if light is None or plan.key == vtk_id(light):
                    return renderer, plan
        which = "no light" if light is None else "this light"
        msg = f"{which} cast a shadow in the last frame; see pl.shadows.last_frame for why"
        raise ValueError(msg)

    def _light_and_renderer(
        self, light: vtk.vtkLight | None
    ) -> tuple[vtk.vtkLight, vtk.vtkRenderer]:
        if light is None:
            renderer, plan = self._plan_of(None)
            return plan.light, renderer.renderer
        self._check_light(light, "light")
        for renderer, candidate in self._all_lights():
            if vtk_id(candidate) == vtk_id(light):
                return candidate, renderer
        raise AssertionError  # _check_light guarantees the light is in the plotter

    def _trace(
        self,
        light: vtk.vtkLight | None,
        *,
        light_size: object = 0.0,
        samples: object = 1,
        scale: object = 1,
    ):
        _check_reference_options(light_size, samples)
        scale = _check_scale(scale)
        light, ren = self._light_and_renderer(light)
        snapshot = self._reader.read(ren)
        width, height = (scale * size for size in ren.GetSize())
        camera = ren.GetActiveCamera()
        matrix = camera.GetCompositeProjectionTransformMatrix(ren.GetTiledAspectRatio(), -1, 1)
        view = ViewSpec(pv.array_from_vtkmatrix(matrix), int(width), int(height))
        pose = light_pose(light)
        faces_seen = tuple(hides_what_is_behind(a, ren) for a in snapshot.actors)
        key = (
            view.world_to_ndc.tobytes(),
            (width, height),
            pose.key(),
            (float(cast(float, light_size)), int(cast(int, samples))),
            tuple((*a.key(), a.caster, a.receiver, a.transmittance) for a in snapshot.actors),
            faces_seen,
        )
        if self._traced is None or self._traced[0] != key:
            require_traceable(
                {a.name: float(np.linalg.norm(np.ptp(a.bounds, axis=0))) for a in snapshot.actors}
            )
            meshes = [
                SceneMesh(
                    world_points(a.triangles, a.matrix),
                    a.triangles.triangles.astype(np.int64),
                    caster=a.caster,
                    receiver=a.receiver,
                    opacity=1.0 - a.transmittance,
                    faces_seen=seen,
                )
                for a, seen in zip(snapshot.actors, faces_seen, strict=True)
            ]
            result = trace_reference(
                meshes,
                view,
                pose,
                light_size=float(cast(float, light_size)),
                samples=int(cast(int, samples)),
            )
            self._traced = (key, result)
        return self._traced[1]


def _light_list(lights: object) -> list[object]:
    if isinstance(lights, vtk.vtkLight):
        return [lights]
    if isinstance(lights, str | bytes) or not isinstance(lights, Iterable):
        msg = (
            "lights must be a pyvista.Light or an iterable of lights of this plotter, "
            f"got {type(lights).__name__}"
        )
        raise TypeError(msg)
    return list(lights)


def _check_reference_options(light_size: object = 0.0, samples: object = 1) -> None:
    if isinstance(light_size, bool) or not isinstance(light_size, Real):
        msg = f"light_size must be a number, got {light_size!r}"
        raise TypeError(msg)
    if isinstance(samples, bool) or not isinstance(samples, Integral):
        msg = f"samples must be an int, got {samples!r}"
        raise TypeError(msg)
    size, count = float(light_size), int(samples)
    if not (np.isfinite(size) and size >= 0.0):
        msg = f"light_size={light_size} is not allowed; it must be a finite number >= 0"
        raise ValueError(msg)
    if not 1 <= count <= MAX_SAMPLES:
        msg = f"samples={samples} is out of range; it must be from 1 to {MAX_SAMPLES}"
        raise ValueError(msg)
    if (count > 1) != (size > 0.0):
        msg = (
            f"samples={samples} with light_size={light_size}: soft shadows need both "
            "samples > 1 and light_size > 0, hard shadows samples=1 and light_size=0"
        )
        raise ValueError(msg)


def _check_transmittance(transmittance: object) -> float | None:
    if transmittance is None:
        return None
    if isinstance(transmittance, bool) or not isinstance(transmittance, Real):
        msg = (
            "transmittance must be a number from 0 (opaque) to 1 (casts nothing) or None "
            f"(1 - opacity), got {transmittance!r}"
        )
        raise TypeError(msg)
    if not 0.0 <= float(transmittance) <= 1.0:
        msg = (
            f"transmittance={transmittance} is out of range; it must be from 0 (opaque) "
            "to 1 (casts nothing)"
        )
        raise ValueError(msg)
    return float(transmittance)


def _check_scale(scale: object) -> int:
    if isinstance(scale, bool) or not isinstance(scale, Integral):
        msg = f"scale must be an int (the screenshot's scale), got {scale!r}"
        raise TypeError(msg)
    if scale < 1:
        msg = f"scale must be 1 or more, got {scale!r}"
        raise ValueError(msg)
    return int(scale)
