"""Show the spot-lit box through trame's server-side backend and save what it streams.

Run by ``tests/test_notebook.py`` in a process of its own::

    python trame_session.py OUT.npz

``pl.show(jupyter_backend="server")`` starts trame's server and its worker
threads in this process, and ``vtkWebApplication`` encodes the streamed JPEG
in threads of its own. None of them belongs in a test worker that goes on to
open and close hundreds of other windows: closing this plotter's window while
they were alive aborted a test worker once in CI, and pytest-xdist cannot
always replace a crashed worker. So the picture is taken here, saved, and the
process ends without tearing trame down, as a notebook's kernel would
simply go on.
"""

from __future__ import annotations

import base64
import io
import os
import sys
import time

import numpy as np
import pyvista as pv
from PIL import Image
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkWebCore import vtkWebApplication

from conftest import spot_box_scene


def streamed_image(window) -> np.ndarray:
    """The JPEG trame-vtk's server-side view sends for a window (its image delivery protocol)."""
    app = vtkWebApplication()
    app.InvalidateCache(window)
    for _ in range(100):
        buffer = app.StillRenderToBuffer(window, 0, 100)
        if (
            buffer is not None
            and buffer.GetDataSize()
            and not app.GetHasImagesBeingProcessed(window)
        ):
            break
        time.sleep(0.05)
    jpeg = base64.b64decode(vtk_to_numpy(buffer).tobytes())
    return np.asarray(Image.open(io.BytesIO(jpeg)).convert("RGB"))


def main(out: str) -> None:
    """Save the streamed picture and whether trame renders the plotter's own window."""
    pv.OFF_SCREEN = True
    pl, _ = spot_box_scene(notebook=True)
    pl.shadows.enable(technique="map", filter="hard")
    widget = pl.show(jupyter_backend="server", return_viewer=True)
    (view,) = widget._viewer.views
    window = view._VtkRemoteView__view  # the window trame-vtk's image delivery renders
    np.savez(out, streamed=streamed_image(window), own_window=window is pl.render_window)
    sys.stdout.flush()
    os._exit(0)


if __name__ == "__main__":
    main(sys.argv[1])
