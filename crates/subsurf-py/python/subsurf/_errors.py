"""Exception classes of subsurf (raised by the compiled module too)."""

from typing import Optional


class SubsurfError(Exception):
    """Base class of subsurf's own errors."""

    def __init__(self, message: str, **attrs: object) -> None:
        super().__init__(message)
        for k, v in attrs.items():
            setattr(self, k, v)


class MeshError(SubsurfError, ValueError):
    """Bad mesh content. ``.face``, ``.corner`` and ``.vertex`` name the element at fault,
    ``.edit`` the sharpness edit of ``LimitSurface.set_sharpness`` (``None`` where they do
    not apply)."""

    face: Optional[int] = None
    corner: Optional[int] = None
    vertex: Optional[int] = None
    edit: Optional[int] = None


class ParseError(SubsurfError, ValueError):
    """A malformed mesh file: ``.path``, and where in it: ``.line`` (1-based) for the text
    formats, ``.location`` (a glTF JSON path such as ``accessors[3]``) for glTF, ``.prim``
    and ``.attribute`` (``/World/Body``, ``faceVertexIndices``) for USD, ``None`` where
    they do not apply."""

    path: Optional[str] = None
    line: Optional[int] = None
    location: Optional[str] = None
    prim: Optional[str] = None
    attribute: Optional[str] = None


class GpuError(SubsurfError, RuntimeError):
    """No usable GPU adapter, or a device failure. Without a GPU, Mesa's lavapipe
    (``apt-get install mesa-vulkan-drivers``) with ``WGPU_BACKEND=vulkan`` works."""


class UnsupportedError(SubsurfError, ValueError):
    """A format, option or construction this build or backend does not handle (an unknown
    file extension, the p-rep of a mesh that is not a closed quad manifold on the GPU, ...)."""
