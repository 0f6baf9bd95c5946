"""Matrices for the shadow passes, built in double precision.

Every matrix handed to the GPU is composed here in float64 and relative to
the light or the camera, so float32 on the GPU only ever holds coordinates of
the size of the scene, not of its distance from the origin.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

from pvshadows import _vtk as vtk

_IDENTITY = np.eye(4)
#: The last row of an affine matrix.
AFFINE_LAST_ROW = (0.0, 0.0, 0.0, 1.0)
#: The rotation part of a matrix that does not turn, row after row.
_NO_TURN = (1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0)

#: Forward and up axes of the six cube faces in GL order (+X, -X, +Y, -Y, +Z, -Z),
#: chosen so that a face rendered with :func:`cube_face_rotation` lands where a
#: ``samplerCube`` lookup with the light-to-point vector reads it.
CUBE_FACE_AXES = (
    ((1.0, 0.0, 0.0), (0.0, -1.0, 0.0)),
    ((-1.0, 0.0, 0.0), (0.0, -1.0, 0.0)),
    ((0.0, 1.0, 0.0), (0.0, 0.0, 1.0)),
    ((0.0, -1.0, 0.0), (0.0, 0.0, -1.0)),
    ((0.0, 0.0, 1.0), (0.0, -1.0, 0.0)),
    ((0.0, 0.0, -1.0), (0.0, -1.0, 0.0)),
)


def look_rotation(forward: npt.ArrayLike, up: npt.ArrayLike) -> np.ndarray:
    """Return the 4x4 rotation of a camera at the origin looking along ``forward``.

    Parameters
    ----------
    forward, up : array_like
        Viewing direction and approximate up vector (need not be unit).

    Returns
    -------
    numpy.ndarray
        ``(4, 4)`` float64 matrix taking world axes to the camera's axes
        (x right, y up, looking down -z).

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.geometry.transforms import look_rotation
    >>> rotation = look_rotation(np.array([0, 0, -1.0]), np.array([0, 1.0, 0]))
    >>> bool(np.allclose(rotation, np.eye(4)))
    True
    """
    along = np.asarray(forward, dtype=np.float64).tolist()
    right, upward, backward = look_axes(along, np.asarray(up, dtype=np.float64).tolist())
    return np.array([[*right, 0.0], [*upward, 0.0], [*backward, 0.0], [0.0, 0.0, 0.0, 1.0]])


def look_axes(
    forward: Sequence[float], up: Sequence[float]
) -> tuple[tuple[float, float, float], tuple[float, float, float], tuple[float, float, float]]:
    """Return the rows of :func:`look_rotation`'s rotation, worked out in plain floats.

    Parameters
    ----------
    forward, up : sequence of float
        Viewing direction and approximate up vector (need not be unit).

    Returns
    -------
    tuple
        The camera's right, up and backward axes in world coordinates, unit
        three-tuples.

    Examples
    --------
    >>> from pvshadows.geometry.transforms import look_axes
    >>> right, up, backward = look_axes((0.0, 0.0, -2.0), (0.0, 1.0, 0.0))
    >>> right[0], up[1], backward[2]
    (1.0, 1.0, 1.0)
    """
    # Three-vectors in Python floats: numpy's cross and norm cost far more than the sums.
    fx, fy, fz = forward
    length = math.sqrt(fx * fx + fy * fy + fz * fz)
    fx, fy, fz = fx / length, fy / length, fz / length
    ux, uy, uz = up
    rx, ry, rz = fy * uz - fz * uy, fz * ux - fx * uz, fx * uy - fy * ux
    length = math.sqrt(rx * rx + ry * ry + rz * rz)
    rx, ry, rz = rx / length, ry / length, rz / length
    return (
        (rx, ry, rz),
        (ry * fz - rz * fy, rz * fx - rx * fz, rx * fy - ry * fx),
        (-fx, -fy, -fz),
    )


def perspective(fov_y_degrees: float, aspect: float, near: float, far: float) -> np.ndarray:
    """Return an OpenGL perspective projection matrix (float64, 4x4).

    Parameters
    ----------
    fov_y_degrees : float
        Full vertical field of view.
    aspect : float
        Width over height.
    near, far : float
        Positive clip distances.

    Returns
    -------
    numpy.ndarray
        The projection, mapping the view frustum to the NDC cube.

    Examples
    --------
    >>> from pvshadows.geometry.transforms import perspective
    >>> m = perspective(90.0, 1.0, 1.0, 10.0)
    >>> round(float(m[0, 0]), 9), float(m[3, 2])
    (1.0, -1.0)
    """
    # Python floats and one array: numpy's calls on single numbers cost more than the sums.
    f = 1.0 / math.tan(math.radians(fov_y_degrees) / 2.0)
    return np.array(
        [
            [f / aspect, 0.0, 0.0, 0.0],
            [0.0, f, 0.0, 0.0],
            [0.0, 0.0, (far + near) / (near - far), 2.0 * far * near / (near - far)],
            [0.0, 0.0, -1.0, 0.0],
        ]
    )


def cube_face_rotation(face: int) -> np.ndarray:
    """Return the rotation of cube face ``face`` (0..5, GL order).

    Parameters
    ----------
    face : int
        Face index: +X, -X, +Y, -Y, +Z, -Z.

    Returns
    -------
    numpy.ndarray
        ``(4, 4)`` float64 rotation for a camera at the light.

    Examples
    --------
    >>> from pvshadows.geometry.transforms import cube_face_rotation
    >>> cube_face_rotation(0)[2, :3].tolist()
    [-1.0, -0.0, -0.0]
    """
    forward, up = CUBE_FACE_AXES[face]
    return look_rotation(np.array(forward), np.array(up))


def cube_face_projections(near: float, far: float) -> np.ndarray:
    """Return the six face matrices (90-degree projection times rotation).

    Parameters
    ----------
    near, far : float
        Clip distances of each face's frustum (depth clamp makes them
        matter only for precision of the clip-space ``z``).

    Returns
    -------
    numpy.ndarray
        ``(6, 4, 4)`` float64, acting on light-centred world positions.

    Examples
    --------
    >>> from pvshadows.geometry.transforms import cube_face_projections
    >>> cube_face_projections(0.1, 10.0).shape
    (6, 4, 4)
    """
    # Only the depth row depends on near and far: each face's is (a, b) times its rotation's
    # third row and last column, as perspective(90.0, 1.0, near, far) @ rotation gives it.
    depth, shift = (far + near) / (near - far), 2.0 * far * near / (near - far)
    return _FACE_FIXED + depth * _FACE_DEPTH + shift * _FACE_SHIFT


def boxes_from_origin(boxes: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Measure boxes from the origin (a light): distances, and the cube faces each may touch.

    One pass over the boxes serves a point light's range and its cube's faces.

    Parameters
    ----------
    boxes : numpy.ndarray
        ``(n, 2, 3)`` min/max corners relative to the origin.

    Returns
    -------
    near, far : numpy.ndarray
        ``(n,)`` each: squared distance to the box (0 inside it) and to its
        farthest corner.
    faces : numpy.ndarray
        ``(n,)`` int masks: bit ``f`` is set when face ``f``'s 90-degree
        pyramid (GL order +X, -X, +Y, -Y, +Z, -Z) and the box may overlap
        (conservative: never misses an overlap; all six for a box holding
        the origin).

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.geometry.transforms import boxes_from_origin
    >>> near, far, faces = boxes_from_origin(np.array([[[2.0, -0.5, -0.5], [3.0, 0.5, 0.5]]]))
    >>> near.tolist(), far.tolist(), faces.tolist()  # only +X sees it
    ([4.0], [9.5], [1])
    """
    boxes = np.asarray(boxes, dtype=np.float64).reshape(-1, 2, 3)
    # How far each box reaches from the origin along -x, -y, -z (``-low``), +x, +y, +z (``high``).
    reach = (boxes * _REACH_SIGNS).reshape(-1, 6)
    # Along each axis, the reach of the box's nearer side: negative outside the box's slab.
    nearer = np.minimum(reach[:, :3], reach[:, 3:])
    outside = np.minimum(nearer, 0.0)
    # The farther side along each axis (an elementwise maximum of the two halves: a
    # reduction over a middle axis of length two costs several times more).
    distance = np.abs(reach)
    farther = np.maximum(distance[:, :3], distance[:, 3:])
    near, far = squared_lengths(outside.T), squared_lengths(farther.T)
    # A face's four side planes each weigh its axis and one other: a box is inside them
    # when it reaches ahead along the face's axis at least as far as it lies outside the
    # slab of either other axis.
    beside = np.maximum(-np.minimum.reduce(nearer[:, _FACE_OTHER_AXES], axis=2), 0.0)
    return near, far, (reach[:, _FACE_REACH] >= beside) @ _FACE_BITS


