"""``strength``: how much of a shadowed light's contribution a shadow removes."""

import numpy as np
import pytest

from conftest import draw, spot_box_scene


def _erode(mask, steps=2):
    mask = mask.copy()
    for _ in range(steps):
        mask[1:-1, 1:-1] &= mask[:-2, 1:-1] & mask[2:, 1:-1] & mask[1:-1, :-2] & mask[1:-1, 2:]
    return mask


@pytest.mark.parametrize("technique", ["cubemap", "map", "volume", "planar"])
def test_strength_scales_the_removed_light_and_visibility_stays_geometric(technique):
    """A shadowed pixel keeps exactly 1 - strength of the light (ambient 0, one light)."""
    pl, spot = spot_box_scene()
    plain = pl.screenshot(return_img=True).astype(int)
    pl.shadows.enable(technique=technique, filter="hard", strength=1.0)
    full = draw(pl).astype(int)
    vis_full = pl.shadows.visibility(spot)
    pl.shadows.configure(spot, strength=0.5)
    half = draw(pl).astype(int)
    vis_half = pl.shadows.visibility(spot)
    pl.shadows.configure(spot, strength=0.0)
    none = draw(pl).astype(int)
    (report,) = pl.shadows.last_frame.lights
    assert report.technique is None and report.passes_run == 0
    assert "strength=0" in " ".join(report.notes)

    np.testing.assert_array_equal(vis_half, vis_full)
    dark = _erode(np.isfinite(vis_full) & (vis_full == 0.0))
    lit = _erode(np.isfinite(vis_full) & (vis_full == 1.0))
    dark &= plain.min(axis=2) > 40  # the light reaches it when unshadowed
    assert dark.sum() > 500 and lit.sum() > 5000
    assert full[dark].max() <= 1
    assert np.abs(2 * half[dark] - plain[dark]).max() <= 2
    assert np.abs(none - plain).max() <= 1
    for frame in (full, half):
        assert np.abs(frame[lit] - plain[lit]).max() <= 1


def test_strength_for_enable_and_per_light_is_validated():
    pl, spot = spot_box_scene()
    pl.shadows.enable(strength=0.25)
    assert pl.shadows.settings(spot).strength == 0.25
    with pytest.raises(ValueError, match=r"strength=1\.5 is out of range"):
        pl.shadows.configure(spot, strength=1.5)
    with pytest.raises(ValueError, match=r"strength=-0\.1 is out of range"):
        pl.shadows.enable(strength=-0.1)
    with pytest.raises(TypeError, match="strength must be a number"):
        pl.shadows.configure(spot, strength="half")
    with pytest.raises(TypeError, match="strength must be a number"):
        pl.shadows.enable(strength=True)
