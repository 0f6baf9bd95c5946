"""What ran in the last frame: per light, the technique and each pass with its time."""

from __future__ import annotations

from dataclasses import dataclass, field

from pvshadows.model.tables import html_table


@dataclass
class PassReport:
    """One pass of one light in one frame.

    Attributes
    ----------
    name : str
        What the pass does, e.g. ``"cube depth (six faces, one draw)"``.
    status : str
        ``"run"``, ``"reused"`` (the map from an earlier frame was still
        right) or ``"skipped"`` (nothing to draw).
    detail : str
        Why, in words.
    ms : float or None
        GPU time of the pass in milliseconds; ``None`` when it did not run,
        and until the GPU has finished it (GPU times are read without
        waiting, usually a frame or two later).
    cpu_ms : float
        CPU time, in milliseconds, of this thread while it issued the
        pass's GL calls (what submitting the pass costs); 0 when it did not
        run.
    """

    name: str
    status: str
    detail: str = ""
    ms: float | None = None
    cpu_ms: float = 0.0

    def __str__(self) -> str:
        time = f"{self.ms:8.3f} ms" if self.ms is not None else "       -   "
        return f"{self.status:8s} {time}  {self.name}" + (
            f" ({self.detail})" if self.detail else ""
        )


@dataclass
class LightReport:
    """What one light did in one frame.

    Attributes
    ----------
    index : int
        Position of the light in the renderer's light list.
    kind : str
        ``"point"``, ``"spot"`` or ``"directional"``.
    technique : str or None
        The technique used, or ``None`` when the light cast no shadow.
    passes : list of PassReport
        Its passes in order.
    notes : list of str
        Decisions in words (why a light casts nothing, what was reused).
    subplot : tuple of int or None
        The subplot of the light's renderer, as ``pl.subplot`` takes it,
        when the plotter has several; ``None`` when it has one.
    """

    index: int
    kind: str
    technique: str | None
    passes: list[PassReport] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    subplot: tuple[int, ...] | None = None

    @property
    def passes_run(self) -> int:
        """Number of passes that ran (were not reused or skipped)."""
        return sum(p.status == "run" for p in self.passes)

    def __str__(self) -> str:
        head = f"light {self.index} ({self.kind}): {self.technique or 'no shadows'}"
        if self.subplot is not None:
            head = f"subplot {self.subplot}, {head}"
        lines = [head] + [f"  {p}" for p in self.passes] + [f"  - {n}" for n in self.notes]
        return "\n".join(lines)


@dataclass
class FrameFailure:
    """Why a frame was drawn without shadows.

    Attributes
    ----------
    frame : int
        The renderer's frame number.
    where : str
        What was running: which light and technique (or the planning, the
        receivers' shader edits, the end of the frame) and the function
        that raised.
    error : str
        The exception, type and message.
    cleanup : list of str
        Clean-up steps that failed too (the frame is still drawn plainly).
    repeats : int
        How many frames in a row failed this same way, this one included.

    Examples
    --------
    >>> from pvshadows.model.report import FrameFailure
    >>> print(FrameFailure(3, "light 0 (point, cubemap)", "RuntimeError: no memory"))
    frame 3 without shadows: light 0 (point, cubemap) raised RuntimeError: no memory
    """

    frame: int
    where: str
    error: str
    cleanup: list[str] = field(default_factory=list)
    repeats: int = 1

    def same_fault(self, other: FrameFailure) -> bool:
        """Whether ``other`` failed in the same place with the same error."""
        return (self.where, self.error) == (other.where, other.error)

    def __str__(self) -> str:
        text = f"frame {self.frame} without shadows: {self.where} raised {self.error}"
        if self.repeats > 1:
            text += f" ({self.repeats} frames in a row)"
        if self.cleanup:
            text += "; clean-up also failed: " + "; ".join(self.cleanup)
        return text


@dataclass
class FrameReport:
    """What pvshadows did in one frame, light by light.

    Attributes
    ----------
    lights : list of LightReport
        One entry per light of the renderer.
    frame : int
        Number of the frame (counted per renderer from 1) whose passes
        these are; their GPU times belong to this frame, whenever they arrive.
    failure : FrameFailure or None
        Why the frame was drawn without shadows, ``None`` when it was not.
    receivers : list of str
        Receivers that show fewer shadows than asked, each with why (its
        shader variant refused pvshadows' edits, or they did not land).
    cpu_ms : float
        CPU milliseconds pvshadows spent on the frame in its own code, on
        the thread drawing it: before VTK drew (reading the scene, planning,
        drawing maps, editing receivers) and after (collecting timings).
        :attr:`pass_cpu_ms` is part of it; VTK's own work for the
        receivers is not.

    Examples
    --------
    >>> from pvshadows.model.report import FrameReport, LightReport, PassReport
    >>> reused = PassReport("cube depth", "reused")
    >>> frame = FrameReport([LightReport(0, "point", "cubemap", [reused])])
    >>> frame.passes_run
    0
    >>> "<td>reused</td>" in frame._repr_html_()  # how Jupyter shows it
    True
    """

    lights: list[LightReport] = field(default_factory=list)
    frame: int = 0
    failure: FrameFailure | None = None
    receivers: list[str] = field(default_factory=list)
    cpu_ms: float = 0.0

    @property
    def gpu_ready(self) -> bool:
        """Whether every pass that ran on the GPU has its time (see :attr:`PassReport.ms`)."""
        return all(
            p.ms is not None for light in self.lights for p in light.passes if p.status == "run"
        )

    @property
    def passes_run(self) -> int:
        """Number of passes that ran in the frame, over all lights."""
        return sum(light.passes_run for light in self.lights)

    @property
    def gpu_ms(self) -> float:
        """Total GPU time of the passes that ran, in milliseconds."""
        return sum(p.ms or 0.0 for light in self.lights for p in light.passes)

    @property
    def pass_cpu_ms(self) -> float:
        """Total CPU time of issuing the passes that ran, in milliseconds."""
        return sum(p.cpu_ms for light in self.lights for p in light.passes)

    def __str__(self) -> str:
        lines = [str(light) for light in self.lights] or ["no lights"]
        if self.failure is not None:
            lines.insert(0, str(self.failure))
        return "\n".join(lines + [f"receiver {note}" for note in self.receivers])

    def _repr_pretty_(self, printer, cycle: bool) -> None:
        printer.text(str(self))

    def _repr_html_(self) -> str:
        rows = []
        for light in self.lights:
            where = f"subplot {light.subplot}, " if light.subplot is not None else ""
            name = f"{where}light {light.index} ({light.kind})"
            technique = light.technique or "no shadows"
            for step in light.passes:
                ms = f"{step.ms:.3f}" if step.ms is not None else None
                rows.append([name, technique, step.name, step.status, ms, step.detail])
            rows.extend([name, technique, None, None, None, note] for note in light.notes)
            if not light.passes and not light.notes:
                rows.append([name, technique, None, None, None, None])
        caption = (
            f"pvshadows frame: {len(self.lights)} light(s), {self.passes_run} pass(es) run, "
            f"{self.gpu_ms:.3f} GPU ms"
        )
        rows.extend(["receivers", None, None, None, None, note] for note in self.receivers)
        return html_table(caption, ["light", "technique", "pass", "status", "GPU ms", "why"], rows)
