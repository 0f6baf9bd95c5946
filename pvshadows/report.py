"""What ran in the last frame: per light, the technique and each pass with its time."""

from __future__ import annotations

from dataclasses import dataclass, field


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
        GPU time of the pass in milliseconds (``None`` when it did not run).
    """

    name: str
    status: str
    detail: str = ""
    ms: float | None = None

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
class FrameReport:
    """What pvshadows did in one frame, light by light.

    Attributes
    ----------
    lights : list of LightReport
        One entry per light of the renderer.
    receivers : list of str
        Receivers that show fewer shadows than asked, each with why (its
        shader variant refused pvshadows' edits, or they did not land).

    Examples
    --------
    >>> from pvshadows.report import FrameReport, LightReport, PassReport
    >>> reused = PassReport("cube depth", "reused")
    >>> frame = FrameReport([LightReport(0, "point", "cubemap", [reused])])
    >>> frame.passes_run
    0
    """

    lights: list[LightReport] = field(default_factory=list)
    receivers: list[str] = field(default_factory=list)

    @property
    def passes_run(self) -> int:
        """Number of passes that ran in the frame, over all lights."""
        return sum(light.passes_run for light in self.lights)

    @property
    def gpu_ms(self) -> float:
        """Total GPU time of the passes that ran, in milliseconds."""
        return sum(p.ms or 0.0 for light in self.lights for p in light.passes)

    def __str__(self) -> str:
        lines = [str(light) for light in self.lights] or ["no lights"]
        return "\n".join(lines + [f"receiver {note}" for note in self.receivers])