def squared_lengths(rows: np.ndarray) -> np.ndarray:
    """Return the squared length of each column of a ``(3, n)`` array (or a stack of them).

    numpy's norm without its checks. The sum is written out, x's and z's,
    then y's (the order numpy's ``einsum`` sums a row of three), so that
    :func:`squared_length` gives the same bits for one vector.

    Parameters
    ----------
    rows : numpy.ndarray
        ``(..., 3, n)`` one coordinate per row (a transposed ``(n, 3)`` serves).

    Returns
    -------
    numpy.ndarray
        ``(..., n)`` the sums of the squares.

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.geometry.transforms import squared_lengths
    >>> squared_lengths(np.array([[3.0, 1], [4, 1], [0, 1]])).tolist()
    [25.0, 3.0]
    """
    x, y, z = rows.swapaxes(0, -2)  # a view: the coordinates first
    return (x * x + z * z) + y * y


def squared_length(vector: list[float]) -> float:
    """Return one vector's squared length in plain floats, as :func:`squared_lengths` sums it.

    Parameters
    ----------
    vector : list of float
        Three coordinates.

    Returns
    -------
    float
        The sum of their squares, to the same bits as :func:`squared_lengths`.

    Examples
    --------
    >>> from pvshadows.geometry.transforms import squared_length
    >>> squared_length([3.0, 4.0, 0.0])
    25.0
    """
    x, y, z = vector
    return (x * x + z * z) + y * y


