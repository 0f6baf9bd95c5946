"""What the shadow-volume passes draw, kept from frame to frame.

The depth pre-pass's actors (:class:`DepthActors`, patched over a snapshot
that follows the last one) and a light's volume draws (:class:`KeptDraws`),
which read the camera's and the light's part from stacked rows taken in
one product each frame (:class:`~pvshadows.passes.volume_stencil.VolumeRows`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows._cached import cached
from pvshadows.geometry.volume_casters import VolumeMesh
from pvshadows.gl.actor_buffers import ActorBuffers
from pvshadows.gl.buffers import IndexedBuffers
from pvshadows.gl.caster_batch import CasterBatch
from pvshadows.model.plan import Cast
from pvshadows.passes.volume_stencil import StencilSide, VolumeDraw, VolumeRows
from pvshadows.scene.actor_state import ActorState, hides_what_is_behind
from pvshadows.scene.snapshot import ALL_ACTORS, Snapshot


@dataclass
class KeptDraws:
    """What a light's stencil count draws, kept while its closed casters and counting hold.

    A camera that moves changes only each caster's model-to-clip matrix,
    and a light that moves the light in each caster's frame: both are
    taken in one product over the stacked matrices (:meth:`rows`). The
    batches, index ranges and draws stay as long as the closed casters
    (the very list), the z-mode (which caps are drawn), the parallel
    projection's reach and the extrusion do; volumes built on the CPU
    follow the light, so theirs stay only for the same cast. Casters that
    moved but cast the same volumes (the same meshes, handedness and
    transmittances, extruded to infinity on the GPU) keep them too, their
    matrices stacked again (:meth:`take`).
    """

    plan: Cast
    closed: list[tuple[ActorState, VolumeMesh]]
    zmode: str
    reach: float
    extrude: str
    batches: list[list[tuple]]
    passing: list[float]
    draws: list[list[VolumeDraw]]
    #: Each count batch's draws by winding, through the light's volume batch or alone.
    sides: list[list[StencilSide]]
    #: The closed casters' model matrices and their inverses, stacked ``(n, 4, 4)``,
    #: and how far each one's volume reaches (0: to infinity).
    models: np.ndarray
    inverses: np.ndarray
    reaches: np.ndarray
    #: The light the draws were last read for, and its place in each caster's frame.
    light: np.ndarray
    lights: np.ndarray

    def holds(
        self,
        plan: Cast,
        closed: list[tuple[ActorState, VolumeMesh]],
        zmode: str,
        reach: float,
        extrude: str,
    ) -> bool:
        """Return whether the draws serve this cast (:meth:`take` its casters where they moved)."""
        if (self.zmode, self.reach, self.extrude) != (zmode, reach, extrude):
            return False
        if self.plan is plan or (extrude == "gpu" and self.closed is closed):
            return True
        return extrude == "gpu" and not reach and same_volumes(closed, self.closed)

    def take(
        self, closed: list[tuple[ActorState, VolumeMesh]], models: np.ndarray, inverses: np.ndarray
    ) -> None:
        """Take casters that cast the same volumes from elsewhere: their stacked matrices."""
        self.closed, self.models, self.inverses = closed, models, inverses
        self.lights = lights_in_models(inverses, self.light)

    @cached
    def every(self) -> list[VolumeDraw]:
        """The draws of every batch in one list (what ``show_volumes`` draws)."""
        return [draw for batch in self.draws for draw in batch]

    @cached
    def bodies(self) -> list[int]:
        """The bodies each batch counts."""
        return [sum(end - start for _, start, end in batch) for batch in self.batches]

    def rows(self, camera: np.ndarray, light: np.ndarray) -> VolumeRows:
        """Return what the draws read for this camera and light."""
        if not np.array_equal(light, self.light):
            self.light, self.lights = light, lights_in_models(self.inverses, light)
        return VolumeRows(camera @ self.models, self.lights, self.reaches)


def lights_in_models(inverses: np.ndarray, light: np.ndarray) -> np.ndarray:
    """Return a homogeneous light in the frames of many models at once.

    Parameters
    ----------
    inverses : numpy.ndarray
        ``(n, 4, 4)`` the models' inverse matrices.
    light : numpy.ndarray
        ``(4,)`` the light in world coordinates: ``(x, y, z, 1)`` or ``(d, 0)``.

    Returns
    -------
    numpy.ndarray
        ``(n, 4)``; a point's ``w`` made 1.

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.geometry.transforms import translation
    >>> from pvshadows.techniques.volume_draws import lights_in_models
    >>> inverses = np.linalg.inv([translation([1.0, 0.0, 0.0])])
    >>> lights_in_models(inverses, np.array([0.0, 0.0, 2.0, 1.0])).tolist()
    [[-1.0, 0.0, 2.0, 1.0]]
    """
    in_models = inverses @ light
    positional = in_models[:, 3] != 0.0
    in_models[positional] /= in_models[positional, 3:4]
    return in_models


@dataclass(frozen=True)
class DepthActors:
    """What the depth pre-pass draws of one snapshot: the actors that hide what is behind them.

    ``models`` stacks their model matrices ``(n, 4, 4)``, so that a camera
    that moves multiplies them in one go; ``rows`` holds each one's row in
    ``batch`` (-1 for an actor drawn on its own), ``None`` without a batch.
    """

    snapshot: Snapshot | None
    hidden: bool
    batch: CasterBatch | None
    keys: tuple
    models: np.ndarray
    buffers: list[IndexedBuffers]
    culls: list[str | None]
    rows: np.ndarray | None
    #: Per actor of the snapshot, its number among those drawn, -1 for one left out.
    numbers: list[int]

    def patched(
        self, snapshot: Snapshot, renderer: vtk.vtkRenderer, buffers: ActorBuffers
    ) -> DepthActors | None:
        """Return this over a snapshot that follows its own, or ``None`` to gather afresh.

        The replaced actors are patched in, as long as each is drawn or left
        out as before.
        """
        keys, models, drawn = list(self.keys), self.models.copy(), list(self.buffers)
        for row, state in snapshot.patches(ALL_ACTORS):
            number = self.numbers[row]
            if (number >= 0) != hides_what_is_behind(state, renderer):
                return None
            if number >= 0:
                keys[number], models[number] = state.key(), state.model_matrix()
                drawn[number] = buffers.get(state)
        return DepthActors(
            snapshot,
            self.hidden,
            self.batch,
            tuple(keys),
            models,
            drawn,
            self.culls,
            self.rows,
            self.numbers,
        )


def same_volumes(
    closed: list[tuple[ActorState, VolumeMesh]], before: list[tuple[ActorState, VolumeMesh]]
) -> bool:
    """Tell whether closed casters cast the volumes of others, wherever they stand.

    The same meshes in the same order, each caster as mirrored and letting
    as much light through as the one before it.
    """
    return len(closed) == len(before) and all(
        mesh is was
        and caster.mirrored == then.mirrored
        and caster.transmittance == then.transmittance
        for (caster, mesh), (then, was) in zip(closed, before, strict=True)
    )