def box_from_origin(low: list[float], high: list[float]) -> tuple[float, float, int]:
    """Measure one box as :func:`boxes_from_origin` does, in plain floats, to the same bits.

    For one box (an actor that moved), numpy's cost per call outweighs its speed.

    Parameters
    ----------
    low, high : list of float
        The box's min and max corners relative to the origin.

    Returns
    -------
    tuple
        Squared distances to the box and to its farthest corner, and the mask
        of the cube faces that may see it.

    Examples
    --------
    >>> from pvshadows.geometry.transforms import box_from_origin
    >>> box_from_origin([2.0, -0.5, -0.5], [3.0, 0.5, 0.5])
    (4.0, 9.5, 1)
    """
    reach = [-a for a in low] + list(high)
    nearer = [min(reach[axis], reach[axis + 3]) for axis in range(3)]
    outside = [min(a, 0.0) for a in nearer]
    farther = [max(abs(reach[axis]), abs(reach[axis + 3])) for axis in range(3)]
    faces = 0
    for face, (ahead, (one, other)) in enumerate(_FACE_SIDES):
        if reach[ahead] >= max(-min(nearer[one], nearer[other]), 0.0):
            faces |= 1 << face
    return squared_length(outside), squared_length(farther), faces


def faces_touching_boxes(boxes: np.ndarray) -> np.ndarray:
    """Return bit masks of the cube faces whose frustum may hold each box.

    Parameters
    ----------
    boxes : numpy.ndarray
        ``(n, 2, 3)`` min/max corners relative to the light.

    Returns
    -------
    numpy.ndarray
        ``(n,)`` int masks, as :func:`boxes_from_origin` gives them.

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.geometry.transforms import faces_touching_boxes
    >>> boxes = np.array([[[-1.0, -1, -1], [1, 1, 1]], [[2, -0.5, -0.5], [3, 0.5, 0.5]]])
    >>> faces_touching_boxes(boxes)  # around the light: all six; ahead along +X: one
    array([63,  1])
    """
    return boxes_from_origin(boxes)[2]


#: Each face's rotation; the axis it looks along; the column of its direction in a box's
#: reaches (-x, -y, -z, +x, +y, +z); the two other axes of each face; each face's bit.
_FACE_ROTATIONS = np.stack([cube_face_rotation(face) for face in range(6)])
#: The parts of :func:`cube_face_projections`: the rows near and far leave alone, and the
#: depth row's two terms.
_FACE_FIXED = perspective(90.0, 1.0, 1.0, 2.0) @ _FACE_ROTATIONS
_FACE_FIXED[:, 2] = 0.0
_FACE_DEPTH = np.zeros((6, 4, 4))
_FACE_DEPTH[:, 2] = _FACE_ROTATIONS[:, 2]
_FACE_SHIFT = np.zeros((6, 4, 4))
_FACE_SHIFT[:, 2, 3] = 1.0
_FACE_AXIS = np.array([int(np.argmax(np.abs(forward))) for forward, _ in CUBE_FACE_AXES])
_FACE_REACH = _FACE_AXIS + 3 * np.array([int(sum(forward) > 0.0) for forward, _ in CUBE_FACE_AXES])
_FACE_OTHER_AXES = np.array([[o for o in range(3) if o != axis] for axis in _FACE_AXIS])
_FACE_BITS = 1 << np.arange(6)
#: Each face's reach and its two other axes, as plain ints.
_FACE_SIDES = list(zip(_FACE_REACH.tolist(), _FACE_OTHER_AXES.tolist(), strict=True))
#: Signs turning a box's ``(low, high)`` corners into its reaches ``(-low, high)``.
_REACH_SIGNS = np.array([[-1.0], [1.0]])


def translation(offset: np.ndarray) -> np.ndarray:
    """Return the 4x4 matrix translating by ``offset``.

    Parameters
    ----------
    offset : numpy.ndarray
        ``(3,)`` translation.

    Returns
    -------
    numpy.ndarray
        ``(4, 4)`` float64.

    Examples
    --------
    >>> from pvshadows.geometry.transforms import translation
    >>> translation([1, 2, 3])[:3, 3].tolist()
    [1.0, 2.0, 3.0]
    """
    m = _IDENTITY.copy()
    m[:3, 3] = offset
    return m


def only_translates(matrix: np.ndarray) -> bool:
    """Return whether a ``(4, 4)`` matrix only translates: no turn, scale or projection.

    Parameters
    ----------
    matrix : numpy.ndarray
        ``(4, 4)``.

    Returns
    -------
    bool
        Whether it is :func:`translation` of some offset.

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.geometry.transforms import only_translates, translation
    >>> only_translates(translation([1, 2, 3])), only_translates(np.diag([2.0, 1, 1, 1]))
    (True, False)
    """
    (a, b, c, _), (d, e, f, _), (g, h, i, _), last = matrix.tolist()
    return (a, b, c, d, e, f, g, h, i) == _NO_TURN and tuple(last) == AFFINE_LAST_ROW


def to_vtk_matrix(matrix: np.ndarray) -> vtk.vtkMatrix4x4:
    """Return a ``vtkMatrix4x4`` holding ``matrix``.

    Parameters
    ----------
    matrix : numpy.ndarray
        ``(4, 4)`` values.

    Returns
    -------
    vtk.vtkMatrix4x4
        A new VTK matrix.

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.geometry.transforms import to_vtk_matrix
    >>> to_vtk_matrix(np.eye(4)).GetElement(2, 2)
    1.0
    """
    result = vtk.vtkMatrix4x4()
    for i in range(4):
        for j in range(4):
            result.SetElement(i, j, float(matrix[i, j]))
    return result


def from_vtk_matrix(matrix: vtk.vtkMatrix4x4) -> np.ndarray:
    """Return the values of a ``vtkMatrix4x4`` as a numpy array.

    Parameters
    ----------
    matrix : vtk.vtkMatrix4x4
        The VTK matrix.

    Returns
    -------
    numpy.ndarray
        ``(4, 4)`` float64, row-major as VTK stores it.

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.geometry.transforms import from_vtk_matrix, to_vtk_matrix
    >>> from_vtk_matrix(to_vtk_matrix(np.diag([1.0, 2.0, 3.0, 1.0]))).diagonal().tolist()
    [1.0, 2.0, 3.0, 1.0]
    """
    # ``GetData`` hands the sixteen values over as one tuple; a numpy array given to
    # ``DeepCopy`` instead is read, and written back, one element at a time.
    return np.array(matrix.GetData()).reshape(4, 4)


def column_major(matrices: np.ndarray) -> np.ndarray:
    """Return float32 values of one or more 4x4 matrices in OpenGL (column) order.

    Parameters
    ----------
    matrices : numpy.ndarray
        ``(4, 4)`` or ``(k, 4, 4)`` row-major matrices acting on column vectors.

    Returns
    -------
    numpy.ndarray
        Flat float32 array for ``glUniformMatrix4fv`` without transpose.

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.geometry.transforms import column_major, translation
    >>> column_major(translation([1, 2, 3]))[12:15].tolist()
    [1.0, 2.0, 3.0]
    """
    m = np.asarray(matrices, dtype=np.float64)
    return m.swapaxes(-1, -2).astype(np.float32, order="C").ravel()
